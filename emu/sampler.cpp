#include "emu/sampler.h"

#include <climits>
#include <cmath>
#include <atomic>
#include <cstring>
#include <type_traits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "emu/lanes.h"
#include "emu/sampler_reactor.h"

namespace emu {

const char* addressName(AddressMode a) {
  switch (a) {
    case AddressMode::ClampToEdge: return "clamp";
    case AddressMode::Repeat: return "repeat";
    default: return "mirror";
  }
}

namespace {

// ---- Lane helpers: one overload per lane kind, so the float path below is one source for a single
// lane (float / int32_t / bool: the model) and for emu lanes (the batch path). ----
template <class F> struct LaneOf;
template <> struct LaneOf<float> { using I = int32_t; using M = bool; };
template <int N> struct LaneOf<F32<N>> { using I = I32<N>; using M = Mask<N>; };

inline float sel(bool m, float a, float b) { return m ? a : b; }
inline int32_t sel(bool m, int32_t a, int32_t b) { return m ? a : b; }
template <class T, class M> T sel(M m, T a, T b) { return select(m, a, b); }

inline float lfloor(float x) { return std::floor(x); }
inline float lrint(float x) { return std::nearbyint(x); }
inline float labs(float x) { return std::fabs(x); }
inline float lfma(float a, float b, float c) { return std::fma(a, b, c); }
template <int N> F32<N> lfloor(F32<N> x) { for (int i = 0; i < N; ++i) x.v[i] = __builtin_floorf(x.v[i]); return x; }
template <int N> F32<N> lrint(F32<N> x) { for (int i = 0; i < N; ++i) x.v[i] = __builtin_nearbyintf(x.v[i]); return x; }
template <int N> F32<N> labs(F32<N> x) { return uintBitsToFloat(floatBitsToUint(x) & 0x7fffffffu); }
template <int N> F32<N> lfma(F32<N> a, F32<N> b, F32<N> c) { return fmaLanes(a, b, c); }
inline float toF(int32_t i) { return float(i); }
template <int N> F32<N> toF(I32<N> i) { return F32<N>(i); }

// x86 cvttps2dq semantics (what LLVM's fptosi lowers to): out-of-range and NaN give INT_MIN.
template <class F> typename LaneOf<F>::I ltrunc(F x) {
  using I = typename LaneOf<F>::I;
  auto inRange = x > -2147483904.0f && x < 2147483648.0f;
  F safe = sel(inRange, x, F(0.0f));
  I t;
  if constexpr (std::is_same_v<F, float>) t = int32_t(safe);
  else t = I(safe);
  return sel(inRange, t, I(INT_MIN));
}
template <class F> typename LaneOf<F>::I lifloor(F x) { return ltrunc(lfloor(x)); }
template <class F> F lfract(F x) { return x - lfloor(x); }
// minps/maxps operand order: NaN in the first operand returns the second.
template <class F> F minSecondNonNan(F a, F b) { return sel(a < b, a, b); }
template <class F> F maxSecondNonNan(F a, F b) { return sel(a > b, a, b); }

inline int32_t imax(int32_t a, int32_t b) { return a > b ? a : b; }
template <int N> I32<N> imax(I32<N> a, I32<N> b) { return select(a > b, a, b); }

bool isPot(uint32_t n) { return (n & (n - 1)) == 0; }
int32_t clampi(int32_t v, int32_t lo, int32_t hi) { return v < lo ? lo : (v > hi ? hi : v); }

// Mirror function of Mesa's SoA sampler: 2 * (x/2 - round(x/2)), absolute value, NaN -> 0.
template <class F> F mirror(F u) {
  F c = u * 0.5f;
  c = c - lrint(c);
  c = labs(c + c);
  return maxSecondNonNan(c, F(0.0f));
}

template <class F> struct Linear1D {
  typename LaneOf<F>::I i0, i1;
  F w;
};

// Addressing for linear filtering, float path. `size` is the sampled level's size per lane;
// `pot` is the base level's (Mesa's static pot_width / pot_height).
template <class F> Linear1D<F> wrapLinear(F u, typename LaneOf<F>::I size, bool pot, AddressMode mode) {
  using I = typename LaneOf<F>::I;
  const F len = toF(size);
  const I last = size - 1;
  Linear1D<F> r{};
  switch (mode) {
    case AddressMode::ClampToEdge: {
      F x = minSecondNonNan(u * len, len);
      x = x - 0.5f;
      x = maxSecondNonNan(x, F(0.0f));
      r.i0 = ltrunc(x);
      r.w = x - toF(r.i0);
      r.i1 = sel(r.i0 + 1 > last, last, r.i0 + 1);
      break;
    }
    case AddressMode::Repeat:
      if (pot) {
        F x = u * len - 0.5f;
        r.i0 = lifloor(x);
        r.w = lfract(x);
        r.i1 = (r.i0 + 1) & last;
        r.i0 = r.i0 & last;
      } else {
        F x = lfract(u) * len - 0.5f;
        auto neg = x < 0.0f;
        r.i0 = sel(neg, last, lifloor(x));
        r.w = lfract(x);
        r.i1 = sel(r.i0 != last, r.i0 + 1, I(0));
      }
      break;
    case AddressMode::MirroredRepeat: {
      F x = mirror(u) * len - 0.5f;
      r.i0 = lifloor(x);
      r.w = lfract(x);
      r.i1 = sel(r.i0 + 1 > last, last, r.i0 + 1);
      r.i0 = sel(r.i0 < 0, I(0), r.i0);
      break;
    }
  }
  return r;
}

// Addressing for nearest filtering, float path.
template <class F> typename LaneOf<F>::I wrapNearest(F u, typename LaneOf<F>::I size, bool pot, AddressMode mode) {
  using I = typename LaneOf<F>::I;
  const F len = toF(size);
  const I last = size - 1;
  switch (mode) {
    case AddressMode::ClampToEdge: {
      I i = ltrunc(u * len);
      return sel(i < 0, I(0), sel(i > last, last, i));
    }
    case AddressMode::Repeat:
      if (pot) return lifloor(u * len) & last;
      return ltrunc(minSecondNonNan(lfract(u), F(0x1.fffffep-1f)) * len);  // = fmin: NaN -> the constant
    case AddressMode::MirroredRepeat: {
      I i = ltrunc(mirror(u) * len);
      return sel(i > last, last, i);
    }
  }
  return I(0);
}

template <class F> struct C4 {
  F r, g, b, a;
};

// One filter lerp per channel: fused fma(w, b - a, a), or a + w (b - a) with a separate multiply and add
// (DeviceProfile::filterLerpFma).
template <class F> F lerp1(F w, F a, F b, bool fused) {
  if (fused) return lfma(w, b - a, a);
  const F p = w * (b - a);
  return a + p;
}
template <class F> C4<F> lerp4(F w, C4<F> a, C4<F> b, bool fused) {
  return {lerp1(w, a.r, b.r, fused), lerp1(w, a.g, b.g, fused), lerp1(w, a.b, b.b, fused), lerp1(w, a.a, b.a, fused)};
}

// Texel loads: one lane reads directly, emu lanes gather.
// scaled: RGBA8 texels as float(b << 8), what SwiftShader's 32-bit filtering of normalized formats
// blends before it scales the result by 1.0f / 0xFF00 (DeviceProfile::Unorm8Path::FloatScaled).
inline C4<float> loadTexel(const Texture& t, int32_t level, int32_t layer, int32_t x, int32_t y, bool scaled = false) {
  if (scaled) {
    const auto b = t.loadBytes(uint32_t(level), uint32_t(layer), uint32_t(x), uint32_t(y));
    return {float(b[0] << 8), float(b[1] << 8), float(b[2] << 8), float(b[3] << 8)};
  }
  Texel4 v = t.loadFloat(uint32_t(level), uint32_t(layer), uint32_t(x), uint32_t(y));
  return {v.r, v.g, v.b, v.a};
}
bool pointFilter(const SamplerDesc& s) { return s.magFilter == Filter::Nearest && s.minFilter == Filter::Nearest; }
// The RGBA8 path a profile takes for sampler s (Unorm8Path::Reactor resolved).
DeviceProfile::Unorm8Path unorm8Path(const DeviceProfile& dev, const SamplerDesc& s) {
  using U = DeviceProfile::Unorm8Path;
  if (dev.unorm8Path != U::Reactor) return dev.unorm8Path;
  return pointFilter(s) ? U::Fixed16 : U::FloatScaled;
}
bool scaledUnorm8(const Texture& t, const DeviceProfile& dev, const SamplerDesc& s) {
  return t.format() == Format::RGBA8_UNORM && unorm8Path(dev, s) == DeviceProfile::Unorm8Path::FloatScaled;
}
template <int N>
C4<F32<N>> loadTexel(const Texture& t, I32<N> level, I32<N> layer, I32<N> x, I32<N> y) {
  C4<F32<N>> c;
  if (t.format() == Format::RGBA32F) {  // the common HDR case: offsets as lanes, direct 16-byte loads
    const I32<N> w = imax(I32<N>(int32_t(t.width())) >> level, I32<N>(1));
    const I32<N> h = imax(I32<N>(int32_t(t.height())) >> level, I32<N>(1));
    const I32<N> texel = (layer * h + y) * w + x;
    for (int i = 0; i < N; ++i) {
      float v[4];
      std::memcpy(v, t.levels()[size_t(level[i])].data() + size_t(uint32_t(texel[i])) * 16, 16);
      c.r.v[i] = v[0];
      c.g.v[i] = v[1];
      c.b.v[i] = v[2];
      c.a.v[i] = v[3];
    }
    return c;
  }
  for (int i = 0; i < N; ++i) {
    Texel4 v = t.loadFloat(uint32_t(level[i]), uint32_t(layer[i]), uint32_t(x[i]), uint32_t(y[i]));
    c.r.v[i] = v.r;
    c.g.v[i] = v.g;
    c.b.v[i] = v.b;
    c.a.v[i] = v.a;
  }
  return c;
}

// Filter kinds of one call: plain nearest, plain linear, "nearest through the linear footprint"
// (Mesa's mipmap_both path for magnified lanes: weight 1 where the linear weight exceeds 1/2, else 0),
// or the linear arithmetic with its half-texel offset and +1 step masked off (SwiftShader's mixed
// filters on their nearest side: both taps are one texel, still blended).
enum class LaneFilter { Nearest, Linear, NearestInLinear, LinearNoOffset };

template <class F>
F weight(F w, const DeviceProfile& dev, LaneFilter filter) {
  if (filter == LaneFilter::NearestInLinear) return sel(w > 0.5f, F(1.0f), F(0.0f));
  if (dev.filterWeightFracBits <= 0) return w;
  const float scale = float(1 << dev.filterWeightFracBits);
  return lrint(w * scale) * (1.0f / scale);
}

typedef float Px __attribute__((vector_size(16)));
inline Px loadPx(const uint8_t* p) {
  Px r;
  std::memcpy(&r, p, 16);
  return r;
}
inline Px lerpPx(float w, Px a, Px b, bool fused) {
  const Px d = b - a;
  Px r;
  if (fused)
    for (int c = 0; c < 4; ++c) r[c] = __builtin_fmaf(w, d[c], a[c]);
  else
    for (int c = 0; c < 4; ++c) {
      const float p = w * d[c];
      r[c] = a[c] + p;
    }
  return r;
}

// One level, one lane, SwiftShader's addressing (DeviceProfile::TexAddressing::Reactor).
C4<float> sampleLevelReactor(const Texture& t, const DeviceProfile& dev, int32_t level, int32_t layer, float u, float v,
                             LaneFilter filter, AddressMode au, AddressMode av, bool sc) {
  const int32_t w = int32_t(t.levelWidth(uint32_t(level))), h = int32_t(t.levelHeight(uint32_t(level)));
  const bool point = filter == LaneFilter::Nearest, offset = filter != LaneFilter::LinearNoOffset;
  const reactor::Axis x = reactor::addressFloat(u, w, au, point, offset), y = reactor::addressFloat(v, h, av, point, offset);
  if (t.format() == Format::RGBA32F && !sc) {  // whole texels as 4-float vectors: the same per-channel operations
    const uint8_t* base = t.levels()[size_t(level)].data();
    auto at = [&](int32_t xi, int32_t yi) { return loadPx(base + ((size_t(layer) * size_t(h) + size_t(yi)) * size_t(w) + size_t(xi)) * 16); };
    Px c;
    if (point) {
      c = at(x.i0, y.i0);
    } else {
      const float a = weight(x.f, dev, filter), b = weight(y.f, dev, filter);
      const bool fused = dev.filterLerpFma;
      c = lerpPx(b, lerpPx(a, at(x.i0, y.i0), at(x.i1, y.i0), fused), lerpPx(a, at(x.i0, y.i1), at(x.i1, y.i1), fused), fused);
    }
    return {c[0], c[1], c[2], c[3]};
  }
  if (point) return loadTexel(t, level, layer, x.i0, y.i0, sc);
  const float a = weight(x.f, dev, filter), b = weight(y.f, dev, filter);
  C4<float> t00 = loadTexel(t, level, layer, x.i0, y.i0, sc), t10 = loadTexel(t, level, layer, x.i1, y.i0, sc);
  C4<float> t01 = loadTexel(t, level, layer, x.i0, y.i1, sc), t11 = loadTexel(t, level, layer, x.i1, y.i1, sc);
  const bool fused = dev.filterLerpFma;
  return lerp4(b, lerp4(a, t00, t10, fused), lerp4(a, t01, t11, fused), fused);
}

template <class F>
C4<F> sampleLevelFloat(const Texture& t, const DeviceProfile& dev, typename LaneOf<F>::I level,
                       typename LaneOf<F>::I layer, F u, F v, LaneFilter filter, AddressMode au, AddressMode av,
                       bool scaled = false) {
  using I = typename LaneOf<F>::I;
  if constexpr (std::is_same_v<F, float>)
    if (dev.texAddressing == DeviceProfile::TexAddressing::Reactor)
      return sampleLevelReactor(t, dev, level, layer, u, v, filter, au, av, scaled);
  const I w = imax(I(int32_t(t.width())) >> level, I(1)), h = imax(I(int32_t(t.height())) >> level, I(1));
  const bool potW = isPot(t.width()), potH = isPot(t.height());
  auto load = [&](I x, I y) {
    if constexpr (std::is_same_v<F, float>) return loadTexel(t, level, layer, x, y, scaled);
    else return loadTexel(t, level, layer, x, y);  // lane blocks never run FloatScaled (perLane)
  };
  if (filter == LaneFilter::Nearest) return load(wrapNearest(u, w, potW, au), wrapNearest(v, h, potH, av));
  Linear1D<F> x = wrapLinear(u, w, potW, au), y = wrapLinear(v, h, potH, av);
  F a = weight(x.w, dev, filter), b = weight(y.w, dev, filter);
  C4<F> t00 = load(x.i0, y.i0), t10 = load(x.i1, y.i0);
  C4<F> t01 = load(x.i0, y.i1), t11 = load(x.i1, y.i1);
  const bool fused = dev.filterLerpFma;
  return lerp4(b, lerp4(a, t00, t10, fused), lerp4(a, t01, t11, fused), fused);
}


// ---- 8-bit fixed-point path (lavapipe's AoS sampler for RGBA8) ----
struct Fixed1D {
  int32_t i0, i1, w;  // w in [0, 255]
};

Fixed1D wrapFixed(float u, uint32_t size, bool pot, AddressMode mode) {
  const int32_t last = int32_t(size) - 1;
  Fixed1D r{};
  if (mode == AddressMode::Repeat && !pot) u = lfract(u);
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
  if (filter == Filter::Nearest)
    return t.loadBytes(level, layer, uint32_t(wrapNearest(u, int32_t(w), isPot(t.width()), au)),
                       uint32_t(wrapNearest(v, int32_t(h), isPot(t.height()), av)));
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
  float f;      // mip fraction (linear mip), 0 at the clamped ends (Gallivm)
  bool minify;  // lambda > 0
  uint32_t layer;
  float lambda;  // the clamped LOD (Reactor's 16-bit path takes its mip weight from it)
};

// LOD selection as Mesa's lod_selector + linear/nearest mip level code: explicit lod + sampler
// bias, then max/min lod clamps; linear: floor/fraction with both levels clamped to
// [0, last] and the fraction zeroed where clamped; nearest: rint, clamped.
LodInfo selectLod(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, float layerCoord, float lod) {
  LodInfo r{};
  if (dev.mipSelection == DeviceProfile::MipSelection::Reactor) {
    const reactor::Lod L = reactor::selectLod(tex, s, lod);
    r.l0 = L.l0, r.l1 = L.l1, r.f = L.f, r.lambda = L.lod, r.minify = L.lod > 0.0f;
    r.layer = uint32_t(clampi(int32_t(std::nearbyint(layerCoord)), 0, int32_t(tex.layers()) - 1));
    return r;
  }
  float lambda = s.lodBias != 0.0f ? lod + s.lodBias : lod;
  lambda = minSecondNonNan(lambda, s.maxLod);
  if (s.minLod > 0.0f) lambda = maxSecondNonNan(lambda, s.minLod);  // Mesa applies min_lod only when > 0
  r.minify = lambda > 0.0f;
  r.lambda = lambda;
  const int32_t last = int32_t(tex.levelCount()) - 1;
  r.layer = uint32_t(clampi(int32_t(std::nearbyint(layerCoord)), 0, int32_t(tex.layers()) - 1));
  if (last == 0) return r;  // single level: no mip filtering at all
  if (s.mipmapMode == MipmapMode::Nearest) {
    r.l0 = r.l1 = clampi(int32_t(std::nearbyint(lambda)), 0, last);
    return r;
  }
  float fl = std::floor(lambda);
  r.l0 = lifloor(lambda);
  r.f = lambda - fl;
  r.l1 = r.l0 + 1;
  if (r.l0 < 0) { r.l0 = r.l1 = 0; r.f = 0.0f; }
  if (r.l0 >= last) { r.l0 = r.l1 = last; r.f = 0.0f; }
  return r;
}

struct VectorFlags {
  bool needLerp = false;    // some lane has a mip fraction > 0
  bool needLinear = false;  // some lane needs the linear filter (mixed mag/min only)
  bool anyMinify = false;   // some lane is minified (the "both" path lerps levels on this)
};

template <class F> F lodFraction(F f, const DeviceProfile& dev) {
  if (dev.lodFractionBits <= 0) return f;
  const float scale = float(1 << dev.lodFractionBits);
  return lfloor(f * scale) * (1.0f / scale);
}

bool laneWantsLinear(const SamplerDesc& s, bool minify) {
  return (minify ? s.minFilter : s.magFilter) == Filter::Linear;
}

// Which path a sampler/texture pair takes: mixed mag/min filters (per-lane "both" path), lavapipe's
// 8-bit fixed-point path (RGBA8, equal filters, no mirrored repeat), and whether mip levels lerp.
// perLane: a strategy the 8-lane blocks do not implement (SwiftShader's), so every lane runs sampleOne.
struct SamplerPaths {
  bool mixed, fixed, mipLinear, fixed16, perLane;
};
SamplerPaths samplerPaths(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev) {
  const bool mixed = s.minFilter != s.magFilter;
  const bool rgba8 = tex.format() == Format::RGBA8_UNORM;
  const bool reactorMip = dev.mipSelection == DeviceProfile::MipSelection::Reactor;
  const DeviceProfile::Unorm8Path path = unorm8Path(dev, s);
  const bool fixed16 = path == DeviceProfile::Unorm8Path::Fixed16 && rgba8;
  return {mixed,
          path == DeviceProfile::Unorm8Path::Fixed8 && rgba8 && (!mixed || s.lodPerQuad) &&
              s.addressU != AddressMode::MirroredRepeat && s.addressV != AddressMode::MirroredRepeat,
          s.mipmapMode == MipmapMode::Linear && (tex.levelCount() > 1 || reactorMip), fixed16,
          fixed16 || reactorMip || dev.texAddressing == DeviceProfile::TexAddressing::Reactor ||
              (rgba8 && path == DeviceProfile::Unorm8Path::FloatScaled)};
}

Texel4 sampleOne(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, float u, float v, const LodInfo& L,
                 VectorFlags vf) {
  const auto [mixed, fixed, mipLinear, fixed16, perLane] = samplerPaths(tex, s, dev);
  if (fixed16) {
    const reactor::Lod R{L.lambda, L.l0, L.l1, L.f};
    return reactor::sampleUnorm16(tex, s, R, L.layer, u, v);
  }
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
  if (dev.mipSelection == DeviceProfile::MipSelection::Reactor) {  // per lane, always blended
    lerpLevels = mipLinear;
    if (!mixed) lane = s.minFilter == Filter::Linear ? LaneFilter::Linear : LaneFilter::Nearest;
    else lane = laneWantsLinear(s, L.minify) ? LaneFilter::Linear : LaneFilter::LinearNoOffset;
  } else if (!mixed) {
    lane = s.minFilter == Filter::Linear ? LaneFilter::Linear : LaneFilter::Nearest;
  } else if (vf.needLinear) {  // combined path: linear footprint, nearest lanes by weight;
    // it lerps levels when any lane of the vector is minified (Mesa: need_lerp = any(lod_positive))
    lane = laneWantsLinear(s, L.minify) ? LaneFilter::Linear : LaneFilter::NearestInLinear;
    lerpLevels = mipLinear && vf.anyMinify;
  } else {  // every lane nearest: the cheap path; without mip filtering when min is the linear one
    lane = LaneFilter::Nearest;
    if (s.minFilter == Filter::Linear) {
      l0 = 0;
      lerpLevels = false;
    }
  }
  const int32_t layer = int32_t(L.layer);
  const bool scaled = scaledUnorm8(tex, dev, s);
  C4<float> c = sampleLevelFloat<float>(tex, dev, l0, layer, u, v, lane, s.addressU, s.addressV, scaled);
  if (lerpLevels) {
    C4<float> c1 = sampleLevelFloat<float>(tex, dev, l1, layer, u, v, lane, s.addressU, s.addressV, scaled);
    c = lerp4(lodFraction(f, dev), c, c1, dev.filterLerpFma);
  }
  if (scaled) {
    const float k = 1.0f / float(0xFF00);
    return {c.r * k, c.g * k, c.b * k, c.a * k};
  }
  return {c.r, c.g, c.b, c.a};
}

// RGBA32F bilinear/trilinear, the HDR hot path: addressing and weights in lanes (the same
// wrapLinear/weight templates), then per lane on whole texels: a texel is one 4-float vector, so the
// four channels lerp together with no SoA transposes of the 8 (or 16) texels per lane. Per channel
// these are exactly the operations of lerp4 (fma(w, b - a, a)), so the bits are the same
// (tests/texture_test.cpp: batch == one-lane model).
template <int N>
struct LevelTaps {
  I32<N> o00, o10, o01, o11;  // byte offsets of the four texels
  F32<N> a, b;                // weights
};

template <int N>
LevelTaps<N> levelTaps(const Texture& t, const DeviceProfile& dev, I32<N> level, I32<N> layer, F32<N> u, F32<N> v,
                       AddressMode au, AddressMode av) {
  using I = I32<N>;
  const I w = imax(I(int32_t(t.width())) >> level, I(1)), h = imax(I(int32_t(t.height())) >> level, I(1));
  Linear1D<F32<N>> x = wrapLinear(u, w, isPot(t.width()), au), y = wrapLinear(v, h, isPot(t.height()), av);
  LevelTaps<N> r;
  r.a = weight(x.w, dev, LaneFilter::Linear);
  r.b = weight(y.w, dev, LaneFilter::Linear);
  const I row0 = (layer * h + y.i0) * w, row1 = (layer * h + y.i1) * w;
  r.o00 = (row0 + x.i0) << 4;
  r.o10 = (row0 + x.i1) << 4;
  r.o01 = (row1 + x.i0) << 4;
  r.o11 = (row1 + x.i1) << 4;
  return r;
}

template <int N>
Px bilinearPx(const uint8_t* base, const LevelTaps<N>& t, int i, bool fused) {
  const float a = t.a[i];
  Px r0 = lerpPx(a, loadPx(base + uint32_t(t.o00[i])), loadPx(base + uint32_t(t.o10[i])), fused);
  Px r1 = lerpPx(a, loadPx(base + uint32_t(t.o01[i])), loadPx(base + uint32_t(t.o11[i])), fused);
  return lerpPx(t.b[i], r0, r1, fused);
}

template <int N>
void sampleBlockLinearRgba32f(const Texture& tex, const DeviceProfile& dev, I32<N> l0, I32<N> l1, I32<N> layer, F32<N> u,
                              F32<N> v, F32<N> f, const bool* lerpLane, bool anyLerp, AddressMode au, AddressMode av,
                              float* out, int count) {
  const LevelTaps<N> t0 = levelTaps(tex, dev, l0, layer, u, v, au, av);
  LevelTaps<N> t1{};
  F32<N> fq(0.0f);
  if (anyLerp) {
    t1 = levelTaps(tex, dev, l1, layer, u, v, au, av);
    fq = lodFraction(f, dev);
  }
  const auto& levels = tex.levels();
  for (int i = 0; i < count; ++i) {
    Px c = bilinearPx(levels[size_t(l0[i])].data(), t0, i, dev.filterLerpFma);
    if (lerpLane[i]) c = lerpPx(fq[i], c, bilinearPx(levels[size_t(l1[i])].data(), t1, i, dev.filterLerpFma), dev.filterLerpFma);
    std::memcpy(out + 4 * i, &c, 16);
  }
}

// Eight lanes of the float path with equal mag/min filters: the same template code as the one-lane
// model above, on emu lanes (tests/texture_test.cpp checks the two agree bit for bit).
constexpr int kLanes = 8;
void sampleBlock(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, const float* q, const LodInfo* L,
                 const bool* lerpLane, float* out, int count) {
  using F = F32<kLanes>;
  using I = I32<kLanes>;
  F u(0.0f), v(0.0f), f(0.0f);
  I l0(0), l1(0), layer(0);
  Mask<kLanes> lerpMask(false);
  bool anyLerp = false;
  for (int i = 0; i < count; ++i) {
    u.v[i] = q[4 * i];
    v.v[i] = q[4 * i + 1];
    f.v[i] = L[i].f;
    l0.v[i] = L[i].l0;
    l1.v[i] = L[i].l1;
    layer.v[i] = int32_t(L[i].layer);
    lerpMask.v[i] = lerpLane[i] ? -1 : 0;
    anyLerp |= lerpLane[i];
  }
  const LaneFilter lane = s.minFilter == Filter::Linear ? LaneFilter::Linear : LaneFilter::Nearest;
  if (lane == LaneFilter::Linear && tex.format() == Format::RGBA32F) {
    sampleBlockLinearRgba32f(tex, dev, l0, l1, layer, u, v, f, lerpLane, anyLerp, s.addressU, s.addressV, out, count);
    return;
  }
  C4<F> c = sampleLevelFloat<F>(tex, dev, l0, layer, u, v, lane, s.addressU, s.addressV);
  if (anyLerp) {
    C4<F> c1 = sampleLevelFloat<F>(tex, dev, l1, layer, u, v, lane, s.addressU, s.addressV);
    C4<F> m = lerp4(lodFraction(f, dev), c, c1, dev.filterLerpFma);
    c = {select(lerpMask, m.r, c.r), select(lerpMask, m.g, c.g), select(lerpMask, m.b, c.b), select(lerpMask, m.a, c.a)};
  }
  for (int i = 0; i < count; ++i) {
    out[4 * i] = c.r[i];
    out[4 * i + 1] = c.g[i];
    out[4 * i + 2] = c.b[i];
    out[4 * i + 3] = c.a[i];
  }
}

}  // namespace

Texel4 textureLod(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, float u, float v, float layerCoord, float lod) {
  LodInfo L = selectLod(tex, s, dev, layerCoord, lod);
  VectorFlags vf{L.f > 0.0f, laneWantsLinear(s, L.minify), L.minify};  // a vector of one lane
  return sampleOne(tex, s, dev, u, v, L, vf);
}

void textureLodBatch(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, Stage stage, const float* q,
                     float* out, size_t n, const uint32_t* vectorOf) {
  const bool flush = dev.denorm(stage) == DenormMode::Flush;
  // Per-vector decisions (only when lanes are grouped): bit 0 need lerp, bit 1 need linear, bit 2 any
  // minified. Vectors may span blocks (fragment layouts), hence the atomic OR. selectLod runs again in
  // the sampling pass: recomputing it is cheaper than storing a LodInfo per query (measured).
  std::vector<uint8_t> flags;
  if (vectorOf) {
    uint32_t groups = 0;
    for (size_t i = 0; i < n; ++i) groups = std::max(groups, vectorOf[i] + 1);
    flags.assign(groups, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 8192), [&](const tbb::blocked_range<size_t>& r) {
      DenormalScope mode(flush);
      for (size_t i = r.begin(); i != r.end(); ++i) {
        LodInfo L = selectLod(tex, s, dev, q[4 * i + 2], q[4 * i + 3]);
        uint8_t bits = uint8_t((L.f > 0.0f ? 1 : 0) | (laneWantsLinear(s, L.minify) ? 2 : 0) | (L.minify ? 4 : 0));
        if (bits) std::atomic_ref<uint8_t>(flags[vectorOf[i]]).fetch_or(bits, std::memory_order_relaxed);
      }
    });
  }
  auto vectorFlags = [&](size_t i, const LodInfo& L) {
    if (!vectorOf) return VectorFlags{L.f > 0.0f, laneWantsLinear(s, L.minify), L.minify};
    uint8_t b = flags[vectorOf[i]];
    return VectorFlags{(b & 1) != 0, (b & 2) != 0, (b & 4) != 0};
  };
  const auto [mixed, fixed, mipLinear, fixed16, perLane] = samplerPaths(tex, s, dev);
  const size_t blocks = (n + kLanes - 1) / kLanes;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks, 256), [&](const tbb::blocked_range<size_t>& r) {
    DenormalScope mode(flush);
    for (size_t b = r.begin(); b != r.end(); ++b) {
      const size_t i0 = b * kLanes;
      const int count = int(std::min<size_t>(kLanes, n - i0));
      LodInfo lods[kLanes];
      bool lerpLane[kLanes] = {};
      for (int k = 0; k < count; ++k) {
        const size_t i = i0 + size_t(k);
        lods[k] = selectLod(tex, s, dev, q[4 * i + 2], q[4 * i + 3]);
        if (mixed || fixed || perLane) {  // per-lane paths
          Texel4 t = sampleOne(tex, s, dev, q[4 * i], q[4 * i + 1], lods[k], vectorFlags(i, lods[k]));
          std::memcpy(out + 4 * i, &t, 16);
        } else {
          lerpLane[k] = mipLinear && vectorFlags(i, lods[k]).needLerp;
        }
      }
      if (!mixed && !fixed && !perLane) sampleBlock(tex, s, dev, q + 4 * i0, lods, lerpLane, out + 4 * i0, count);
    }
  });
}

void textureLodVector(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, const float* q, float* out,
                      int n) {
  LodInfo lods[16];
  VectorFlags vf;
  for (int k = 0; k < n; ++k) {
    lods[k] = selectLod(tex, s, dev, q[4 * k + 2], q[4 * k + 3]);
    vf.needLerp |= lods[k].f > 0.0f;
    vf.needLinear |= laneWantsLinear(s, lods[k].minify);
    vf.anyMinify |= lods[k].minify;
  }
  const auto [mixed, fixed, mipLinear, fixed16, perLane] = samplerPaths(tex, s, dev);
  if (mixed || fixed || perLane) {
    for (int k = 0; k < n; ++k) {
      Texel4 t = sampleOne(tex, s, dev, q[4 * k], q[4 * k + 1], lods[k], vf);
      std::memcpy(out + 4 * k, &t, 16);
    }
    return;
  }
  for (int b = 0; b < n; b += kLanes) {
    const int count = std::min(kLanes, n - b);
    bool lerpLane[kLanes];
    for (int k = 0; k < count; ++k) lerpLane[k] = mipLinear && vf.needLerp;
    sampleBlock(tex, s, dev, q + 4 * b, lods + b, lerpLane, out + 4 * b, count);
  }
}

Texel4 texelFetch(const Texture& tex, int32_t x, int32_t y, int32_t layer, int32_t level) {
  return tex.loadFloat(uint32_t(level), uint32_t(layer), uint32_t(x), uint32_t(y));
}

float implicitLod(const Texture& tex, const SamplerDesc& sd, const DeviceProfile& dev, const float s[4], const float t[4]) {
  const float W = float(tex.width()), H = float(tex.height());
  const float dsdx = (s[1] - s[0]) * W, dsdy = (s[2] - s[0]) * W;
  const float dtdx = (t[1] - t[0]) * H, dtdy = (t[2] - t[0]) * H;
  const float rx = dsdx * dsdx + dtdx * dtdx, ry = dsdy * dsdy + dtdy * dtdy;  // separate mul, add
  const float rho2 = rx > ry ? rx : ry;
  uint32_t bits;
  std::memcpy(&bits, &rho2, 4);
  // gallivm's LOD selector skips the float LOD when nothing follows the log2 (Mesa's apply_min_lod is
  // minLod > 0, apply_max_lod maxLod < PIPE_MAX_TEXTURE_LEVELS - 1 = 15).
  if (dev.implicitNearestShortcut && sd.mipmapMode == MipmapMode::Nearest && sd.lodBias == 0.0f &&
      !(sd.minLod > 0.0f) && !(sd.maxLod < 15.0f)) {
    const int32_t level = (int32_t((bits >> 23) & 0xffu) - 126) >> 1;  // lp_build_ilog2_sqrt
    return level != 0 ? float(level) : rho2 > 1.0f ? 0.25f : 0.0f;
  }
  if (dev.implicitLod == DeviceProfile::ImplicitLod::Exact) return 0.5f * std::log2(rho2);
  if (dev.implicitLod == DeviceProfile::ImplicitLod::ReactorLog2Sqrt) {
    const float rho4 = rho2 * rho2;
    int32_t ib;
    std::memcpy(&ib, &rho4, 4);
    return (float(ib) - float(0x3F800000)) * 0x1p-25f;
  }
  // gallivm's fast log2: (biased exponent - 127 - 1) + mantissa with the exponent bits set to 1.0.
  const int32_t e = int32_t((bits >> 23) & 0xffu) - 127 - 1;
  const uint32_t mbits = (bits & 0x007fffffu) | 0x3f800000u;
  float m;
  std::memcpy(&m, &mbits, 4);
  return (float(e) + m) * 0.5f;
}

}  // namespace emu
