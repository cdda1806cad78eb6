#include "emu/sampler.h"

#include <climits>
#include <cmath>
#include <cstring>

namespace emu {

const char* filterName(Filter f) { return f == Filter::Nearest ? "nearest" : "linear"; }
const char* addressName(AddressMode a) {
  switch (a) {
    case AddressMode::ClampToEdge: return "clamp";
    case AddressMode::Repeat: return "repeat";
    default: return "mirror";
  }
}

namespace {

// x86 cvttps2dq semantics (what LLVM's fptosi lowers to): out-of-range and NaN give INT_MIN.
int32_t itrunc(float x) {
  if (!(x > -2147483904.0f && x < 2147483648.0f)) return INT_MIN;
  return int32_t(x);
}
int32_t ifloor(float x) {
  if (!(x > -2147483904.0f && x < 2147483648.0f)) return INT_MIN;
  return int32_t(std::floor(x));
}
float fract(float x) { return x - std::floor(x); }
bool isPot(uint32_t n) { return (n & (n - 1)) == 0; }
int32_t clampi(int32_t v, int32_t lo, int32_t hi) { return v < lo ? lo : (v > hi ? hi : v); }
// minps/maxps operand order: NaN in the first operand returns the second.
float minSecondNonNan(float a, float b) { return a < b ? a : b; }
float maxSecondNonNan(float a, float b) { return a > b ? a : b; }

// Mirror function of Mesa's SoA sampler: 2 * (x/2 - round(x/2)), absolute value, NaN -> 0.
float mirror(float u) {
  float c = u * 0.5f;
  c = c - std::nearbyint(c);
  c = std::fabs(c + c);
  return maxSecondNonNan(c, 0.0f);
}

struct Linear1D {
  int32_t i0, i1;
  float w;
};

// Addressing for linear filtering, float path.
Linear1D wrapLinear(float u, uint32_t size, bool pot, AddressMode mode) {
  const float len = float(size);
  const int32_t last = int32_t(size) - 1;
  Linear1D r{};
  switch (mode) {
    case AddressMode::ClampToEdge: {
      float x = minSecondNonNan(u * len, len);
      x = x - 0.5f;
      x = maxSecondNonNan(x, 0.0f);
      r.i0 = itrunc(x);
      r.w = x - float(r.i0);
      r.i1 = r.i0 + 1 > last ? last : r.i0 + 1;
      break;
    }
    case AddressMode::Repeat:
      if (pot) {
        float x = u * len - 0.5f;
        r.i0 = ifloor(x);
        r.w = fract(x);
        r.i1 = (r.i0 + 1) & last;
        r.i0 &= last;
      } else {
        float x = fract(u) * len - 0.5f;
        bool neg = x < 0.0f;
        r.i0 = ifloor(x);
        r.w = fract(x);
        if (neg) r.i0 = last;
        r.i1 = r.i0 != last ? r.i0 + 1 : 0;
      }
      break;
    case AddressMode::MirroredRepeat: {
      float x = mirror(u) * len - 0.5f;
      r.i0 = ifloor(x);
      r.w = fract(x);
      r.i1 = r.i0 + 1 > last ? last : r.i0 + 1;
      r.i0 = r.i0 < 0 ? 0 : r.i0;
      break;
    }
  }
  return r;
}

// Addressing for nearest filtering, float path.
int32_t wrapNearest(float u, uint32_t size, bool pot, AddressMode mode) {
  const float len = float(size);
  const int32_t last = int32_t(size) - 1;
  switch (mode) {
    case AddressMode::ClampToEdge: return clampi(itrunc(u * len), 0, last);
    case AddressMode::Repeat:
      if (pot) return ifloor(u * len) & last;
      return itrunc(std::fmin(fract(u), 0x1.fffffep-1f) * len);
    case AddressMode::MirroredRepeat: {
      int32_t i = itrunc(mirror(u) * len);
      return i > last ? last : i;
    }
  }
  return 0;
}

Texel4 lerp(float w, Texel4 a, Texel4 b) {
  return {std::fma(w, b.r - a.r, a.r), std::fma(w, b.g - a.g, a.g), std::fma(w, b.b - a.b, a.b), std::fma(w, b.a - a.a, a.a)};
}

float quantizeWeight(float w, int bits) {
  if (bits <= 0) return w;
  const float scale = float(1 << bits);
  return std::nearbyint(w * scale) / scale;
}

Texel4 sampleLevelFloat(const Texture& t, const DeviceProfile& dev, uint32_t level, uint32_t layer, float u, float v,
                        Filter filter, AddressMode au, AddressMode av) {
  const uint32_t w = t.levelWidth(level), h = t.levelHeight(level);
  if (filter == Filter::Nearest) return t.loadFloat(level, layer, uint32_t(wrapNearest(u, w, isPot(t.width()), au)), uint32_t(wrapNearest(v, h, isPot(t.height()), av)));
  Linear1D x = wrapLinear(u, w, isPot(t.width()), au), y = wrapLinear(v, h, isPot(t.height()), av);
  float a = quantizeWeight(x.w, dev.filterWeightFracBits), b = quantizeWeight(y.w, dev.filterWeightFracBits);
  Texel4 t00 = t.loadFloat(level, layer, x.i0, y.i0), t10 = t.loadFloat(level, layer, x.i1, y.i0);
  Texel4 t01 = t.loadFloat(level, layer, x.i0, y.i1), t11 = t.loadFloat(level, layer, x.i1, y.i1);
  return lerp(b, lerp(a, t00, t10), lerp(a, t01, t11));
}

// ---- 8-bit fixed-point path (lavapipe's AoS sampler for RGBA8) ----
struct Fixed1D {
  int32_t i0, i1, w;  // w in [0, 255]
};

Fixed1D wrapFixed(float u, uint32_t size, bool pot, AddressMode mode) {
  const int32_t last = int32_t(size) - 1;
  Fixed1D r{};
  if (mode == AddressMode::Repeat && !pot) u = fract(u);
  float scaled = u * float(size);
  int32_t s = int32_t(std::nearbyint(scaled * 256.0f)) - 128;
  r.i0 = s >> 8;
  r.w = s & 255;
  r.i1 = r.i0 + 1;
  if (mode == AddressMode::Repeat) {
    if (pot) {
      r.i0 &= last;
      r.i1 &= last;
    } else {
      r.i0 = r.i0 < 0 ? last : r.i0;
      r.i1 = r.i1 > last ? 0 : r.i1;
    }
  } else {
    r.i0 = clampi(r.i0, 0, last);
    r.i1 = clampi(r.i1, 0, last);
  }
  return r;
}

using Bytes4 = std::array<uint8_t, 4>;
Bytes4 lerp8(Bytes4 a, Bytes4 b, int32_t w) {
  Bytes4 r;
  for (int c = 0; c < 4; ++c) r[c] = uint8_t(a[c] + ((w * (int32_t(b[c]) - a[c]) + 128) >> 8));
  return r;
}

Bytes4 sampleLevelFixed(const Texture& t, uint32_t level, uint32_t layer, float u, float v, Filter filter, AddressMode au,
                        AddressMode av) {
  const uint32_t w = t.levelWidth(level), h = t.levelHeight(level);
  if (filter == Filter::Nearest) return t.loadBytes(level, layer, uint32_t(wrapNearest(u, w, isPot(t.width()), au)), uint32_t(wrapNearest(v, h, isPot(t.height()), av)));
  Fixed1D x = wrapFixed(u, w, isPot(t.width()), au), y = wrapFixed(v, h, isPot(t.height()), av);
  Bytes4 r0 = lerp8(t.loadBytes(level, layer, x.i0, y.i0), t.loadBytes(level, layer, x.i1, y.i0), x.w);
  Bytes4 r1 = lerp8(t.loadBytes(level, layer, x.i0, y.i1), t.loadBytes(level, layer, x.i1, y.i1), x.w);
  return lerp8(r0, r1, y.w);
}

Texel4 toFloat(Bytes4 b) { return {unorm8ToFloat(b[0]), unorm8ToFloat(b[1]), unorm8ToFloat(b[2]), unorm8ToFloat(b[3])}; }

}  // namespace

Texel4 textureLod(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, float u, float v, float layerCoord, float lod) {
  // LOD: explicit lod + sampler bias, then the sampler's max and min clamps.
  float lambda = s.lodBias != 0.0f ? lod + s.lodBias : lod;
  lambda = minSecondNonNan(lambda, s.maxLod);
  lambda = maxSecondNonNan(lambda, s.minLod);
  const bool minify = lambda > 0.0f;
  const Filter filter = minify ? s.minFilter : s.magFilter;
  const int32_t maxLevel = int32_t(tex.levelCount()) - 1;
  const uint32_t layer = uint32_t(clampi(int32_t(std::nearbyint(layerCoord)), 0, int32_t(tex.layers()) - 1));
  // Linear mip filtering runs for every lane, magnified ones too (at level 0 with fraction 0),
  // except on single-level textures.
  const bool mipLerp = s.mipmapMode == MipmapMode::Linear && maxLevel > 0;
  int32_t l0 = 0, l1 = maxLevel > 0 ? 1 : 0;
  float f = 0.0f;
  if (minify) {
    if (s.mipmapMode == MipmapMode::Nearest) {
      l0 = clampi(int32_t(std::nearbyint(lambda)), 0, maxLevel);
    } else {
      float fl = std::floor(lambda);
      l0 = int32_t(fl);
      f = lambda - fl;
      if (l0 >= maxLevel) {
        l0 = maxLevel;
        f = 0.0f;
      }
      l1 = l0 + 1 > maxLevel ? maxLevel : l0 + 1;
    }
    if (dev.lodFractionBits > 0) f = std::floor(f * float(1 << dev.lodFractionBits)) / float(1 << dev.lodFractionBits);
  }
  const bool fixed = dev.unorm8FixedPoint && tex.format() == Format::RGBA8_UNORM &&
                     s.addressU != AddressMode::MirroredRepeat && s.addressV != AddressMode::MirroredRepeat;
  if (fixed) {
    Bytes4 c0 = sampleLevelFixed(tex, uint32_t(l0), layer, u, v, filter, s.addressU, s.addressV);
    int32_t lf = int32_t(f * 256.0f);
    if (lf == 0) return toFloat(c0);
    Bytes4 c1 = sampleLevelFixed(tex, uint32_t(l1), layer, u, v, filter, s.addressU, s.addressV);
    return toFloat(lerp8(c0, c1, lf));
  }
  Texel4 c0 = sampleLevelFloat(tex, dev, uint32_t(l0), layer, u, v, filter, s.addressU, s.addressV);
  // Mesa decides "need_lerp" per SIMD vector, so a lane whose fraction is 0 is usually still
  // lerped (fma(0, c1 - c0, c0)): same value for finite texels, NaN when c1 - c0 is not finite.
  // The emulator lerps whenever mip filtering is linear (per-vector grouping not modelled yet).
  if (!mipLerp) return c0;
  Texel4 c1 = sampleLevelFloat(tex, dev, uint32_t(l1), layer, u, v, filter, s.addressU, s.addressV);
  return lerp(f, c0, c1);
}

Texel4 texelFetch(const Texture& tex, int32_t x, int32_t y, int32_t layer, int32_t level) {
  return tex.loadFloat(uint32_t(level), uint32_t(layer), uint32_t(x), uint32_t(y));
}

void textureLodBatch(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, const float* q, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    Texel4 t = textureLod(tex, s, dev, q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);
    std::memcpy(out + 4 * i, &t, 16);
  }
}

}  // namespace emu
