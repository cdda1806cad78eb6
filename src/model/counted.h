// The shared shading source instantiated once more, with the counting 8-lane types of model/op_count.h, in
// namespace shadetwin::shade::counted (as lanes/instantiate.h does per lane type): for the performance model's
// counted passes (model/shade_counts.cpp) and the FIS roofline (bench/fis_roofline.cpp).
#pragma once

#include "lanes/instantiate.h"
#include "model/op_count.h"

namespace shadetwin::shade::counted {
namespace {
using Float = opcount::F<8>;
using Int = opcount::I<8>;
using Uint = opcount::U<8>;
using Mask = opcount::M<8>;
using namespace ::shadetwin::shade;
using ::shadetwin::shade::select;
using ::shadetwin::shade::floatBitsToUint;
using ::shadetwin::shade::uintBitsToFloat;
using ::shadetwin::shade::mulHi;
using ::std::int32_t;
using ::std::uint32_t;
inline constexpr int kLanes = 8;
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "shade/all.inl"
#pragma GCC diagnostic pop
}  // namespace
}  // namespace shadetwin::shade::counted
