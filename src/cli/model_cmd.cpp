#include "cli/model_cmd.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "cli/calibrate.h"
#include "emu/device_profile.h"
#include "inputs/environment.h"
#include "inputs/glints.h"
#include "inputs/material.h"
#include "inputs/paraboloid.h"
#include "inputs/sh_irradiance.h"
#include "inputs/shade_inputs.h"
#include "model/model.h"
#include "passes/mips.h"
#include "passes/passes_vk.h"
#include "passes/visibility.h"
#include "scene/scene.h"
#include "util/timer.h"
#include "util/output_file.h"
#include "vk/context.h"

namespace shadetwin {
namespace {

// Every pass of the frame on the Vulkan device, as the Vulkan build runs it (the fastest of `repeat` runs, submit to
// completion, as calibrate times its microkernels: util/timer.h's fastestOf):
// the persistent passes through their lastMs after a warm-up run, the technique inputs (built inside one function
// each) through vk::DispatchLog.
std::map<std::string, double> measurePasses(vk::Context& ctx, const Scene& scene, const emu::Texture& env, const ShadeInputs& in,
                                            const GBuffer& g, const VisibilityImage* vis, uint32_t repeat) {
  std::map<std::string, std::vector<double>> t;
  // The frame's persistent passes: built once, run once to warm up (first-touch pages, caches), then timed.
  {
    GbufferPassVk gp(ctx, scene);
    for (uint32_t r = 0; r <= repeat; ++r) {
      gp.run();
      if (r) t["gbuffer"].push_back(gp.lastMs);
    }
  }
  if (in.visibility) {
    VisibilityPassVk vp(ctx, scene, in.visibility->settings.size);
    for (uint32_t r = 0; r <= repeat; ++r) {
      VisibilityStats vt;
      vk::DispatchLog dl;  // the fit's and the filter's dispatches (their uploads and read-backs are not the pass)
      vp.run(g, *in.visibility, &vt);
      if (!r) continue;
      t["shadow"].push_back(vt.shadowMs);
      if (!dl.ms.empty()) t["visibility-fit"].push_back(dl.ms[0]);
      if (in.visibility->settings.filterRadius && dl.ms.size() > 1) t["visibility-filter"].push_back(dl.ms[1]);
    }
  }
  if (scene.technique != "glints-gxd") {
    ShadePassVk sp(ctx, scene, in);
    for (uint32_t r = 0; r <= repeat; ++r) {
      sp.run(g, vis);
      if (r) t["shade"].push_back(sp.lastMs);
    }
  }
  // The technique inputs, as the Vulkan build makes them once per environment: each function builds its pipeline and
  // buffers and dispatches once, so its dispatches are timed as they run there (vk::DispatchLog), `repeat` calls.
  for (uint32_t r = 0; r < repeat; ++r) {
    double mips = 0;
    bool anyMips = false;
    if (in.atlas) {
      vk::DispatchLog pl;
      const std::vector<float> atlas = paraboloidAtlasVulkan(ctx, env, scene.fisFaceSize);
      t["paraboloid"].push_back(pl.ms.empty() ? 0.0 : pl.ms[0]);
      vk::DispatchLog ml;
      mipChainGpu(ctx, atlas, 2 * scene.fisFaceSize, scene.fisFaceSize, 1);
      mips += ml.totalMs(), anyMips = true;
      vk::DispatchLog sl;
      shIrradianceVulkan(ctx, env);
      if (sl.ms.size() == 2) t["sh-project"].push_back(sl.ms[0]), t["sh-reduce"].push_back(sl.ms[1]);
    }
    if (in.maps) {
      const MaterialMapImages m = loadMaterialMaps(scene);
      if (m.width > 1 || m.height > 1) {
        vk::DispatchLog ml;
        mipChainGpu(ctx, m.texels, m.width, m.height, m.layers);
        mips += ml.totalMs(), anyMips = true;
      }
    }
    if (anyMips) t["mips"].push_back(mips);
    if (in.glints) {
      vk::DispatchLog gl;
      glintLightingVulkan(ctx, env, in.glints->lightingSpec);
      t["glint-lighting"].push_back(gl.totalMs());
    }
  }
  std::map<std::string, double> m;
  for (auto& [k, v] : t) m[k] = fastestOf(v);
  return m;
}

// The frame's passes measured on `ctx`, with the inputs the Vulkan build would have (the emulator's: the same bits).
std::map<std::string, double> measureFrame(vk::Context& ctx, const Scene& scene, const EnvironmentMap& env, const emu::DeviceProfile& dev,
                                           uint32_t repeat) {
  const ShadeInputs in = shadeInputsEmu(scene, *env.texture, dev);
  const GBuffer g = gbufferEmu(scene, dev);
  std::unique_ptr<VisibilityImage> vis;
  if (in.visibility) vis = std::make_unique<VisibilityImage>(visibilityEmu(scene, g, *in.visibility, dev));
  return measurePasses(ctx, scene, *env.texture, in, g, vis.get(), repeat);
}

struct Row {
  std::string scene, technique, device, pass, bound;
  double predictedMs = 0, measuredMs = -1;
  double aluMs = 0, codeFactor = 1;  // the prediction's ALU term (code-size factor, loop state included) and that factor
  uint64_t moduleWords = 0;
  double loopStateMs = 0;  // the loop-state term (in aluMs)
};

// One frame of `scene` modelled on `desc` (and measured on `ctx` when given); returns the rows, false in `same` when a
// counted pass changed a bit.
std::vector<Row> modelFrame(const Scene& scene, const std::string& sceneName, const EnvironmentMap& env, const model::DeviceDesc& desc,
                            vk::Context* ctx, const emu::DeviceProfile& dev, uint32_t repeat, std::ostream& log, bool& same) {
  const model::FrameCounts fc = model::countFrame(scene, *env.texture, dev, model::coreModel(desc));
  log << "counted passes: " << fc.identical << "/" << fc.compared << " output values bit-identical to the emulator's";
  for (const std::string& d : fc.differing) log << " (differs: " << d << ")";
  log << "\n";
  same = same && fc.differing.empty() && fc.identical == fc.compared;
  std::map<std::string, double> measured;
  if (ctx) measured = measureFrame(*ctx, scene, env, dev, repeat);
  std::vector<Row> rows;
  double totalP = 0, totalM = 0;
  for (const model::PassCounts& c : fc.passes) {
    const model::Prediction p = model::predict(c, desc);
    const auto ops = model::scalarOps(c);
    const double inv = std::max(1.0, double(c.invocations));
    Row r{sceneName, scene.technique, desc.device, c.pass, p.bound, p.seconds * 1e3, -1.0, p.aluSeconds * 1e3, p.codeFactor, c.moduleWords,
          p.loopStateSeconds * 1e3};
    log << std::fixed << std::setprecision(2) << "  " << std::left << std::setw(18) << c.pass << std::right << " predicted "
        << std::setw(9) << r.predictedMs << " ms (alu " << p.aluSeconds * 1e3 << ", texture " << p.textureSeconds * 1e3
        << ", memory " << p.memorySeconds * 1e3 << ", raster " << p.rasterSeconds * 1e3 << ", launch " << p.launchSeconds * 1e3
        << "; bound " << p.bound << ")";
    if (p.codeFactor != 1.0)
      log << " (alu x " << std::setprecision(3) << p.codeFactor << " for a module of " << c.moduleWords << " words)" << std::setprecision(2);
    if (p.loopStateSeconds > 0.0)
      log << " (alu + " << std::setprecision(3) << p.loopStateSeconds * 1e3 << " ms for loops carrying " << c.loopCarried[0] << "/"
          << c.loopCarried[1] << "/" << c.loopCarried[2] << " values at depth 1/2/3)" << std::setprecision(2);
    if (auto it = measured.find(c.pass); it != measured.end()) {
      r.measuredMs = it->second;
      log << "  measured " << std::setw(9) << r.measuredMs << " ms  error " << std::showpos << std::setprecision(1)
          << 100.0 * (r.predictedMs - r.measuredMs) / r.measuredMs << "%" << std::noshowpos;
      totalM += r.measuredMs;
    }
    log << "\n" << std::setprecision(1) << "      per invocation:";
    for (int k = 0; k < model::kOpClasses; ++k) log << " " << model::kOpClassNames[k] << " " << ops[size_t(k)] / inv;
    log << "; lookups nearest " << c.ops[opcount::kTexNearest] / inv << " bilinear " << c.ops[opcount::kTexBilinear] / inv
        << " trilinear " << c.ops[opcount::kTexTrilinear] / inv << " uniform " << c.ops[opcount::kTexUniform] / inv
        << " fetch " << c.ops[opcount::kTexFetch] / inv
        << "; texture lines " << c.ops[opcount::kTexLine] / inv << " (missed " << c.ops[opcount::kTexMiss] / inv << ", in streams "
        << c.ops[opcount::kTexStreamMiss] / inv << "); "
        << c.invocations << " invocations, " << c.dispatches
        << (c.triangles ? " draws" : " dispatches");
    if (c.triangles) log << ", " << c.triangles << " triangles, " << c.fragments << " fragments, " << c.blocks << " 4x4 blocks (" << c.partialBlocks << " partly covered), " << c.helperLanes << " helper lanes, "
                         << c.vertexRuns << " vertex runs, " << c.spanningTriangles << " triangles spanning a pixel row, "
                         << c.outsideTriangles << " outside a clip plane, " << c.culledTriangles << " rejected at set-up";
    log << "\n";
    totalP += r.predictedMs;
    rows.push_back(r);
  }
  log << std::setprecision(2) << "  frame              predicted " << std::setw(9) << totalP << " ms";
  if (ctx) log << "  measured " << std::setw(9) << totalM << " ms";
  log << std::endl;  // a long --validate run shows its progress
  return rows;
}

Scene sceneWith(const ModelOptions& o, const std::string& path, const std::string& technique) {
  SceneOverrides ov = o;
  ov.technique = technique;  // --validate runs each technique of a scene
  return loadScene(path, ov);
}

bool isSoftware(const std::string& d) { return d == "lavapipe" || d == "swiftshader"; }

}  // namespace

int modelCommand(const ModelOptions& opts, std::ostream& log) {
  if (!opts.validate) {
    const Scene scene = sceneWith(opts, opts.scene, opts.technique);
    const std::string descPath = opts.devicesDir + "/" + opts.device + ".json";
    const model::DeviceDesc desc = model::loadDeviceDesc(descPath);
    // The counted passes run under the device's profile (software) or lavapipe's (a GPU's profile is unverified).
    std::unique_ptr<vk::Context> ctx;
    if (isSoftware(opts.device)) ctx = std::make_unique<vk::Context>(vk::ContextOptions{opts.device == "lavapipe" ? "" : opts.device, false});
    const emu::DeviceProfile& dev = ctx ? emu::profileForDevice(ctx->deviceName()) : emu::lavapipeProfile();
    log << "model " << opts.scene << ": " << scene.width << "x" << scene.height << ", technique " << scene.technique << "; device "
        << desc.device << " (" << descPath << ", " << (desc.verified ? "measured" : "public figures, unverified") << ")\n";
    std::ostringstream quiet;
    const EnvironmentMap env = loadEnvironment(scene, quiet);
    bool same = true;
    modelFrame(scene, opts.scene, env, desc, ctx.get(), dev, opts.repeat, log, same);
    return same ? 0 : 1;
  }
  // --validate: every shipped scene x technique (the scene's own, and for the non-glint scenes every shading pass kind:
  // fis, mirror, env, kdtree-mis) x every present software device.
  std::vector<std::string> scenes = opts.scenes;
  if (scenes.empty()) {
    for (const auto& e : std::filesystem::directory_iterator("scenes"))
      if (e.path().extension() == ".json") scenes.push_back(e.path().string());
    std::sort(scenes.begin(), scenes.end());
  }
  const std::vector<std::string> devices = opts.devices.empty() ? std::vector<std::string>{"lavapipe", "swiftshader"} : opts.devices;
  std::vector<Row> all;
  struct Frame {
    std::string path, technique;
    size_t first, last;  // its rows in `all`
  };
  std::vector<Frame> frames;  // the current device's
  bool same = true;
  for (const std::string& d : devices) {
    if (!isSoftware(d)) throw std::runtime_error("model --validate: " + d + " is not a software device present here");
    if (opts.calibrate) {
      CalibrateOptions co;
      co.device = d;
      co.rounds = opts.calibrateRounds;
      co.quick = opts.calibrateQuick;
      std::filesystem::create_directories(opts.devicesDir);
      model::saveDeviceDesc(calibrateDevice(co, log), opts.devicesDir + "/" + d + ".json");
      log << "wrote " << opts.devicesDir << "/" << d << ".json\n";
    }
    const model::DeviceDesc desc = model::loadDeviceDesc(opts.devicesDir + "/" + d + ".json");
    vk::Context ctx(vk::ContextOptions{d == "lavapipe" ? "" : d, false});
    const emu::DeviceProfile& dev = emu::profileForDevice(ctx.deviceName());
    for (const std::string& path : scenes) {
      const Scene base = sceneWith(opts, path, "");
      std::vector<std::string> techniques{base.technique};
      if (!isGlintsTechnique(base.technique))
        for (const char* t : {"fis", "mirror", "env", "kdtree-mis"})
          if (base.technique != t) techniques.push_back(t);
      std::ostringstream quiet;
      const EnvironmentMap env = loadEnvironment(base, quiet);
      for (const std::string& t : techniques) {
        Scene scene;
        try {
          scene = sceneWith(opts, path, t);
        } catch (const std::exception& e) {  // a scene the overrides do not fit
          log << "model " << path << " " << t << ": skipped (" << e.what() << ")\n";
          continue;
        }
        log << "model " << path << " " << scene.width << "x" << scene.height << " " << t << " on " << d << "\n";
        try {
          const std::vector<Row> rows = modelFrame(scene, path, env, desc, &ctx, dev, opts.repeat, log, same);
          all.insert(all.end(), rows.begin(), rows.end());
          frames.push_back({path, t, all.size() - rows.size(), all.size()});
        } catch (const std::invalid_argument& e) {  // a technique the scene's materials do not allow (maps under mirror)
          log << "  skipped: " << e.what() << std::endl;
        }
      }
    }
    // Further rounds: every frame measured again, in the same order, after all the others; each pass keeps its fastest.
    for (uint32_t round = 2; round <= opts.rounds; ++round) {
      std::string loaded;
      EnvironmentMap env;
      size_t faster = 0;
      for (const Frame& f : frames) {
        const Scene scene = sceneWith(opts, f.path, f.technique);
        if (loaded != f.path) {
          std::ostringstream quiet;
          env = loadEnvironment(scene, quiet), loaded = f.path;
        }
        const std::map<std::string, double> m = measureFrame(ctx, scene, env, dev, opts.repeat);
        for (size_t i = f.first; i < f.last; ++i)
          if (auto it = m.find(all[i].pass); it != m.end() && it->second < all[i].measuredMs) all[i].measuredMs = it->second, ++faster;
      }
      log << "round " << round << "/" << opts.rounds << " on " << d << ": " << faster << " of " << (frames.empty() ? 0 : frames.back().last - frames.front().first)
          << " passes measured faster than before" << std::endl;
    }
    frames.clear();
  }
  double sum = 0, worst = 0;
  size_t n = 0;
  std::map<std::string, std::pair<double, size_t>> perDevice, perPass;
  for (const Row& r : all) {
    if (r.measuredMs <= 0) continue;
    const double e = std::fabs(r.predictedMs - r.measuredMs) / r.measuredMs * 100.0;
    sum += e, worst = std::max(worst, e), ++n;
    perDevice[r.device].first += e, ++perDevice[r.device].second;
    perPass[r.pass].first += e, ++perPass[r.pass].second;
  }
  if (!opts.csv.empty()) {
    OutputFile file(opts.csv);
    std::ostream& f = file.stream();
    f << "scene,technique,device,pass,bound,predicted_ms,measured_ms,error_pct,alu_ms,module_words,code_factor,loop_state_ms\n";
    for (const Row& r : all)
      f << r.scene << "," << r.technique << "," << r.device << "," << r.pass << "," << r.bound << "," << r.predictedMs << ","
        << r.measuredMs << "," << (r.measuredMs > 0 ? 100.0 * (r.predictedMs - r.measuredMs) / r.measuredMs : 0.0) << ","
        << r.aluMs << "," << r.moduleWords << "," << r.codeFactor << "," << r.loopStateMs << "\n";
    file.commit();
    log << "wrote " << opts.csv << "\n";
  }
  log << std::fixed << std::setprecision(1);
  for (const auto& [d, v] : perDevice) log << "  " << d << ": mean abs error " << v.first / double(v.second) << "% over " << v.second << " passes\n";
  for (const auto& [p, v] : perPass) log << "  " << p << ": mean abs error " << v.first / double(v.second) << "% over " << v.second << " runs\n";
  log << "model: mean abs error " << (n ? sum / double(n) : 0.0) << "% over " << n << " passes (worst " << worst << "%)\n";
  if (!same) log << "model: a counted pass changed a bit\n";
  return same ? 0 : 1;
}

}  // namespace shadetwin
