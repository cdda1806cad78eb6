// Cost of the portable exact-math layer on the Vulkan device (lavapipe by default): the shared
// kernel (verify_math.glsl) against the device's native GLSL operation, per function, 2^20 inputs,
// wall time per dispatch (submit to fence).
#include <benchmark/benchmark.h>

#include <cstring>
#include <memory>
#include <random>
#include <span>
#include <vector>

#include "lanes/kernels.h"
#include "vk/context.h"

namespace {
#include "bench_exact_0.inc"
#include "bench_exact_1.inc"
#include "bench_exact_2.inc"
#include "bench_exact_3.inc"
#include "bench_exact_4.inc"
#include "bench_exact_5.inc"
#include "bench_exact_6.inc"
#include "bench_exact_7.inc"
#include "bench_exact_8.inc"
#include "bench_exact_9.inc"
#include "bench_exact_10.inc"
#include "bench_exact_11.inc"
#include "bench_exact_12.inc"
#include "bench_native_0.inc"
#include "bench_native_1.inc"
#include "bench_native_2.inc"
#include "bench_native_3.inc"
#include "bench_native_4.inc"
#include "bench_native_5.inc"
#include "bench_native_6.inc"
#include "bench_native_7.inc"
#include "bench_native_8.inc"
#include "bench_native_9.inc"
#include "bench_native_10.inc"
#include "bench_native_11.inc"
#include "bench_native_12.inc"
const std::span<const uint32_t> kExact[] = {kSpv_bench_exact_0, kSpv_bench_exact_1, kSpv_bench_exact_2, kSpv_bench_exact_3,
    kSpv_bench_exact_4, kSpv_bench_exact_5, kSpv_bench_exact_6, kSpv_bench_exact_7, kSpv_bench_exact_8, kSpv_bench_exact_9,
    kSpv_bench_exact_10, kSpv_bench_exact_11, kSpv_bench_exact_12};
const std::span<const uint32_t> kNative[] = {kSpv_bench_native_0, kSpv_bench_native_1, kSpv_bench_native_2,
    kSpv_bench_native_3, kSpv_bench_native_4, kSpv_bench_native_5, kSpv_bench_native_6, kSpv_bench_native_7,
    kSpv_bench_native_8, kSpv_bench_native_9, kSpv_bench_native_10, kSpv_bench_native_11, kSpv_bench_native_12};

using namespace shadetwin::vk;
constexpr uint32_t kN = 1u << 20;

struct Setup {
  Context ctx;
  std::unique_ptr<Buffer> in, out;
  std::unique_ptr<Kernel> exact[13], native[13];
  Setup() {
    const VkDescriptorType layout[] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    in = std::make_unique<Buffer>(ctx, kN * 12);
    out = std::make_unique<Buffer>(ctx, kN * 12);
    for (int f = 0; f < 13; ++f) {
      exact[f] = std::make_unique<Kernel>(ctx, Stage::Compute, kExact[f], layout, 12);
      native[f] = std::make_unique<Kernel>(ctx, Stage::Compute, kNative[f], layout, 12);
    }
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> U(0.1f, 10.0f);
    float* p = in->as<float>();
    for (uint32_t i = 0; i < 3 * kN; ++i) p[i] = U(rng);
  }
};
Setup& setup() {
  static Setup s;
  return s;
}

void run(benchmark::State& state, bool exact) {
  Setup& s = setup();
  const int fn = int(state.range(0));
  struct { int32_t fn; uint32_t count, width; } push{fn, kN, 1024};
  const Binding b[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, s.in->handle()}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, s.out->handle()}};
  Kernel& k = exact ? *s.exact[fn] : *s.native[fn];
  k.run(b, &push, kN);  // warm-up (first dispatch compiles)
  for (auto _ : state) k.run(b, &push, kN);
  state.SetItemsProcessed(int64_t(state.iterations()) * kN);
  state.SetLabel(std::string(shadetwin::mathKernelName(fn)) + (exact ? " exact" : " native"));
}
void BM_LavapipeExact(benchmark::State& state) { run(state, true); }
void BM_LavapipeNative(benchmark::State& state) { run(state, false); }
BENCHMARK(BM_LavapipeExact)->DenseRange(0, 12)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LavapipeNative)->DenseRange(0, 12)->Unit(benchmark::kMillisecond)->UseRealTime();
}  // namespace

BENCHMARK_MAIN();
