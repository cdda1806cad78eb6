// The device's environment samplers (issue 5, items 2-3) on one core: directions per second, each with
// the pdf lookup of its direction, for the kd-tree (fitted block distribution), the alias table over the
// same blocks and the inversion method, in the C++ scalar and 8-lane builds of shade/env_sampling.h; and
// the host's table build. `shadetwin sweep` measures the same probe on every core and on Vulkan.
#include <benchmark/benchmark.h>

#include <cstring>
#include <sstream>
#include <string>

#include "emu/device_profile.h"
#include "inputs/env_sampling.h"
#include "passes/shade.h"
#include "inputs/environment.h"
#include "lanes/instantiate.h"

namespace {
const emu::Texture& city() {
  static const emu::Texture t = [] {
    std::ostringstream quiet;
    const shadetwin::EnvironmentMap env =
        shadetwin::loadEnvironment(std::string(SHADETWIN_SOURCE_DIR) + "/assets/hdri/city.exr", quiet);
    return emu::floatTexture(emu::Format::RGBA32F, env.width, env.height, env.levels[0].data());
  }();
  return t;
}

void BM_EnvSamplingTables(benchmark::State& state) {
  for (auto _ : state) {
    const auto T = shadetwin::envSamplingTables(city(), uint32_t(state.range(0)), 6144);
    benchmark::DoNotOptimize(T.table.get());
  }
}
BENCHMARK(BM_EnvSamplingTables)->Arg(0)->Arg(1)->Arg(2)->ArgNames({"method"})->Unit(benchmark::kMillisecond);

template <int Lanes>
void BM_EnvSample(benchmark::State& state) {
  const auto T = shadetwin::envSamplingTables(city(), uint32_t(state.range(0)), 6144);
  const auto& dev = emu::lavapipeProfile();
  const auto table = shadetwin::environmentSampler(*T.table, dev, false),
             texels = shadetwin::environmentSampler(*T.texels, dev, false);
  const auto& u = T.uniforms;
  const uint32_t per = 64;
  uint32_t stream = 0;
  for (auto _ : state) {
    if constexpr (Lanes == 1) {
      const auto es = shadetwin::toEnvSampling<shadetwin::shade::scalar::EnvSampling>(u);
      benchmark::DoNotOptimize(shadetwin::shade::scalar::envSamplingChecksum(table, texels, es, stream++, per, 1u));
    } else {
      const auto es = shadetwin::toEnvSampling<shadetwin::shade::x8::EnvSampling>(u);
      emu::U32<8> idx;
      for (int l = 0; l < 8; ++l) idx.set(l, stream * 8 + uint32_t(l));
      ++stream;
      benchmark::DoNotOptimize(shadetwin::shade::x8::envSamplingChecksum(table, texels, es, idx, per, 1u));
    }
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * per * Lanes);
}
BENCHMARK_TEMPLATE(BM_EnvSample, 1)->Arg(0)->Arg(1)->Arg(2)->ArgNames({"method"});
BENCHMARK_TEMPLATE(BM_EnvSample, 8)->Arg(0)->Arg(1)->Arg(2)->ArgNames({"method"});
}  // namespace
BENCHMARK_MAIN();
