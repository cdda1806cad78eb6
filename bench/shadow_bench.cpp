// Shadow-map passes (issue 16): the emulated pass and the same pass on the Vulkan device, K
// orthographic depth maps of the bunny at S^2 (K = 1, 4, 16, 64; S = 512, 1024), one run each
// iteration into reused maps; time per map is the slope in K (the paper's Fig. 2 is linear in K).
// The `shadetwin bench --passes shadow` ratio is the target; this isolates the passes.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "passes/passes_vk.h"
#include "passes/shadow.h"
#include "scene/scene.h"
#include "util/memory.h"
#include "vk/context.h"

namespace {
const shadetwin::Scene& bunny() {
  static const shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/bunny.json");
  return s;
}

void BM_ShadowEmu(benchmark::State& state) {
  const auto dirs = shadetwin::sphereDirections(uint32_t(state.range(0)));
  const uint32_t size = uint32_t(state.range(1));
  shadetwin::ShadowMaps maps;
  shadetwin::ShadowStats stats;
  for (auto _ : state) {
    shadetwin::shadowEmu(bunny(), dirs, size, emu::lavapipeProfile(), maps, &stats);
    benchmark::DoNotOptimize(maps.maps.data());
  }
  state.counters["maps"] = double(dirs.size());
  state.counters["fragments"] = double(stats.raster.fragments);
  state.counters["quads"] = double(stats.raster.quads);
}

void BM_ShadowVulkan(benchmark::State& state) {
  static shadetwin::vk::Context ctx;
  const auto dirs = shadetwin::sphereDirections(uint32_t(state.range(0)));
  shadetwin::ShadowPassVk pass(ctx, bunny(), uint32_t(state.range(1)));
  pass.run(dirs);  // pipeline compile outside the timing
  for (auto _ : state) {
    benchmark::DoNotOptimize(pass.run(dirs).maps.data());
    state.SetIterationTime(pass.lastMs / 1000.0);  // submit to fence, as `shadetwin bench` (no readback)
  }
  state.counters["maps"] = double(dirs.size());
}

void shapes(benchmark::internal::Benchmark* b) {
  for (int k : {1, 4, 16, 64}) b->Args({k, 1024});
  b->Args({16, 512});
  b->Unit(benchmark::kMillisecond);
}
BENCHMARK(BM_ShadowEmu)->Apply(shapes)->UseRealTime();
BENCHMARK(BM_ShadowVulkan)->Apply(shapes)->UseManualTime();
}  // namespace

int main(int argc, char** argv) {
  shadetwin::keepHeapAcrossFrames();  // as the CLI: lavapipe's freed frame memory stays in the heap (util/memory.h)
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
