// The emulated shading pass's drivers (every technique), written once and compiled once per build of the shared
// dialect: passes/shade_emu.cpp (SHADE_EMU_NS x8, the emulator) and model/shade_counts.cpp (the counted lanes of
// the performance model, issue 19). The includer defines SHADE_EMU_NS, SHADE_EMU_F/U/I/M (the 8-lane types) and
// SHADE_EMU_ENTRY (the entry point's name), and includes this inside namespace shadetwin; optionally
// SHADE_EMU_INVOCATION() (a statement run before each 8-pixel vector: the counted build starts an invocation there).
namespace {
using F8 = SHADE_EMU_F;
using V3x = shade::V3<F8>;
using V4x = shade::V4<F8>;

// One device vector of a shading pass: 8 consecutive pixels of the G-buffer (tail lanes repeat the
// last pixel, as the GPU's tail invocations do), their material slots and camera rays.
struct PixelBlock {
  V4x g0, g1, g2, g3;
  V3x eye, ray;
  SHADE_EMU_U pixel;  // row-major pixel index (tail lanes: the last pixel)
  uint32_t slot[8];
};

V3x splat(const float v[3]) { return V3x(F8(v[0]), F8(v[1]), F8(v[2])); }

// The compute-stage loop shared by the techniques: TBB over blocks of 8 pixels in the device's
// denormal mode; shade(block) returns the 4 output floats of each lane.
template <class Shade>
void shadePixelBlocks(const Scene& scene, const GBuffer& g, const emu::DeviceProfile& dev, size_t grain,
                      uint32_t materialCount, std::vector<float>& out, Shade shade) {
  const size_t n = size_t(g.width) * g.height;
  out.resize(4 * n);
  const CameraRays cam = cameraRays(scene);
  const F8 invW(1.0f / float(g.width)), invH(1.0f / float(g.height));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, (n + 7) / 8, grain), [&](const tbb::blocked_range<size_t>& r) {
    emu::DenormalScope mode(dev.denormCompute == emu::DenormMode::Flush);
    for (size_t b = r.begin(); b != r.end(); ++b) {
#ifdef SHADE_EMU_INVOCATION
      SHADE_EMU_INVOCATION();
#endif
      PixelBlock p;
      F8 px, py;
      for (int l = 0; l < 8; ++l) {
        const size_t i = std::min(b * 8 + size_t(l), n - 1);
        const float* t = g.texels.data() + i * kGbufFloats;
        p.g0.x.set(l, t[0]), p.g0.y.set(l, t[1]), p.g0.z.set(l, t[2]), p.g0.w.set(l, t[3]);
        p.g1.x.set(l, t[4]), p.g1.y.set(l, t[5]), p.g1.z.set(l, t[6]), p.g1.w.set(l, t[7]);
        p.g2.x.set(l, t[8]), p.g2.y.set(l, t[9]), p.g2.z.set(l, t[10]), p.g2.w.set(l, t[11]);
        p.g3.x.set(l, t[12]), p.g3.y.set(l, t[13]), p.g3.z.set(l, t[14]), p.g3.w.set(l, t[15]);
        p.slot[l] = shade::scalar::materialSlot(t[3], materialCount);
        p.pixel.set(l, uint32_t(i));
        px.set(l, float(i % g.width));
        py.set(l, float(i / g.width));
      }
      p.eye = splat(cam.eye);
      p.ray = shade::SHADE_EMU_NS::cameraRay(splat(cam.fwd), splat(cam.right), splat(cam.down), px, py, invW, invH);
      const V4x c = shade(p);
      for (int l = 0; l < 8 && b * 8 + size_t(l) < n; ++l) {
        float* o = &out[4 * (b * 8 + size_t(l))];
        o[0] = c.x[l], o[1] = c.y[l], o[2] = c.z[l], o[3] = c.w[l];
      }
    }
  });
}

// Each lane's material record (inputs/material.h), gathered into lanes; surface() is the shared
// shade/material.h step (BRDF parameters unpacked, maps applied), as the GLSL entry points do it.
struct LaneMaterials {
  V3x diffuse, specular;
  shade::SHADE_EMU_NS::BrdfParams brdf;
  SHADE_EMU_U maps[3];
};
LaneMaterials laneMaterials(const PixelBlock& p, const std::vector<MaterialGpu>& table) {
  V4x v[6];  // diffuse, specular, brdf, lobe0, lobe1, rho
  SHADE_EMU_U kind(0u), maps[3];
  for (int l = 0; l < 8; ++l) {
    const MaterialGpu& m = table[p.slot[l]];
    const float* src[6] = {m.diffuse, m.specular, m.brdf, m.lobe0, m.lobe1, m.rho};
    for (int k = 0; k < 6; ++k) v[k].x.set(l, src[k][0]), v[k].y.set(l, src[k][1]), v[k].z.set(l, src[k][2]), v[k].w.set(l, src[k][3]);
    kind.set(l, m.kind[0]);
    for (int k = 0; k < 3; ++k) maps[k].set(l, m.maps[k]);
  }
  return {V3x(v[0].x, v[0].y, v[0].z), V3x(v[1].x, v[1].y, v[1].z),
          shade::SHADE_EMU_NS::brdfParamsPacked(kind, v[2], v[3], v[4], v[5]), {maps[0], maps[1], maps[2]}};
}
shade::SHADE_EMU_NS::SurfaceMaterial surface(const PixelBlock& p, const std::vector<MaterialGpu>& table, const shade::Sampler2D& maps) {
  const LaneMaterials m = laneMaterials(p, table);
  return shade::SHADE_EMU_NS::surfaceMaterial(maps, m.diffuse, m.specular, m.brdf, m.maps[0], m.maps[1], m.maps[2], p.g1, p.g2, p.g3);
}

// Technique env: the light loop of shade_env.comp (light 0 first, one envAddLight each).
void shadeEnvEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                 std::vector<float>& out) {
  const shade::Sampler2D s = environmentSampler(*in.environment, dev, true);
  const F8 intensity(scene.environmentIntensity);
  const shade::Sampler2D maps = materialMapSampler(*in.maps, dev);
  const std::vector<MaterialGpu> mats = materialRecords(scene, true);
  const std::vector<float>& L = in.lights.data;
  shadePixelBlocks(scene, g, dev, 16, uint32_t(mats.size()), out, [&](const PixelBlock& p) {
    const auto m = surface(p, mats, maps);
    V3x sum(F8(0.0f), F8(0.0f), F8(0.0f));
    const SHADE_EMU_M geometry = p.g0.w != F8(0.0f);
    if (anyLane(geometry)) {  // IF_ANY, as shade_env.comp's per-invocation if
      const auto F = shade::SHADE_EMU_NS::envFrame(p.g0, p.g1, p.g2, p.eye);
      for (uint32_t j = 0; j < in.lights.count; ++j)
        sum = shade::SHADE_EMU_NS::envAddLight(sum, F, m.brdf, m.diffuse, m.specular, splat(&L[8 * j]), splat(&L[8 * j + 4]));
    }
    return shade::SHADE_EMU_NS::envFinish(s, p.g0, p.ray, sum, intensity);
  });
}

// kFisVis* for a pass with `vis` (the frame's fit of g) or without it.
uint32_t visModeOf(const GBuffer& g, const ShadeInputs& in, const VisibilityImage* vis) {
  if (!vis || !in.visibility) return shade::SHADE_EMU_NS::kFisVisNone;
  if (vis->width != g.width || vis->height != g.height)
    throw std::invalid_argument("shading pass: the visibility fit is not of this G-buffer");
  return in.visibility->settings.fitCosine ? shade::SHADE_EMU_NS::kFisVisCos : shade::SHADE_EMU_NS::kFisVisV;
}

// The lanes' SH visibility coefficients (zero without visibility: the kernel does not read them).
shade::SHADE_EMU_NS::Sh16 laneVisibility(const PixelBlock& p, const VisibilityImage* vis) {
  float c[16][8] = {};
  if (vis)
    for (int l = 0; l < 8; ++l)
      for (int k = 0; k < 16; ++k) c[k][l] = vis->coeffs[size_t(p.pixel[l]) * 16 + size_t(k)];
  auto v4 = [&](int k) {
    V4x r;
    for (int l = 0; l < 8; ++l) r.x.set(l, c[k][l]), r.y.set(l, c[k + 1][l]), r.z.set(l, c[k + 2][l]), r.w.set(l, c[k + 3][l]);
    return r;
  };
  return {v4(0), v4(4), v4(8), v4(12)};
}

void shadeFisEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                 std::vector<float>& out, const VisibilityImage* vis) {
  const emu::Texture& atlas = *in.atlas;
  const shade::Sampler2D s = environmentSampler(atlas, dev, false);  // the atlas clamps in u too
  const shade::Sampler2D env = environmentSampler(*in.environment, dev, true);  // the background
  const uint32_t background = scene.fisBackgroundAtlas ? shade::SHADE_EMU_NS::kFisBackgroundAtlas
                                                       : shade::SHADE_EMU_NS::kFisBackgroundEnvironment;
  const F8 maxLod(float(atlas.levelCount() - 1)), levelC(fisLevelConstant(scene)), bias(scene.fisLevelBias),
      intensity(scene.environmentIntensity);
  V3x c[9];
  for (int k = 0; k < 9; ++k) c[k] = splat(&in.sh.c[3 * size_t(k)]);
  const shade::SHADE_EMU_NS::ShRgb sh{c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8]};
  const uint32_t mode = fisMode(scene);
  const shade::Sampler2D maps = materialMapSampler(*in.maps, dev);
  const std::vector<MaterialGpu> mats = materialRecords(scene, true);
  const bool useVis = vis && in.visibility;
  const uint32_t visMode = visModeOf(g, in, vis);
  auto sh16 = [&](const float* c) {
    return shade::SHADE_EMU_NS::Sh16{V4x(F8(c[0]), F8(c[1]), F8(c[2]), F8(c[3])), V4x(F8(c[4]), F8(c[5]), F8(c[6]), F8(c[7])),
                           V4x(F8(c[8]), F8(c[9]), F8(c[10]), F8(c[11])), V4x(F8(c[12]), F8(c[13]), F8(c[14]), F8(c[15]))};
  };
  const shade::SHADE_EMU_NS::VisLighting vl{sh16(&in.visLighting[0]), sh16(&in.visLighting[16]), sh16(&in.visLighting[32])};
  shadePixelBlocks(scene, g, dev, 16, uint32_t(mats.size()), out, [&](const PixelBlock& p) {
    const auto m = surface(p, mats, maps);
    return shade::SHADE_EMU_NS::shadeFis(s, env, background, mode, maxLod, levelC, bias, scene.fisSamples, intensity, sh, p.pixel, p.g0, p.g1, p.g2,
                               p.eye, p.ray, m.diffuse, m.specular, m.brdf, visMode,
                               laneVisibility(p, useVis ? vis : nullptr), vl);
  });
}
// Techniques *-mis: shade_env_mis.comp's shadeEnvMis over the environment and its sampler's tables.
void shadeMisEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                 std::vector<float>& out, const VisibilityImage* vis) {
  const shade::Sampler2D env = environmentSampler(*in.environment, dev, true);
  const shade::Sampler2D table = environmentSampler(*in.envTables->table, dev, false);
  const shade::Sampler2D texels = environmentSampler(*in.envTables->texels, dev, false);
  const EnvSamplingUniforms& u = in.envTables->uniforms;
  const auto es = toEnvSampling<shade::SHADE_EMU_NS::EnvSampling>(u);
  const shade::SHADE_EMU_NS::MisSettings ms{scene.misHeuristic, scene.misSamples, scene.misFrame, scene.misSeed};
  const bool useVis = vis && in.visibility;
  const uint32_t visMode = visModeOf(g, in, vis);
  const F8 intensity(scene.environmentIntensity);
  const shade::Sampler2D maps = materialMapSampler(*in.maps, dev);
  const std::vector<MaterialGpu> mats = materialRecords(scene, true);
  shadePixelBlocks(scene, g, dev, 4, uint32_t(mats.size()), out, [&](const PixelBlock& p) {
    const auto m = surface(p, mats, maps);
    return shade::SHADE_EMU_NS::shadeEnvMis(env, table, texels, es, ms, intensity, p.pixel, p.g0, p.g1, p.g2, p.eye, p.ray, m.diffuse,
                                  m.specular, m.brdf, visMode, laneVisibility(p, useVis ? vis : nullptr));
  });
}
// Technique glints: shade_glints.comp's shadeGlints over the frame's glint inputs.
void shadeGlintsEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                    std::vector<float>& out) {
  const GlintInputs& gi = *in.glints;
  const shade::Sampler2D env = environmentSampler(*in.environment, dev, true);
  const shade::USampler2DArray sat{gi.sat.get()};
  const shade::Sampler2D bins = environmentSampler(*gi.binDirs, dev, false), mats = environmentSampler(*gi.materials, dev, false),
                         lighting = environmentSampler(*gi.lighting, dev, false), coef = environmentSampler(*gi.coef, dev, false),
                         lobes = environmentSampler(*gi.lobes, dev, false);
  const GlintUniforms u = glintUniforms(gi);
  const shade::SHADE_EMU_NS::GlintSettings s{u.order, u.rings,     u.sectors,     u.mapW,      u.mapH,
                                   u.invW,  u.invH,      u.viewRings,   u.viewSectors, u.lobeRings, u.lobeSectors};
  const F8 intensity(scene.environmentIntensity);
  shadePixelBlocks(scene, g, dev, 2, uint32_t(scene.materials.size()), out, [&](const PixelBlock& p) {
    SHADE_EMU_I row;
    for (int l = 0; l < 8; ++l) row.set(l, int32_t(p.slot[l]));
    return shade::SHADE_EMU_NS::shadeGlints(sat, bins, mats, lighting, coef, lobes, env, s, intensity, p.g0, p.g1, p.g2, p.g3, p.eye, p.ray, row);
  });
}
}  // namespace

void SHADE_EMU_ENTRY(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
              std::vector<float>& out, const VisibilityImage* vis) {
  if (scene.technique == "glints") return shadeGlintsEmu(scene, g, in, dev, out);
  if (usesFisPass(scene.technique)) return shadeFisEmu(scene, g, in, dev, out, vis);
  if (usesMisPass(scene.technique)) return shadeMisEmu(scene, g, in, dev, out, vis);
  if (scene.technique == "env") return shadeEnvEmu(scene, g, in, dev, out);
  const emu::Texture& env = *in.environment;
  const shade::Sampler2D envS = environmentSampler(env, dev, true);
  const F8 maxLod(float(env.levelCount() - 1)), intensity(scene.environmentIntensity);
  const std::vector<MaterialGpu> mats = materialRecords(scene, false);
  shadePixelBlocks(scene, g, dev, 64, uint32_t(mats.size()), out, [&](const PixelBlock& p) {
    const LaneMaterials m = laneMaterials(p, mats);
    return shade::SHADE_EMU_NS::shadeMirror(envS, maxLod, intensity, p.g0, p.g1, p.eye, p.ray, m.diffuse, m.specular);
  });
}

