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
#include <tuple>
#include <utility>

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
#include "util/output_file.h"
#include "util/timer.h"
#include "reference/ref_environment.h"
#include "vk/context.h"

namespace shadetwin {

int glintsSweep(const SweepOptions& opts, std::ostream& log) {
  Scene scene = loadScene(opts.scene, opts);
  scene.technique = "glints";
  if (!std::all_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.glints; }))
    throw std::invalid_argument("sweep --technique glints: every material of " + opts.scene + " needs a glints block");
  const std::vector<uint32_t> ladder = parseCounts(opts.samples, "--samples", "a G x D sample-pair count", 1, 1 << 20);
  // Up to the shading kernel's capacity (64); a Vulkan device whose loop limit a degree could exceed
  // refuses it (ShadePassVk), and the row says so.
  const std::vector<uint32_t> orders = parseCounts(opts.glintOrders, "--glint-orders", "a degree", 0, 64);
  std::filesystem::create_directories(opts.out);
  std::ostringstream quiet;
  EnvironmentMap env = loadEnvironment(scene, quiet);
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
  OutputFile csvFile(csvPath);
  std::ostream& csv = csvFile.stream();
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
  ShadeInputs inputsAtScene;  // the scene degree's tables, reused by the temporal study
  // One setting on the emulator: its inputs (timed), a warm-up and the timed shading pass.
  struct EmuRun {
    ShadeInputs in;
    std::vector<float> img;
    double msIn = 0, ms = 0;
  };
  auto emuRun = [&](const Scene& sc) {
    EmuRun r;
    r.msIn = timeMs([&] { r.in = shadeInputsEmu(sc, *env.texture, *dev); });
    shadeEmu(sc, g, r.in, *dev, r.img);  // warm-up
    r.ms = timeMs([&] { shadeEmu(sc, g, r.in, *dev, r.img); });
    return r;
  };
  // The same setting on the Vulkan device (when there is one): inputs and pass timed, the bits against
  // the emulator's image, or why the device refused it.
  struct VkRun {
    double msIn = NAN, ms = NAN;
    size_t same = 0;
    std::string skipped;
  };
  auto vulkanRun = [&](const Scene& sc, const std::vector<float>& img) {
    VkRun r;
    if (!ctx) return r;
    try {
      ShadeInputs iv;
      r.msIn = timeMs([&] { iv = shadeInputsVulkan(*ctx, sc, *env.texture); });
      ShadePassVk pass(*ctx, sc, iv);
      pass.run(gv);  // warm-up (pipeline)
      const std::vector<float> v = pass.run(gv);
      r.ms = pass.lastMs;
      for (size_t i = 0; i < v.size(); ++i) r.same += std::memcmp(&v[i], &img[i], 4) == 0;
    } catch (const vk::Error& e) {
      r.skipped = e.what();
    }
    return r;
  };
  for (uint32_t order : orders) {
    scene.glintOrder = order;
    const EmuRun e = emuRun(scene);
    const ShadeInputs& in = e.in;
    const std::vector<float>& img = e.img;
    const double ms = e.ms, msIn = e.msIn;
    const VkRun vr = vulkanRun(scene, img);
    const double msVk = vr.ms, msInVk = vr.msIn;
    const size_t same = vr.same;
    const std::string& vkSkipped = vr.skipped;
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
    if (order == sceneOrder) glintMsAtScene = ms, glintInputsAtScene = msIn, glintErrAtScene = m.rmse, inputsAtScene = in;
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
  // The lighting table's view grid at the scene's degree (the paper's Fig. 17): build time, memory, error.
  std::stringstream vl(opts.glintViews);
  while (std::getline(vl, spec, ',')) {
    Scene sv = scene;
    std::tie(sv.glintViewRings, sv.glintViewSectors) = parseGlintGrid(spec, "--glint-views");
    const EmuRun e = emuRun(sv);
    const ShadeInputs& in = e.in;
    const double ms = e.ms;
    const ImageMetrics m = imageMetrics(e.img, ref, covered);
    csv << "glints-views," << spec << "," << std::setprecision(2) << ms << ",," << in.glints->lightingMs << ",," << std::setprecision(6)
        << m.rmse << "," << m.relMse << "," << std::setprecision(3) << m.psnr << ",," << in.glints->lightingBytes << "\n";
    log << "  glints views " << std::setw(8) << spec << " (degree " << sceneOrder << ")  emu " << std::setprecision(1) << ms
        << " ms  table " << in.glints->lightingMs << " ms, " << std::setprecision(2) << double(in.glints->lightingBytes) / (1 << 20)
        << " MiB  RMSE " << std::setprecision(5) << m.rmse << "  PSNR " << std::setprecision(2) << m.psnr << " dB\n";
  }
  // The rotated-lobe table instead of the recurrences (Fig. 16): its build, memory, the shading time and error,
  // and on the Vulkan device the bits and the time.
  std::stringstream ll(opts.glintLobes);
  while (std::getline(ll, spec, ',')) {
    Scene sl = scene;
    std::tie(sl.glintLobeRings, sl.glintLobeSectors) = parseGlintGrid(spec, "--glint-lobes");
    const EmuRun e = emuRun(sl);
    const ShadeInputs& in = e.in;
    const std::vector<float>& img = e.img;
    const double ms = e.ms;
    const VkRun vr = vulkanRun(sl, img);
    const double msVk = vr.ms;
    const size_t same = vr.same;
    const std::string& vkSkipped = vr.skipped;
    const ImageMetrics m = imageMetrics(img, ref, covered);
    csv << "glints-lobes," << spec << "," << std::setprecision(2) << ms << "," << msVk << "," << in.glints->lobeMs << ",," << std::setprecision(6)
        << m.rmse << "," << m.relMse << "," << std::setprecision(3) << m.psnr << "," << same << "," << in.glints->lobeBytes << "\n";
    log << "  glints lobe table " << std::setw(8) << spec << " (degree " << in.glints->order << ")  emu " << std::setprecision(1) << ms << " ms";
    if (ctx && vkSkipped.empty()) log << ", vulkan " << msVk << " ms";
    log << "  table " << in.glints->lobeMs << " ms, " << std::setprecision(2) << double(in.glints->lobeBytes) / (1 << 20) << " MiB  RMSE "
        << std::setprecision(5) << m.rmse << "  PSNR " << std::setprecision(2) << m.psnr << " dB";
    if (ctx && vkSkipped.empty()) log << "  " << same << "/" << img.size() << " bit-identical";
    log << "\n";
    if (!vkSkipped.empty()) log << "    vulkan not run: " << vkSkipped << "\n";
  }
  // Temporal stability: the camera orbits the target about +y; per frame its G-buffer, the reference,
  // glints (tables built once: they do not depend on the camera) and G x D at glints' shading time with
  // a fixed seed and with a new seed per frame. Shimmer = RMS over the pixels covered in both frames of
  // (I_f - I_f-1) - (R_f - R_f-1): frame-to-frame change the reference does not have.
  if (opts.glintFrames > 1 && (gxdMs.empty() || std::isnan(glintMsAtScene)))
    log << "  temporal: not run (it needs the scene's degree " << sceneOrder << " in --glint-orders and a --samples ladder)\n";
  if (opts.glintFrames > 1 && !gxdMs.empty() && !std::isnan(glintMsAtScene)) {
    const uint32_t pairs = std::max<uint32_t>(1, uint32_t(std::lround(glintMsAtScene / (gxdMs.back() / ladder.back()))));
    const ShadeInputs& in = inputsAtScene;  // built by the degree loop (the tables do not depend on the camera)
    const Vec3 eye0 = scene.camera.eye, tgt = scene.camera.target;
    const char* names[4] = {"reference", "glints", "glints-gxd (fixed seed)", "glints-gxd (new seed per frame)"};
    std::vector<float> prev[4], cur[4];
    std::vector<uint8_t> prevCov;
    double shimmer2[4] = {0, 0, 0, 0}, change[4] = {0, 0, 0, 0}, frameErr[4] = {0, 0, 0, 0};
    size_t count = 0;
    for (uint32_t f = 0; f < opts.glintFrames; ++f) {
      Scene sf = scene;
      const double a = opts.glintOrbit * f * 3.14159265358979323846 / 180.0, dx = eye0[0] - tgt[0], dz = eye0[2] - tgt[2];
      sf.camera.eye = Vec3{float(tgt[0] + dx * std::cos(a) + dz * std::sin(a)), eye0[1], float(tgt[2] - dx * std::sin(a) + dz * std::cos(a))};
      const GBuffer gf = gbufferEmu(sf, *dev);
      std::vector<uint8_t> cov(gf.texels.size() / kGbufFloats);
      for (size_t p = 0; p < cov.size(); ++p) cov[p] = gf.texels[p * kGbufFloats + 3] != 0.0f;
      const reference::Environment re(EnvImage{env.width, env.height, env.levels[0].data()}, sf.environmentIntensity);
      auto gxd = [&](uint32_t samples, uint64_t seed) {
        GlintGxdOptions o;
        o.samples = samples, o.seed = seed, o.only = &cov;
        return glintGxdImage(sf, gf.texels.data(), gf.width, gf.height, re, o);
      };
      cur[0] = gxd(opts.referenceSpp, 1000003);
      shadeEmu(sf, gf, in, *dev, cur[1]);
      cur[2] = gxd(pairs, 1);
      cur[3] = gxd(pairs, 1 + f);
      for (int k = 1; k < 4; ++k) frameErr[k] += imageMetrics(cur[k], cur[0], cov).rmse / opts.glintFrames;
      if (f > 0)
        for (size_t p = 0; p < cov.size(); ++p) {
          if (!cov[p] || !prevCov[p]) continue;
          for (int c = 0; c < 3; ++c) {
            const size_t i = 4 * p + size_t(c);
            const double dr = double(cur[0][i]) - prev[0][i];
            for (int k = 0; k < 4; ++k) {
              const double d = double(cur[k][i]) - prev[k][i];
              shimmer2[k] += (d - dr) * (d - dr), change[k] += std::fabs(d);
            }
          }
          count += 3;
        }
      for (int k = 0; k < 4; ++k) std::swap(prev[k], cur[k]);
      prevCov = cov;
    }
    log << "  temporal: " << opts.glintFrames << " frames, camera orbiting " << std::setprecision(2) << opts.glintOrbit
        << " deg per frame; reference " << opts.referenceSpp << " pairs; G x D at glints' time: " << pairs << " pairs\n";
    for (int k = 0; k < 4; ++k) {
      const double shimmer = std::sqrt(shimmer2[k] / std::max<size_t>(1, count)), meanChange = change[k] / std::max<size_t>(1, count);
      csv << "temporal," << names[k] << ",,,,," << std::setprecision(6) << (k ? frameErr[k] : 0.0) << ",,,," << shimmer << ";"
          << meanChange << "\n";
      log << "  temporal " << std::setw(32) << std::left << names[k] << std::right << "  mean |frame change| " << std::setprecision(5)
          << meanChange << "  shimmer (RMS change - reference's) " << shimmer;
      if (k) log << "  mean frame RMSE " << frameErr[k];
      log << "\n";
    }
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
  csvFile.commit();
  log << "wrote " << csvPath << ", " << p << "\n";
  return 0;
}

}  // namespace shadetwin
