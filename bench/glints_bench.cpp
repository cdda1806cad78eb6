// Glints (issue 17): build times and memory of every table, per normal-map kind and size.
//   BM_NormalMap/kind/size   generating the map
//   BM_NdfSat/kind/size      the NDF histogram SAT (9 x 32 bins): counters MiB (allocated), fullMiB
//                            (every ring stored: the paper's table, 576 MB at 1024^2), rings stored
//   BM_LightingTable/degree/views  the lighting table on the emulator (views x 2 views, the smallest
//                            level of a 1024 x 512 sky at least 3 (degree + 1) texels wide): counter MiB
//   BM_LobeTable/degree/rings      the rotated-lobe table (rings x 2 (rings - 1) directions): counter MiB
//   BM_LegendreTable/degree        the recurrences' coefficient table
// kind: 0 flat, 1 flakes, 2 scratches, 3 brushed, 4 bumps (default parameters of NormalMapSpec).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "emu/device_profile.h"
#include "inputs/environment.h"
#include "inputs/glint_lighting.h"
#include "inputs/glint_tables.h"
#include "inputs/ndf_histogram.h"
#include "inputs/normal_map.h"
#include "inputs/sh_legendre.h"

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

void BM_LightingTable(benchmark::State& state) {
  const uint32_t order = uint32_t(state.range(0)), rings = uint32_t(state.range(1));
  std::vector<float> px(size_t(1024) * 512 * 4);
  for (size_t i = 0; i < px.size(); ++i) px[i] = i % 4 == 3 ? 1.0f : 0.5f + 0.4f * std::sin(0.001f * float(i));
  const shadetwin::EnvironmentMap env = shadetwin::environmentFromLevel0(px, 1024, 512);
  shadetwin::GlintLightingSpec s;
  s.order = order, s.rings = rings, s.sectors = 2 * (rings - 1);
  while (s.level + 1 < env.texture->levelCount() && env.texture->levelWidth(s.level + 1) >= 3 * (order + 1)) ++s.level;
  size_t bytes = 0;
  for (auto _ : state) bytes = shadetwin::glintLightingEmu(*env.texture, emu::lavapipeProfile(), s).bytes();
  state.counters["MiB"] = double(bytes) / (1 << 20);
}

void BM_LobeTable(benchmark::State& state) {
  const uint32_t order = uint32_t(state.range(0)), rings = uint32_t(state.range(1));
  size_t bytes = 0;
  for (auto _ : state) bytes = shadetwin::glintLobeTable(order, rings, 2 * (rings - 1)).levels()[0].size();
  state.counters["MiB"] = double(bytes) / (1 << 20);
}

void BM_LegendreTable(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(shadetwin::shLegendreCoefficients(uint32_t(state.range(0))).levels()[0].data());
}

}  // namespace

BENCHMARK(BM_NormalMap)->ArgsProduct({{1, 2, 3, 4}, {1024}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NdfSat)->ArgsProduct({{1, 2, 3, 4}, {256, 1024, 2048}})->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK(BM_LightingTable)->ArgsProduct({{8, 16}, {33, 65}})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LobeTable)->ArgsProduct({{16, 28}, {33, 65}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LegendreTable)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
