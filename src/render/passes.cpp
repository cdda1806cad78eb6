#include "render/gbuffer.h"

#include <cmath>

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "render/material.h"
#include "shade/instantiate.h"
#include "util/timer.h"

namespace shadetwin {

std::vector<VertexGpu> interleave(const Mesh& m) {
  std::vector<VertexGpu> v(m.positions.size());
  for (size_t i = 0; i < v.size(); ++i) {
    std::memcpy(v[i].pos, m.positions[i].data(), 12);
    std::memcpy(v[i].normal, m.normals[i].data(), 12);
    std::memcpy(v[i].tangent, m.tangents[i].data(), 16);
    std::memcpy(v[i].uv, m.uvs[i].data(), 8);
  }
  return v;
}

ObjectGpu objectGpu(const Object& o) {
  ObjectGpu g{};
  std::memcpy(g.model, o.model.data(), 64);
  Mat4 n = normalMatrix(o.model);
  std::memcpy(g.normal, n.data(), 64);
  g.materialId = float(o.material);
  return g;
}

namespace {
using V2f = shade::V2<float>;
using V3f = shade::V3<float>;
using V4f = shade::V4<float>;
V4f col(const float* m, int c) { return V4f(m[4 * c], m[4 * c + 1], m[4 * c + 2], m[4 * c + 3]); }
}  // namespace

GBuffer gbufferEmu(const Scene& scene, const emu::DeviceProfile& dev, GbufferStats* stats) {
  GBuffer g;
  gbufferEmu(scene, dev, g, stats);
  return g;
}

void gbufferEmu(const Scene& scene, const emu::DeviceProfile& dev, GBuffer& g, GbufferStats* stats) {
  emu::Framebuffer fb;
  fb.color.swap(g.texels);
  fb.depth.swap(g.depth);
  fb.reset(scene.width, scene.height, kGbufFloats);
  const Mat4 vp = scene.viewProjection();
  GbufferStats local;
  for (uint32_t oi = 0; oi < scene.objects.size(); ++oi) {
    const Object& obj = scene.objects[oi];
    const Mesh& mesh = scene.meshes[obj.mesh];
    const ObjectGpu og = objectGpu(obj);
    // Vertex stage: the shared gbufferVertex, scalar build, vertex-stage denormal mode (preserve).
    auto t0 = std::chrono::steady_clock::now();
    const size_t nv = mesh.positions.size();
    std::vector<float> clip(4 * nv), vary(kGbufVaryings * nv);
    tbb::parallel_for(size_t(0), nv, [&](size_t i) {
      auto& P = mesh.positions[i];
      auto& N = mesh.normals[i];
      auto& T = mesh.tangents[i];
      auto& U = mesh.uvs[i];
      auto o = shade::scalar::gbufferVertex(col(og.model, 0), col(og.model, 1), col(og.model, 2), col(og.model, 3),
                                            col(og.normal, 0), col(og.normal, 1), col(og.normal, 2), col(vp.data(), 0),
                                            col(vp.data(), 1), col(vp.data(), 2), col(vp.data(), 3), V3f(P[0], P[1], P[2]),
                                            V3f(N[0], N[1], N[2]), V4f(T[0], T[1], T[2], T[3]), V2f(U[0], U[1]));
      float* c = &clip[4 * i];
      c[0] = o.clip.x, c[1] = o.clip.y, c[2] = o.clip.z, c[3] = o.clip.w;
      float* v = &vary[kGbufVaryings * i];
      const float vals[kGbufVaryings] = {o.worldPos.x, o.worldPos.y, o.worldPos.z, o.normal.x,  o.normal.y,  o.normal.z,
                                         o.tangent.x,  o.tangent.y,  o.tangent.z,  o.tangent.w, o.uv.x, o.uv.y};
      std::memcpy(v, vals, sizeof vals);
    });
    local.vertexMs += msSince(t0);
    // Raster + fragment stage: the shared gbufferFragment per pixel, derivatives from the quad.
    t0 = std::chrono::steady_clock::now();
    emu::DrawInput in;
    in.clip = clip.data();
    in.varyings = vary.data();
    in.numVaryings = kGbufVaryings;
    in.indices = mesh.indices.data();
    in.triangles = mesh.triangles();
    in.drawId = oi;
    const float materialId = og.materialId;
    emu::draw(dev, fb, in, [&](const emu::Quad& q, float (*out)[4]) {
      float dudx[4], dudy[4], dvdx[4], dvdy[4];
      emu::quadDerivatives(dev, q.v[10], dudx, dudy);
      emu::quadDerivatives(dev, q.v[11], dvdx, dvdy);
      for (int i = 0; i < 4; ++i) {
        auto g = shade::scalar::gbufferFragment(V3f(q.v[0][i], q.v[1][i], q.v[2][i]), V3f(q.v[3][i], q.v[4][i], q.v[5][i]),
                                                V4f(q.v[6][i], q.v[7][i], q.v[8][i], q.v[9][i]), V2f(q.v[10][i], q.v[11][i]),
                                                V2f(dudx[i], dvdx[i]), V2f(dudy[i], dvdy[i]), materialId);
        const V4f att[4] = {g.g0, g.g1, g.g2, g.g3};
        for (int a = 0; a < 4; ++a) {
          out[4 * a][i] = att[a].x;
          out[4 * a + 1][i] = att[a].y;
          out[4 * a + 2][i] = att[a].z;
          out[4 * a + 3][i] = att[a].w;
        }
      }
    }, &local.raster);
    local.rasterMs += msSince(t0);
  }
  if (stats) *stats = local;
  g.width = scene.width;
  g.height = scene.height;
  g.texels.swap(fb.color);
  g.depth.swap(fb.depth);
}

std::vector<float> shadeEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev) {
  std::vector<float> out;
  shadeEmu(scene, g, in, dev, out);
  return out;
}

shade::Sampler2D environmentSampler(const emu::Texture& tex, const emu::DeviceProfile& dev, bool repeatU) {
  shade::Sampler2D s;
  s.tex = &tex;
  s.dev = &dev;
  s.desc.addressU = repeatU ? emu::AddressMode::Repeat : emu::AddressMode::ClampToEdge;
  s.desc.addressV = emu::AddressMode::ClampToEdge;
  return s;
}

shade::Sampler2D materialMapSampler(const emu::Texture& tex, const emu::DeviceProfile& dev) {
  shade::Sampler2D s = environmentSampler(tex, dev, true);
  s.desc.addressV = emu::AddressMode::Repeat;
  return s;
}

uint32_t fisMode(const Scene& scene) {
  if (scene.technique == "unfiltered") return shade::scalar::kFisUnfiltered;
  if (scene.technique == "stochastic") return shade::scalar::kFisStochastic;
  return shade::scalar::kFisFiltered;
}

float fisLevelConstant(const Scene& scene) {
  const double S = scene.fisFaceSize;
  return float(std::log2(double(scene.fisK) * S * S / double(scene.fisSamples)));
}

namespace {
using F8 = emu::F32<8>;
using V3x = shade::V3<F8>;
using V4x = shade::V4<F8>;

// One device vector of a shading pass: 8 consecutive pixels of the G-buffer (tail lanes repeat the
// last pixel, as the GPU's tail invocations do), their material slots and camera rays.
struct PixelBlock {
  V4x g0, g1, g2, g3;
  V3x eye, ray;
  emu::U32<8> pixel;  // row-major pixel index (tail lanes: the last pixel)
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
      p.ray = shade::x8::cameraRay(splat(cam.fwd), splat(cam.right), splat(cam.down), px, py, invW, invH);
      const V4x c = shade(p);
      for (int l = 0; l < 8 && b * 8 + size_t(l) < n; ++l) {
        float* o = &out[4 * (b * 8 + size_t(l))];
        o[0] = c.x[l], o[1] = c.y[l], o[2] = c.z[l], o[3] = c.w[l];
      }
    }
  });
}

// Each lane's material record (render/material.h), gathered into lanes; surface() is the shared
// shade/material.h step (BRDF parameters unpacked, maps applied), as the GLSL entry points do it.
struct LaneMaterials {
  V3x diffuse, specular;
  shade::x8::BrdfParams brdf;
  emu::U32<8> maps[3];
};
LaneMaterials laneMaterials(const PixelBlock& p, const std::vector<MaterialGpu>& table) {
  V4x v[6];  // diffuse, specular, brdf, lobe0, lobe1, rho
  emu::U32<8> kind(0u), maps[3];
  for (int l = 0; l < 8; ++l) {
    const MaterialGpu& m = table[p.slot[l]];
    const float* src[6] = {m.diffuse, m.specular, m.brdf, m.lobe0, m.lobe1, m.rho};
    for (int k = 0; k < 6; ++k) v[k].x.set(l, src[k][0]), v[k].y.set(l, src[k][1]), v[k].z.set(l, src[k][2]), v[k].w.set(l, src[k][3]);
    kind.set(l, m.kind[0]);
    for (int k = 0; k < 3; ++k) maps[k].set(l, m.maps[k]);
  }
  return {V3x(v[0].x, v[0].y, v[0].z), V3x(v[1].x, v[1].y, v[1].z),
          shade::x8::brdfParamsPacked(kind, v[2], v[3], v[4], v[5]), {maps[0], maps[1], maps[2]}};
}
shade::x8::SurfaceMaterial surface(const PixelBlock& p, const std::vector<MaterialGpu>& table, const shade::Sampler2D& maps) {
  const LaneMaterials m = laneMaterials(p, table);
  return shade::x8::surfaceMaterial(maps, m.diffuse, m.specular, m.brdf, m.maps[0], m.maps[1], m.maps[2], p.g1, p.g2, p.g3);
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
    const emu::Mask<8> geometry = p.g0.w != F8(0.0f);
    if (anyLane(geometry)) {  // IF_ANY, as shade_env.comp's per-invocation if
      const auto F = shade::x8::envFrame(p.g0, p.g1, p.g2, p.eye);
      for (uint32_t j = 0; j < in.lights.count; ++j)
        sum = shade::x8::envAddLight(sum, F, m.brdf, m.diffuse, m.specular, splat(&L[8 * j]), splat(&L[8 * j + 4]));
    }
    return shade::x8::envFinish(s, p.g0, p.ray, sum, intensity);
  });
}

void shadeFisEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                 std::vector<float>& out) {
  const emu::Texture& atlas = *in.atlas;
  const shade::Sampler2D s = environmentSampler(atlas, dev, false);  // the atlas clamps in u too
  const F8 maxLod(float(atlas.levelCount() - 1)), levelC(fisLevelConstant(scene)), bias(scene.fisLevelBias),
      intensity(scene.environmentIntensity);
  V3x c[9];
  for (int k = 0; k < 9; ++k) c[k] = splat(&in.sh.c[3 * size_t(k)]);
  const shade::x8::ShRgb sh{c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8]};
  const uint32_t mode = fisMode(scene);
  const shade::Sampler2D maps = materialMapSampler(*in.maps, dev);
  const std::vector<MaterialGpu> mats = materialRecords(scene, true);
  shadePixelBlocks(scene, g, dev, 16, uint32_t(mats.size()), out, [&](const PixelBlock& p) {
    const auto m = surface(p, mats, maps);
    return shade::x8::shadeFis(s, mode, maxLod, levelC, bias, scene.fisSamples, intensity, sh, p.pixel, p.g0, p.g1, p.g2,
                               p.eye, p.ray, m.diffuse, m.specular, m.brdf);
  });
}
// Techniques *-mis: shade_env_mis.comp's shadeEnvMis over the environment and its sampler's tables.
void shadeMisEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                 std::vector<float>& out) {
  const shade::Sampler2D env = environmentSampler(*in.environment, dev, true);
  const shade::Sampler2D table = environmentSampler(*in.envTables->table, dev, false);
  const shade::Sampler2D texels = environmentSampler(*in.envTables->texels, dev, false);
  const EnvSamplingUniforms& u = in.envTables->uniforms;
  const auto es = toEnvSampling<shade::x8::EnvSampling>(u);
  const shade::x8::MisSettings ms{scene.misHeuristic, scene.misSamples, scene.misFrame, scene.misSeed};
  const F8 intensity(scene.environmentIntensity);
  const shade::Sampler2D maps = materialMapSampler(*in.maps, dev);
  const std::vector<MaterialGpu> mats = materialRecords(scene, true);
  shadePixelBlocks(scene, g, dev, 4, uint32_t(mats.size()), out, [&](const PixelBlock& p) {
    const auto m = surface(p, mats, maps);
    return shade::x8::shadeEnvMis(env, table, texels, es, ms, intensity, p.pixel, p.g0, p.g1, p.g2, p.eye, p.ray, m.diffuse,
                                  m.specular, m.brdf);
  });
}
}  // namespace

void shadeEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
              std::vector<float>& out) {
  if (usesFisPass(scene.technique)) return shadeFisEmu(scene, g, in, dev, out);
  if (usesMisPass(scene.technique)) return shadeMisEmu(scene, g, in, dev, out);
  if (scene.technique == "env") return shadeEnvEmu(scene, g, in, dev, out);
  const emu::Texture& env = *in.environment;
  const shade::Sampler2D envS = environmentSampler(env, dev, true);
  const F8 maxLod(float(env.levelCount() - 1)), intensity(scene.environmentIntensity);
  const std::vector<MaterialGpu> mats = materialRecords(scene, false);
  shadePixelBlocks(scene, g, dev, 64, uint32_t(mats.size()), out, [&](const PixelBlock& p) {
    const LaneMaterials m = laneMaterials(p, mats);
    return shade::x8::shadeMirror(envS, maxLod, intensity, p.g0, p.g1, p.eye, p.ray, m.diffuse, m.specular);
  });
}

}  // namespace shadetwin
