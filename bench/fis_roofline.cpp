// Roofline of the FIS shading pass (issue 4, item 8): operations and texel reads per pixel of the
// shared shade_fis.h as executed (counted lane types, model/op_count.h) against this machine's
// measured peak for the same operations (8 independent mul + add chains on 16-lane vectors, no FMA:
// the exactness contract forbids contraction) and the emulator's own time for the pass.
// Results and the derived roofline: docs/RESULTS.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "model/op_count.h"
#include "passes/shade.h"
#include "inputs/material.h"
#include "inputs/environment.h"
#include "inputs/shade_inputs.h"
#include "lanes/instantiate.h"
#include "scene/scene.h"

#include "model/counted.h"

namespace {
using namespace shadetwin;
namespace cs = shade::counted;
using CF = opcount::F<8>;
using CV3 = shade::V3<CF>;
using CV4 = shade::V4<CF>;

struct Setup {
  Scene scene;
  EnvironmentMap env;
  GBuffer g;
  ShadeInputs in;
  size_t covered = 0;
  explicit Setup(uint32_t size, uint32_t samples) {
    scene = loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/bunny.json");
    scene.width = scene.height = size;
    scene.fisSamples = samples;
    std::ostringstream quiet;
    env = loadEnvironment(scene.environment, quiet);
    g = gbufferEmu(scene, emu::lavapipeProfile());
    in = shadeInputsEmu(scene, *env.texture, emu::lavapipeProfile());
    for (size_t p = 0; p < size_t(size) * size; ++p) covered += g.texels[p * kGbufFloats + 3] != 0.0f;
  }
};

Setup& setup() {
  static Setup s(512, 40);
  return s;
}

CV4 lanes4(const GBuffer& g, size_t first, int at) {
  CV4 r;
  const size_t n = size_t(g.width) * g.height;
  for (int l = 0; l < 8; ++l) {
    const float* t = g.texels.data() + std::min(first + size_t(l), n - 1) * kGbufFloats + at;
    r.x.set(l, t[0]), r.y.set(l, t[1]), r.z.set(l, t[2]), r.w.set(l, t[3]);
  }
  return r;
}
CV3 splat(const float v[3]) { return CV3(CF(v[0]), CF(v[1]), CF(v[2])); }

// The FIS pass of passes/shade_emu.cpp (shadeFisEmu) with counted lanes: vectors of 8 consecutive pixels.
// Gathering the G-buffer and material records (memory loads on a GPU) is not counted.
void countFisPass(const Setup& s) {
  const Scene& scene = s.scene;
  const GBuffer& g = s.g;
  const emu::DeviceProfile& dev = emu::lavapipeProfile();
  const shade::Sampler2D atlas = environmentSampler(*s.in.atlas, dev, false);
  const shade::Sampler2D env = environmentSampler(*s.env.texture, dev, true);
  const shade::Sampler2D maps = materialMapSampler(*s.in.maps, dev);
  const std::vector<MaterialGpu> mats = materialRecords(scene, true);
  const CameraRays cam = cameraRays(scene);
  CV3 c[9];
  for (int k = 0; k < 9; ++k) c[k] = splat(&s.in.sh.c[3 * size_t(k)]);
  const cs::ShRgb sh{c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8]};
  const CF maxLod(float(s.in.atlas->levelCount() - 1)), levelC(fisLevelConstant(scene)), bias(scene.fisLevelBias),
      intensity(scene.environmentIntensity), invW(1.0f / float(g.width)), invH(1.0f / float(g.height));
  const size_t n = size_t(g.width) * g.height;
  for (size_t b = 0; b < (n + 7) / 8; ++b) {
    const CV4 g0 = lanes4(g, 8 * b, 0), g1 = lanes4(g, 8 * b, 4), g2 = lanes4(g, 8 * b, 8), g3 = lanes4(g, 8 * b, 12);
    CV4 rec[6];
    opcount::U<8> kind(0u), mp[3], pixel(0u);
    CF px, py;
    for (int l = 0; l < 8; ++l) {
      const size_t i = std::min(8 * b + size_t(l), n - 1);
      const MaterialGpu& m = mats[shade::scalar::materialSlot(g.texels[i * kGbufFloats + 3], uint32_t(mats.size()))];
      const float* src[6] = {m.diffuse, m.specular, m.brdf, m.lobe0, m.lobe1, m.rho};
      for (int k = 0; k < 6; ++k) rec[k].x.set(l, src[k][0]), rec[k].y.set(l, src[k][1]), rec[k].z.set(l, src[k][2]), rec[k].w.set(l, src[k][3]);
      kind.set(l, m.kind[0]);
      for (int k = 0; k < 3; ++k) mp[k].set(l, m.maps[k]);
      pixel.set(l, uint32_t(i));
      px.set(l, float(i % g.width));
      py.set(l, float(i / g.width));
    }
    const CV3 ray = cs::cameraRay(splat(cam.fwd), splat(cam.right), splat(cam.down), px, py, invW, invH);
    const cs::SurfaceMaterial m =
        cs::surfaceMaterial(maps, CV3(rec[0].x, rec[0].y, rec[0].z), CV3(rec[1].x, rec[1].y, rec[1].z),
                            cs::brdfParamsPacked(kind, rec[2], rec[3], rec[4], rec[5]), mp[0], mp[1], mp[2], g1, g2, g3);
    const CV4 zero(CF(0.0f), CF(0.0f), CF(0.0f), CF(0.0f));
    const cs::Sh16 noVis{zero, zero, zero, zero};  // the roofline counts the pass without visibility
    const CV4 out = cs::shadeFis(atlas, env, shade::scalar::kFisBackgroundEnvironment, shade::scalar::kFisFiltered, maxLod, levelC, bias, scene.fisSamples, intensity, sh,
                                 pixel, g0, g1, g2, splat(cam.eye), ray, m.diffuse, m.specular, m.brdf,
                                 shade::scalar::kFisVisNone, noVis, cs::VisLighting{noVis, noVis, noVis});
    benchmark::DoNotOptimize(out);
  }
}

void BM_FisOpCount(benchmark::State& state) {
  const Setup& s = setup();
  std::array<uint64_t, opcount::kKinds> total{};
  // The roofline compares elementary operations with the machine's mul/add peak: exact divisions and square roots
  // count as their portable routines' operations (not the performance model's ex_div / ex_sqrt classes).
  opcount::countPortableExactMath = true;
  for (auto _ : state) {
    opcount::counts = {};
    countFisPass(s);
    total = opcount::counts;
  }
  opcount::countPortableExactMath = false;
  const double pixels = double(s.scene.width) * s.scene.height;
  // Vector operations count 8 lane operations; texture counts are per lane already.
  double laneOps = 0;
  for (int k = 0; k < opcount::kKinds; ++k) {
    const double perPixel = (k == opcount::kTexLookup || k == opcount::kTexel) ? double(total[size_t(k)]) / pixels
                                                                               : 8.0 * double(total[size_t(k)]) / pixels;
    state.counters[std::string(opcount::kKindNames[k]) + "/px"] = perPixel;
    if (k < opcount::kTexLookup) laneOps += perPixel;
  }
  state.counters["alu_ops/px"] = laneOps;
  state.counters["covered"] = double(s.covered) / pixels;
  state.counters["samples"] = s.scene.fisSamples;
}
BENCHMARK(BM_FisOpCount)->Unit(benchmark::kMillisecond)->Iterations(1);

// The emulated pass itself (TBB over all cores, as shadetwin render / bench run it).
void BM_FisPassEmu(benchmark::State& state) {
  const Setup& s = setup();
  std::vector<float> out;
  for (auto _ : state) {
    shadeEmu(s.scene, s.g, s.in, emu::lavapipeProfile(), out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["pixels/s"] = benchmark::Counter(double(s.scene.width) * s.scene.height, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_FisPassEmu)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

// Peak of the counted operation mix on this machine: 8 independent chains of x = x * a + b (a separate
// mul and add: no FMA under the exactness contract) on 16-lane vectors; items = lane operations.
void BM_PeakMulAdd(benchmark::State& state) {
  using V = emu::F32<16>;
  V x[8];
  for (int i = 0; i < 8; ++i) x[i] = V(1.0f + 0.01f * float(i));
  const V a(0.999f), b(0.001f);
  constexpr int kIter = 4096;
  for (auto _ : state) {
    for (int it = 0; it < kIter; ++it)
      for (int i = 0; i < 8; ++i) x[i] = x[i] * a + b;
    benchmark::DoNotOptimize(x);
  }
  state.SetItemsProcessed(state.iterations() * kIter * 8 * 2 * 16);
}
BENCHMARK(BM_PeakMulAdd)->Threads(1)->Threads(2)->UseRealTime();

// Memory bandwidth (a read of 256 MiB, summed): the texel traffic bound.
void BM_ReadBandwidth(benchmark::State& state) {
  static std::vector<float> big(size_t(64) << 20, 1.0f);
  const size_t per = big.size() / size_t(state.threads()), off = per * size_t(state.thread_index());
  for (auto _ : state) {
    emu::F32<16> acc(0.0f);
    for (size_t i = off; i + 16 <= off + per; i += 16) {
      emu::F32<16> v;
      std::memcpy(&v.v, &big[i], 64);
      acc = acc + v;
    }
    benchmark::DoNotOptimize(acc);
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(per * 4));
}
BENCHMARK(BM_ReadBandwidth)->Threads(1)->Threads(2)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
