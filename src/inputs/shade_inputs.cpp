#include "inputs/shade_inputs.h"

#include <chrono>

#include "inputs/material.h"
#include "inputs/paraboloid.h"
#include "util/timer.h"

namespace shadetwin {
namespace {
// One recipe for both builds: the atlas, the SH and the material maps come from the build that renders
// (atlas(), sh(), maps()); the light list and the sampler tables are host-built, the same for both.
template <class Atlas, class Sh, class Maps, class Glints>
ShadeInputs shadeInputsWith(const Scene& scene, const emu::Texture& env, Atlas atlas, Sh sh, Maps maps, Glints glints) {
  ShadeInputs in;
  in.environment = &env;
  if (usesFisPass(scene.technique)) {
    in.atlasMs = timeMs([&] { in.atlas = std::make_shared<emu::Texture>(atlas()); });
    in.shMs = timeMs([&] { in.sh = sh(); });
    if (scene.visMaps) in.visLighting = visibilityLighting(in.sh);
  }
  if (scene.visMaps && (usesFisPass(scene.technique) || usesMisPass(scene.technique)))
    in.visibility = std::make_shared<VisibilitySetup>(visibilitySetup(scene, env, visibilitySettings(scene)));
  if (scene.technique == "env") in.lights = envLights(env, scene.fisSamples);
  if (usesMisPass(scene.technique))
    in.envTables = std::make_shared<EnvSamplingTables>(envSamplingTables(env, envMethodOf(scene.technique), scene.envBlocks));
  if (scene.technique == "glints") in.glints = std::make_shared<GlintInputs>(glints());
  if (scene.technique != "mirror" && !isGlintsTechnique(scene.technique))
    in.maps = std::make_shared<emu::Texture>(maps(loadMaterialMaps(scene)));
  return in;
}
}  // namespace

ShadeInputs shadeInputsEmu(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev) {
  return shadeInputsWith(
      scene, env, [&] { return paraboloidTextureEmu(env, dev, scene.fisFaceSize); }, [&] { return shIrradianceEmu(env, dev); },
      [](const MaterialMapImages& m) { return materialMapsEmu(m); }, [&] { return glintInputsEmu(scene, env, dev); });
}

ShadeInputs shadeInputsVulkan(vk::Context& ctx, const Scene& scene, const emu::Texture& env) {
  return shadeInputsWith(
      scene, env, [&] { return paraboloidTextureVulkan(ctx, env, scene.fisFaceSize); }, [&] { return shIrradianceVulkan(ctx, env); },
      [&](const MaterialMapImages& m) { return materialMapsVulkan(ctx, m); }, [&] { return glintInputsVulkan(ctx, scene, env); });
}

uint64_t shadeInputsKey(const Scene& scene, const emu::Texture& env) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bit
  auto mix = [&](const void* data, size_t n) {
    const auto* b = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  const uint32_t dims[6] = {env.width(), env.height(), uint32_t(env.format()), scene.fisFaceSize, scene.fisSamples, scene.envBlocks};
  mix(dims, sizeof dims);
  const float vis[7] = {float(scene.visMaps), float(scene.visSize), scene.visFitCosine ? 1.0f : 0.0f, scene.visBias,
                        scene.visSlopeBias, float(scene.visFilterRadius), scene.visFilterEdge ? 1.0f : 0.0f};
  mix(vis, sizeof vis);
  mix(env.levels()[0].data(), env.levels()[0].size());
  mix(scene.technique.data(), scene.technique.size());
  for (const Material& m : scene.materials) {
    for (const std::string* f : {&m.diffuseMap, &m.specularMap, &m.roughnessMap}) mix(f->data(), f->size() + 1);
    if (!m.glints) continue;
    mix(m.glintMap.data(), m.glintMap.size() + 1);
    const float g[12] = {float(m.glintMapSize), float(m.glintMapSeed), m.glintSpread, m.glintScale, m.glintSigma, m.glintEta[0],
                         m.glintEta[1], m.glintEta[2], m.glintK[0], m.glintK[1], m.glintK[2], 0.0f};
    mix(g, sizeof g);
  }
  const float gs[8] = {float(scene.glintOrder),     float(scene.glintRings),       float(scene.glintSectors),
                       scene.glintThetaMax,           float(scene.glintViewRings),   float(scene.glintViewSectors),
                       float(scene.glintLobeRings), float(scene.glintLobeSectors)};
  mix(gs, sizeof gs);
  return h;
}

template <class Build>
const ShadeInputs& ShadeInputsCache::get(const Scene& scene, const emu::Texture& env, Build build) {
  const uint64_t key = shadeInputsKey(scene, env);
  rebuilt_ = !have_ || key != key_;
  if (rebuilt_) {
    in_ = build();
    key_ = key;
    have_ = true;
    ++builds_;
  }
  in_.environment = &env;  // the same texels; the caller's texture object may be a new one
  return in_;
}

const ShadeInputs& ShadeInputsCache::emu(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev) {
  return get(scene, env, [&] { return shadeInputsEmu(scene, env, dev); });
}

const ShadeInputs& ShadeInputsCache::vulkan(vk::Context& ctx, const Scene& scene, const emu::Texture& env) {
  return get(scene, env, [&] { return shadeInputsVulkan(ctx, scene, env); });
}

}  // namespace shadetwin
