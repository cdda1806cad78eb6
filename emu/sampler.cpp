#include "emu/sampler.h"

#include <climits>
#include <cmath>
#include <cstring>
#include <vector>

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

// Filter kinds of one lane: plain nearest, plain linear, or "nearest through the linear footprint"
// (Mesa's mipmap_both path for magnified lanes: weight 1 where the linear weight exceeds 1/2, else 0).
enum class LaneFilter { Nearest, Linear, NearestInLinear };

Texel4 sampleLevelFloat(const Texture& t, const DeviceProfile& dev, uint32_t level, uint32_t layer, float u, float v,
                        LaneFilter filter, AddressMode au, AddressMode av) {
  const uint32_t w = t.levelWidth(level), h = t.levelHeight(level);
  if (filter == LaneFilter::Nearest)
    return t.loadFloat(level, layer, uint32_t(wrapNearest(u, w, isPot(t.width()), au)),
                       uint32_t(wrapNearest(v, h, isPot(t.height()), av)));
  Linear1D x = wrapLinear(u, w, isPot(t.width()), au), y = wrapLinear(v, h, isPot(t.height()), av);
  float a = quantizeWeight(x.w, dev.filterWeightFracBits), b = quantizeWeight(y.w, dev.filterWeightFracBits);
  if (filter == LaneFilter::NearestInLinear) {
    a = x.w > 0.5f ? 1.0f : 0.0f;
    b = y.w > 0.5f ? 1.0f : 0.0f;
  }
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

namespace {

struct LodInfo {
  int32_t l0, l1;
  float f;      // mip fraction (linear mip), 0 at the clamped ends
  bool minify;  // lambda > 0
  uint32_t layer;
};

// LOD selection as Mesa's lod_selector + linear/nearest mip level code: explicit lod + sampler
// bias, then max/min lod clamps; linear: floor/fraction with both levels clamped to
// [0, last] and the fraction zeroed where clamped; nearest: rint, clamped.
LodInfo selectLod(const Texture& tex, const SamplerDesc& s, float layerCoord, float lod) {
  LodInfo r{};
  float lambda = s.lodBias != 0.0f ? lod + s.lodBias : lod;
  lambda = minSecondNonNan(lambda, s.maxLod);
  if (s.minLod > 0.0f) lambda = maxSecondNonNan(lambda, s.minLod);  // Mesa applies min_lod only when > 0
  r.minify = lambda > 0.0f;
  const int32_t last = int32_t(tex.levelCount()) - 1;
  r.layer = uint32_t(clampi(int32_t(std::nearbyint(layerCoord)), 0, int32_t(tex.layers()) - 1));
  if (last == 0) return r;  // single level: no mip filtering at all
  if (s.mipmapMode == MipmapMode::Nearest) {
    r.l0 = r.l1 = clampi(int32_t(std::nearbyint(lambda)), 0, last);
    return r;
  }
  float fl = std::floor(lambda);
  r.l0 = ifloor(lambda);
  r.f = lambda - fl;
  r.l1 = r.l0 + 1;
  if (r.l0 < 0) { r.l0 = r.l1 = 0; r.f = 0.0f; }
  if (r.l0 >= last) { r.l0 = r.l1 = last; r.f = 0.0f; }
  return r;
}

struct VectorFlags {
  bool needLerp = false;    // some lane has a mip fraction > 0
  bool needLinear = false;  // some lane needs the linear filter (mixed mag/min only)
};

bool laneWantsLinear(const SamplerDesc& s, bool minify) {
  return (minify ? s.minFilter : s.magFilter) == Filter::Linear;
}

Texel4 sampleOne(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, float u, float v, const LodInfo& L,
                 VectorFlags vf) {
  const bool mipLinear = s.mipmapMode == MipmapMode::Linear && tex.levelCount() > 1;
  const bool mixed = s.minFilter != s.magFilter;
  const bool fixed = dev.unorm8FixedPoint && tex.format() == Format::RGBA8_UNORM && !mixed &&
                     s.addressU != AddressMode::MirroredRepeat && s.addressV != AddressMode::MirroredRepeat;
  if (fixed) {  // AoS: per-lane lerp8 with weight 0 is exact, so vector grouping is invisible
    const Filter filter = L.minify ? s.minFilter : s.magFilter;
    Bytes4 c0 = sampleLevelFixed(tex, uint32_t(L.l0), L.layer, u, v, filter, s.addressU, s.addressV);
    int32_t lf = int32_t(L.f * 256.0f);
    if (!mipLinear || lf == 0) return toFloat(c0);
    Bytes4 c1 = sampleLevelFixed(tex, uint32_t(L.l1), L.layer, u, v, filter, s.addressU, s.addressV);
    return toFloat(lerp8(c0, c1, lf));
  }
  LaneFilter lane;
  int32_t l0 = L.l0, l1 = L.l1;
  float f = L.f;
  bool lerpLevels = mipLinear && vf.needLerp;
  if (!mixed) {
    lane = s.minFilter == Filter::Linear ? LaneFilter::Linear : LaneFilter::Nearest;
  } else if (vf.needLinear) {  // combined path: linear footprint, nearest lanes by weight
    lane = laneWantsLinear(s, L.minify) ? LaneFilter::Linear : LaneFilter::NearestInLinear;
  } else {  // every lane nearest: the cheap path; without mip filtering when min is the linear one
    lane = LaneFilter::Nearest;
    if (s.minFilter == Filter::Linear) {
      l0 = 0;
      lerpLevels = false;
    }
  }
  Texel4 c0 = sampleLevelFloat(tex, dev, uint32_t(l0), L.layer, u, v, lane, s.addressU, s.addressV);
  if (!lerpLevels) return c0;
  if (dev.lodFractionBits > 0) f = std::floor(f * float(1 << dev.lodFractionBits)) / float(1 << dev.lodFractionBits);
  Texel4 c1 = sampleLevelFloat(tex, dev, uint32_t(l1), L.layer, u, v, lane, s.addressU, s.addressV);
  return lerp(f, c0, c1);
}

}  // namespace

Texel4 textureLod(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, float u, float v, float layerCoord, float lod) {
  LodInfo L = selectLod(tex, s, layerCoord, lod);
  VectorFlags vf{L.f > 0.0f, laneWantsLinear(s, L.minify)};  // a vector of one lane
  return sampleOne(tex, s, dev, u, v, L, vf);
}

void textureLodBatch(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, const float* q, float* out, size_t n,
                     const uint32_t* vectorOf) {
  std::vector<LodInfo> lods(n);
  std::vector<VectorFlags> flags;
  for (size_t i = 0; i < n; ++i) {
    lods[i] = selectLod(tex, s, q[4 * i + 2], q[4 * i + 3]);
    size_t g = vectorOf ? vectorOf[i] : i;
    if (g >= flags.size()) flags.resize(g + 1);
    flags[g].needLerp |= lods[i].f > 0.0f;
    flags[g].needLinear |= laneWantsLinear(s, lods[i].minify);
  }
  for (size_t i = 0; i < n; ++i) {
    Texel4 t = sampleOne(tex, s, dev, q[4 * i], q[4 * i + 1], lods[i], flags[vectorOf ? vectorOf[i] : i]);
    std::memcpy(out + 4 * i, &t, 16);
  }
}

Texel4 texelFetch(const Texture& tex, int32_t x, int32_t y, int32_t layer, int32_t level) {
  return tex.loadFloat(uint32_t(level), uint32_t(layer), uint32_t(x), uint32_t(y));
}

}  // namespace emu
