#include "cli/bench.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "emu/device_profile.h"
#include "passes/passes_vk.h"
#include "inputs/environment.h"
#include "scene/scene.h"
#include "util/timer.h"
#include "vk/context.h"

namespace shadetwin {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

int benchCommand(const BenchOptions& opts, std::ostream& log) {
  Scene scene = loadScene(opts.scene, opts);
  if (scene.technique == "glints-gxd")
    throw std::invalid_argument("bench: glints-gxd shades on the host (no device pass to time); its times are in sweep --technique glints");
  std::vector<std::string> passes;
  std::stringstream ss(opts.passes);
  for (std::string p; std::getline(ss, p, ',');) {
    if (p != "gbuffer" && p != "shadow" && p != "shade") throw std::invalid_argument("--passes: unknown pass '" + p + "' (expected gbuffer, shadow, shade)");
    passes.push_back(p);
  }
  vk::ContextOptions co;
  co.device = opts.device;
  vk::Context ctx(co);
  const emu::DeviceProfile& dev = emu::profileForDevice(ctx.deviceName());
  log << "bench " << opts.scene << ": " << scene.width << "x" << scene.height << ", " << scene.triangles()
      << " triangles; shadow maps " << opts.directions << " x " << opts.shadowSize << "^2; device " << ctx.deviceName()
      << " (profile " << dev.name << "); technique " << scene.technique;
  if (usesMisPass(scene.technique)) log << " (" << scene.misSamples << " sample pairs)";
  else if (scene.technique != "mirror") log << " (" << scene.fisSamples << " samples)";
  log << "; median of " << opts.repeat << " runs\n";
  const std::vector<Vec3> dirs = sphereDirections(opts.directions);
  std::ostringstream quiet;
  std::unique_ptr<EnvironmentMap> env;
  ShadeInputs inputs;  // the technique's inputs, built once by the emulator, read by both passes
  GbufferPassVk gpass(ctx, scene);
  std::unique_ptr<ShadowPassVk> spass;
  std::unique_ptr<ShadePassVk> shpass;
  GBuffer g = gpass.run();  // warm-up, and the G-buffer the shading pass reads
  GBuffer gEmu;
  ShadowMaps smEmu;
  std::vector<float> shaded;
  double emuSum = 0, vkSum = 0;
  log << std::fixed << std::setprecision(1);
  for (const std::string& p : passes) {
    std::vector<double> te, tv;
    if (p == "shadow") spass = std::make_unique<ShadowPassVk>(ctx, scene, opts.shadowSize);
    if (p == "shade") {
      if (!env) env = std::make_unique<EnvironmentMap>(loadEnvironment(scene, quiet));
      inputs = shadeInputsEmu(scene, *env->texture, dev);
      shpass = std::make_unique<ShadePassVk>(ctx, scene, inputs);
    }
    for (uint32_t r = 0; r <= opts.repeat; ++r) {  // run 0 warms up, not counted
      double e = 0, v = 0;
      if (p == "gbuffer") {
        e = timeMs([&] { gbufferEmu(scene, dev, gEmu); });
        gpass.run();
        v = gpass.lastMs;
      } else if (p == "shadow") {
        e = timeMs([&] { shadowEmu(scene, dirs, opts.shadowSize, dev, smEmu); });
        spass->run(dirs);
        v = spass->lastMs;
      } else {
        e = timeMs([&] { shadeEmu(scene, g, inputs, dev, shaded); });
        shpass->run(g);
        v = shpass->lastMs;
      }
      if (r) te.push_back(e), tv.push_back(v);
    }
    const double me = median(te), mv = median(tv);
    emuSum += me, vkSum += mv;
    log << "  " << std::setw(8) << std::left << p << std::right << "  emu " << std::setw(8) << me << " ms   vulkan "
        << std::setw(8) << mv << " ms   ratio " << std::setprecision(3) << me / mv << std::setprecision(1) << "\n";
  }
  log << "  total     emu " << std::setw(8) << emuSum << " ms   vulkan " << std::setw(8) << vkSum << " ms\n";
  if (shpass) {  // the frame each build renders on its own: its G-buffer, then its shading pass
    const std::vector<float> e = shadeEmu(scene, gbufferEmu(scene, dev), inputs, dev), v = shpass->run(gpass.run());
    size_t same = 0;
    for (size_t i = 0; i < e.size(); ++i) same += std::memcmp(&e[i], &v[i], 4) == 0;
    log << "frame: " << same << "/" << e.size() << " bit-identical\n";
  }
  log << std::setprecision(3) << "ratio emu/vulkan: " << emuSum / vkSum << "\n";
  return 0;
}

}  // namespace shadetwin
