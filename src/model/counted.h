// The shared shading source instantiated with the counting lane types of model/op_count.h (as lanes/instantiate.h
// does per lane type), twice: namespace shadetwin::shade::counted with 8 lanes (the emulator's x8 drivers counted)
// and shadetwin::shade::counted1 with 1 lane (its scalar drivers: vertex stages, G-buffer fragments, SH reduction).
// For the performance model's counted passes (model/pass_counts.cpp) and the FIS roofline (bench/fis_roofline.cpp).
#pragma once

#include "lanes/instantiate.h"
#include "model/op_count.h"

#define SHADE_COUNTED_NS(NS, N)                      \
  namespace shadetwin::shade::NS {                   \
  namespace {                                        \
  using Float = opcount::F<N>;                       \
  using Int = opcount::I<N>;                         \
  using Uint = opcount::U<N>;                        \
  using Mask = opcount::M<N>;                        \
  using namespace ::shadetwin::shade;                \
  using ::shadetwin::shade::select;                  \
  using ::shadetwin::shade::floatBitsToUint;         \
  using ::shadetwin::shade::uintBitsToFloat;         \
  using ::shadetwin::shade::mulHi;                   \
  using ::std::int32_t;                              \
  using ::std::uint32_t;                             \
  inline constexpr int kLanes = N;

#define SHADE_RUNTIME_BRDF_KINDS (::opcount::sceneBrdfKinds)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
SHADE_COUNTED_NS(counted, 8)
#include "shade/all.inl"
}  // namespace
}  // namespace shadetwin::shade::counted

SHADE_COUNTED_NS(counted1, 1)
#include "shade/all.inl"
}  // namespace
}  // namespace shadetwin::shade::counted1
#pragma GCC diagnostic pop
#undef SHADE_COUNTED_NS
#undef kSceneBrdfKinds
#undef SHADE_RUNTIME_BRDF_KINDS

namespace opcount {
/// A counted lane value as a float (one-lane builds): what a scalar driver stores.
inline float lane0(float x) { return x; }
template <class T> float lane0(const T& x) { return x[0]; }
}  // namespace opcount
