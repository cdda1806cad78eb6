// SIMD lane types for the emulated GPU: N lanes of f32 / u32 / i32 and a lane mask.
//
// Built on GCC/Clang vector extensions (see docs/DESIGN.md, "Lane types"): every operation here is
// an IEEE single-precision or two's-complement integer operation per lane, with no contraction
// (the project compiles with -ffp-contract=off), so a lane computes exactly what the scalar `float`
// instantiation computes. What is deliberately missing is part of the contract:
//   - no operator/ and no sqrt on F32: shared shading code must use the exact-math layer;
//   - no conversion of a Mask to bool: divergent control flow on lanes does not compile, shared code
//     must use select() or uniform loops.
#pragma once

#include <immintrin.h>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace emu {

template <class T, int N>
struct VecOf {
  typedef T type __attribute__((vector_size(N * sizeof(T))));
};
template <class T, int N>
using vec_t = typename VecOf<T, N>::type;

template <int N> struct F32;
template <int N> struct U32;
template <int N> struct I32;

/// Per-lane boolean (all bits set = true). Deliberately not convertible to bool.
template <int N>
struct Mask {
  vec_t<int32_t, N> v;
  Mask() = default;
  Mask(bool b) { v = (vec_t<int32_t, N>){} + (b ? -1 : 0); }  // uniform broadcast
  explicit Mask(vec_t<int32_t, N> x) : v(x) {}
  explicit operator bool() const = delete;  // per-lane branches must become select()
  friend Mask operator&&(Mask a, Mask b) { return Mask(a.v & b.v); }
  friend Mask operator||(Mask a, Mask b) { return Mask(a.v | b.v); }
  friend Mask operator!(Mask a) { return Mask(~a.v); }
  friend Mask operator==(Mask a, Mask b) { return Mask(~(a.v ^ b.v)); }
  friend Mask operator!=(Mask a, Mask b) { return Mask(a.v ^ b.v); }
  bool lane(int i) const { return v[i] != 0; }
  /// Whether any lane is set: only for skipping work whose every effect is a select on this mask
  /// (the dialect's IF_ANY), never for per-lane control flow.
  /// The shading dialect's IF_ANY hook (src/shade/prelude.h): anyLane here.
  friend bool ifAnyScope(Mask m) { return anyLane(m); }
  friend bool anyLane(Mask m) {
    for (int i = 0; i < N; ++i)
      if (m.v[i]) return true;
    return false;
  }
  // select() between two uniform values gives a lane value.
  friend F32<N> select(Mask m, float a, float b) { return select(m, F32<N>(a), F32<N>(b)); }
  friend U32<N> select(Mask m, uint32_t a, uint32_t b) { return select(m, U32<N>(a), U32<N>(b)); }
  friend I32<N> select(Mask m, int32_t a, int32_t b) { return select(m, I32<N>(a), I32<N>(b)); }
  friend Mask select(Mask m, Mask a, Mask b) { return Mask(m.v ? a.v : b.v); }
};

#define EMU_LANE_COMMON(Self, Elem)                                                   \
  using V = vec_t<Elem, N>;                                                             \
  V v;                                                                                  \
  Self() = default;                                                                     \
  Self(Elem s) { for (int i = 0; i < N; ++i) v[i] = s; } /* keeps -0 and NaN bits */     \
  explicit Self(V x) : v(x) {}                                                          \
  Elem operator[](int i) const { return v[i]; }                                         \
  void set(int i, Elem x) { v[i] = x; }                                                 \
  friend Self operator+(Self a, Self b) { return Self(a.v + b.v); }                     \
  friend Self operator-(Self a, Self b) { return Self(a.v - b.v); }                     \
  friend Self operator*(Self a, Self b) { return Self(a.v * b.v); }                     \
  friend Self operator-(Self a) { return Self(-a.v); }                                  \
  Self& operator+=(Self b) { v = v + b.v; return *this; }                               \
  Self& operator-=(Self b) { v = v - b.v; return *this; }                               \
  Self& operator*=(Self b) { v = v * b.v; return *this; }                               \
  friend Mask<N> operator<(Self a, Self b) { return Mask<N>(a.v < b.v); }               \
  friend Mask<N> operator<=(Self a, Self b) { return Mask<N>(a.v <= b.v); }             \
  friend Mask<N> operator>(Self a, Self b) { return Mask<N>(a.v > b.v); }               \
  friend Mask<N> operator>=(Self a, Self b) { return Mask<N>(a.v >= b.v); }             \
  friend Mask<N> operator==(Self a, Self b) { return Mask<N>(a.v == b.v); }             \
  friend Mask<N> operator!=(Self a, Self b) { return Mask<N>(a.v != b.v); }             \
  friend Self select(Mask<N> m, Self a, Self b) { return Self(m.v ? a.v : b.v); }

#define EMU_LANE_INT_OPS(Self)                                                        \
  friend Self operator&(Self a, Self b) { return Self(a.v & b.v); }                     \
  friend Self operator|(Self a, Self b) { return Self(a.v | b.v); }                     \
  friend Self operator^(Self a, Self b) { return Self(a.v ^ b.v); }                     \
  friend Self operator~(Self a) { return Self(~a.v); }                                  \
  friend Self operator<<(Self a, Self b) { return Self(a.v << b.v); }                   \
  friend Self operator>>(Self a, Self b) { return Self(a.v >> b.v); }                   \
  friend Self operator<<(Self a, int s) { return Self(a.v << s); }                      \
  friend Self operator>>(Self a, int s) { return Self(a.v >> s); }                      \
  Self& operator&=(Self b) { v = v & b.v; return *this; }                               \
  Self& operator|=(Self b) { v = v | b.v; return *this; }                               \
  Self& operator^=(Self b) { v = v ^ b.v; return *this; }                               \
  Self& operator<<=(int s) { v = v << s; return *this; }                                \
  Self& operator>>=(int s) { v = v >> s; return *this; }

template <int N>
struct U32 {
  EMU_LANE_COMMON(U32, uint32_t)
  EMU_LANE_INT_OPS(U32)
  explicit U32(I32<N> x);  // bit-preserving, like GLSL uint(int)
  explicit U32(F32<N> x);  // truncation toward zero, like GLSL uint(float)
};

template <int N>
struct I32 {
  EMU_LANE_COMMON(I32, int32_t)
  EMU_LANE_INT_OPS(I32)
  explicit I32(U32<N> x) : v((V)x.v) {}
  explicit I32(F32<N> x);  // truncation toward zero, like GLSL int(float)
};

template <int N>
struct F32 {
  EMU_LANE_COMMON(F32, float)
  explicit F32(I32<N> x) : v(__builtin_convertvector(x.v, V)) {}
  explicit F32(U32<N> x) : v(__builtin_convertvector(x.v, V)) {}
  // No operator/ : division must go through the exact-math layer.
};

template <int N> U32<N>::U32(I32<N> x) : v((V)x.v) {}
template <int N> U32<N>::U32(F32<N> x) : v(__builtin_convertvector(x.v, V)) {}
template <int N> I32<N>::I32(F32<N> x) : v(__builtin_convertvector(x.v, V)) {}

#undef EMU_LANE_COMMON
#undef EMU_LANE_INT_OPS

template <int N> inline U32<N> floatBitsToUint(F32<N> x) { return U32<N>((typename U32<N>::V)x.v); }
template <int N> inline I32<N> floatBitsToInt(F32<N> x) { return I32<N>((typename I32<N>::V)x.v); }
template <int N> inline F32<N> uintBitsToFloat(U32<N> x) { return F32<N>((typename F32<N>::V)x.v); }
template <int N> inline F32<N> intBitsToFloat(I32<N> x) { return F32<N>((typename F32<N>::V)x.v); }
/// The shading dialect's FOR hook (src/shade/prelude.h): nothing for the emulator's lanes.
template <int N> inline int loopScope(F32<N>) { return 0; }
template <int N> inline void loopIteration(F32<N>) {}
/// The dialect's specMask and texelFetchUniform hooks: a plain mask, and nothing to count.
template <int N> inline Mask<N> specConstantMask(F32<N>, bool b) { return Mask<N>(b); }
/// The dialect's uniformMask: a plain mask.
template <int N> inline Mask<N> runtimeUniformMask(F32<N>, bool b) { return Mask<N>(b); }
template <int N> inline void countUniformFetches(F32<N>) {}
/// x86 MINPS / MAXPS per lane: `a < b ? a : b` and `a > b ? a : b` (b where unordered or equal), made by the min/max
/// instruction itself. The devices' FMin/FMax are those instructions (llvmpipe's and SwiftShader's x86 back ends), so
/// under a flushing stage's DAZ a subnormal operand reads as zero in them, while a select of the same compare keeps its
/// bits. Written as a compare and a select, GCC makes a min instruction of it at -O1 and above but not at -Og, and the
/// emulator's bits would follow the optimisation level (seen: verify math's atan2 in the fragment stage at -Og).
template <bool Max, int N>
inline F32<N> minMaxMachine(F32<N> a, F32<N> b) {
  F32<N> r;
  const float* pa = reinterpret_cast<const float*>(&a.v);
  const float* pb = reinterpret_cast<const float*>(&b.v);
  float* pr = reinterpret_cast<float*>(&r.v);
  int i = 0;
#ifdef __AVX__  // whole 8-lane registers (two 4-lane halves would go through memory)
  for (; i + 8 <= N; i += 8) {
    const __m256 x = _mm256_loadu_ps(pa + i), y = _mm256_loadu_ps(pb + i);
    _mm256_storeu_ps(pr + i, Max ? _mm256_max_ps(x, y) : _mm256_min_ps(x, y));
  }
#endif
  for (; i + 4 <= N; i += 4) {
    const __m128 x = _mm_loadu_ps(pa + i), y = _mm_loadu_ps(pb + i);
    _mm_storeu_ps(pr + i, Max ? _mm_max_ps(x, y) : _mm_min_ps(x, y));
  }
  for (; i < N; ++i) {
    const __m128 x = _mm_set_ss(pa[i]), y = _mm_set_ss(pb[i]);
    pr[i] = _mm_cvtss_f32(Max ? _mm_max_ss(x, y) : _mm_min_ss(x, y));
  }
  return r;
}
template <int N> inline F32<N> minMachine(F32<N> a, F32<N> b) { return minMaxMachine<false>(a, b); }
template <int N> inline F32<N> maxMachine(F32<N> a, F32<N> b) { return minMaxMachine<true>(a, b); }
/// The dialect's arrayGet / arraySet hooks (a private array at a non-literal index): the value itself.
template <int N> inline F32<N> indexedRead(F32<N> v) { return v; }
template <int N> inline I32<N> indexedRead(I32<N> v) { return v; }
template <int N> inline U32<N> indexedRead(U32<N> v) { return v; }
template <int N> inline F32<N> indexedWrite(F32<N> v) { return v; }
template <int N> inline I32<N> indexedWrite(I32<N> v) { return v; }
template <int N> inline U32<N> indexedWrite(U32<N> v) { return v; }

/// High 32 bits of the 64-bit product (GLSL umulExtended's msb).
template <int N>
inline U32<N> mulHi(U32<N> a, U32<N> b) {
  using W = vec_t<uint64_t, N>;
  W p = __builtin_convertvector(a.v, W) * __builtin_convertvector(b.v, W);
  return U32<N>(__builtin_convertvector(p >> 32, typename U32<N>::V));
}

/// Fused multiply-add per lane (used by the emulated texture unit, never by shared shading code).
template <int N>
inline F32<N> fmaLanes(F32<N> a, F32<N> b, F32<N> c) {
  F32<N> r;
  for (int i = 0; i < N; ++i) r.v[i] = __builtin_fmaf(a.v[i], b.v[i], c.v[i]);
  return r;
}


}  // namespace emu
