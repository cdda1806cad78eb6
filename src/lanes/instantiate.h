// C++ instantiations of the shared shading dialect (Highway's foreach_target idea): every shared
// header listed in all.inl is compiled once per lane type, each time inside its own namespace:
//   shadetwin::shade::scalar   Float = float           (the "C++ scalar" build)
//   shadetwin::shade::x4/x8/x16 Float = emu::F32<N>     (the SIMD builds, N lanes)
// Code that wants "the SIMD build" uses shade::simd (= x8).
#pragma once

#include <cstdint>

#include "emu/lanes.h"
#include "lanes/vec.h"
#include "lanes/sampler_bridge.h"
#include "lanes/native_exact.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"

#define SHADE_INSTANTIATE(NS, FLOAT, INT, UINT, MASK)      \
  namespace shadetwin::shade::NS {                         \
  namespace { /* shared functions are plain (GLSL) functions: internal linkage per TU */ \
  using Float = FLOAT;                                     \
  using Int = INT;                                         \
  using Uint = UINT;                                       \
  using Mask = MASK;                                       \
  using namespace ::shadetwin::shade;                      \
  using ::shadetwin::shade::select;                        \
  using ::shadetwin::shade::floatBitsToUint;               \
  using ::shadetwin::shade::uintBitsToFloat;               \
  using ::shadetwin::shade::mulHi;                         \
  using ::std::int32_t;                                    \
  using ::std::uint32_t;

SHADE_INSTANTIATE(scalar, float, int32_t, uint32_t, bool)
inline constexpr int kLanes = 1;
#include "shade/all.inl"
}  // namespace
}  // namespace shadetwin::shade::scalar

SHADE_INSTANTIATE(x4, emu::F32<4>, emu::I32<4>, emu::U32<4>, emu::Mask<4>)
inline constexpr int kLanes = 4;
#include "shade/all.inl"
}  // namespace
}  // namespace shadetwin::shade::x4

SHADE_INSTANTIATE(x8, emu::F32<8>, emu::I32<8>, emu::U32<8>, emu::Mask<8>)
inline constexpr int kLanes = 8;
#include "shade/all.inl"
}  // namespace
}  // namespace shadetwin::shade::x8

SHADE_INSTANTIATE(x16, emu::F32<16>, emu::I32<16>, emu::U32<16>, emu::Mask<16>)
inline constexpr int kLanes = 16;
#include "shade/all.inl"
}  // namespace
}  // namespace shadetwin::shade::x16

namespace shadetwin::shade {
namespace simd = x8;
}

// SHADE_INSTANTIATE stays defined: model/counted.h instantiates the counting lane types with it.
#pragma GCC diagnostic pop
