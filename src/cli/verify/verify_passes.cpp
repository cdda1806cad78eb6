// verify shadow / shade / frame: the shadow-map passes, the shading pass (both builds on the same
// G-buffer, the Vulkan build's) and whole frames, emulator vs Vulkan build, bit for bit.
#include <cstring>
#include <memory>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "emu/device_profile.h"
#include "passes/mips.h"
#include "inputs/paraboloid.h"
#include "inputs/sh_irradiance.h"
#include "inputs/glint_lighting.h"
#include "passes/passes_vk.h"
#include "passes/visibility.h"
#include "inputs/environment.h"
#include "scene/scene.h"
#include "cli/verify/verify.h"
#include "vk/context.h"

namespace shadetwin {
namespace {

struct Setup {
  Scene scene;
  std::unique_ptr<vk::Context> ctx;
  std::unique_ptr<emu::DeviceProfile> profile;  // the device's, with --profile-set overrides
  const emu::DeviceProfile* dev = nullptr;
};

Setup setUp(const VerifyOptions& opts, std::ostream& out) {
  Setup s;
  s.scene = loadScene(opts.scene, opts);  // the shared scene options (an unknown --technique is refused there)
  vk::ContextOptions co;
  co.device = opts.device;
  co.validation = opts.validate;
  s.ctx = std::make_unique<vk::Context>(co);
  s.profile = std::make_unique<emu::DeviceProfile>(emu::profileForDevice(s.ctx->deviceName()));
  for (const std::string& kv : opts.profileSet) {
    emu::setProfileField(*s.profile, kv);
    out << "profile override: " << kv << "\n";
  }
  s.dev = s.profile.get();
  out << "scene " << opts.scene << ": " << s.scene.width << "x" << s.scene.height << ", " << s.scene.triangles()
      << " triangles; device: " << s.ctx->deviceName() << " (profile " << s.dev->name << ")\n";
  return s;
}

// The tallies' table, `note`, the --junit / --json reports, then the suite's last line (or the validation errors).
// `width`: pixels per row when the tallies' elements are pixels (the reports give a first difference as (x, y)).
int finish(const char* what, const std::vector<UlpTally>& t, uint32_t width, const vk::Context& ctx, const VerifyOptions& opts,
           std::ostream& out, const std::string& note = "") {
  const auto it = printTallies(t, out);
  out << note;
  writeVerifyReports(opts, {what, ctx.deviceName(), opts.scene, width, t, ctx.validationErrors(), ctx.lastValidationMessage}, out);
  if (opts.validate && ctx.validationErrors()) {
    out << "validation errors: " << ctx.validationErrors() << " (last: " << ctx.lastValidationMessage << ")\n";
    return 1;
  }
  out << what << ": " << it[0] << "/" << it[1] << " bit-identical\n";
  return it[0] == it[1] ? 0 : 1;
}

std::vector<UlpTally> compareRgba(const std::vector<float>& e, const std::vector<float>& g) {
  std::vector<UlpTally> t;
  for (int c = 0; c < 4; ++c) t.push_back({std::string("color.") + "rgba"[c]});
  for (size_t i = 0; i < e.size(); ++i) t[i % 4].add(e[i], g[i]);
  return t;
}

}  // namespace

int verifyShadow(const VerifyOptions& opts, std::ostream& out) {
  Setup s = setUp(opts, out);
  const std::vector<Vec3> dirs = sphereDirections(opts.directions);
  ShadowStats st;
  ShadowMaps e = shadowEmu(s.scene, dirs, opts.shadowSize, *s.dev, &st);
  ShadowPassVk pass(*s.ctx, s.scene, opts.shadowSize);
  ShadowMaps g = pass.run(dirs);
  out << dirs.size() << " directions, " << opts.shadowSize << "x" << opts.shadowSize << " D32F each; "
      << st.raster.fragments << " fragments, " << st.raster.trianglesClipped << " clipped\n";
  std::vector<UlpTally> t{{"depth"}, {"covered"}};
  size_t worst = 0, worstDiff = 0;
  const size_t px = size_t(opts.shadowSize) * opts.shadowSize;
  for (size_t d = 0; d < dirs.size(); ++d) {
    size_t diff = 0;
    for (size_t p = 0; p < px; ++p) {
      const float a = e.map(d)[p], b = g.map(d)[p];
      const size_t before = t[0].identical;
      t[0].add(a, b);
      diff += t[0].identical == before;
      t[1].addSame((a < 1.0f) == (b < 1.0f));
    }
    if (diff > worstDiff) worst = d, worstDiff = diff;
  }
  std::ostringstream note;
  if (worstDiff)
    note << "most differences in direction " << worst << " (" << dirs[worst][0] << ", " << dirs[worst][1] << ", "
         << dirs[worst][2] << "): " << worstDiff << " depth values\n";
  return finish("shadow", t, 0, *s.ctx, opts, out, note.str());
}

int verifyShade(const VerifyOptions& opts, std::ostream& out) {
  Setup s = setUp(opts, out);
  std::ostringstream quiet;
  EnvironmentMap env = loadEnvironment(s.scene, quiet);
  GBuffer g = gbufferVulkan(*s.ctx, s.scene);  // one G-buffer for both shading passes
  // The technique's inputs, the same for both passes (fis: the emulator's atlas and SH irradiance).
  const ShadeInputs in = shadeInputsEmu(s.scene, *env.texture, *s.dev);
  // With visibility (fis + "visibility" block): the same fit for both (the emulator's maps and fit of g;
  // verify visibility checks that stage).
  std::unique_ptr<VisibilityImage> vis;
  if (in.visibility) vis = std::make_unique<VisibilityImage>(visibilityEmu(s.scene, g, *in.visibility, *s.dev));
  std::vector<float> e = shadeEmu(s.scene, g, in, *s.dev, vis.get());
  ShadePassVk pass(*s.ctx, s.scene, in);
  std::vector<float> v = pass.run(g, vis.get());
  out << "technique " << s.scene.technique << (vis ? " with SH visibility" : "")
      << ", shading the Vulkan build's G-buffer in both builds\n";
  return finish("shade", compareRgba(e, v), g.width, *s.ctx, opts, out);
}

int verifyFrame(const VerifyOptions& opts, std::ostream& out) {
  Setup s = setUp(opts, out);
  std::ostringstream quiet;
  EnvironmentMap env = loadEnvironment(s.scene, quiet);
  // Each build makes its own technique inputs (fis: atlas + MIP chain, SH irradiance).
  const ShadeInputs inE = shadeInputsEmu(s.scene, *env.texture, *s.dev);
  const ShadeInputs inV = shadeInputsVulkan(*s.ctx, s.scene, *env.texture);
  const GBuffer gE = gbufferEmu(s.scene, *s.dev), gV = gbufferVulkan(*s.ctx, s.scene);
  // With visibility, each build also renders its own shadow maps and fits them.
  std::unique_ptr<VisibilityImage> visE, visV;
  if (inE.visibility) {
    visE = std::make_unique<VisibilityImage>(visibilityEmu(s.scene, gE, *inE.visibility, *s.dev));
    visV = std::make_unique<VisibilityImage>(
        VisibilityPassVk(*s.ctx, s.scene, inV.visibility->settings.size).run(gV, *inV.visibility));
  }
  std::vector<float> e = shadeEmu(s.scene, gE, inE, *s.dev, visE.get());
  ShadePassVk pass(*s.ctx, s.scene, inV);
  std::vector<float> v = pass.run(gV, visV.get());
  out << "technique " << s.scene.technique << (visE ? " with SH visibility (each build: shadow maps + fit)" : "")
      << ", whole frames (G-buffer + shading) of each build\n";
  return finish("frame", compareRgba(e, v), gE.width, *s.ctx, opts, out);
}

int verifyParaboloid(const VerifyOptions& opts, std::ostream& out) {
  Setup s = setUp(opts, out);
  std::ostringstream quiet;
  EnvironmentMap env = loadEnvironment(s.scene, quiet);
  const uint32_t S = opts.faceSize;
  std::vector<float> e = paraboloidAtlasEmu(*env.texture, *s.dev, S);
  std::vector<float> v = paraboloidAtlasVulkan(*s.ctx, *env.texture, S);
  out << "environment " << s.scene.environment << " (" << env.width << "x" << env.height << ") -> paraboloid atlas "
      << 2 * S << "x" << S << "\n";
  std::vector<UlpTally> t = compareRgba(e, v);
  // The MIP chain of the (emulator's) atlas, shared downsampling kernel on both sides.
  const auto ce = mipChainCpu(e, 2 * S, S, 1, 8), cv = mipChainGpu(*s.ctx, e, 2 * S, S, 1);
  UlpTally mips{"mip levels 1.."};
  for (size_t l = 1; l < ce.size(); ++l)
    for (size_t i = 0; i < ce[l].size(); ++i) mips.add(ce[l][i], cv[l][i]);
  t.push_back(mips);
  return finish("paraboloid", t, 2 * S, *s.ctx, opts, out);
}

int verifyShIrradiance(const VerifyOptions& opts, std::ostream& out) {
  Setup s = setUp(opts, out);
  std::ostringstream quiet;
  EnvironmentMap env = loadEnvironment(s.scene, quiet);
  const ShIrradiance e = shIrradianceEmu(*env.texture, *s.dev), v = shIrradianceVulkan(*s.ctx, *env.texture);
  out << "environment " << s.scene.environment << " (" << env.width << "x" << env.height
      << ") -> 9 x RGB coefficients of E/pi, 7 x RGB of band-3 radiance\n";
  UlpTally t{"coefficients"}, t3{"band 3"};
  for (size_t i = 0; i < e.c.size(); ++i) t.add(e.c[i], v.c[i]);
  for (size_t i = 0; i < e.band3.size(); ++i) t3.add(e.band3[i], v.band3[i]);
  out << "E/pi(+y) = " << shIrradianceAt(e, {0, 1, 0})[1] << ", E/pi(-y) = " << shIrradianceAt(e, {0, -1, 0})[1]
      << " (green)\n";
  return finish("sh", {t, t3}, 0, *s.ctx, opts, out);
}

int verifyVisibility(const VerifyOptions& opts, std::ostream& out) {
  Setup s = setUp(opts, out);
  std::ostringstream quiet;
  EnvironmentMap env = loadEnvironment(s.scene, quiet);
  VisibilitySettings vs;
  vs.maps = opts.directions;
  vs.size = opts.shadowSize;
  vs.fitCosine = !opts.visibilityV;
  const VisibilitySetup v = visibilitySetup(s.scene, *env.texture, vs);
  // Both builds fit the same inputs: the Vulkan build's G-buffer and the emulator's maps (verify
  // raster and verify shadow check those stages).
  const GBuffer g = gbufferVulkan(*s.ctx, s.scene);
  const emu::Texture maps = shadowMapArray(shadowEmu(s.scene, v.directions, vs.size, *s.dev));
  VisibilityPassVk pass(*s.ctx, s.scene, vs.size);
  const VisibilityImage e = visibilityFitEmu(g, maps, v, *s.dev), k = pass.fit(g, maps, v);
  out << vs.maps << " directions from the luminance of " << s.scene.environment
      << (v.uniformFallback ? " (none positive: uniform)" : "") << ", maps " << vs.size << "x" << vs.size
      << ", fit " << (vs.fitCosine ? "V max(0, n.w)" : "V") << ", rank of M " << v.rank << "/16\n";
  std::vector<UlpTally> t;
  for (int c = 0; c < 16; ++c) t.push_back({"c" + std::to_string(c)});
  size_t diffGeometry = 0, diffBackground = 0;
  for (size_t i = 0; i < e.coeffs.size(); ++i) {
    t[i % 16].add(e.coeffs[i], k.coeffs[i]);
    if (!sameBits(e.coeffs[i], k.coeffs[i])) ++(g.texels[i / 16 * kGbufFloats + 3] != 0.0f ? diffGeometry : diffBackground);
  }
  if (diffGeometry + diffBackground)
    out << "differing values: " << diffGeometry << " on geometry, " << diffBackground << " on background pixels\n";
  // The spatial filter (radius 2, edge-aware, the scene defaults; box with --fit-v to cover both) of
  // the emulator's fit on both builds.
  VisibilitySetup vf = v;
  vf.settings.filterRadius = 2;
  vf.settings.filterEdgeAware = !opts.visibilityV;
  const VisibilityImage fe = visibilityFilterEmu(g, e, vf, *s.dev), fk = pass.filter(g, e, vf);
  out << "filter: radius " << vf.settings.filterRadius << ", " << (vf.settings.filterEdgeAware ? "edge-aware" : "box") << "\n";
  for (int c = 0; c < 16; ++c) t.push_back({"filtered c" + std::to_string(c)});
  for (size_t i = 0; i < fe.coeffs.size(); ++i) t[16 + i % 16].add(fe.coeffs[i], fk.coeffs[i]);
  return finish("visibility", t, g.width, *s.ctx, opts, out);
}

int verifyGlintLighting(const VerifyOptions& opts, std::ostream& out) {
  Setup s = setUp(opts, out);
  std::ostringstream quiet;
  EnvironmentMap env = loadEnvironment(s.scene, quiet);
  GlintLightingSpec spec;
  spec.order = opts.glintOrder, spec.rings = opts.glintRings, spec.sectors = opts.glintSectors;
  if (opts.glintLevel >= 0) spec.level = uint32_t(opts.glintLevel);
  else
    while (spec.level + 1 < env.texture->levelCount() && env.texture->levelWidth(spec.level) > 64) ++spec.level;
  spec.bandRows = glintBandRows(s.dev->loopIterationLimit, env.texture->levelWidth(spec.level),
                                env.texture->levelHeight(spec.level), spec.order);  // the device's loop limit
  const GlintLightingTable e = glintLightingEmu(*env.texture, *s.dev, spec), v = glintLightingVulkan(*s.ctx, *env.texture, spec);
  out << "environment " << s.scene.environment << " level " << spec.level << " (" << env.texture->levelWidth(spec.level) << "x"
      << env.texture->levelHeight(spec.level) << " texels) -> glint lighting table: " << spec.rings << " x " << spec.sectors
      << " views, degree " << spec.order << " (" << e.coeffs << " RGB coefficients each, " << e.bytes() / (1 << 20)
      << " MiB; bands of " << (spec.bandRows ? spec.bandRows : env.texture->levelHeight(spec.level)) << " rows); build emu " << e.buildMs << " ms, vulkan " << v.buildMs << " ms\n";
  const std::vector<UlpTally> t = compareRgba(e.rgba, v.rgba);
  return finish("glint-lighting", t, 0, *s.ctx, opts, out);
}

}  // namespace shadetwin
