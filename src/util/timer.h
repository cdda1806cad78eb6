// Wall-clock timing of host work in milliseconds (passes, benches, sweeps).
#pragma once
#include <algorithm>
#include <chrono>
#include <vector>

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

/// The time the performance model is compared with (calibrate's microkernels and the passes `model` measures): the
/// fastest of several runs after a warm-up. On a shared host, contention (other tenants, a preempted driver thread)
/// only ever adds time, so the minimum estimates the uncontended time a throughput model predicts and is far more
/// repeatable than a median (Chen & Revels, "Robust benchmarking in noisy environments", 2016). -1 for no runs.
inline double fastestOf(const std::vector<double>& t) { return t.empty() ? -1.0 : *std::min_element(t.begin(), t.end()); }

}  // namespace shadetwin
