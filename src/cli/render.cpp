#include "cli/render.h"

#include <memory>

#include "inputs/paraboloid.h"

#include <chrono>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <algorithm>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "emu/device_profile.h"
#include "emu/format.h"
#include "util/output_file.h"
#include "util/image_io.h"
#include "util/memory.h"
#include "passes/frame_memory.h"
#include "passes/mips.h"
#include "passes/shade.h"
#include "passes/passes_vk.h"
#include "passes/visibility.h"
#include "inputs/shade_inputs.h"
#include "reference/glints_gxd.h"
#include "reference/reference.h"
#include "vk/context.h"
#include "scene/scene.h"
#include "util/timer.h"

namespace shadetwin {
using Clock = std::chrono::steady_clock;

namespace {
void visibilityLines(std::ostream& passes, const char* build, const VisibilitySetup& v, const VisibilityStats& t) {
  passes << "  shadow maps (" << build << ")       " << std::setw(8) << t.shadowMs << " ms  (" << v.settings.maps << " x "
         << v.settings.size << "^2, directions from the environment's luminance" << (v.uniformFallback ? ": none, uniform" : "")
         << ")\n";
  passes << "  visibility fit (" << build << ")    " << std::setw(8) << t.fitMs << " ms  (order-4 SH, "
         << (v.settings.fitCosine ? "V max(0, n.w)" : "V") << ", rank " << v.rank << "/16)\n";
  if (v.settings.filterRadius)
    passes << "  visibility filter (" << build << ") " << std::setw(8) << t.filterMs << " ms  ("
           << (v.settings.filterEdgeAware ? "edge-aware" : "box") << ", radius " << v.settings.filterRadius << ")\n";
  const auto mib = [](size_t b) { return double(b) / (1024.0 * 1024.0); };
  const auto flags = passes.flags();
  const auto prec = passes.precision();
  passes << "  visibility memory (" << build << ")  " << std::setprecision(1) << std::fixed << mib(t.mapBytes)
         << " MiB maps + " << mib(t.mapArrayBytes) << " MiB as the fit's array, " << mib(t.coeffBytes)
         << " MiB coefficients" << (t.filteredBytes ? " + " : "");
  if (t.filteredBytes) passes << mib(t.filteredBytes) << " MiB filtered";
  passes << "\n";
  passes.flags(flags);
  passes.precision(prec);
}

void glintLines(std::ostream& passes, const char* build, const GlintInputs& g) {
  passes << "  glint SATs (host)       " << std::setw(8) << g.satMs << " ms  (" << g.maps << " normal map" << (g.maps > 1 ? "s" : "")
         << " of " << g.mapSize << "^2, " << g.bins.rings << " x " << g.bins.sectors << " bins, " << g.satBytes / (1 << 20) << " MiB)\n";
  passes << "  glint lighting (" << build << ")    " << std::setw(8) << g.lightingMs << " ms  (" << g.lightingSpec.rings << " x "
         << g.lightingSpec.sectors << " views, degree " << g.lightingSpec.order << ", environment level " << g.lightingSpec.level
         << ", " << g.lightingBytes / (1 << 20) << " MiB)\n";
  if (g.lobeRings)
    passes << "  glint lobe table (host)  " << std::setw(8) << g.lobeMs << " ms  (" << g.lobeRings << " x " << g.lobeSectors
           << " directions, degree " << g.order << ", " << std::setprecision(2) << double(g.lobeBytes) / (1 << 20) << " MiB)\n"
           << std::setprecision(1);
  if (!g.lobeBandLimits.empty() && !g.lightBandLimits.empty()) {
    const auto [n0, n1] = std::minmax_element(g.lobeBandLimits.begin(), g.lobeBandLimits.end());
    const auto [l0, l1] = std::minmax_element(g.lightBandLimits.begin(), g.lightBandLimits.end());
    passes << "  glint band limits at 1e-6: M_NDF " << *n0 << ".." << *n1 << " (materials), M_light " << *l0 << ".." << *l1
           << " (views); M* = min per pixel\n";
  }
}

// Output path of frame f: OUT itself for a single frame, else OUT's stem + _NNNN.
std::string frameOut(const std::string& out, uint32_t frames, uint32_t f) {
  if (frames == 1) return out;
  std::filesystem::path p(out);
  std::ostringstream name;
  name << p.stem().string() << "_" << std::setw(4) << std::setfill('0') << f << p.extension().string();
  return (p.parent_path() / name.str()).string();
}
}  // namespace

int renderCommand(const RenderOptions& opts, std::ostream& log) {
  const auto tStart = Clock::now();
  auto t0 = tStart;
  Scene scene = loadScene(opts.scene, opts);
  const double tScene = msSince(t0);
  if (opts.device != "emu" && opts.device != "vulkan") throw std::invalid_argument("--device " + opts.device + ": expected emu or vulkan");
  if (opts.frames == 0) throw std::invalid_argument("--frames: expected at least 1");
  const emu::DeviceProfile& dev = emu::profileByName(opts.profile);
  log << "scene " << opts.scene << ": " << scene.objects.size() << " objects, " << scene.triangles() << " triangles, "
      << scene.width << "x" << scene.height << ", environment " << scene.environment << "\n";
  std::string out = opts.out;
  if (out.empty()) out = std::filesystem::path(opts.scene).stem().string() + ".exr";
  checkWritable(out);  // a missing or unwritable output folder fails now, not after the render
  // A frame that would need more memory than the machine has fails now, with what it would need, not in an allocation.
  {
    const ImageHeader eh = imageHeader(scene.environment);
    std::vector<MemoryNeed> needs =
        frameMemory(scene, eh.width, eh.height, eh.channels, opts.device == "vulkan" ? FrameBuild::Vulkan : FrameBuild::Emu);
    if (opts.frames > 1 && opts.envRotate != 0)
      needs.push_back({"turned environment", double(eh.width) * eh.height * 16.0 * 4.0 / 3.0 * 2});
    const MemoryBudget budget = memoryBudget();
    checkMemoryBudget(opts.scene, needs, budget);
    log << "  memory: about " << formatBytes(totalBytes(needs)) << " estimated for a frame, beside " << formatBytes(residentBytes())
        << " held (scene and meshes); " << formatBytes(budget.bytes) << " may be used\n";
  }
  t0 = Clock::now();
  const EnvironmentMap env0 = loadEnvironment(scene, log);
  const double tEnv = msSince(t0);
  log << std::fixed << std::setprecision(1);
  log << "  load scene + meshes      " << std::setw(8) << tScene << " ms\n";
  log << "  environment + MIP chain  " << std::setw(8) << tEnv << " ms  (" << env0.width << "x" << env0.height << ", "
      << env0.texture->levelCount() << " levels, " << env0.negative << " negative texel values)\n";

  // Frames: the environment turns by --env-rotate degrees per frame (a whole-column shift of level 0,
  // then its MIP chain); the technique inputs (atlas + MIP chain, SH, lights) are rebuilt on a frame
  // whose environment changed and reused otherwise; the G-buffer does not depend on the environment
  // and is drawn once.
  ShadeInputsCache cache;
  std::unique_ptr<vk::Context> ctx;
  std::unique_ptr<GbufferPassVk> gpass;
  std::unique_ptr<ShadePassVk> spass;
  std::unique_ptr<VisibilityPassVk> vpass;
  GBuffer g;
  // MIS techniques draw new random numbers every frame (Philox key word 1 = the frame) and average
  // progressively: frame f writes the mean of the frames since the environment last changed.
  const bool progressive = usesMisPass(scene.technique);
  std::vector<double> accum;
  uint32_t accumFrames = 0;
  const Mat4 model0 = scene.objects.empty() ? Mat4{} : scene.objects[0].model;
  const bool moving = opts.objectRotate != 0 && !scene.objects.empty();
  // glints-gxd: the ground truth, shaded on the host over the G-buffer either build drew.
  const bool gxd = scene.technique == "glints-gxd";
  auto gxdImage = [&](const EnvironmentMap& e) {
    const reference::Environment renv(EnvImage{e.width, e.height, e.levels[0].data()}, scene.environmentIntensity);
    GlintGxdOptions o;
    o.samples = scene.glintGxdSamples;
    return glintGxdImage(scene, g.texels.data(), g.width, g.height, renv, o);
  };
  std::string lastPng;
  for (uint32_t f = 0; f < opts.frames; ++f) {
    scene.misFrame = f;
    if (moving) scene.objects[0].model = rotateAboutOwnAxis(model0, opts.objectRotate * f);
    const bool drawGbuffer = f == 0 || moving;
    // The frame's visibility set-up: the cached one, or, when an object moved (the scene bounds and so
    // the maps' matrices change; the directions do not), a new one.
    auto frameVisibility = [&](const ShadeInputs& in, const emu::Texture& envTex) -> std::shared_ptr<const VisibilitySetup> {
      if (!in.visibility || !moving) return in.visibility;
      return std::make_shared<VisibilitySetup>(visibilitySetup(scene, envTex, visibilitySettings(scene)));
    };
    std::ostringstream passes;
    passes << std::fixed << std::setprecision(1);
    const double degrees = opts.envRotate * f;
    t0 = Clock::now();
    const EnvironmentMap rotated = f && environmentShift(env0.width, degrees) ? rotateEnvironment(env0, degrees) : EnvironmentMap{};
    const EnvironmentMap& env = rotated.texture ? rotated : env0;
    const double tRotate = msSince(t0);
    std::vector<float> image;
    if (opts.device == "emu") {
      GbufferStats gs;
      t0 = Clock::now();
      if (drawGbuffer) g = gbufferEmu(scene, dev, &gs);
      const double tGbuf = msSince(t0);
      const ShadeInputs& in = cache.emu(scene, *env.texture, dev);
      VisibilityStats vt;
      std::unique_ptr<VisibilityImage> vis;
      const std::shared_ptr<const VisibilitySetup> vsetup = frameVisibility(in, *env.texture);
      if (vsetup) vis = std::make_unique<VisibilityImage>(visibilityEmu(scene, g, *vsetup, dev, &vt));
      t0 = Clock::now();
      if (gxd) image = gxdImage(env);
      else image = shadeEmu(scene, g, in, dev, vis.get());
      const double tShade = msSince(t0);
      if (rotated.texture)
        passes << "  environment turned      " << std::setw(8) << tRotate << " ms  (" << degrees << " degrees = "
               << environmentShift(env0.width, degrees) << " columns, + MIP chain)\n";
      if (in.atlas && cache.lastRebuilt()) {
        passes << "  paraboloid atlas (emu)   " << std::setw(8) << in.atlasMs << " ms  (" << 2 * scene.fisFaceSize << "x"
               << scene.fisFaceSize << " + MIP chain)\n";
        passes << "  SH irradiance (emu)      " << std::setw(8) << in.shMs << " ms  (order 3, " << env.width << " x "
               << env.height << " texels)\n";
      } else if (!cache.lastRebuilt()) {
        passes << "  technique inputs                -     (environment unchanged: reused)\n";
      }
      if (in.glints && cache.lastRebuilt()) glintLines(passes, "emu", *in.glints);
      if (in.envTables && cache.lastRebuilt()) {
        const EnvSamplingTables& T = *in.envTables;
        passes << "  sampler tables (host)    " << std::setw(8) << T.buildMs << " ms  (" << scene.technique;
        if (T.uniforms.count) passes << ": " << T.uniforms.count << " blocks, alpha " << std::setprecision(4) << T.fit.alpha << ", L1 misfit " << T.fit.l1
                             << std::setprecision(1);
        passes << ")\n";
      }
      if (drawGbuffer)
        passes << "  G-buffer (emu, " << dev.name << ")  " << std::setw(8) << tGbuf << " ms  (vertex " << gs.vertexMs
               << " ms, raster+fragment " << gs.rasterMs << " ms; " << gs.raster.fragments << " fragments, "
               << gs.raster.trianglesClipped << " clipped, " << gs.raster.trianglesCulled << " culled)\n";
      if (vis) visibilityLines(passes, "emu", *vsetup, vt);  // after the G-buffer they read
      passes << "  shading (" << (gxd ? "host, double" : "emu") << ", " << scene.technique;
      if (progressive) passes << ", " << scene.misSamples << " sample pairs, frame " << f;
      else if (scene.technique == "glints" && in.glints) passes << ", degree " << in.glints->order;
      else if (gxd) passes << ", " << scene.glintGxdSamples << " sample pairs";
      else if (scene.technique != "mirror") passes << ", " << scene.fisSamples << " samples";
      passes << ")    " << std::setw(8) << tShade << " ms\n";
    } else {
      t0 = Clock::now();
      if (f == 0) ctx = std::make_unique<vk::Context>();
      if (drawGbuffer) gpass = std::make_unique<GbufferPassVk>(*ctx, scene);  // the scene's object buffer, as moved
      const ShadeInputs& in = cache.vulkan(*ctx, scene, *env.texture);
      if (!gxd && (cache.lastRebuilt() || rotated.texture)) spass = std::make_unique<ShadePassVk>(*ctx, scene, in);
      const double tSetup = msSince(t0);
      if (drawGbuffer) g = gpass->run();
      VisibilityStats vt;
      std::unique_ptr<VisibilityImage> vis;
      const std::shared_ptr<const VisibilitySetup> vsetup = frameVisibility(in, *env.texture);
      if (vsetup) {
        if (!vpass || moving) vpass = std::make_unique<VisibilityPassVk>(*ctx, scene, vsetup->settings.size);  // built once
        vis = std::make_unique<VisibilityImage>(vpass->run(g, *vsetup, &vt));
      }
      t0 = Clock::now();
      image = gxd ? gxdImage(env) : spass->run(g, vis.get());
      const double tShade = gxd ? msSince(t0) : spass->lastMs;
      passes << "  Vulkan set-up (" << ctx->deviceName() << ")  " << std::setw(8) << tSetup << " ms"
             << (cache.lastRebuilt() ? "" : "  (technique inputs reused)") << "\n";
      if (drawGbuffer) passes << "  G-buffer (vulkan)        " << std::setw(8) << gpass->lastMs << " ms  (submit to read-back)\n";
      if (vis) visibilityLines(passes, "vulkan", *vsetup, vt);
      if (gxd)
        passes << "  shading (host, double, glints-gxd, " << scene.glintGxdSamples << " sample pairs)  " << std::setw(8) << tShade << " ms\n";
      else
        passes << "  shading (vulkan, " << scene.technique << ") " << std::setw(8) << tShade << " ms  (submit to read-back)\n";
    }
    // Passes the technique does not use are not run.
    if (!(scene.visMaps && usesFisPass(scene.technique)))
      passes << "  shadow maps              " << std::setw(8) << "-" << "     (not run: technique " << scene.technique
             << (usesFisPass(scene.technique) ? " without a visibility block" : " uses no visibility") << ")\n";
    if (progressive) {
      if (f == 0 || cache.lastRebuilt() || rotated.texture) accum.assign(image.size(), 0.0), accumFrames = 0;
      ++accumFrames;
      for (size_t i = 0; i < image.size(); ++i) {
        accum[i] += image[i];
        image[i] = float(accum[i] / accumFrames);
      }
      if (opts.frames > 1) passes << "  progressive mean of " << accumFrames << " frame(s)\n";
    }
    const std::string exr = frameOut(out, opts.frames, f);
    const std::string png = std::filesystem::path(exr).replace_extension(".png").string();
    t0 = Clock::now();
    writeExr(exr, scene.width, scene.height, image);
    writePngToneMapped(png, scene.width, scene.height, image);
    const double tWrite = msSince(t0);
    if (opts.frames > 1) log << "frame " << f << ":\n";
    log << passes.str();
    log << "  write EXR + PNG          " << std::setw(8) << tWrite << " ms\n";
    log << "wrote " << exr << " and " << png << "\n";
    lastPng = png;
  }
  if (opts.frames > 1)
    log << opts.frames << " frames, technique inputs built " << cache.builds() << " time(s)\n";
  log << "peak memory " << formatBytes(peakResidentBytes()) << " resident (" << std::setprecision(1) << msSince(tStart) / 1000.0
      << " s in all)\n";
  log << "image: " << std::filesystem::absolute(lastPng).lexically_normal().string() << "\n";  // the last line: what to open
  return 0;
}

}  // namespace shadetwin
