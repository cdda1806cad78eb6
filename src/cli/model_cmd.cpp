#include "cli/model_cmd.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <memory>
#include <sstream>
#include <vector>

#include "emu/device_profile.h"
#include "inputs/environment.h"
#include "inputs/shade_inputs.h"
#include "model/model.h"
#include "passes/passes_vk.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace shadetwin {

int modelCommand(const ModelOptions& opts, std::ostream& log) {
  Scene scene = loadScene(opts.scene);
  if (opts.width) scene.width = opts.width;
  if (opts.height) scene.height = opts.height;
  if (!opts.technique.empty()) scene.technique = opts.technique;
  if (opts.samples) scene.fisSamples = opts.samples;
  const std::string descPath = opts.devicesDir + "/" + opts.device + ".json";
  const model::DeviceDesc desc = model::loadDeviceDesc(descPath);
  const bool software = opts.device == "lavapipe" || opts.device == "swiftshader";
  // The counted pass runs under the device's profile (software) or lavapipe's (a GPU's profile is unverified).
  std::unique_ptr<vk::Context> ctx;
  if (software) ctx = std::make_unique<vk::Context>(vk::ContextOptions{opts.device == "lavapipe" ? "" : opts.device, false});
  const emu::DeviceProfile& dev = ctx ? emu::profileForDevice(ctx->deviceName()) : emu::lavapipeProfile();
  log << "model " << opts.scene << ": " << scene.width << "x" << scene.height << ", technique " << scene.technique
      << "; device " << desc.device << " (" << descPath << ", " << (desc.verified ? "measured" : "public figures, unverified")
      << ")\n";
  std::ostringstream quiet;
  const EnvironmentMap env = loadEnvironment(scene.environment, quiet);
  const GBuffer g = gbufferEmu(scene, dev);
  const ShadeInputs in = shadeInputsEmu(scene, *env.texture, dev);
  std::vector<float> counted;
  const model::PassCounts c = model::countShadePass(scene, g, in, dev, nullptr, &counted);
  const std::vector<float> emuImage = shadeEmu(scene, g, in, dev);
  size_t same = 0;
  for (size_t i = 0; i < emuImage.size() && i < counted.size(); ++i) same += std::memcmp(&emuImage[i], &counted[i], 4) == 0;
  log << "counted pass: " << same << "/" << emuImage.size() << " bit-identical to the emulator's\n";
  const auto ops = model::scalarOps(c);
  const double px = double(c.invocations);
  log << std::fixed << std::setprecision(1) << "  per pixel:";
  for (int k = 0; k < model::kOpClasses; ++k) log << " " << model::kOpClassNames[k] << " " << ops[size_t(k)] / px;
  log << "; lookups nearest " << double(c.ticks[opcount::kTexNearest]) / px << " bilinear "
      << double(c.ticks[opcount::kTexBilinear]) / px << " trilinear " << double(c.ticks[opcount::kTexTrilinear]) / px << "\n";
  const model::Prediction p = model::predict(c, desc);
  log << std::setprecision(2) << "  shade  predicted " << p.seconds * 1e3 << " ms (alu " << p.aluSeconds * 1e3 << ", texture "
      << p.textureSeconds * 1e3 << ", memory " << p.memorySeconds * 1e3 << ", launch " << p.launchSeconds * 1e3 << "; bound "
      << p.bound << ")";
  if (ctx) {
    ShadePassVk pass(*ctx, scene, in);
    std::vector<double> t;
    for (uint32_t r = 0; r <= opts.repeat; ++r) {  // run 0 warms up
      pass.run(g);
      if (r) t.push_back(pass.lastMs);
    }
    std::sort(t.begin(), t.end());
    const double measured = t[t.size() / 2];
    log << "  measured " << measured << " ms  error " << std::showpos << 100.0 * (p.seconds * 1e3 - measured) / measured
        << std::noshowpos << "%";
  }
  log << "\n";
  return same == emuImage.size() ? 0 : 1;
}

}  // namespace shadetwin
