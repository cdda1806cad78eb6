// Cost of the portable exact-math layer against the native C++ operation, per function, on the
// scalar and the 8-lane SIMD builds (inputs per second).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "lanes/kernels.h"

namespace {
std::vector<float>& inputs() {
  static std::vector<float> in = [] {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> U(0.1f, 10.0f);
    std::vector<float> v(3 * 65536);
    for (auto& x : v) x = U(rng);
    return v;
  }();
  return in;
}

void BM_Exact(benchmark::State& state) {
  const int fn = int(state.range(0)), lanes = int(state.range(1));
  auto& in = inputs();
  std::vector<float> out(in.size());
  const size_t n = in.size() / 3;
  for (auto _ : state) {
    shadetwin::evalMathKernel(fn, in.data(), out.data(), n, lanes);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
  state.SetLabel(std::string(shadetwin::mathKernelName(fn)) + (lanes == 1 ? " scalar" : " simd x" + std::to_string(lanes)));
}
BENCHMARK(BM_Exact)->ArgsProduct({benchmark::CreateDenseRange(0, 12, 1), {1, 8}});

void BM_NativeDiv(benchmark::State& state) {
  auto& in = inputs();
  std::vector<float> out(in.size() / 3);
  for (auto _ : state) {
    for (size_t i = 0; i < out.size(); ++i) out[i] = in[3 * i] / in[3 * i + 1];
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(out.size()));
}
BENCHMARK(BM_NativeDiv);

void BM_NativeSin(benchmark::State& state) {
  auto& in = inputs();
  std::vector<float> out(in.size() / 3);
  for (auto _ : state) {
    for (size_t i = 0; i < out.size(); ++i) out[i] = std::sin(in[3 * i]);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(out.size()));
}
BENCHMARK(BM_NativeSin);
}  // namespace

BENCHMARK_MAIN();
