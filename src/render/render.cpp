#include "render/render.h"

#include <memory>

#include "render/paraboloid.h"

#include <chrono>
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
#include "vk/context.h"
#include "scene/scene.h"

namespace shadetwin {
namespace {

using Clock = std::chrono::steady_clock;
double ms(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

}  // namespace

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

EnvironmentMap loadEnvironment(const std::string& path, std::ostream& log) {
  ImageRGBA img = loadImageRGBA(path);
  EnvironmentMap env;
  // Policy for the source HDRI (docs/DESIGN.md): NaN and infinite texels become 0 and are counted;
  // negative texels are kept (they are real data in the CC0 maps) and counted.
  for (float& v : img.texels) {
    if (!std::isfinite(v)) {
      v = 0.0f;
      ++env.nonFinite;
    } else if (v < 0.0f) {
      ++env.negative;
    }
  }
  auto levels = mipChainCpu(img.texels, img.width, img.height, 1, 8);
  env.texture = std::make_unique<emu::Texture>(packTexture(emu::Format::RGBA32F, img.width, img.height, 1, levels));
  env.levels = std::move(levels);
  env.width = img.width;
  env.height = img.height;
  if (env.nonFinite) log << "  environment: " << env.nonFinite << " non-finite texel values replaced by 0\n";
  return env;
}

int renderCommand(const RenderOptions& opts, std::ostream& log) {
  auto t0 = Clock::now();
  Scene scene = loadScene(opts.scene);
  if (opts.width) scene.width = opts.width;
  if (opts.height) scene.height = opts.height;
  const double tScene = ms(t0);
  if (opts.device != "emu" && opts.device != "vulkan") throw std::invalid_argument("--device " + opts.device + ": expected emu or vulkan");
  const emu::DeviceProfile& dev = emu::profileByName(opts.profile);
  log << "scene " << opts.scene << ": " << scene.objects.size() << " objects, " << scene.triangles() << " triangles, "
      << scene.width << "x" << scene.height << ", environment " << scene.environment << "\n";
  t0 = Clock::now();
  EnvironmentMap env = loadEnvironment(scene.environment, log);
  const double tEnv = ms(t0);
  std::vector<float> image;
  std::ostringstream passes;
  passes << std::fixed << std::setprecision(1);
  if (opts.device == "emu") {
    GbufferStats gs;
    t0 = Clock::now();
    GBuffer g = gbufferEmu(scene, dev, &gs);
    const double tGbuf = ms(t0);
    const ShadeInputs in = shadeInputsEmu(scene, *env.texture, dev);
    t0 = Clock::now();
    image = shadeEmu(scene, g, in, dev);
    const double tShade = ms(t0);
    if (in.atlas) {
      passes << "  paraboloid atlas (emu)   " << std::setw(8) << in.atlasMs << " ms  (" << 2 * scene.fisFaceSize << "x"
             << scene.fisFaceSize << " + MIP chain)\n";
      passes << "  SH irradiance (emu)      " << std::setw(8) << in.shMs << " ms  (order 3, " << env.width << " x "
             << env.height << " texels)\n";
    }
    passes << "  G-buffer (emu, " << dev.name << ")  " << std::setw(8) << tGbuf << " ms  (vertex " << gs.vertexMs
           << " ms, raster+fragment " << gs.rasterMs << " ms; " << gs.raster.fragments << " fragments, "
           << gs.raster.trianglesClipped << " clipped, " << gs.raster.trianglesCulled << " culled)\n";
    passes << "  shading (emu, " << scene.technique;
    if (scene.technique != "mirror") passes << ", " << scene.fisSamples << " samples";
    passes << ")    " << std::setw(8) << tShade << " ms\n";
  } else {
    t0 = Clock::now();
    vk::Context ctx;
    GbufferPassVk gpass(ctx, scene);
    const ShadeInputs in = shadeInputsVulkan(ctx, scene, *env.texture);
    ShadePassVk spass(ctx, scene, in);
    const double tSetup = ms(t0);
    GBuffer g = gpass.run();
    image = spass.run(g);
    passes << "  Vulkan set-up (" << ctx.deviceName() << ")  " << std::setw(8) << tSetup << " ms\n";
    passes << "  G-buffer (vulkan)        " << std::setw(8) << gpass.lastMs << " ms  (submit to read-back)\n";
    passes << "  shading (vulkan, " << scene.technique << ") " << std::setw(8) << spass.lastMs << " ms  (submit to read-back)\n";
  }
  // Passes the technique does not use are not run.
  passes << "  shadow maps              " << std::setw(8) << "-" << "     (not run: technique " << scene.technique
         << " uses no visibility)\n";
  std::string out = opts.out;
  if (out.empty()) out = std::filesystem::path(opts.scene).stem().string() + ".exr";
  std::string png = std::filesystem::path(out).replace_extension(".png").string();
  t0 = Clock::now();
  writeExr(out, scene.width, scene.height, image);
  writePngToneMapped(png, scene.width, scene.height, image);
  const double tWrite = ms(t0);
  log << std::fixed << std::setprecision(1);
  log << "  load scene + meshes      " << std::setw(8) << tScene << " ms\n";
  log << "  environment + MIP chain  " << std::setw(8) << tEnv << " ms  (" << env.width << "x" << env.height << ", "
      << env.texture->levelCount() << " levels, " << env.negative << " negative texel values)\n";
  log << passes.str();
  log << "  write EXR + PNG          " << std::setw(8) << tWrite << " ms\n";
  log << "wrote " << out << " and " << png << "\n";
  return 0;
}

}  // namespace shadetwin
