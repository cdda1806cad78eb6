// Trilinear lookups per second: the emulator (lavapipe profile) against lavapipe itself, same
// texture, same queries, in one run. 512x512 RGBA32F with a full chain, clamp-to-edge.
#include <benchmark/benchmark.h>

#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "emu/sampler.h"
#include "vk/context.h"

namespace {
#include "verify_texture_comp.inc"

struct Fixture {
  std::unique_ptr<emu::Texture> tex;
  std::vector<float> queries;
  Fixture() {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    std::vector<std::vector<uint8_t>> levels;
    for (uint32_t l = 0; l < 10; ++l) {
      uint32_t s = 512u >> l;
      std::vector<float> px(size_t(s) * s * 4);
      for (auto& v : px) v = U(rng);
      levels.emplace_back(px.size() * 4);
      std::memcpy(levels.back().data(), px.data(), px.size() * 4);
    }
    tex = std::make_unique<emu::Texture>(emu::Format::RGBA32F, 512, 512, 1, std::move(levels));
    const size_t n = 1 << 20;
    queries.resize(4 * n);
    for (size_t i = 0; i < n; ++i) {
      queries[4 * i] = U(rng);
      queries[4 * i + 1] = U(rng);
      queries[4 * i + 2] = 0.0f;
      queries[4 * i + 3] = U(rng) * 9.0f;
    }
  }
};
Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_EmulatorTrilinear(benchmark::State& state) {
  Fixture& f = fixture();
  const size_t n = f.queries.size() / 4;
  std::vector<float> out(4 * n);
  emu::SamplerDesc s;
  for (auto _ : state) {
    emu::textureLodBatch(*f.tex, s, emu::lavapipeProfile(), emu::Stage::Compute, f.queries.data(), out.data(), n);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
}
BENCHMARK(BM_EmulatorTrilinear)->Unit(benchmark::kMillisecond)->UseRealTime();

// The one-lane model (textureLod per query, one thread): the same bits, without lanes or threads.
void BM_EmulatorTrilinearScalar(benchmark::State& state) {
  Fixture& f = fixture();
  const size_t n = f.queries.size() / 4;
  std::vector<float> out(4 * n);
  emu::SamplerDesc s;
  for (auto _ : state) {
    for (size_t i = 0; i < n; ++i) {
      emu::Texel4 t = emu::textureLod(*f.tex, s, emu::lavapipeProfile(), f.queries[4 * i], f.queries[4 * i + 1],
                                      f.queries[4 * i + 2], f.queries[4 * i + 3]);
      std::memcpy(&out[4 * i], &t, 16);
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
}
BENCHMARK(BM_EmulatorTrilinearScalar)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LavapipeTrilinear(benchmark::State& state) {
  Fixture& f = fixture();
  using namespace shadetwin::vk;
  Context ctx;
  const size_t n = f.queries.size() / 4;
  Image image(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, 512, 512, 1, f.tex->levels(), 16);
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = 1000.0f;
  Sampler sampler(ctx, si);
  const VkDescriptorType layout[] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  Kernel k(ctx, Stage::Compute, kSpv_verify_texture_comp, layout, 12);
  Buffer q(ctx, n * 16), r(ctx, n * 16);
  std::memcpy(q.data(), f.queries.data(), n * 16);
  const Binding b[] = {{layout[0], VK_NULL_HANDLE, image.view(), sampler.handle()}, {layout[1], q.handle()}, {layout[2], r.handle()}};
  struct { uint32_t mode, count, width; } push{0, uint32_t(n), 1024};
  k.run(b, &push, uint32_t(n));  // warm-up: shader compile
  for (auto _ : state) k.run(b, &push, uint32_t(n));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
}
BENCHMARK(BM_LavapipeTrilinear)->Unit(benchmark::kMillisecond)->UseRealTime();
}  // namespace

BENCHMARK_MAIN();
