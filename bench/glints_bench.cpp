// Glints (issue 17): build times and memory of every table, per normal-map kind and size.
//   BM_NormalMap/kind/size   generating the map
//   BM_NdfSat/kind/size      the NDF histogram SAT (9 x 32 bins): counters MiB (allocated), fullMiB
//                            (every ring stored: the paper's table, 576 MB at 1024^2), rings stored
// kind: 0 flat, 1 flakes, 2 scratches, 3 brushed, 4 bumps (default parameters of NormalMapSpec).
#include <benchmark/benchmark.h>

#include "inputs/ndf_histogram.h"
#include "inputs/normal_map.h"

namespace {

shadetwin::NormalMapSpec spec(const benchmark::State& state) {
  shadetwin::NormalMapSpec s;
  s.kind = shadetwin::NormalMapKind(state.range(0));
  s.size = uint32_t(state.range(1));
  s.cells = s.size / 16;
  return s;
}

void BM_NormalMap(benchmark::State& state) {
  const auto s = spec(state);
  for (auto _ : state) benchmark::DoNotOptimize(shadetwin::generateNormalMap(s).n.data());
  state.SetLabel(shadetwin::normalMapKindName(s.kind));
}

void BM_NdfSat(benchmark::State& state) {
  const auto s = spec(state);
  const shadetwin::NormalMap m = shadetwin::generateNormalMap(s);
  size_t bytes = 0, full = 0, rings = 0;
  for (auto _ : state) {
    const shadetwin::NdfSat sat = shadetwin::buildNdfSat(m, shadetwin::NdfBinningSpec{});
    bytes = sat.bytes(), full = sat.fullBytes(), rings = sat.storedRings;
    benchmark::DoNotOptimize(sat.table.data());
  }
  state.counters["MiB"] = double(bytes) / (1 << 20);
  state.counters["fullMiB"] = double(full) / (1 << 20);
  state.counters["rings"] = double(rings);
  state.SetLabel(shadetwin::normalMapKindName(s.kind));
}

}  // namespace

BENCHMARK(BM_NormalMap)->ArgsProduct({{1, 2, 3, 4}, {1024}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NdfSat)->ArgsProduct({{1, 2, 3, 4}, {256, 1024, 2048}})->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
