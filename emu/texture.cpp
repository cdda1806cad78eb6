#include "emu/texture.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace emu {

Texture floatTexture(Format format, uint32_t width, uint32_t height, const float* texels) {
  if (format != Format::RGBA32F && format != Format::R32F) throw std::invalid_argument("floatTexture: expected rgba32f or r32f");
  std::vector<std::vector<uint8_t>> levels(1, std::vector<uint8_t>(size_t(width) * height * formatInfo(format).texelBytes));
  std::memcpy(levels[0].data(), texels, levels[0].size());
  return Texture(format, width, height, 1, std::move(levels));
}

uint32_t Texture::fullChainLevels(uint32_t width, uint32_t height) {
  uint32_t m = width > height ? width : height, n = 1;
  while (m > 1) { m >>= 1; ++n; }
  return n;
}

Texture::Texture(Format format, uint32_t width, uint32_t height, uint32_t layers, std::vector<std::vector<uint8_t>> levels)
    : format_(format), width_(width), height_(height), layers_(layers), texelBytes_(formatInfo(format).texelBytes),
      levels_(std::move(levels)) {
  if (width == 0 || height == 0 || layers == 0)
    throw std::invalid_argument("texture: zero size (" + std::to_string(width) + "x" + std::to_string(height) + "x" +
                                std::to_string(layers) + ")");
  if (levels_.empty()) throw std::invalid_argument("texture: no MIP levels given");
  const uint32_t full = fullChainLevels(width, height);
  if (levels_.size() > full)
    throw std::invalid_argument("texture: " + std::to_string(levels_.size()) + " MIP levels given, a " + std::to_string(width) +
                                "x" + std::to_string(height) + " texture has at most " + std::to_string(full));
  for (uint32_t l = 0; l < levels_.size(); ++l) {
    size_t want = size_t(levelWidth(l)) * levelHeight(l) * layers * texelBytes_;
    if (levels_[l].size() != want)
      throw std::invalid_argument("texture: MIP level " + std::to_string(l) + " has " + std::to_string(levels_[l].size()) +
                                  " bytes, expected " + std::to_string(want) + " (" + std::to_string(levelWidth(l)) + "x" +
                                  std::to_string(levelHeight(l)) + "x" + std::to_string(layers) + " texels of " +
                                  std::to_string(texelBytes_) + " bytes)");
  }
}

Texel4 Texture::loadFloat(uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const {
  const uint8_t* p = texelPtr(level, layer, x, y);
  Texel4 t{};
  switch (format_) {
    case Format::RGBA32F: std::memcpy(&t, p, 16); break;
    case Format::RGBA16F: {
      uint16_t h[4];
      std::memcpy(h, p, 8);
      t = {halfToFloat(h[0]), halfToFloat(h[1]), halfToFloat(h[2]), halfToFloat(h[3])};
      break;
    }
    case Format::RGBA8_UNORM: t = {unorm8ToFloat(p[0]), unorm8ToFloat(p[1]), unorm8ToFloat(p[2]), unorm8ToFloat(p[3])}; break;
    case Format::R32F: std::memcpy(&t.r, p, 4); t.g = 0.0f; t.b = 0.0f; t.a = 1.0f; break;
    case Format::RGBA32UI: throw std::logic_error("texture: an RGBA32UI texture is read with loadUint (texelFetch of a usampler), not as floats");
  }
  return t;
}

}  // namespace emu
