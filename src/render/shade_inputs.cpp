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
  if (scene.technique != "mirror") in.maps = std::make_shared<emu::Texture>(materialMapsVulkan(ctx, loadMaterialMaps(scene)));
  return in;
}

}  // namespace shadetwin
