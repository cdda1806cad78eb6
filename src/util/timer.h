// Wall-clock timing of host work in milliseconds (passes, benches, sweeps).
#pragma once
#include <chrono>

namespace shadetwin {

inline double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// Runs f once and returns its wall time in ms.
template <class F>
double timeMs(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return msSince(t0);
}

}  // namespace shadetwin
