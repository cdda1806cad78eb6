#include "inputs/environment.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "emu/format.h"
#include "passes/mips.h"
#include "util/image_io.h"

namespace shadetwin {

std::array<size_t, 2> sanitizeTexels(std::vector<float>& texels, bool clampNegative) {
  std::array<size_t, 2> n{0, 0};
  for (float& v : texels) {
    if (!std::isfinite(v)) {
      v = 0.0f;
      ++n[0];
    } else if (v < 0.0f) {
      ++n[1];
      if (clampNegative) v = 0.0f;
    }
  }
  return n;
}

EnvironmentMap environmentFromLevel0(std::vector<float> texels, uint32_t width, uint32_t height, bool clampNegative) {
  if (width == 0 || height == 0 || texels.size() != size_t(width) * height * 4)
    throw std::invalid_argument("environment: " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                                std::to_string(texels.size()) + " values (expected a non-empty RGBA image)");
  EnvironmentMap env;
  const auto n = sanitizeTexels(texels, clampNegative);
  env.nonFinite = n[0], env.negative = n[1];
  auto levels = mipChainCpu(texels, width, height, 1, 8);
  env.texture = std::make_unique<emu::Texture>(packTexture(emu::Format::RGBA32F, width, height, 1, levels));
  env.levels = std::move(levels);
  env.width = width;
  env.height = height;
  return env;
}

EnvironmentMap loadEnvironment(const std::string& path, std::ostream& log, bool clampNegative) {
  ImageRGBA img = loadImageRGBA(path);
  EnvironmentMap env = environmentFromLevel0(std::move(img.texels), img.width, img.height, clampNegative);
  if (env.nonFinite) log << "  environment: " << path << ": " << env.nonFinite << " non-finite texel values replaced by 0\n";
  if (env.negative && clampNegative) log << "  environment: " << path << ": " << env.negative << " negative texel values clamped to 0\n";
  return env;
}

EnvironmentMap loadEnvironment(const Scene& scene, std::ostream& log) {
  return loadEnvironment(scene.environment, log, scene.envClampNegative);
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
  return environmentFromLevel0(std::move(dst), W, H);  // the texels moved already follow the source's policy
}

}  // namespace shadetwin
