// C++ fast paths of the exact-math layer (shade/exact_math.h), for the emulator's speed only.
//
// exDiv and exSqrt are correctly rounded to nearest-even for every input (a float estimate made exact by an
// integer residual and corrections: exDivPortable / exSqrtPortable; tested
// on random bit patterns and dense sweeps). IEEE 754 requires the CPU's division and square root to be
// correctly rounded too, so wherever both agree on what is being rounded they give the same bits:
// every operand a normal finite number (no zero, subnormal, inf or NaN: their encodings and the
// FTZ/DAZ modes of a flushing stage are where a native operation and the portable path could
// differ, e.g. NaN payloads) and a normal result (no underflow to a subnormal or zero, no overflow).
// nativeDiv / nativeSqrt return the native result and `ok` when that holds for every lane of the
// vector; otherwise exact_math.h runs its portable path for the whole vector (the GPU always does).
// The rounding mode is round-to-nearest-even (the emulator never changes it).
#pragma once
#include <cstdint>

#include "emu/lanes.h"

namespace shadetwin::shade {

template <class F>
struct NativeResult {
  bool ok;
  F value;
};

namespace detail {
inline bool normalBits(uint32_t bits) {  // exponent field in [1, 254]
  const uint32_t e = (bits >> 23) & 0xffu;
  return e - 1u < 254u;
}
template <int N>
inline bool allNormal(emu::F32<N> x) {
  const emu::U32<N> e = (emu::floatBitsToUint(x) >> 23) & emu::U32<N>(0xffu);
  return !anyLane(e - emu::U32<N>(1u) >= emu::U32<N>(254u));
}
}  // namespace detail

inline NativeResult<float> nativeDiv(float a, float b) {
  const float q = a / b;
  return {detail::normalBits(__builtin_bit_cast(uint32_t, a)) && detail::normalBits(__builtin_bit_cast(uint32_t, b)) &&
              detail::normalBits(__builtin_bit_cast(uint32_t, q)),
          q};
}
inline NativeResult<float> nativeSqrt(float x) {
  const float r = __builtin_sqrtf(x);
  return {x > 0.0f && detail::normalBits(__builtin_bit_cast(uint32_t, x)), r};  // sqrt of a normal is normal
}

template <int N>
inline NativeResult<emu::F32<N>> nativeDiv(emu::F32<N> a, emu::F32<N> b) {
  const emu::F32<N> q(a.v / b.v);
  return {detail::allNormal(a) && detail::allNormal(b) && detail::allNormal(q), q};
}
template <int N>
inline NativeResult<emu::F32<N>> nativeSqrt(emu::F32<N> x) {
  emu::F32<N> r;
  for (int i = 0; i < N; ++i) r.v[i] = __builtin_sqrtf(x.v[i]);
  return {detail::allNormal(x) && !anyLane(x < emu::F32<N>(0.0f)), r};
}

}  // namespace shadetwin::shade
