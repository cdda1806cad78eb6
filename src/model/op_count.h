// Operation counting for the performance model (issue 19, model/shade_counts.cpp) and the roofline of a shading
// pass (bench/fis_roofline.cpp): lane types that
// wrap the emulator's N-lane types (emu/lanes.h), compute exactly what they compute, and count every
// vector operation by kind in thread-local counters. The shared shading source instantiated with them
// (namespace shadetwin::shade::counted) runs the same code path as the emulator's SIMD build (same
// IF_ANY skips per vector of 8 pixels), so counts / 8 are operations per pixel as executed. Texture
// lookups are counted per lane with the texels the filter reads (bilinear 4 per level, trilinear 8).
#pragma once
#include <array>
#include <cmath>
#include <cstdint>

#include "emu/lanes.h"
#include "lanes/native_exact.h"
#include "lanes/sampler_bridge.h"
#include "lanes/vec.h"

namespace opcount {

enum Kind { kFAdd, kFMul, kFCmp, kIAlu, kIMul, kCvt, kSel, kMaskOp, kTexLookup, kTexel, kTexNearest, kTexBilinear, kTexTrilinear, kKinds };
inline const char* kKindNames[kKinds] = {"fadd", "fmul", "fcmp", "ialu", "imul", "cvt", "select", "mask", "tex_lookup", "texel",
                                          "tex_nearest", "tex_bilinear", "tex_trilinear"};
inline thread_local std::array<uint64_t, kKinds> counts{};
inline void tick(Kind k, uint64_t n = 1) { counts[size_t(k)] += n; }

template <int N> struct F;
template <int N> struct U;
template <int N> struct I;

template <int N>
struct M {
  emu::Mask<N> m;
  M() = default;
  M(bool b) : m(b) {}
  explicit M(emu::Mask<N> x) : m(x) {}
  explicit operator bool() const = delete;
  friend M operator&&(M a, M b) { tick(kMaskOp); return M(a.m && b.m); }
  friend M operator||(M a, M b) { tick(kMaskOp); return M(a.m || b.m); }
  friend M operator!(M a) { tick(kMaskOp); return M(!a.m); }
  friend M operator==(M a, M b) { tick(kMaskOp); return M(a.m == b.m); }
  friend M operator!=(M a, M b) { tick(kMaskOp); return M(a.m != b.m); }
  friend bool anyLane(M a) { return anyLane(a.m); }
  friend F<N> select(M c, float a, float b) { return select(c, F<N>(a), F<N>(b)); }
  friend U<N> select(M c, uint32_t a, uint32_t b) { return select(c, U<N>(a), U<N>(b)); }
  friend I<N> select(M c, int32_t a, int32_t b) { return select(c, I<N>(a), I<N>(b)); }
  friend M select(M c, M a, M b) { tick(kSel); return M(select(c.m, a.m, b.m)); }
};

#define OPCOUNT_COMMON(Self, Lane, Elem, AddKind, MulKind, CmpKind)                       \
  Lane x;                                                                                  \
  Self() = default;                                                                        \
  Self(Elem s) : x(s) {}                                                                   \
  explicit Self(Lane l) : x(l) {}                                                          \
  Elem operator[](int i) const { return x[i]; }                                            \
  void set(int i, Elem e) { x.set(i, e); }                                                 \
  friend Self operator+(Self a, Self b) { tick(AddKind); return Self(a.x + b.x); }         \
  friend Self operator-(Self a, Self b) { tick(AddKind); return Self(a.x - b.x); }         \
  friend Self operator*(Self a, Self b) { tick(MulKind); return Self(a.x * b.x); }         \
  friend Self operator-(Self a) { tick(AddKind); return Self(-a.x); }                      \
  Self& operator+=(Self b) { return *this = *this + b; }                                   \
  Self& operator-=(Self b) { return *this = *this - b; }                                   \
  Self& operator*=(Self b) { return *this = *this * b; }                                   \
  friend M<N> operator<(Self a, Self b) { tick(CmpKind); return M<N>(a.x < b.x); }         \
  friend M<N> operator<=(Self a, Self b) { tick(CmpKind); return M<N>(a.x <= b.x); }       \
  friend M<N> operator>(Self a, Self b) { tick(CmpKind); return M<N>(a.x > b.x); }         \
  friend M<N> operator>=(Self a, Self b) { tick(CmpKind); return M<N>(a.x >= b.x); }       \
  friend M<N> operator==(Self a, Self b) { tick(CmpKind); return M<N>(a.x == b.x); }       \
  friend M<N> operator!=(Self a, Self b) { tick(CmpKind); return M<N>(a.x != b.x); }       \
  friend Self select(M<N> m, Self a, Self b) { tick(kSel); return Self(select(m.m, a.x, b.x)); }

#define OPCOUNT_INT(Self)                                                                   \
  friend Self operator&(Self a, Self b) { tick(kIAlu); return Self(a.x & b.x); }           \
  friend Self operator|(Self a, Self b) { tick(kIAlu); return Self(a.x | b.x); }           \
  friend Self operator^(Self a, Self b) { tick(kIAlu); return Self(a.x ^ b.x); }           \
  friend Self operator~(Self a) { tick(kIAlu); return Self(~a.x); }                        \
  friend Self operator<<(Self a, Self b) { tick(kIAlu); return Self(a.x << b.x); }         \
  friend Self operator>>(Self a, Self b) { tick(kIAlu); return Self(a.x >> b.x); }         \
  friend Self operator<<(Self a, int s) { tick(kIAlu); return Self(a.x << s); }            \
  friend Self operator>>(Self a, int s) { tick(kIAlu); return Self(a.x >> s); }            \
  Self& operator&=(Self b) { return *this = *this & b; }                                   \
  Self& operator|=(Self b) { return *this = *this | b; }                                   \
  Self& operator^=(Self b) { return *this = *this ^ b; }                                   \
  Self& operator<<=(int s) { return *this = *this << s; }                                  \
  Self& operator>>=(int s) { return *this = *this >> s; }

template <int N>
struct U {
  OPCOUNT_COMMON(U, emu::U32<N>, uint32_t, kIAlu, kIMul, kIAlu)
  OPCOUNT_INT(U)
  explicit U(I<N> a);
  explicit U(F<N> a);
  friend U mulHi(U a, U b) { tick(kIMul); return U(emu::mulHi(a.x, b.x)); }
};

template <int N>
struct I {
  OPCOUNT_COMMON(I, emu::I32<N>, int32_t, kIAlu, kIMul, kIAlu)
  OPCOUNT_INT(I)
  explicit I(U<N> a) : x(emu::I32<N>(a.x)) {}
  explicit I(F<N> a);
};

template <int N>
struct F {
  OPCOUNT_COMMON(F, emu::F32<N>, float, kFAdd, kFMul, kFCmp)
  explicit F(I<N> a) : x(emu::F32<N>(a.x)) { tick(kCvt); }
  explicit F(U<N> a) : x(emu::F32<N>(a.x)) { tick(kCvt); }
};

template <int N> U<N>::U(I<N> a) : x(emu::U32<N>(a.x)) {}
template <int N> U<N>::U(F<N> a) : x(emu::U32<N>(a.x)) { tick(kCvt); }
template <int N> I<N>::I(F<N> a) : x(emu::I32<N>(a.x)) { tick(kCvt); }

#undef OPCOUNT_COMMON
#undef OPCOUNT_INT

// Bit casts are free (no instruction on either build).
template <int N> inline U<N> floatBitsToUint(F<N> a) { return U<N>(emu::floatBitsToUint(a.x)); }
template <int N> inline I<N> floatBitsToInt(F<N> a) { return I<N>(emu::floatBitsToInt(a.x)); }
template <int N> inline F<N> uintBitsToFloat(U<N> a) { return F<N>(emu::uintBitsToFloat(a.x)); }
template <int N> inline F<N> intBitsToFloat(I<N> a) { return F<N>(emu::intBitsToFloat(a.x)); }

/// Texels a linear-filtered lookup at `lod` reads on a texture of `levels` levels: 4 per level, two
/// levels when the LOD falls strictly between levels (trilinear), one otherwise.
inline uint64_t texelsRead(float lod, uint32_t levels) {
  const float l = std::fmin(std::fmax(lod, 0.0f), float(levels - 1));
  return (l > 0.0f && l < float(levels - 1) && l != std::floor(l)) ? 8 : 4;
}

}  // namespace opcount

// The sampler bridge for the counted lanes (qualified calls from the C++ prelude resolve here).
namespace shadetwin::shade {
template <int N>
V4<opcount::F<N>> textureLodLanes(const Sampler2D& s, opcount::F<N> u, opcount::F<N> v, opcount::F<N> lod,
                                  opcount::F<N> layer = opcount::F<N>(0.0f)) {
  opcount::tick(opcount::kTexLookup, N);
  const bool nearest = s.desc.magFilter == emu::Filter::Nearest && s.desc.minFilter == emu::Filter::Nearest;
  for (int i = 0; i < N; ++i) {
    const uint64_t texels = opcount::texelsRead(lod[i], s.tex->levelCount());
    opcount::tick(opcount::kTexel, nearest ? 1 : texels);
    opcount::tick(nearest ? opcount::kTexNearest : texels == 8 && s.desc.mipmapMode == emu::MipmapMode::Linear ? opcount::kTexTrilinear
                                                                                                            : opcount::kTexBilinear);
  }
  const V4<emu::F32<N>> r = textureLodLanes(s, u.x, v.x, lod.x, layer.x);
  return V4<opcount::F<N>>(opcount::F<N>(r.x), opcount::F<N>(r.y), opcount::F<N>(r.z), opcount::F<N>(r.w));
}
template <int N>
V4<opcount::F<N>> texelFetchLanes(const Sampler2D& s, opcount::I<N> x, opcount::I<N> y, int level,
                                   opcount::I<N> layer = opcount::I<N>(0)) {
  opcount::tick(opcount::kTexLookup, N);
  opcount::tick(opcount::kTexel, N);
  opcount::tick(opcount::kTexNearest, N);  // a fetch: one texel, no filtering
  const V4<emu::F32<N>> r = texelFetchLanes(s, x.x, y.x, level, layer.x);
  return V4<opcount::F<N>>(opcount::F<N>(r.x), opcount::F<N>(r.y), opcount::F<N>(r.z), opcount::F<N>(r.w));
}
template <int N>
void uintFetchLanes(const USampler2DArray& s, opcount::I<N> x, opcount::I<N> y, opcount::I<N> layer, int level, opcount::U<N>& a,
                    opcount::U<N>& b, opcount::U<N>& c, opcount::U<N>& d) {
  opcount::tick(opcount::kTexLookup, N);
  opcount::tick(opcount::kTexel, N);
  opcount::tick(opcount::kTexNearest, N);  // a fetch: one texel, no filtering
  emu::U32<N> ra, rb, rc, rd;
  uintFetchLanes(s, x.x, y.x, layer.x, level, ra, rb, rc, rd);
  a.x = ra, b.x = rb, c.x = rc, d.x = rd;
}
}  // namespace shadetwin::shade

// The counted build counts the portable recurrences (what a GPU runs), not the emulator's native
// fast paths (lanes/native_exact.h).
namespace shadetwin::shade {
template <int N>
inline NativeResult<opcount::F<N>> nativeDiv(opcount::F<N>, opcount::F<N>) { return {false, opcount::F<N>(0.0f)}; }
template <int N>
inline NativeResult<opcount::F<N>> nativeSqrt(opcount::F<N>) { return {false, opcount::F<N>(0.0f)}; }
}  // namespace shadetwin::shade
