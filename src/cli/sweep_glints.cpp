// `shadetwin sweep --technique glints` (issue 17): glints against its ground truth, the G x D
// baseline (reference/glints_gxd.h), per SH degree, and G x D itself against sample count; the speed
// of glints against the time G x D needs for the same error, measured in one run.
#include <algorithm>
#include <cstdio>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <tbb/parallel_for.h>

#include "cli/sweep.h"
#include "inputs/environment.h"
#include "inputs/glints.h"
#include "lanes/instantiate.h"
#include "passes/gbuffer.h"
#include "passes/passes_vk.h"
#include "passes/shade.h"
#include "reference/glints_gxd.h"
#include "util/compare.h"
#include "util/plot.h"
#include "util/timer.h"
#include "vk/context.h"

namespace shadetwin {

int glintsSweep(const SweepOptions& opts, std::ostream& log) {
  Scene scene = loadScene(opts.scene);
  if (opts.width) scene.width = opts.width;
  if (opts.height) scene.height = opts.height;
  scene.technique = "glints";
  if (!std::all_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.glints; }))
    throw std::invalid_argument("sweep --technique glints: every material of " + opts.scene + " needs a glints block");
  const std::vector<uint32_t> ladder = parseCounts(opts.samples, "--samples", "a G x D sample-pair count", 1, 1 << 20);
  // Up to the shading kernel's capacity (32); a Vulkan device whose loop limit a degree could exceed
  // refuses it (ShadePassVk), and the row says so.
  const std::vector<uint32_t> orders = parseCounts(opts.glintOrders, "--glint-orders", "a degree", 0, 32);
  std::filesystem::create_directories(opts.out);
  std::ostringstream quiet;
  EnvironmentMap env = loadEnvironment(scene.environment, quiet);
  log << "sweep " << opts.scene << " (glints): " << scene.width << "x" << scene.height << ", " << scene.environment << "\n";
  SweepBuilds builds = sweepBuilds(opts, scene, log);
  const emu::DeviceProfile* dev = builds.dev;
  std::unique_ptr<vk::Context>& ctx = builds.ctx;
  const GBuffer &gv = builds.gv, &g = builds.g;
  const std::vector<uint8_t>& covered = builds.covered;

  // G x D (technique glints-gxd) over the covered pixels: each pixel's frame and footprint as the
  // kernel forms them (the footprint by the shared glintFootprint on the same floats).
  const reference::Environment renv(EnvImage{env.width, env.height, env.levels[0].data()}, scene.environmentIntensity);
  auto gxdImage = [&](uint32_t samples, uint64_t seed) {
    GlintGxdOptions o;
    o.samples = samples, o.seed = seed, o.only = &covered;
    return glintGxdImage(scene, g.texels.data(), g.width, g.height, renv, o);
  };
  const std::string csvPath = (std::filesystem::path(opts.out) / "glints.csv").string();
  std::ofstream csv(csvPath);
  if (!csv) throw std::runtime_error("sweep: cannot write " + csvPath);
  csv << "technique,param,ms_emu,ms_vulkan,ms_inputs_emu,ms_inputs_vulkan,rmse,relmse,psnr,bit_identical,values\n";
  log << std::fixed;
  std::vector<float> ref;
  const double msRef = timeMs([&] { ref = gxdImage(opts.referenceSpp, 1000003); });
  writeExr((std::filesystem::path(opts.out) / "reference.exr").string(), g.width, g.height, ref);
  log << "  reference: G x D, " << opts.referenceSpp << " sample pairs per pixel, " << std::setprecision(1) << msRef / 1000 << " s\n";
  PlotSeries gxdSeries{"glints-gxd", {}, {}}, glSeries{"glints (emu)", {}, {}};
  std::vector<double> gxdMs, gxdErr;
  for (uint32_t N : ladder) {
    std::vector<float> img;
    const double ms = timeMs([&] { img = gxdImage(N, 1); });
    const ImageMetrics m = imageMetrics(img, ref, covered);
    csv << "glints-gxd," << N << "," << std::setprecision(2) << ms << ",,,," << std::setprecision(6) << m.rmse << "," << m.relMse << ","
        << std::setprecision(3) << m.psnr << ",,\n";
    log << "  glints-gxd " << std::setw(6) << N << " pairs  " << std::setprecision(1) << std::setw(9) << ms << " ms  RMSE "
        << std::setprecision(5) << m.rmse << "  PSNR " << std::setprecision(2) << m.psnr << " dB\n";
    gxdSeries.x.push_back(ms), gxdSeries.y.push_back(m.rmse), gxdMs.push_back(ms), gxdErr.push_back(m.rmse);
  }
  const uint32_t sceneOrder = scene.glintOrder;
  double glintMsAtScene = NAN, glintInputsAtScene = NAN, glintErrAtScene = NAN;
  for (uint32_t order : orders) {
    scene.glintOrder = order;
    ShadeInputs in;
    const double msIn = timeMs([&] { in = shadeInputsEmu(scene, *env.texture, *dev); });
    std::vector<float> img;
    shadeEmu(scene, g, in, *dev, img);  // warm-up
    const double ms = timeMs([&] { shadeEmu(scene, g, in, *dev, img); });
    double msVk = NAN, msInVk = NAN;
    size_t same = 0;
    std::string vkSkipped;
    if (ctx) {
      try {
        ShadeInputs iv;
        msInVk = timeMs([&] { iv = shadeInputsVulkan(*ctx, scene, *env.texture); });
        ShadePassVk pass(*ctx, scene, iv);
        pass.run(gv);  // warm-up (pipeline)
        const std::vector<float> v = pass.run(gv);
        msVk = pass.lastMs;
        for (size_t i = 0; i < v.size(); ++i) same += std::memcmp(&v[i], &img[i], 4) == 0;
      } catch (const vk::Error& e) {
        vkSkipped = e.what();
      }
    }
    const ImageMetrics m = imageMetrics(img, ref, covered);
    csv << "glints," << order << "," << std::setprecision(2) << ms << "," << msVk << "," << msIn << "," << msInVk << ","
        << std::setprecision(6) << m.rmse << "," << m.relMse << "," << std::setprecision(3) << m.psnr << "," << same << "," << img.size()
        << "\n";
    log << "  glints degree " << std::setw(2) << order << " (shading degree " << in.glints->order << ")  emu " << std::setprecision(1)
        << ms << " ms + inputs " << msIn << " ms";
    if (ctx && vkSkipped.empty()) log << ", vulkan " << msVk << " ms + inputs " << msInVk << " ms";
    log << "  RMSE " << std::setprecision(5) << m.rmse << "  PSNR " << std::setprecision(2) << m.psnr << " dB";
    if (ctx && vkSkipped.empty()) log << "  " << same << "/" << img.size() << " bit-identical";
    log << "\n";
    if (!vkSkipped.empty()) log << "    vulkan not run: " << vkSkipped << "\n";
    glSeries.x.push_back(ms), glSeries.y.push_back(m.rmse);
    if (order == sceneOrder) glintMsAtScene = ms, glintInputsAtScene = msIn, glintErrAtScene = m.rmse;
  }
  // The histogram's binning at the scene's degree (the paper's Figs. 11, 15): error against the same reference.
  scene.glintOrder = sceneOrder;
  std::stringstream bl(opts.glintBins);
  std::string spec;
  while (std::getline(bl, spec, ',')) {
    unsigned rings = 0, sectors = 0;
    float theta = 0;
    if (std::sscanf(spec.c_str(), "%ux%u@%f", &rings, &sectors, &theta) != 3 || rings < 1 || rings > 16 || sectors < 8 ||
        sectors > 64 || sectors % 8 || !(theta > 0 && theta <= 180))
      throw std::invalid_argument("--glint-bins: '" + spec + "' is not RINGSxSECTORS@THETAMAX (rings 1-16, sectors 8-64 by 8, degrees)");
    Scene sb = scene;
    sb.glintRings = rings, sb.glintSectors = sectors, sb.glintThetaMax = theta * 3.14159265f / 180.0f;
    const ShadeInputs in = shadeInputsEmu(sb, *env.texture, *dev);
    std::vector<float> img;
    const double ms = timeMs([&] { shadeEmu(sb, g, in, *dev, img); });
    const ImageMetrics m = imageMetrics(img, ref, covered);
    csv << "glints-bins," << spec << "," << std::setprecision(2) << ms << ",,,," << std::setprecision(6) << m.rmse << "," << m.relMse
        << "," << std::setprecision(3) << m.psnr << ",," << in.glints->satBytes << "\n";
    log << "  glints bins " << std::setw(10) << spec << " (degree " << sceneOrder << ")  emu " << std::setprecision(1) << ms
        << " ms  SATs " << in.glints->satBytes / (1 << 20) << " MiB  RMSE " << std::setprecision(5) << m.rmse << "  PSNR "
        << std::setprecision(2) << m.psnr << " dB\n";
  }
  // Speed at equal error: the G x D time for glints' error at the scene's degree, on the ladder's
  // log-log line (error ~ time^-1/2 beyond its ends).
  if (!std::isnan(glintErrAtScene) && !gxdMs.empty()) {
    double tEq = NAN;
    bool extrapolated = true;
    for (size_t i = 0; i + 1 < gxdMs.size(); ++i)
      if ((gxdErr[i] - glintErrAtScene) * (gxdErr[i + 1] - glintErrAtScene) <= 0 && gxdErr[i] != gxdErr[i + 1]) {
        const double a = (std::log(glintErrAtScene) - std::log(gxdErr[i])) / (std::log(gxdErr[i + 1]) - std::log(gxdErr[i]));
        tEq = std::exp(std::log(gxdMs[i]) + a * (std::log(gxdMs[i + 1]) - std::log(gxdMs[i])));
        extrapolated = false;
        break;
      }
    if (std::isnan(tEq)) {
      const size_t k = glintErrAtScene < gxdErr.back() ? gxdErr.size() - 1 : 0;
      tEq = gxdMs[k] * std::pow(gxdErr[k] / glintErrAtScene, 2.0);
    }
    log << "  at degree " << sceneOrder << ": glints RMSE " << std::setprecision(5) << glintErrAtScene << " in " << std::setprecision(1)
        << glintMsAtScene << " ms (+ " << glintInputsAtScene << " ms of tables); G x D needs " << tEq << " ms for it"
        << (extrapolated ? " (extrapolated at error ~ time^-1/2)" : "") << "\n";
    log << "glints speed-up at equal error: " << std::setprecision(1) << tEq / glintMsAtScene << "x (with the tables' build: "
        << tEq / (glintMsAtScene + glintInputsAtScene) << "x)\n";
  }
  const std::string p = (std::filesystem::path(opts.out) / "rmse_vs_time.png").string();
  const std::string w = writeLogLogPlot(p, {gxdSeries, glSeries}, {"RMSE vs emulator time, glints vs G x D", "ms per frame (emu)", "RMSE", false});
  if (!w.empty()) log << "  warning: " << w << "\n";
  log << "wrote " << csvPath << ", " << p << "\n";
  return 0;
}

}  // namespace shadetwin
