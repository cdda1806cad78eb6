// Texture objects of the emulated GPU: 2D arrays with a MIP chain in one of the emulated formats.
#pragma once
#include <array>
#include <cstring>
#include <cstdint>
#include <vector>

#include "emu/format.h"

namespace emu {

struct Texel4 {
  float r, g, b, a;
};

class Texture {
 public:
  /// levels[l] holds layers * w_l * h_l texels (layer-major, then rows), w_l = max(1, width >> l).
  /// Throws std::invalid_argument for zero sizes, more levels than the full chain, or a level whose
  /// byte size is wrong (the message names the level, the size found and the size expected).
  Texture(Format format, uint32_t width, uint32_t height, uint32_t layers, std::vector<std::vector<uint8_t>> levels);

  Format format() const { return format_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t layers() const { return layers_; }
  uint32_t levelCount() const { return uint32_t(levels_.size()); }
  uint32_t levelWidth(uint32_t l) const { return width_ >> l ? width_ >> l : 1; }
  uint32_t levelHeight(uint32_t l) const { return height_ >> l ? height_ >> l : 1; }
  const std::vector<std::vector<uint8_t>>& levels() const { return levels_; }

  const uint8_t* texelPtr(uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const {
    const uint32_t w = levelWidth(level), h = levelHeight(level);
    return levels_[level].data() + ((size_t(layer) * h + y) * w + x) * texelBytes_;
  }
  /// The texel as the float path sees it: f32 as is, f16 exactly widened, unorm8 as byte * (1/255),
  /// R32F as (r, 0, 0, 1).
  Texel4 loadFloat(uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const;
  /// The texel of an integer format (RGBA32UI) as its four 32-bit values, exactly.
  std::array<uint32_t, 4> loadUint(uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const {
    std::array<uint32_t, 4> v;
    std::memcpy(v.data(), texelPtr(level, layer, x, y), 16);
    return v;
  }
  std::array<uint8_t, 4> loadBytes(uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const {
    const uint8_t* p = texelPtr(level, layer, x, y);
    return {p[0], p[1], p[2], p[3]};
  }

  /// Number of levels of a full chain for this size.
  static uint32_t fullChainLevels(uint32_t width, uint32_t height);

 private:
  Format format_;
  uint32_t width_, height_, layers_, texelBytes_;
  std::vector<std::vector<uint8_t>> levels_;
};

/// One level, one layer of 32-bit float texels copied from `texels` (RGBA32F: 4 floats per texel,
/// R32F: 1); throws std::invalid_argument for other formats.
Texture floatTexture(Format format, uint32_t width, uint32_t height, const float* texels);

/// unorm8 -> float as lavapipe converts it: byte * (1.0f / 255.0f) (1 ulp off byte/255 for 126 values).
inline float unorm8ToFloat(uint8_t b) { return float(b) * (1.0f / 255.0f); }

}  // namespace emu
