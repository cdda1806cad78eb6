#include "render/render.h"

#include <memory>

#include "render/paraboloid.h"

#include <chrono>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "emu/device_profile.h"
#include "emu/format.h"
#include "image_io.h"
#include "mips.h"
#include "render/gbuffer.h"
#include "render/passes_vk.h"
#include "render/shade_inputs.h"
#include "vk/context.h"
#include "scene/scene.h"
#include "util/timer.h"

namespace shadetwin {
using Clock = std::chrono::steady_clock;

CameraRays cameraRays(const Scene& scene) {
  const CameraBasis b = scene.basis();
  const double t = std::tan(scene.camera.fovY * 3.14159265358979323846 / 360.0);
  const double aspect = double(scene.width) / scene.height;
  CameraRays r;
  for (int k = 0; k < 3; ++k) {
    r.eye[k] = scene.camera.eye[k];
    r.fwd[k] = b.forward[size_t(k)];
    r.right[k] = float(b.right[size_t(k)] * t * aspect);
    r.down[k] = float(-b.up[size_t(k)] * t);
  }
  return r;
}

EnvironmentMap environmentFromLevel0(std::vector<float> texels, uint32_t width, uint32_t height) {
  EnvironmentMap env;
  // Policy for the source HDRI (docs/DESIGN.md): NaN and infinite texels become 0 and are counted;
  // negative texels are kept (they are real data in the CC0 maps) and counted.
  for (float& v : texels) {
    if (!std::isfinite(v)) {
      v = 0.0f;
      ++env.nonFinite;
    } else if (v < 0.0f) {
      ++env.negative;
    }
  }
  auto levels = mipChainCpu(texels, width, height, 1, 8);
  env.texture = std::make_unique<emu::Texture>(packTexture(emu::Format::RGBA32F, width, height, 1, levels));
  env.levels = std::move(levels);
  env.width = width;
  env.height = height;
  return env;
}

EnvironmentMap loadEnvironment(const std::string& path, std::ostream& log) {
  ImageRGBA img = loadImageRGBA(path);
  EnvironmentMap env = environmentFromLevel0(std::move(img.texels), img.width, img.height);
  if (env.nonFinite) log << "  environment: " << env.nonFinite << " non-finite texel values replaced by 0\n";
  return env;
}

uint32_t environmentShift(uint32_t width, double degrees) {
  const double cols = std::fmod(degrees / 360.0, 1.0) * width;
  return uint32_t(std::lround(cols < 0 ? cols + width : cols)) % width;
}

std::vector<float> repeatTexels(const float* rgba, uint32_t width, uint32_t height, uint32_t scale) {
  const uint32_t W = width * scale, H = height * scale;
  std::vector<float> out(size_t(W) * H * 4);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) std::memcpy(&out[4 * (size_t(y) * W + x)], rgba + 4 * (size_t(y / scale) * width + x / scale), 16);
  return out;
}

EnvironmentMap rotateEnvironment(const EnvironmentMap& env, double degrees) {
  const uint32_t W = env.width, H = env.height, s = environmentShift(W, degrees);
  const std::vector<float>& src = env.levels[0];
  std::vector<float> dst(src.size());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x)
      std::memcpy(&dst[4 * (size_t(y) * W + (x + W - s) % W)], &src[4 * (size_t(y) * W + x)], 16);
  return environmentFromLevel0(std::move(dst), W, H);
}

namespace {
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
  auto t0 = Clock::now();
  Scene scene = loadScene(opts.scene);
  if (opts.width) scene.width = opts.width;
  if (opts.height) scene.height = opts.height;
  if (opts.blocks) scene.envBlocks = opts.blocks;
  const double tScene = msSince(t0);
  if (opts.device != "emu" && opts.device != "vulkan") throw std::invalid_argument("--device " + opts.device + ": expected emu or vulkan");
  if (opts.frames == 0) throw std::invalid_argument("--frames: expected at least 1");
  const emu::DeviceProfile& dev = emu::profileByName(opts.profile);
  log << "scene " << opts.scene << ": " << scene.objects.size() << " objects, " << scene.triangles() << " triangles, "
      << scene.width << "x" << scene.height << ", environment " << scene.environment << "\n";
  t0 = Clock::now();
  const EnvironmentMap env0 = loadEnvironment(scene.environment, log);
  const double tEnv = msSince(t0);
  std::string out = opts.out;
  if (out.empty()) out = std::filesystem::path(opts.scene).stem().string() + ".exr";
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
  GBuffer g;
  // MIS techniques draw new random numbers every frame (Philox key word 1 = the frame) and average
  // progressively: frame f writes the mean of the frames since the environment last changed.
  const bool progressive = usesMisPass(scene.technique);
  std::vector<double> accum;
  uint32_t accumFrames = 0;
  for (uint32_t f = 0; f < opts.frames; ++f) {
    scene.misFrame = f;
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
      if (f == 0) g = gbufferEmu(scene, dev, &gs);
      const double tGbuf = msSince(t0);
      const ShadeInputs& in = cache.emu(scene, *env.texture, dev);
      t0 = Clock::now();
      image = shadeEmu(scene, g, in, dev);
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
      if (in.envTables && cache.lastRebuilt()) {
        const EnvSamplingTables& T = *in.envTables;
        passes << "  sampler tables (host)    " << std::setw(8) << T.buildMs << " ms  (" << scene.technique;
        if (T.uniforms.count) passes << ": " << T.uniforms.count << " blocks, alpha " << std::setprecision(4) << T.fit.alpha << ", L1 misfit " << T.fit.l1
                             << std::setprecision(1);
        passes << ")\n";
      }
      if (f == 0)
        passes << "  G-buffer (emu, " << dev.name << ")  " << std::setw(8) << tGbuf << " ms  (vertex " << gs.vertexMs
               << " ms, raster+fragment " << gs.rasterMs << " ms; " << gs.raster.fragments << " fragments, "
               << gs.raster.trianglesClipped << " clipped, " << gs.raster.trianglesCulled << " culled)\n";
      passes << "  shading (emu, " << scene.technique;
      if (progressive) passes << ", " << scene.misSamples << " sample pairs, frame " << f;
      else if (scene.technique != "mirror") passes << ", " << scene.fisSamples << " samples";
      passes << ")    " << std::setw(8) << tShade << " ms\n";
    } else {
      t0 = Clock::now();
      if (f == 0) {
        ctx = std::make_unique<vk::Context>();
        gpass = std::make_unique<GbufferPassVk>(*ctx, scene);
      }
      const ShadeInputs& in = cache.vulkan(*ctx, scene, *env.texture);
      if (cache.lastRebuilt() || rotated.texture) spass = std::make_unique<ShadePassVk>(*ctx, scene, in);
      const double tSetup = msSince(t0);
      if (f == 0) g = gpass->run();
      image = spass->run(g);
      passes << "  Vulkan set-up (" << ctx->deviceName() << ")  " << std::setw(8) << tSetup << " ms"
             << (cache.lastRebuilt() ? "" : "  (technique inputs reused)") << "\n";
      if (f == 0) passes << "  G-buffer (vulkan)        " << std::setw(8) << gpass->lastMs << " ms  (submit to read-back)\n";
      passes << "  shading (vulkan, " << scene.technique << ") " << std::setw(8) << spass->lastMs << " ms  (submit to read-back)\n";
    }
    // Passes the technique does not use are not run.
    passes << "  shadow maps              " << std::setw(8) << "-" << "     (not run: technique " << scene.technique
           << " uses no visibility)\n";
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
  }
  if (opts.frames > 1)
    log << opts.frames << " frames, technique inputs built " << cache.builds() << " time(s)\n";
  return 0;
}

}  // namespace shadetwin
