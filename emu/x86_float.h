// Scalar semantics of the SSE instructions a JIT-compiled device's code lowers to, where they differ from plain
// C++ (SwiftShader's Reactor: emu/sampler_reactor.*, the Reactor setup of emu/raster.cpp).
#pragma once
#include <climits>
#include <cmath>
#include <cstdint>

namespace emu::x86 {

/// minps / maxps (and a select on an ordered compare): a NaN operand gives the second operand.
inline float minps(float a, float b) { return a < b ? a : b; }
inline float maxps(float a, float b) { return a > b ? a : b; }
/// cvttps2dq: truncation; NaN and out of range give INT_MIN.
inline int32_t cvttps2dq(float x) {
  if (!(x > -2147483904.0f && x < 2147483648.0f)) return INT_MIN;
  return int32_t(x);
}
/// cvtps2dq under round-to-nearest-even; NaN and out of range give INT_MIN.
inline int32_t cvtps2dq(float x) {
  if (!(x > -2147483904.0f && x < 2147483648.0f)) return INT_MIN;
  return int32_t(std::nearbyint(x));
}

}  // namespace emu::x86
