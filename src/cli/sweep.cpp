#include "cli/sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "emu/device_profile.h"
#include "util/compare.h"
#include "util/image_io.h"
#include "passes/visibility.h"
#include "reference/reference.h"
#include "inputs/env_sampling.h"
#include "inputs/env_sampling_speed.h"
#include "passes/shade.h"
#include "passes/passes_vk.h"
#include "inputs/environment.h"
#include "scene/scene.h"
#include "util/plot.h"
#include "util/output_file.h"
#include "util/timer.h"
#include "vk/context.h"

namespace shadetwin {
namespace {

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> r;
  std::stringstream ss(s);
  for (std::string p; std::getline(ss, p, ',');)
    if (!p.empty()) r.push_back(p);
  return r;
}

}  // namespace

std::vector<uint32_t> parseCounts(const std::string& list, const char* flag, const char* noun, uint32_t lo, uint32_t hi) {
  std::vector<uint32_t> v;
  for (const std::string& s : splitList(list)) {
    char* end = nullptr;
    const unsigned long x = std::strtoul(s.c_str(), &end, 10);
    if (*end || x < lo || x > hi)
      throw std::invalid_argument(std::string(flag) + ": '" + s + "' is not " + noun + " in [" + std::to_string(lo) + ", " +
                                  std::to_string(hi) + "]");
    v.push_back(uint32_t(x));
  }
  return v;
}

SweepBuilds sweepBuilds(const SweepOptions& opts, const Scene& scene, std::ostream& log) {
  SweepBuilds b;
  b.dev = &emu::lavapipeProfile();
  if (opts.vulkan) {
    vk::ContextOptions co;
    co.device = opts.device;
    b.ctx = std::make_unique<vk::Context>(co);
    b.dev = &emu::profileForDevice(b.ctx->deviceName());
    b.gv = gbufferVulkan(*b.ctx, scene);
    log << "  Vulkan device " << b.ctx->deviceName() << " (profile " << b.dev->name << ")\n";
  }
  b.g = gbufferEmu(scene, *b.dev);
  b.covered.resize(size_t(b.g.width) * b.g.height);
  for (size_t p = 0; p < b.covered.size(); ++p) b.covered[p] = b.g.texels[p * kGbufFloats + 3] != 0.0f;
  log << "  metrics over the " << std::count(b.covered.begin(), b.covered.end(), 1) << " covered pixels\n";
  return b;
}

namespace {

// The sampler study of the MIS techniques (issue 5, item 5): env_sampling.csv.
void envSamplerStudy(const SweepOptions& opts, const Scene& scene, const emu::DeviceProfile& dev, vk::Context* ctx, std::ostream& log) {
  const std::string path = (std::filesystem::path(opts.out) / "env_sampling.csv").string();
  OutputFile csvFile(path);
  std::ostream& csv = csvFile.stream();
  csv << "map,width,height,method,blocks,alpha,l1_misfit,build_ms,sampling_bytes,pdf_bytes,packed_kd_bytes,inversion_bytes,"
         "compression_packed,compression_stored,samples_per_s_scalar,samples_per_s_simd,samples_per_s_vulkan,"
         "ratio_vs_inversion_simd,ratio_vs_inversion_vulkan,checksums_equal\n";
  const std::filesystem::path dir = std::filesystem::path(scene.environment).parent_path();
  const char* names[3] = {"kd-tree", "alias", "inversion"};
  log << "  sampler study (" << scene.envBlocks << " blocks; samples/s = one direction + the pdf lookup of it):\n";
  for (const std::string& name : splitList(opts.maps)) {
    const std::string file = (dir / (name + ".exr")).string();
    if (!std::filesystem::exists(file)) throw std::invalid_argument("--maps: " + file + " does not exist (run scripts/setup.sh)");
    std::ostringstream quiet;
    const EnvironmentMap env = loadEnvironment(file, quiet);
    for (uint32_t scale : {1u, 2u}) {
      const emu::Texture tex = emu::floatTexture(emu::Format::RGBA32F, env.width * scale, env.height * scale,
                                                 repeatTexels(env.levels[0].data(), env.width, env.height, scale).data());
      SamplerSpeed speed[3];
      EnvSamplingTables T[3];
      for (uint32_t m = 0; m < 3; ++m) {
        T[m] = envSamplingTables(tex, m, scene.envBlocks);
        if (scale == 1) speed[m] = envSamplerSpeed(T[m], dev, ctx, 32768, 32);
      }
      for (uint32_t m = 0; m < 3; ++m) {
        const EnvSamplingTables& t = T[m];
        const size_t inv = inversionTableBytes(tex.width(), tex.height()), packed = packedKdTreeBytes(t.uniforms.count);
        csv << name << "," << tex.width() << "," << tex.height() << "," << names[m] << "," << t.uniforms.count << "," << std::setprecision(6)
            << (m == 0 ? t.fit.alpha : NAN) << "," << (m == 0 ? t.fit.l1 : NAN) << "," << std::setprecision(3) << t.buildMs << ","
            << t.samplingBytes << "," << t.pdfBytes << "," << (m < 2 ? packed : 0) << "," << inv << ","
            << (m < 2 ? double(inv) / packed : 1.0) << "," << double(inv) / double(t.samplingBytes + t.pdfBytes) << ",";
        if (scale == 1)
          csv << std::setprecision(4) << speed[m].scalar << "," << speed[m].simd << "," << speed[m].vulkan << ","
              << speed[m].simd / speed[2].simd << "," << speed[m].vulkan / speed[2].vulkan << ","
              << (speed[m].checksumScalar == speed[m].checksumSimd && (!ctx || speed[m].checksumSimd == speed[m].checksumVulkan)) << "\n";
        else
          csv << ",,,,,\n";
        log << "    " << std::left << std::setw(10) << name << std::right << std::setw(5) << tex.width() << "x" << std::setw(4)
            << std::left << tex.height() << std::right << " " << std::setw(9) << names[m] << std::setprecision(1) << std::setw(7)
            << t.buildMs << " ms  " << std::setw(9) << (t.samplingBytes + t.pdfBytes) / 1024.0 << " KiB";
        if (m == 0) log << "  alpha " << std::setprecision(4) << t.fit.alpha << "  L1 " << t.fit.l1;
        if (m < 2) log << "  1:" << std::setprecision(0) << double(inv) / packed << " packed";
        if (scale == 1)
          log << "  " << std::setprecision(2) << speed[m].scalar / 1e6 << " / " << speed[m].simd / 1e6 << " / " << speed[m].vulkan / 1e6
              << " M/s (scalar / simd / vulkan)";
        log << "\n";
      }
    }
  }
  csvFile.commit();
  log << "  wrote " << path << "\n";
}

}  // namespace

int sweepCommand(const SweepOptions& opts, std::ostream& log) {
  if (opts.techniques == "glints") return glintsSweep(opts, log);
  Scene scene = loadScene(opts.scene, opts);
  const std::vector<std::string> techniques = splitList(opts.techniques);
  const std::vector<uint32_t> samples = parseCounts(opts.samples, "--samples", "a count", 1, 4096);
  for (const std::string& t : techniques)
    if (!isTechnique(t) || t == "mirror" || t == "glints")
      throw std::invalid_argument("--technique: '" + t +
                                  "' is not a sampling technique (fis, unfiltered, stochastic, env, kdtree-mis, alias-mis, inversion-mis; glints alone runs the glints study)");
  if (techniques.empty() || samples.empty()) throw std::invalid_argument("sweep: no techniques or no sample counts");
  const std::vector<uint32_t> visMaps = parseCounts(opts.visMapCounts, "--vis-maps", "a map count", 0, 1024);
  std::filesystem::create_directories(opts.out);
  std::ostringstream quiet;
  EnvironmentMap env = loadEnvironment(scene, quiet);
  log << "sweep " << opts.scene << ": " << scene.width << "x" << scene.height << ", " << scene.environment << "\n";

  // Reference: given, or rendered here (MIS, no visibility: the techniques have none).
  std::vector<float> ref;
  if (!opts.reference.empty()) {
    ImageRGBA r = loadImageRGBA(opts.reference);
    if (r.width != scene.width || r.height != scene.height)
      throw std::invalid_argument("--reference " + opts.reference + ": " + std::to_string(r.width) + "x" +
                                  std::to_string(r.height) + ", the sweep renders " + std::to_string(scene.width) + "x" +
                                  std::to_string(scene.height));
    ref = std::move(r.texels);
    log << "  reference " << opts.reference << "\n";
  } else {
    ReferenceOptions ro;
    ro.spp = opts.referenceSpp;
    ro.visibility = !visMaps.empty();
    const auto t0 = std::chrono::steady_clock::now();
    ref = renderReference(scene, EnvImage{env.width, env.height, env.levels[0].data()}, ro);
    const std::string path = (std::filesystem::path(opts.out) / "reference.exr").string();
    writeExr(path, scene.width, scene.height, ref);
    log << "  reference: " << ro.spp << " spp x 2 (MIS" << (ro.visibility ? ", occlusion rays" : "") << "), " << std::fixed << std::setprecision(1) << msSince(t0) / 1000
        << " s, wrote " << path << "\n";
  }

  SweepBuilds builds = sweepBuilds(opts, scene, log);
  const emu::DeviceProfile* dev = builds.dev;
  std::unique_ptr<vk::Context>& ctx = builds.ctx;
  const GBuffer &gv = builds.gv, &g = builds.g;
  const std::vector<uint8_t>& covered = builds.covered;

  const std::string csvPath = (std::filesystem::path(opts.out) / "sweep.csv").string();
  OutputFile csvFile(csvPath);
  std::ostream& csv = csvFile.stream();
  csv << "technique,samples,ms_emu,ms_vulkan,rmse,relmse,psnr,bit_identical,values\n";
  std::vector<PlotSeries> bySamples, byTime;
  log << std::fixed;
  for (const std::string& t : techniques) {
    scene.technique = t;
    PlotSeries ps{t, {}, {}}, pt{t, {}, {}};
    std::unique_ptr<ShadeInputs> inE;
    for (uint32_t n : samples) {
      (usesMisPass(t) ? scene.misSamples : scene.fisSamples) = n;
      if (!inE || t == "env") inE = std::make_unique<ShadeInputs>(shadeInputsEmu(scene, *env.texture, *dev));
      std::vector<float> img;
      shadeEmu(scene, g, *inE, *dev, img);  // warm-up
      auto t0 = std::chrono::steady_clock::now();
      shadeEmu(scene, g, *inE, *dev, img);
      const double msEmu = msSince(t0);
      double msVk = NAN;
      size_t same = 0;
      if (ctx) {
        ShadePassVk pass(*ctx, scene, *inE);
        const std::vector<float> v = pass.run(gv);
        msVk = pass.lastMs;
        for (size_t i = 0; i < v.size(); ++i) same += std::memcmp(&v[i], &img[i], 4) == 0;
      }
      const ImageMetrics m = imageMetrics(img, ref, covered);
      csv << std::fixed << t << "," << n << "," << std::setprecision(2) << msEmu << "," << msVk << "," << std::setprecision(6) << m.rmse
          << "," << m.relMse << "," << std::setprecision(3) << m.psnr << "," << same << "," << img.size() << "\n";
      log << "  " << std::setw(10) << std::left << t << std::right << std::setw(5) << n << " samples  emu " << std::setprecision(1)
          << std::setw(8) << msEmu << " ms  vulkan " << std::setw(8) << msVk << " ms  RMSE " << std::setprecision(5)
          << m.rmse << "  relMSE " << m.relMse << "  PSNR " << std::setprecision(2) << m.psnr << " dB";
      if (ctx) log << "  " << same << "/" << img.size() << " bit-identical";
      log << "\n";
      ps.x.push_back(n), ps.y.push_back(m.rmse), pt.x.push_back(msEmu), pt.y.push_back(m.rmse);
    }
    bySamples.push_back(ps), byTime.push_back(pt);
  }
  if (std::any_of(techniques.begin(), techniques.end(), [](const std::string& t) { return usesMisPass(t); }))
    envSamplerStudy(opts, scene, *dev, ctx.get(), log);
  if (!visMaps.empty()) {
    // The SH visibility study: fis at the scene's sample count with K maps (the scene's other
    // visibility settings), each build its own maps, fit and filter of its own G-buffer.
    const std::string vPath = (std::filesystem::path(opts.out) / "visibility.csv").string();
    OutputFile vcsvFile(vPath);
    std::ostream& vcsv = vcsvFile.stream();
    vcsv << "maps,samples,rank,ms_shadow_emu,ms_fit_emu,ms_filter_emu,ms_shade_emu,ms_shadow_vulkan,ms_fit_vulkan,ms_filter_vulkan,"
            "ms_shade_vulkan,rmse,relmse,psnr,rmse_unfiltered,psnr_unfiltered,bit_identical,values\n";
    scene.technique = "fis";
    const uint32_t visMapsScene = scene.visMaps;
    // The best an order-4 SH can do (the paper's Figure 5 (b)): an Embree fit per pixel from visRays
    // stratified rays, shaded by the same pass; its error is the SH-order error.
    if (opts.visRays) {
      scene.visMaps = std::max(1u, visMapsScene);
      const ShadeInputs in = shadeInputsEmu(scene, *env.texture, *dev);
      VisibilityImage ideal;
      ideal.width = g.width, ideal.height = g.height;
      const double ms = timeMs(
          [&] { ideal.coeffs = referenceVisibilitySh(scene, g.texels, g.width, g.height, opts.visRays, scene.visFitCosine); });
      std::vector<float> img;
      shadeEmu(scene, g, in, *dev, img, &ideal);
      const ImageMetrics m = imageMetrics(img, ref, covered);
      vcsv << std::fixed << "ideal," << scene.fisSamples << ",16,,,,,,,,," << std::setprecision(6) << m.rmse << "," << m.relMse << ","
           << std::setprecision(3) << m.psnr << ",,,,\n";
      log << "  fis + visibility, Embree order-4 SH fit from " << opts.visRays << " rays per pixel (" << std::setprecision(1)
          << ms / 1000 << " s): RMSE " << std::setprecision(5) << m.rmse << "  PSNR " << std::setprecision(2) << m.psnr
          << " dB (the SH-order error)\n";
    }
    for (uint32_t K : visMaps) {
      scene.visMaps = K;
      const ShadeInputs in = shadeInputsEmu(scene, *env.texture, *dev);
      VisibilityStats te, tv;
      std::unique_ptr<VisibilityImage> vis;
      ImageMetrics mu{};
      if (in.visibility) {
        // Unfiltered first (the angular-sampling error), then the filter on it (the filter's part).
        VisibilitySetup unfiltered = *in.visibility;
        unfiltered.settings.filterRadius = 0;
        VisibilityImage raw = visibilityEmu(scene, g, unfiltered, *dev, &te);
        std::vector<float> imgU;
        shadeEmu(scene, g, in, *dev, imgU, &raw);
        mu = imageMetrics(imgU, ref, covered);
        te.filterMs = timeMs([&] { vis = std::make_unique<VisibilityImage>(visibilityFilterEmu(g, raw, *in.visibility, *dev)); });
      }
      std::vector<float> img;
      const double msShade = timeMs([&] { shadeEmu(scene, g, in, *dev, img, vis.get()); });
      double msVk = NAN;
      size_t same = 0;
      if (ctx) {
        std::unique_ptr<VisibilityImage> visV;
        if (in.visibility)
          visV = std::make_unique<VisibilityImage>(
              VisibilityPassVk(*ctx, scene, in.visibility->settings.size).run(gv, *in.visibility, &tv));
        ShadePassVk pass(*ctx, scene, in);
        const std::vector<float> v = pass.run(gv, visV.get());
        msVk = pass.lastMs;
        for (size_t i = 0; i < v.size(); ++i) same += std::memcmp(&v[i], &img[i], 4) == 0;
      }
      const ImageMetrics m = imageMetrics(img, ref, covered);
      const uint32_t rank = in.visibility ? in.visibility->rank : 0;
      vcsv << std::fixed << K << "," << scene.fisSamples << "," << rank << "," << std::setprecision(2) << te.shadowMs << "," << te.fitMs
           << "," << te.filterMs << "," << msShade << "," << tv.shadowMs << "," << tv.fitMs << "," << tv.filterMs << "," << msVk << ","
           << std::setprecision(6) << m.rmse << "," << m.relMse << "," << std::setprecision(3) << m.psnr << ","
           << std::setprecision(6) << (vis ? mu.rmse : m.rmse) << "," << std::setprecision(3) << (vis ? mu.psnr : m.psnr) << ","
           << same << "," << img.size() << "\n";
      log << "  fis + visibility " << std::setw(3) << K << " maps (rank " << std::setw(2) << rank << ")  emu shadow "
          << std::setprecision(1) << te.shadowMs << " + fit " << te.fitMs << " + filter " << te.filterMs << " + shade " << msShade
          << " ms  RMSE " << std::setprecision(5) << m.rmse << " (unfiltered " << (vis ? mu.rmse : m.rmse) << ")  PSNR "
          << std::setprecision(2) << m.psnr << " dB";
      if (ctx) log << "  " << same << "/" << img.size() << " bit-identical";
      log << "\n";
    }
    scene.visMaps = visMapsScene;
    vcsvFile.commit();
    log << "wrote " << vPath << "\n";
  }
  const std::string stem = std::filesystem::path(opts.scene).stem().string();
  const std::string p1 = (std::filesystem::path(opts.out) / "rmse_vs_samples.png").string();
  const std::string p2 = (std::filesystem::path(opts.out) / "rmse_vs_time.png").string();
  std::string w1 = writeLogLogPlot(p1, bySamples, {"RMSE vs samples per pixel, " + stem, "samples N", "RMSE", true});
  std::string w2 = writeLogLogPlot(p2, byTime, {"RMSE vs emulator shading time, " + stem, "ms per frame (emu)", "RMSE", false});
  if (!w1.empty()) log << "  warning: " << w1 << "\n";
  if (!w2.empty()) log << "  warning: " << w2 << "\n";
  csvFile.commit();
  log << "wrote " << csvPath << ", " << p1 << ", " << p2 << "\n";
  return 0;
}

}  // namespace shadetwin
