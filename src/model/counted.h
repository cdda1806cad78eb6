// The shared shading source instantiated with the counting lane types of model/op_count.h (lanes/instantiate.h's
// SHADE_INSTANTIATE), twice: namespace shadetwin::shade::counted with 8 lanes (the emulator's x8 drivers counted)
// and shadetwin::shade::counted1 with 1 lane (its scalar drivers: vertex stages, G-buffer fragments, SH reduction).
// For the performance model's counted passes (model/pass_counts.cpp) and the FIS roofline (bench/fis_roofline.cpp).
#pragma once

#include "lanes/instantiate.h"
#include "model/op_count.h"

#define SHADE_RUNTIME_BRDF_KINDS (::opcount::sceneBrdfKinds)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
SHADE_INSTANTIATE(counted, opcount::F<8>, opcount::I<8>, opcount::U<8>, opcount::M<8>)
inline constexpr int kLanes = 8;
#include "shade/all.inl"
}  // namespace
}  // namespace shadetwin::shade::counted

SHADE_INSTANTIATE(counted1, opcount::F<1>, opcount::I<1>, opcount::U<1>, opcount::M<1>)
inline constexpr int kLanes = 1;
#include "shade/all.inl"
}  // namespace
}  // namespace shadetwin::shade::counted1
#pragma GCC diagnostic pop
#undef kSceneBrdfKinds
#undef SHADE_RUNTIME_BRDF_KINDS

namespace opcount {
/// A counted lane value as a float (one-lane builds): what a scalar driver stores.
inline float lane0(float x) { return x; }
template <class T> float lane0(const T& x) { return x[0]; }
}  // namespace opcount
