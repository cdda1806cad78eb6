// Kd-tree build time (issue 5, item 1): 6144 blocks on the CC0 maps at their 1024x512 and upsampled
// (each texel 2x2) to 2048x1024; summed-area tables included.
#include <benchmark/benchmark.h>

#include <sstream>
#include <string>

#include "inputs/env_kdtree.h"
#include "inputs/environment.h"

namespace {
std::vector<double> weights(const std::string& name, int scale, uint32_t& W, uint32_t& H) {
  std::ostringstream quiet;
  const shadetwin::EnvironmentMap env =
      shadetwin::loadEnvironment(std::string(SHADETWIN_SOURCE_DIR) + "/assets/hdri/" + name + ".exr", quiet);
  W = env.width * uint32_t(scale), H = env.height * uint32_t(scale);
  const std::vector<float> big = shadetwin::repeatTexels(env.levels[0].data(), env.width, env.height, uint32_t(scale));
  return shadetwin::envSamplingWeights(big.data(), W, H);
}

void BM_KdTreeBuild(benchmark::State& state) {
  const int scale = int(state.range(0));
  uint32_t W, H;
  const std::vector<double> w = weights("city", scale, W, H);
  size_t blocks = 0;
  for (auto _ : state) {
    const auto t = shadetwin::buildEnvKdTree(w, W, H, uint32_t(state.range(1)));
    blocks = t.blocks.size();
    benchmark::DoNotOptimize(t.blocks.data());
  }
  state.counters["blocks"] = double(blocks);
  state.counters["width"] = W;
}
BENCHMARK(BM_KdTreeBuild)->Args({1, 6144})->Args({2, 6144})->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
