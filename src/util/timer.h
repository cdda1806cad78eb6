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

/// The best each measurement of a repeated sequence has read (calibrate's rounds): the k-th low() or high() call after
/// nextRound() is the k-th measurement of the round, and returns the lowest (a time) or highest (a rate) it has read in
/// any round so far. A host that is slow for a while then moves a measurement only if it is slow in every round.
class BestOfRounds {
 public:
  void nextRound() { at_ = 0; }
  double low(double x) {
    if (at_ == v_.size()) v_.push_back(x);
    v_[at_] = std::min(v_[at_], x);
    return v_[at_++];
  }
  double high(double x) { return -low(-x); }
  size_t measurements() const { return v_.size(); }

 private:
  std::vector<double> v_;
  size_t at_ = 0;
};

}  // namespace shadetwin
