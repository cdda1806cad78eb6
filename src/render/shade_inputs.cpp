#include "render/shade_inputs.h"

#include <chrono>

#include "render/material.h"
#include "render/paraboloid.h"
#include "util/timer.h"

namespace shadetwin {
ShadeInputs shadeInputsEmu(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev) {
  ShadeInputs in;
  in.environment = &env;
  if (usesFisPass(scene.technique)) {
    in.atlasMs = timeMs([&] { in.atlas = std::make_shared<emu::Texture>(paraboloidTextureEmu(env, dev, scene.fisFaceSize)); });
    in.shMs = timeMs([&] { in.sh = shIrradianceEmu(env, dev); });
  }
  if (scene.technique == "env") in.lights = envLights(env, scene.fisSamples);
  if (usesMisPass(scene.technique))
    in.envTables = std::make_shared<EnvSamplingTables>(envSamplingTables(env, envMethodOf(scene.technique), scene.envBlocks));
  if (scene.technique != "mirror") in.maps = std::make_shared<emu::Texture>(materialMapsEmu(loadMaterialMaps(scene)));
  return in;
}

ShadeInputs shadeInputsVulkan(vk::Context& ctx, const Scene& scene, const emu::Texture& env) {
  ShadeInputs in;
  in.environment = &env;
  if (usesFisPass(scene.technique)) {
    in.atlasMs = timeMs([&] { in.atlas = std::make_shared<emu::Texture>(paraboloidTextureVulkan(ctx, env, scene.fisFaceSize)); });
    in.shMs = timeMs([&] { in.sh = shIrradianceVulkan(ctx, env); });
  }
  if (scene.technique == "env") in.lights = envLights(env, scene.fisSamples);
  if (usesMisPass(scene.technique))
    in.envTables = std::make_shared<EnvSamplingTables>(envSamplingTables(env, envMethodOf(scene.technique), scene.envBlocks));
  if (scene.technique != "mirror") in.maps = std::make_shared<emu::Texture>(materialMapsVulkan(ctx, loadMaterialMaps(scene)));
  return in;
}

uint64_t shadeInputsKey(const Scene& scene, const emu::Texture& env) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bit
  auto mix = [&](const void* data, size_t n) {
    const auto* b = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  const uint32_t dims[6] = {env.width(), env.height(), uint32_t(env.format()), scene.fisFaceSize, scene.fisSamples, scene.envBlocks};
  mix(dims, sizeof dims);
  mix(env.levels()[0].data(), env.levels()[0].size());
  mix(scene.technique.data(), scene.technique.size());
  for (const Material& m : scene.materials)
    for (const std::string* f : {&m.diffuseMap, &m.specularMap, &m.roughnessMap}) mix(f->data(), f->size() + 1);
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
