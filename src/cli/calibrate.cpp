#include "cli/calibrate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <span>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include <unistd.h>

#include "emu/device_profile.h"
#include "model/spirv_loops.h"
#include "model/vertex_cache.h"
#include "passes/passes_vk.h"
#include "passes/gbuffer.h"
#include "passes/shadow.h"
#include "scene/scene.h"
#include "util/timer.h"
#include "vk/context.h"

namespace shadetwin {

namespace {
#include "calibrate_modules.inc"
#include "calibrate_group_comp.inc"
#include "calibrate_compile_comp.inc"

struct Push {
  uint32_t kind, iters, count, pad;
  float c, lod, step, pad2;
};
static_assert(sizeof(Push) == 32, "calibrate.comp push constants");

enum Kind : uint32_t {
  kFAddK, kFMulK, kIAluK, kIMulK, kCvtK, kSelectK, kTexK, kCopyK, kEmptyK, kWindowK, kBranchK, kBranchLoopK,
  kBranchUnrolledK, kSpecBranchK, kUniformFetchK, kStreamK, kShiftK, kICmpK, kISelectK,
  kPrivReadK, kPrivWriteK,
  kExDivK, kExSqrtK,  // calibrate_exmath.comp's kinds 0 and 1 (the shared exDiv and exSqrt)
  kSharedBlocksK, kDistinctBlocksK,  // calibrate.comp's kinds 23 and 24
  kRereadK,                          // calibrate.comp's kind 25
  kFetchK                            // calibrate.comp's kind 26
};
// Chain steps per iteration of the arithmetic kernels (calibrate.comp STEPS_INDEP, STEPS_DEP).
constexpr double kSteps = 128.0;

// The host's last-level cache, for the description: line size and capacity, and where they were read (sysfs; where a
// virtual machine has no sysfs cache entries, glibc's sysconf from CPUID: its level 3 where it is a plausible size, a
// VM's CPUID can report the whole host's, 508 MiB on one; else its level 2; else 1 MiB assumed).
std::string hostCache(int& lineBytes, double& bytes) {
  lineBytes = 64, bytes = 0.0;
  int bestLevel = 0;
  for (int idx = 0; idx < 8; ++idx) {
    const std::string dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(idx) + "/";
    std::ifstream lv(dir + "level"), sz(dir + "size"), ln(dir + "coherency_line_size"), ty(dir + "type");
    int level = 0, line = 0;
    std::string size, type;
    if (!(lv >> level) || !(sz >> size) || !(ln >> line) || !(ty >> type) || type == "Instruction") continue;
    double b = std::stod(size);
    if (size.back() == 'K') b *= 1024.0;
    if (size.back() == 'M') b *= 1024.0 * 1024.0;
    if (level >= bestLevel) bestLevel = level, bytes = b, lineBytes = line;
  }
  if (bytes > 0.0) return "sysfs";
  const long l3 = sysconf(_SC_LEVEL3_CACHE_SIZE), l2 = sysconf(_SC_LEVEL2_CACHE_SIZE);
  const long line = sysconf(_SC_LEVEL1_DCACHE_LINESIZE);
  if (line > 0) lineBytes = int(line);
  if (l3 > 0 && l3 <= 256L << 20) return bytes = double(l3), "sysconf level 3 (no sysfs cache entries)";
  if (l2 > 0) return bytes = double(l2), "sysconf level 2 (no sysfs cache entries; level 3 " + std::to_string(l3 >> 20) + " MiB is not a plausible size)";
  bytes = 1024.0 * 1024.0;
  return "1 MiB assumed (no sysfs cache entries, no sysconf sizes)";
}
}  // namespace

model::DeviceDesc calibrateDevice(const CalibrateOptions& opts, std::ostream& log) {
  vk::Context ctx({opts.device == "lavapipe" ? std::string("llvmpipe") : opts.device, false});
  log << "calibrate: " << ctx.deviceName() << (opts.quick ? " (quick)" : "") << std::endl;
  const VkDescriptorType layout[] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  // One pipeline per kind and chain layout, each its own module (calibrate_modules.inc, built by CMakeLists.txt: the
  // other kinds' code is not in it). Specialization constants: 0 is the exact-math module's prelude constant (~0u);
  // 1 is kind 13's DEPENDENT (pad = 1 asks for the dependent chain; the other modules have none, and ignore it).
  std::unique_ptr<vk::Kernel> kernels[2][kFetchK + 1];
  // Modules outside the [dependent][kind] table: while `special` is not empty, the kernel runs from it (the division
  // kernel's larger modules, kCalibrateCodeSizeModules: the code-size term; kCalibrateCarriedModules: the loop-state term).
  std::span<const uint32_t> special;
  std::map<const uint32_t*, std::unique_ptr<vk::Kernel>> specialKernels;
  auto kernel = [&](uint32_t kind, uint32_t dependent) -> vk::Kernel& {
    if (!special.empty()) {
      const uint32_t spec[] = {~0u, 0u};
      std::unique_ptr<vk::Kernel>& k = specialKernels[special.data()];
      if (!k)
        k = std::make_unique<vk::Kernel>(ctx, vk::Stage::Compute, special, layout, sizeof(Push), std::span<const uint32_t>{},
                                         std::span<const uint32_t>(spec));
      return *k;
    }
    if (!kernels[dependent][kind]) {
      const std::span<const uint32_t> module = kCalibrateModules[dependent][kind];
      if (module.empty()) throw std::logic_error("calibrate: no module for kind " + std::to_string(kind) + (dependent ? " (dependent)" : ""));
      const uint32_t spec[] = {~0u, dependent};
      kernels[dependent][kind] = std::make_unique<vk::Kernel>(ctx, vk::Stage::Compute, module, layout, sizeof(Push),
                                                              std::span<const uint32_t>{}, std::span<const uint32_t>(spec));
    }
    return *kernels[dependent][kind];
  };
  // A 256^2 RGBA32F texture with its full chain of random texels.
  const uint32_t T = 256;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  std::vector<std::vector<uint8_t>> levels;
  for (uint32_t s = T; s >= 1; s /= 2) {
    std::vector<float> px(size_t(s) * s * 4);
    for (float& v : px) v = U(rng);
    levels.emplace_back(px.size() * 4);
    std::memcpy(levels.back().data(), px.data(), levels.back().size());
  }
  vk::Image img(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, T, T, 1, levels, 16, VK_IMAGE_VIEW_TYPE_2D);
  // A texture far larger than the host's last-level cache (one level, 256 MiB; quick: 64 MiB) for the miss kernel.
  const uint32_t B = opts.quick ? 2048u : 4096u;
  std::unique_ptr<vk::Image> big;
  {
    std::vector<std::vector<uint8_t>> one(1);
    one[0].resize(size_t(B) * B * 16);
    for (size_t i = 0; i < one[0].size(); i += 4) {
      const float f = float(i & 1023u) * (1.0f / 1024.0f);
      std::memcpy(&one[0][i], &f, 4);
    }
    big = std::make_unique<vk::Image>(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, B, B, 1, one, 16, VK_IMAGE_VIEW_TYPE_2D);
  }
  VkImageView view = img.view();  // the texture the kernels read
  auto makeSampler = [&](VkFilter f, VkSamplerMipmapMode m) {
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = f;
    si.mipmapMode = m;
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    si.maxLod = 1000.0f;
    return std::make_unique<vk::Sampler>(ctx, si);
  };
  auto nearest = makeSampler(VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST);
  auto bilinear = makeSampler(VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST);
  auto trilinear = makeSampler(VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR);
  const size_t copyVec4s = (opts.quick ? 8u : 64u) << 16;  // vec4s per buffer: 8 MiB / 64 MiB, past the host caches
  vk::Buffer src(ctx, copyVec4s * 16), dst(ctx, copyVec4s * 16);
  std::memset(src.data(), 0, copyVec4s * 16);
  const uint32_t count = opts.quick ? 16384u : 131072u;
  const double target = opts.quick ? 0.02 : 0.25;  // seconds per timed run

  // One dispatch of `k` over n invocations, submit to completion, in seconds.
  auto runOnce = [&](vk::Kernel& k, Push p, VkSampler s, uint32_t n) {
    const vk::Binding b[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, view, s},
                             {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, src.handle()},
                             {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, dst.handle()}};
    p.count = n;
    const auto t0 = std::chrono::steady_clock::now();
    k.run(b, &p, n);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  // `run` once to warm up (pipeline, caches, first-touch pages), then the fastest of `timed` runs.
  auto fastestAfterWarmUp = [](int timed, auto&& run) {
    run();
    std::vector<double> t;
    for (int r = 0; r < timed; ++r) t.push_back(run());
    return fastestOf(t);
  };
  auto timeRun = [&](Push p, VkSampler s, uint32_t n) {
    return fastestAfterWarmUp(3, [&] { return runOnce(kernel(p.kind, p.pad), p, s, n); });
  };
  // Rounds: every measurement below runs once per round, and each keeps the best it read in any round (the fastest
  // time, the highest rate: util/timer.h BestOfRounds, keyed by its place in the round). A host that is slow for a
  // while (another process, a noisy neighbour: one SwiftShader calibration read 0.75 GB/s and a 181 us dispatch where
  // the one before read 5.5 GB/s and 72 us) then moves a measurement only if it is slow in every round; the pass times
  // the model is checked against are the fastest of their runs too. The rates derived from others (shift, cvt, the
  // compares and selects, the latencies) are derived in each round from the best so far, so the last round's are from
  // the best of all.
  BestOfRounds best;
  const int rounds = std::max(1, opts.rounds ? opts.rounds : opts.quick ? 1 : 3);
  // The empty kernel in a module of its own (calibrate_group.comp): the launch and the per-workgroup cost.
  vk::Kernel group(ctx, vk::Stage::Compute, kSpv_calibrate_group_comp, layout, sizeof(Push));
  std::vector<uint32_t> rateIters;  // each rate's iteration count, found in the first round and kept after
  std::ostringstream earlier;  // the rounds before the last: their details are not printed
  model::DeviceDesc result;
  std::string cacheSource;  // where hostCache read the cache
  for (int round = 0; round < rounds; ++round) {
    best.nextRound();
    earlier.str("");
    std::ostream& out = round + 1 == rounds ? log : earlier;
    const auto roundStart = std::chrono::steady_clock::now();
    // Launch cost: an empty dispatch of one workgroup, the fastest of many, in the empty kernel's own module.
    Push e{kEmptyK, 0, 0, 0, 1.0f, 0.0f, 0.0f, 0.0f};
    std::vector<double> empties;
    for (int r = 0; r < 15; ++r)
      empties.push_back(fastestAfterWarmUp(3, [&] { return runOnce(group, e, nearest->handle(), 64); }));
    const double dispatch = best.low(fastestOf(empties));
    double perGroup = 0.0;  // the model's cost per workgroup (the rates below are differences: it cancels there)
    // Per workgroup of 64 invocations: a kernel that does nothing, in a module of its own (calibrate_group.comp), over
    // 4096 workgroups against 64, the fastest of five each. (When calibrate.comp was one module of every kernel,
    // SwiftShader's workgroups there cost ~33-120 us each: not a set-up that grows with the module, as sessions 22-40
    // read it, but every other kernel's code run under a false mask, SwiftShader not folding the specialization
    // constant that picked the kernel; docs/RESULTS.md session 41. Each kernel now has its own module.)
    {
      auto groups = [&](uint32_t n) { return fastestAfterWarmUp(3, [&] { return runOnce(group, e, nearest->handle(), 64u * n); }); };
      std::vector<double> many, few;
      for (int r = 0; r < 5; ++r) many.push_back(groups(4096)), few.push_back(groups(64));
      const double tMany = best.low(fastestOf(many)), tFew = best.low(fastestOf(few));
      perGroup = std::max(tMany - tFew, 0.0) / 4032.0;
      out << "  workgroup " << perGroup * 1e9 << " ns per workgroup of 64 (an empty kernel in a module of its own, 4096 "
          << "workgroups vs 64: " << tMany * 1e3 << " / " << tFew * 1e3 << " ms)\n";
    }
    // A pipeline's first dispatch (the Vulkan build creates the technique inputs' pipelines each time it builds them,
    // and a pass made that way runs once on it): lavapipe compiles a compute shader's machine code at its first dispatch,
    // and the compiled code then runs cold, so the first dispatch costs more than a warm one, more for a larger module
    // (probes, docs/RESULTS.md session 31: 0.3 ms more for the 0.4K-word group module, 0.6 ms for mip_downsample's 6K
    // words, 1.0 ms for the paraboloid module's 12K). Two modules of their own and of known size, calibrate_group.comp
    // and the straight-line calibrate_compile.comp: on each, the fastest first dispatch of 9 pipelines created just
    // before, less the warm dispatch above (the pass times are the fastest of their runs, each on a new pipeline, so the
    // fastest against the fastest). The cost per SPIR-V word is the line through the two; the cost of a pipeline
    // itself is that line at zero words. Earlier calibrations read the first dispatch of calibrate.comp's empty kind
    // against its second: 0.58 ms, more than the whole SH reduction measures (0.37 ms), as that module is 102K words
    // before its kinds fold.
    double firstDispatch = 0.0, compilePerWord = 0.0;
    {
      auto firstOf = [&](std::span<const uint32_t> spv) {
        std::vector<double> t;
        for (int r = 0; r < 9; ++r) {
          vk::Kernel fresh(ctx, vk::Stage::Compute, spv, layout, sizeof(Push));
          t.push_back(runOnce(fresh, e, nearest->handle(), 64));
        }
        return std::max(best.low(fastestOf(t)) - dispatch, 0.0);
      };
      const double w0 = double(std::size(kSpv_calibrate_group_comp)), w1 = double(std::size(kSpv_calibrate_compile_comp));
      const double small = firstOf(kSpv_calibrate_group_comp), large = firstOf(kSpv_calibrate_compile_comp);
      compilePerWord = std::max(large - small, 0.0) / (w1 - w0);
      firstDispatch = std::max(small - compilePerWord * w0, 0.0);
      out << "  first dispatch of a new pipeline: " << small * 1e6 << " us beyond a warm dispatch for " << w0 << " SPIR-V words, "
          << large * 1e6 << " us for " << w1 << ": " << firstDispatch * 1e6 << " us + " << compilePerWord * 1e9
          << " ns per word\n";
    }
    // A rate from the difference of two runs: N iterations and 2N, N grown in the first round until a run takes half
    // of `target` seconds (and kept in the rounds after, so each run's time is the fastest of every round). The
    // difference is N iterations' work alone: the launch, the workgroups' setup and the prologue and epilogue of each
    // invocation cancel (subtracting an empty kernel's run instead would leave whatever the two modules' prologues
    // differ by).
    size_t rateAt = 0;
    int inseparable = 0;  // rates read from one run (printed at the end of the round)
    auto rate = [&](uint32_t kind, double workPerIter, VkSampler s, float c, float lod, uint32_t dependent = 0,
                    uint32_t startIters = 16) {
      Push p{kind, startIters, 0, dependent, c, lod, 0.0173f, 0.0f};
      double t = 0.0, tq = 0.0;  // the runs at N and 2N: in the first round the last pair of the search for N
      if (rateAt == rateIters.size()) {
        // N grows until a run takes half of `target` and N iterations' work is at least half the run's fixed part
        // (the 2N run at least 1.33x the N run): a run at half of a --quick target may be mostly fixed part (it was on
        // SwiftShader while every kernel shared one module, and its 2N run only 5% longer).
        for (;;) {
          t = timeRun(p, s, count);
          Push q2 = p;
          q2.iters = 2 * p.iters;
          tq = timeRun(q2, s, count);
          const double w = tq - t;  // N iterations' work (noisy while small)
          if ((t >= 0.5 * target && w >= 0.33 * t) || p.iters >= (1u << 23)) break;
          const double byTime = 0.6 * target / std::max(t, 1e-6), byWork = t / std::max(w, t / 16.0);
          p.iters = uint32_t(std::min<double>(double(1u << 23), double(p.iters) * std::clamp(std::max(byTime, byWork), 2.0, 64.0)));
        }
        rateIters.push_back(p.iters);
      } else {
        p.iters = rateIters[rateAt];
        t = timeRun(p, s, count);
      }
      ++rateAt;
      Push q = p;
      q.iters = 2 * p.iters;
      if (tq == 0.0) tq = timeRun(q, s, count);  // a later round: the 2N run right after the N run
      // The difference is N iterations' work only if neither run fell into a slow spell: the 2N run takes 1.15-2.3
      // times the N run (2x the work plus the same fixed part, which may be up to ~6x the work in SwiftShader's
      // workgroup-heavy runs). Outside that, both are re-run (the fastest of each kept): one single-round SwiftShader
      // calibration (session 26) differenced its fmul to 2.8 Tops/s and its conversions to 21 Tops/s, 90x and 960x
      // every other reading, from a t2 barely above t1. Still outside after the retries (or after the best of the
      // rounds is taken), the rate is the 2N run's alone: it includes the fixed part, so it errs low, never absurdly.
      double t1 = t, t2 = tq;
      const auto separable = [](double a, double b) { return b > 1.15 * a && b < 2.3 * a; };
      for (int retry = 0; retry < 6 && !separable(t1, t2); ++retry) {
        t1 = std::min(t1, timeRun(p, s, count));
        t2 = std::min(t2, timeRun(q, s, count));
      }
      t1 = best.low(t1), t2 = best.low(t2);
      const double work = double(count) * double(p.iters) * workPerIter;
      if (separable(t1, t2)) return work / (t2 - t1);
      out << "  (kernel " << kind << ": runs of N and 2N iterations took " << t1 * 1e3 << " and " << t2 * 1e3
          << " ms, not separable: its rate from the 2N run alone)\n";
      ++inseparable;
      return 2.0 * work / t2;
    };
    model::DeviceDesc d;
    const std::string name = ctx.deviceName();
    d.device = name.find("SwiftShader") != std::string::npos ? "swiftshader" : name.find("llvmpipe") != std::string::npos ? "lavapipe" : opts.device;
    d.name = name;
    d.verified = true;
    d.cores = int(std::max(1u, std::thread::hardware_concurrency()));
    d.lanes = d.device == "swiftshader" ? 4 : name.find("256 bits") != std::string::npos ? 8 : 4;
    // The post-transform vertex cache the model simulates, from the driver's source (DeviceDesc VertexCacheDesc):
    // SwiftShader's direct-mapped 64 entries, batches of 128 triangles, a miss shading 4 consecutive entries. lavapipe's
    // draw module (a hashed cache per vertex segment) is not simulated: its vertex work stays in the triangle rate.
    if (d.device == "swiftshader") d.vertexCache = {64, 128, 4};
    auto& ops = d.opsPerSecond;
    ops[model::kFAdd] = rate(kFAddK, kSteps, nearest->handle(), 1.0e-3f, 0.0f);
    ops[model::kFMul] = rate(kFMulK, kSteps, nearest->handle(), 1.0000001f, 0.0f);
    ops[model::kIAlu] = rate(kIAluK, 2.0 * kSteps, nearest->handle(), 1.5f, 0.0f);
    {  // shift: 1 shift + 1 integer add per chain step; the add's share at the measured ialu rate is removed
      const double mixed = rate(kShiftK, 2.0 * kSteps, nearest->handle(), 1.5f, 0.0f);
      const double perStep = 2.0 / mixed, add = 1.0 / ops[model::kIAlu];
      ops[model::kShift] = 1.0 / std::max(perStep - add, perStep * 0.25);
    }
    ops[model::kIMul] = rate(kIMulK, kSteps, nearest->handle(), 1.5f, 0.0f);
    {  // cvt: 2 conversions + 1 fmul per chain step; the fmul's share at the measured fmul rate is removed
      const double mixed = rate(kCvtK, 3.0 * kSteps, nearest->handle(), 1.0001f, 0.0f);  // ops/s of the mix
      const double perStep = 3.0 / mixed, alu = 1.0 / ops[model::kFMul];
      ops[model::kCvt] = 2.0 / std::max(perStep - alu, perStep * 0.25);
    }
    {  // select + compare: 1 + 1 per chain step beside 2 fadd, whose share is removed; the two share the rest
      const double mixed = rate(kSelectK, 4.0 * kSteps, nearest->handle(), 0.75f, 0.0f);
      const double perStep = 4.0 / mixed, fadd = 2.0 / ops[model::kFAdd];
      ops[model::kSelect] = ops[model::kFCmp] = 2.0 / std::max(perStep - fadd, perStep * 0.25);
    }
    {  // iselect: 1 fcmp + 1 integer select + 2 integer ALU + 1 fadd per chain step, all but the select's share removed;
       // icmp: 1 integer compare + 1 integer select + 2 integer ALU, the select's and the ALU's shares removed
      const double perSel = 5.0 / rate(kISelectK, 5.0 * kSteps, nearest->handle(), 1.0e-3f, 0.0f);
      const double known = 1.0 / ops[model::kFCmp] + 2.0 / ops[model::kIAlu] + 1.0 / ops[model::kFAdd];
      ops[model::kISelect] = 1.0 / std::max(perSel - known, perSel * 0.1);
      const double perCmp = 4.0 / rate(kICmpK, 4.0 * kSteps, nearest->handle(), 1.5f, 0.0f);
      const double knownCmp = 1.0 / ops[model::kISelect] + 2.0 / ops[model::kIAlu];
      ops[model::kICmp] = 1.0 / std::max(perCmp - knownCmp, perCmp * 0.1);
    }
    {  // A local array at a run-time index (the dialect's arrayGet / arraySet): kind 19 does 1 private read + 1 fadd a
       // step, kind 20 1 private read + 1 fadd + 1 private write (32 steps an iteration); the known shares are removed.
      constexpr double kPrivSteps = 32.0;
      const double perRead = 2.0 / rate(kPrivReadK, 2.0 * kPrivSteps, nearest->handle(), 1.0e-3f, 0.0f);
      ops[model::kPrivateRead] = 1.0 / std::max(perRead - 1.0 / ops[model::kFAdd], perRead * 0.1);
      const double perRmw = 3.0 / rate(kPrivWriteK, 3.0 * kPrivSteps, nearest->handle(), 1.0e-3f, 0.0f);
      ops[model::kPrivateWrite] =
          1.0 / std::max(perRmw - 1.0 / ops[model::kFAdd] - 1.0 / ops[model::kPrivateRead], perRmw * 0.1);
    }
    // The exact-math layer's division and square root, each the shared routine itself (calibrate_exmath.comp, 16 steps
    // an iteration): a division a step; a square root and an fadd (whose share is removed) a step.
    constexpr double kExSteps = 16.0;
    ops[model::kExDiv] = rate(kExDivK, kExSteps, nearest->handle(), 1.0001f, 0.0f);
    {  // Code size: the division kernel written out 4x and 16x (the same divisions a step, each step in a module that many
       // times the size) against the 1x module's rate just read: the slowdown rate(1x) / rate(Ux) at words(Ux), never
       // below 1 (DeviceDesc codeWords, codeSlowdown; the shading modules are up to 14x the 1x module's 16K words). Each
       // search for N starts at the 1x kernel's divisions per invocation (16 / U iterations). --quick leaves out the 16x
       // module (SwiftShader takes ~20 s to create its pipeline).
       // Reported, not written: the file gets no points (the term off). The module's size is not what the device's
       // code costs: SwiftShader's 16x point read 2.13 (session 43), 2.76 and 0.92 (two session-44 runs), and with the
       // points the shading passes of its largest modules were over-predicted (kdtree-mis +48% and +102%, fis +18% and
       // +52%) where without them they are within -26% and -11% (docs/RESULTS.md sessions 43, 44). The model keeps the
       // term for a file that has points (model::codeSizeFactor).
      const double w1 = double(kCalibrateCodeSizeModules[0].size());
      out << "  code size " << w1 << " words: ex_div " << ops[model::kExDiv] / 1e6 << " M/s";
      for (size_t m = 1; m < (opts.quick ? 2u : std::size(kCalibrateCodeSizeModules)); ++m) {
        special = kCalibrateCodeSizeModules[m];
        const uint32_t u = kCalibrateCodeSizeUnroll[m];
        const double r = rate(kExDivK, kExSteps * u, nearest->handle(), 1.0001f, 0.0f, 0, std::max(1u, 16u / u));
        special = {};
        const double f = ops[model::kExDiv] / r;
        out << "; " << kCalibrateCodeSizeModules[m].size() << " words: " << r / 1e6 << " M/s (x " << f << ")";
      }
      out << " (reported, not used: no code_size points written)\n";
    }
    {  // Loop state: 128 multiply-adds an iteration into 8 and into 64 accumulators (calibrate_carried.comp). Each
       // invocation-iteration's time is 128 over the rate; the difference over the difference of the carried values
       // (model/spirv_loops.h, read off the two modules) is the price of a value carried beyond the 8-value kernel's.
      double perIter[2];
      uint32_t carried[2];
      for (int m = 0; m < 2; ++m) {
        special = kCalibrateCarriedModules[m];
        perIter[m] = 128.0 / rate(kFAddK, 128.0, nearest->handle(), 1.0f, 0.0f);
        special = {};
        carried[m] = model::carriedByDepth(kCalibrateCarriedModules[m])[0];
      }
      if (carried[1] <= carried[0]) throw std::logic_error("calibrate: the loop-state kernels carry " + std::to_string(carried[0]) +
                                                         " and " + std::to_string(carried[1]) + " values");
      d.loopStateValues = double(carried[0]);
      d.loopStateSeconds = std::max(0.0, (perIter[1] - perIter[0]) / double(carried[1] - carried[0]));
      out << "  loop state: " << carried[0] << " values carried " << perIter[0] * 1e9 << " ns an invocation-iteration, "
          << carried[1] << " values " << perIter[1] * 1e9 << " ns: " << d.loopStateSeconds * 1e12 << " ps a value beyond "
          << carried[0] << "\n";
    }
    {
      const double perStep = 1.0 / rate(kExSqrtK, kExSteps, nearest->handle(), 0.25f, 0.0f);
      ops[model::kExSqrt] = 1.0 / std::max(perStep - 1.0 / ops[model::kFAdd], perStep * 0.5);
    }
    {  // Latencies: the same kernels on one chain (DEPENDENT). Per chain step a device vector waits for the previous
       // step, so one core's step time is cores x lanes / (steps per second). Steps: fadd, fmul, imul (squaring) one
       // operation; ialu two dependent ones (xor, add); shift a shift then an add; cvt an fmul then two conversions;
       // select a compare beside an fadd, then the select (compare latency taken as fadd's).
      const double perCore = double(d.cores) * d.lanes;
      auto step = [&](uint32_t k, float c) { return perCore / rate(k, kSteps, nearest->handle(), c, 0.0f, 1); };
      auto& lat = d.latencySeconds;
      lat[model::kFAdd] = lat[model::kFCmp] = step(kFAddK, 1.0e-3f);
      lat[model::kFMul] = step(kFMulK, 1.0000001f);
      lat[model::kIAlu] = step(kIAluK, 1.5f) / 2.0;
      lat[model::kShift] = std::max(step(kShiftK, 1.5f) - lat[model::kIAlu], 0.1 * lat[model::kIAlu]);
      lat[model::kIMul] = step(kIMulK, 1.5f);
      lat[model::kCvt] = std::max(0.5 * (step(kCvtK, 1.0001f) - lat[model::kFMul]), 0.1 * lat[model::kFMul]);
      lat[model::kSelect] = std::max(step(kSelectK, 0.75f) - lat[model::kFAdd], 0.1 * lat[model::kFAdd]);
      // iselect: the select waits for the add (the compare is on the float chain beside it); icmp: the select waits for
      // the compare (the add and xor beside it).
      lat[model::kISelect] = std::max(step(kISelectK, 1.0e-3f) - lat[model::kIAlu], 0.1 * lat[model::kIAlu]);
      lat[model::kICmp] = std::max(step(kICmpK, 1.5f) - lat[model::kISelect], 0.1 * lat[model::kIAlu]);
      // A private access: its issue interval (what the glints kernels wait on is the accumulation's fadd chain; their
      // indices do not depend on the values read).
      lat[model::kPrivateRead] = perCore / ops[model::kPrivateRead];
      lat[model::kPrivateWrite] = perCore / ops[model::kPrivateWrite];
      // A division or square root on one chain of 16 (the square root's fadd latency removed).
      lat[model::kExDiv] = perCore / rate(kExDivK, kExSteps, nearest->handle(), 1.0001f, 0.0f, 1);
      lat[model::kExSqrt] = std::max(perCore / rate(kExSqrtK, kExSteps, nearest->handle(), 0.25f, 0.0f, 1) - lat[model::kFAdd],
                                     0.5 * lat[model::kFAdd]);
      // The window: iterations independent of each other, each a chain of L = 64 dependent fadds. A core that keeps W
      // operations in flight overlaps W / L chains, so an iteration takes L^2 latency / W (never less than its issue
      // time, never more than L latency): W = L^2 latency / t. In counted 8-lane operations: W lanes / 8.
      const double L = 64.0;
      const double tIter = perCore / rate(kWindowK, 1.0, nearest->handle(), 1.0e-3f, 0.0f);
      const double wDevice = std::clamp(L * L * lat[model::kFAdd] / tIter, L, 16.0 * L);
      d.windowOps = wDevice * d.lanes / 8.0;
      out << "  latency  ";
      for (int c = 0; c < model::kOpClasses; ++c) out << " " << model::kOpClassNames[c] << " " << lat[size_t(c)] * 1e9 << " ns";
      out << "\n  window    " << d.windowOps << " counted operations (" << wDevice << " device vector operations; an iteration "
          << tIter * 1e9 << " ns)\n";
    }
    d.lookupsPerSecond[model::kNearest] = rate(kTexK, 1.0, nearest->handle(), 1.0f, 0.0f);
    {  // A texture-cache miss: the same nearest lookups on the large texture, where each lane's next texel is a new line
       // (steps of ~71 texels and ~35 rows; the lanes start 16 texels apart), against the cache-resident 256^2. The lines
       // that still hit (the cache's share of the texture) are taken out.
      view = big->view();
      const double missRate = rate(kTexK, 1.0, nearest->handle(), 1.0f, 0.0f);
      view = img.view();
      cacheSource = hostCache(d.cacheLineBytes, d.cacheBytes);  // the description's cache; its share of the large texture still hits
      const double missShare = std::max(0.0, 1.0 - d.cacheBytes / (double(B) * B * 16));
      d.textureMissSeconds = std::max(1.0 / missRate - 1.0 / d.lookupsPerSecond[model::kNearest], 0.0) / std::max(missShare, 0.5);
      // A streamed line: texelFetch along the rows of the large texture against the same on the cache-resident one,
      // per lookup, times the lookups a line holds (RGBA32F: 16 bytes each).
      view = big->view();
      const double streamRate = rate(kStreamK, 1.0, nearest->handle(), 1.0f, 0.0f);
      view = img.view();
      const double residentRate = rate(kStreamK, 1.0, nearest->handle(), 1.0f, 0.0f);
      d.textureStreamSeconds = std::max(1.0 / streamRate - 1.0 / residentRate, 0.0) * double(d.cacheLineBytes) / 16.0 /
                               std::max(missShare, 0.5);
      out << "  texture   a scattered cache miss " << d.textureMissSeconds * 1e9 << " ns (nearest lookups " << missRate / 1e6
          << " M/s on " << B << "^2 RGBA32F, " << d.lookupsPerSecond[model::kNearest] / 1e6
          << " M/s on 256^2), a streamed line " << d.textureStreamSeconds * 1e9 << " ns (row-order fetches "
          << streamRate / 1e6 << " / " << residentRate / 1e6 << " M/s)\n";
    }
    d.lookupsPerSecond[model::kBilinear] = rate(kTexK, 1.0, bilinear->handle(), 1.0f, 0.0f);
    d.lookupsPerSecond[model::kTrilinear] = rate(kTexK, 1.0, trilinear->handle(), 1.0f, 1.5f);
    d.lookupsPerSecond[model::kUniformFetch] = rate(kUniformFetchK, 1.0, nearest->handle(), 1.0f, 0.0f);
    d.lookupsPerSecond[model::kFetch] = rate(kFetchK, 1.0, nearest->handle(), 1.0f, 0.0f);
    {
      // One pass over the buffers against three, the fastest of six (each of three) each: the copy is the noisiest
      // rate on a shared host. Like every rate, a difference: the launch and the 4,096 workgroups' setup cancel.
      const uint32_t invocations = uint32_t(copyVec4s / 16);
      // The rate is the round's own difference, and the best of rounds keeps the highest rate: the fastest one-pass run
      // of one round against the fastest three-pass run of another would mix two states of the host (one calibration
      // here read 7.3, 7.2 and then 13.4 GB/s that way, where paired runs read 4.9-6.4 GB/s, session 31).
      auto passes = [&](uint32_t n) {
        Push p{kCopyK, n, 0, 0, 1.5f, 0.0f, 0.0f, 0.0f};
        std::vector<double> t;
        for (int r = 0; r < 6; ++r) t.push_back(timeRun(p, nearest->handle(), invocations));
        return fastestOf(t);
      };
      const double one = passes(1), three = passes(3);
      d.bandwidthBytesPerSecond = best.high(2.0 * double(copyVec4s) * 32.0 / std::max(three - one, 1e-3 * three));
    }
    {
      // Re-reads: a table row loaded again and again (kind 25: 16 vec4 loads, 256 bytes, at lane-shared indices of a
      // cache-resident table, and 16 vec4 fadds, whose share is removed). Not the copy rate: a copy streams each
      // element once and stores it, a re-read loads an element the caches hold (lavapipe still loads it one lane and
      // one component at a time; a GPU's cache serves it).
      const double perByte = 1.0 / rate(kRereadK, 256.0, nearest->handle(), 1.0f, 0.0f);
      d.rereadBytesPerSecond = 1.0 / std::max(perByte - 0.25 / ops[model::kFAdd], perByte * 0.25);
    }
    d.dispatchSeconds = dispatch;
    d.firstDispatchSeconds = firstDispatch;
    d.compileSecondsPerWord = compilePerWord;
    d.workgroupSeconds = perGroup;
    {  // Blocks no lane takes: the fadd kernel's steps behind a never-true per-lane `if`, inside and around the loop.
      // Each time less the empty kind's over the same invocations in the same module (the launch and the workgroups'
      // setup there).
      Push p{kFAddK, opts.quick ? 1u << 8 : 1u << 11, 0, 0, 1.0e-3f, -1.0f, 0.0f, 0.0f};
      Push none = p;
      none.kind = kEmptyK;
      const double base = best.low(timeRun(none, nearest->handle(), count));
      const double work = best.low(timeRun(p, nearest->handle(), count)) - base;
      p.kind = kBranchK;
      const double straight = best.low(timeRun(p, nearest->handle(), count)) - base;
      p.kind = kBranchLoopK;
      const double loop = best.low(timeRun(p, nearest->handle(), count)) - base;
      p.kind = kBranchUnrolledK;
      const double unrolled = best.low(timeRun(p, nearest->handle(), count)) - base;
      p.kind = kBranchK, p.lod = 1.0e30f;  // the same block taken by every lane
      const double taken = best.low(timeRun(p, nearest->handle(), count)) - base;
      p.lod = -1.0f;
      d.executesEveryBlock = straight > 0.5 * work;
      // The same block behind a specialization constant that is false (DEPENDENT = true): a compiler that specializes
      // removes it (and the loop, then empty); one that does not runs it under the constant as under a mask.
      p.kind = kSpecBranchK, p.pad = 1;
      const double spec = best.low(timeRun(p, nearest->handle(), count)) - base;
      d.foldsSpecConstants = spec < 0.5 * work;
      p.pad = 0;
      // Two blocks under complementary masks computing the same 32 sums from the same operands (the second block
      // repeats the first's expressions) against two computing different ones: a compiler that numbers values across
      // the blocks it has made one straight line computes the shared sums once, about half the distinct pair's time
      // (and the merges); one that does not, the same time.
      p.kind = kSharedBlocksK;
      const double shared = best.low(timeRun(p, nearest->handle(), count)) - base;
      p.kind = kDistinctBlocksK;
      const double distinct = best.low(timeRun(p, nearest->handle(), count)) - base;
      d.valueNumbering = shared < 0.8 * distinct;
      out << "  values    two blocks repeating one computation cost " << std::setprecision(3)
          << 100.0 * shared / std::max(distinct, 1e-12) << "% of two computing different ones: "
          << (d.valueNumbering ? "repeated expressions are computed once (value numbering across blocks)"
                               : "each block computes its own") << "\n";
      out << "  branch    an untaken block costs " << std::setprecision(3) << 100.0 * straight / std::max(work, 1e-12)
          << "% of its work, an untaken loop " << 100.0 * loop / std::max(work, 1e-12) << "%, an untaken 16-iteration loop "
          << 100.0 * unrolled / std::max(work, 1e-12) << "%: "
          << (d.executesEveryBlock ? "every block runs under its mask" : "untaken blocks are skipped") << "; a block behind a false "
          << "specialization constant in a loop " << 100.0 * spec / std::max(work, 1e-12) << "%: "
          << (d.foldsSpecConstants ? "compiled out" : "runs") << "; the block taken by every lane "
          << 100.0 * taken / std::max(work, 1e-12) << "%\n";
    }
    {  // Raster rates per pipeline from synthetic draws (generated geometry, never a scene): through the shadow pass's
       // depth-only pipeline and through the G-buffer pass's (four RGBA32F targets, its vertex and fragment shaders).
       // Per pipeline three runs: many tiny triangles into small targets (triangle-bound), two large triangles into large
       // targets (coverage-bound), and zero-area triangles (nothing covered: the targets' clear and copy-out alone) in the
       // same targets as each. The emulator under the device's profile counts their triangles and covered pixels; each
       // empty run's time is removed, and the two equations give the two rates.
      const emu::DeviceProfile& prof = emu::profileForDevice(ctx.deviceName());
      struct Run { double seconds, triangles, fragments, vertexRuns, outside, spanning, partial; };
      auto sceneOf = [](Mesh mesh, uint32_t objects) {  // `objects` draws of the mesh, in place
        Scene sc;
        sc.meshes.push_back(std::move(mesh));
        sc.materials.emplace_back();
        for (uint32_t i = 0; i < objects; ++i) {
          Object o;
          o.model = identity();
          sc.objects.push_back(o);
        }
        return sc;
      };
      // maps depth-only maps of size^2 seen from +y (the shadow pass), or `draws` draws of the mesh into a size^2
      // G-buffer seen from +y (the plane faces the camera; the sphere fills most of the image).
      auto depthRun = [&](Mesh mesh, uint32_t size, uint32_t maps, uint32_t objects = 1) {
        const Scene sc = sceneOf(std::move(mesh), objects);
        const std::vector<Vec3> dirs(maps, Vec3{0.0f, 1.0f, 0.0f});
        ShadowPassVk pass(ctx, sc, size);
        const double t = best.low(fastestAfterWarmUp(5, [&] { pass.run(dirs); return pass.lastMs * 1e-3; }));
        ShadowStats st;
        shadowEmu(sc, dirs, size, prof, &st);
        return Run{t, double(st.raster.trianglesIn), double(st.raster.fragments),
                   double(model::vertexCacheRuns(sc.meshes[0].indices, d.vertexCache)) * maps * objects,
                   double(st.raster.trianglesOutside), double(st.raster.trianglesSpanning), double(st.raster.partialBlocks)};
      };
      auto gbufferRun = [&](Mesh mesh, uint32_t size, uint32_t draws) {
        Scene sc = sceneOf(std::move(mesh), draws);
        sc.width = sc.height = size;
        sc.camera.eye = {0.0f, 3.0f, 0.0f}, sc.camera.up = {0.0f, 0.0f, -1.0f};
        GbufferPassVk pass(ctx, sc);
        const double t = best.low(fastestAfterWarmUp(5, [&] { pass.run(); return pass.lastMs * 1e-3; }));
        GbufferStats st;
        gbufferEmu(sc, prof, &st);
        return Run{t, double(st.raster.trianglesIn), double(st.raster.fragments),
                   double(model::vertexCacheRuns(sc.meshes[0].indices, d.vertexCache)) * draws,
                   double(st.raster.trianglesOutside), double(st.raster.trianglesSpanning), double(st.raster.partialBlocks)};
      };
      auto flat = [](Mesh m) {  // every vertex at the centre: zero-area triangles, the same bounds as a point
        for (auto& p : m.positions) p = {0.0f, 0.0f, 0.0f};
        m.positions.push_back({-1.0f, -1.0f, -1.0f});  // unused vertices keep the bounds of the original
        m.positions.push_back({1.0f, 1.0f, 1.0f});
        m.normals.resize(m.positions.size(), {0.0f, 1.0f, 0.0f});
        m.tangents.resize(m.positions.size(), {1.0f, 0.0f, 0.0f, 1.0f});
        m.uvs.resize(m.positions.size(), {0.0f, 0.0f});
        return m;
      };
      // a, a0: the triangle-bound run and its empty run; s: a's triangles with the vertices numbered in strips (the same
      // triangles and pixels, fewer vertex routine runs where the device's vertex cache is simulated); b, b0: the
      // coverage-bound run and its empty run; targetBytes: the bytes of b's targets (cleared and copied out).
      // o: a's mesh out of the view (every triangle outside a clip plane; for the depth-only pipeline, whose maps enclose
      // the scene, a's own run: no triangle is outside); eMany, eFew: two empty runs that differ by `draws` draws.
      // m, m0: a's mesh into medium targets, where most of its triangles span a pixel-centre row (in a's 32^2 or 64^2
      // targets most do not: the rasterizer drops them after set-up), and its empty run. c, c0: a's mesh into large
      // targets (~16 pixels a triangle: several partly covered 4x4 blocks each, where m's hold a pixel and b's blocks
      // are full), and its empty run.
      auto rates = [&](const char* name, const Run& a, const Run& s, const Run& a0, const Run& b, const Run& b0,
                       double targetBytes, const Run& o, const Run& eMany, const Run& eFew, double draws, const Run& m,
                       const Run& m0, const Run& c, const Run& c0) {
        // A vertex routine run: the time a and s differ by, over the runs they differ by (0 where not simulated). The
        // triangle-bound equation below uses s, whose runs are the fewer (a noisy a - s moves it least), and the runs
        // never take more than three quarters of s's time (a contended run of a once left no time for the triangles).
        const double tsRaw = s.seconds - a0.seconds;
        double sv = a.vertexRuns > s.vertexRuns + 0.1 * a.triangles
                        ? std::max(a.seconds - s.seconds, 0.0) / (a.vertexRuns - s.vertexRuns) : 0.0;
        sv = std::min(sv, 0.75 * std::max(tsRaw, 0.0) / std::max(s.vertexRuns - a0.vertexRuns, 1.0));
        const double ta = std::max(tsRaw - sv * (s.vertexRuns - a0.vertexRuns), 1e-9),
                     tb = std::max(b.seconds - b0.seconds - sv * (b.vertexRuns - b0.vertexRuns), 1e-9);
        const double tm = std::max(m.seconds - m0.seconds - sv * (m.vertexRuns - m0.vertexRuns), 1e-9);
        const double tc = std::max(c.seconds - c0.seconds - sv * (c.vertexRuns - c0.vertexRuns), 1e-9);
        // Gaussian elimination with partial pivoting on the n x n system [A | r]; false where it is singular.
        auto solve = [](std::vector<std::vector<double>> M, std::vector<double>& x) {
          const size_t n = M.size();
          for (size_t k = 0; k < n; ++k) {
            size_t p = k;
            for (size_t i = k + 1; i < n; ++i)
              if (std::fabs(M[i][k]) > std::fabs(M[p][k])) p = i;
            if (std::fabs(M[p][k]) < 1e-30) return false;
            std::swap(M[k], M[p]);
            for (size_t i = 0; i < n; ++i) {
              if (i == k) continue;
              const double f = M[i][k] / M[k][k];
              for (size_t j = k; j <= n; ++j) M[i][j] -= f * M[k][j];
            }
          }
          x.resize(n);
          for (size_t k = 0; k < n; ++k) x[k] = M[k][n] / M[k][k];
          return true;
        };
        // t = triangles s_t + spanning s_s + fragments s_f for s, m and b (the 3x3 system); where it is singular or a cost
        // comes out non-positive (noise), the two-run solution without s_s (s and b), as before session 34.
        std::vector<double> x;
        if (!solve({{s.triangles, s.spanning, s.fragments, ta}, {m.triangles, m.spanning, m.fragments, tm},
                    {b.triangles, b.spanning, b.fragments, tb}},
                   x))
          x.assign(3, 0.0);
        double st = x[0], ss = x[1], sf = x[2];
        // A triangle in view does all that one outside a clip plane does (fetch, vertex routine, clip) and more: where
        // the solution prices a set-up below an outside triangle (lavapipe's G-buffer, whose set-ups without a row are
        // nearly free beside its spanning ones), the set-up is the outside cost and the spanning and pixel costs come
        // from m and b (the runs with the most of each).
        const double outsideCost = o.outside > 0.5 * o.triangles
                                       ? (o.seconds - a0.seconds - sv * (o.vertexRuns - a0.vertexRuns)) / o.outside : 0.0;
        if (st > 0 && st < outsideCost && ss >= 0 && sf > 0) {
          st = outsideCost;
          const double rm = tm - st * m.triangles, rb = tb - st * b.triangles;
          const double det = m.spanning * b.fragments - b.spanning * m.fragments;
          const double ss2 = (rm * b.fragments - rb * m.fragments) / det, sf2 = (m.spanning * rb - b.spanning * rm) / det;
          if (ss2 >= 0 && sf2 > 0) ss = ss2, sf = sf2;
          else st = x[0];  // noise: keep the 3x3 solution
        }
        if (!(st > 0 && ss >= 0 && sf > 0)) {
          const double det = s.triangles * b.fragments - b.triangles * s.fragments;
          st = (ta * b.fragments - tb * s.fragments) / det, sf = (s.triangles * tb - b.triangles * ta) / det, ss = 0.0;
          if (!(st > 0)) st = ta / s.triangles;
          if (!(sf > 0)) sf = tb / b.fragments;
        }
        // Partly covered 4x4 blocks (session 37): with c, t = triangles s_t + spanning s_s + partial blocks s_b +
        // fragments s_f for s, m, c and b (Gaussian elimination with partial pivoting). m's triangles hold a pixel (one
        // partial block each), c's ~16 (~6 partial blocks), b's two a map cover it (full blocks but for its edges): the
        // four tell the costs apart. Kept where every cost is positive (s_s, s_b non-negative); where the set-up comes out
        // below an outside triangle's, the set-up is that and the rest comes from m, c and b; otherwise s_b = 0 and the
        // three-run costs above.
        double sb = 0.0;
        {
          std::vector<double> y;
          if (solve({{s.triangles, s.spanning, s.partial, s.fragments, ta}, {m.triangles, m.spanning, m.partial, m.fragments, tm},
                     {c.triangles, c.spanning, c.partial, c.fragments, tc}, {b.triangles, b.spanning, b.partial, b.fragments, tb}},
                    y) &&
              y[0] > 0 && y[1] >= 0 && y[2] >= 0 && y[3] > 0) {
            if (y[0] >= outsideCost) {
              st = y[0], ss = y[1], sb = y[2], sf = y[3];
            } else {  // the set-up at an outside triangle's cost, the rest from m, c and b
              std::vector<double> z;
              const double t0 = outsideCost;
              if (solve({{m.spanning, m.partial, m.fragments, tm - t0 * m.triangles}, {c.spanning, c.partial, c.fragments, tc - t0 * c.triangles},
                         {b.spanning, b.partial, b.fragments, tb - t0 * b.triangles}},
                        z) &&
                  z[0] >= 0 && z[1] >= 0 && z[2] > 0)
                st = t0, ss = z[0], sb = z[1], sf = z[2];
            }
          }
        }
        out << "  raster    " << name << ": " << s.triangles << " triangles (" << s.spanning << " spanning) + " << s.fragments
            << " pixels in " << ta * 1e3 << " ms; " << m.triangles << " triangles (" << m.spanning << " spanning) + "
            << m.fragments << " pixels in " << tm * 1e3 << " ms; " << b.triangles << " triangles + " << b.fragments
            << " pixels in " << tb * 1e3 << " ms; empty targets " << a0.seconds * 1e3 << " / " << m0.seconds * 1e3 << " / "
            << b0.seconds * 1e3 << " ms; " << c.triangles << " triangles + " << c.partial << " partly covered 4x4 blocks + " << c.fragments
            << " pixels in " << tc * 1e3 << " ms (empty " << c0.seconds * 1e3 << " ms): " << st * 1e9 << " ns per triangle, "
            << ss * 1e9 << " ns more per spanning one, " << sb * 1e9 << " ns per partly covered 4x4 block, " << sf * 1e9 << " ns per pixel";
        if (d.vertexCache.entries)
          out << "; vertex runs " << a.vertexRuns << " in " << a.seconds * 1e3 << " ms vs " << s.vertexRuns << " strip-numbered in "
              << s.seconds * 1e3 << " ms: " << sv * 1e9 << " ns per run (excluded above)";
        out << "\n";
        // A triangle outside: o's time less the empty run's, per outside triangle (never above a set-up one's cost); a
        // draw: the empty runs' difference per draw they differ by.
        const double to = o.seconds - a0.seconds - sv * (o.vertexRuns - a0.vertexRuns);
        const double so = o.outside > 0.5 * o.triangles ? std::clamp(to / o.outside, 0.0, st) : st;
        const double sd = std::max(eMany.seconds - eFew.seconds, 0.0) / draws;
        out << "  raster    " << name << ": " << o.outside << " triangles outside the view in " << to * 1e3
            << " ms beyond the empty run: " << so * 1e9 << " ns per triangle; " << draws << " more empty draws "
            << (eMany.seconds - eFew.seconds) * 1e3 << " ms: " << sd * 1e6 << " us per draw\n";
        // The targets' clear + copy-out per byte (the large empty run less a launch).
        return model::RasterRates{1.0 / st, 1.0 / sf, targetBytes / std::max(b0.seconds - dispatch, 1e-9), sv, so, sd, ss, sb};
      };
      const uint32_t segs = opts.quick ? 128 : 256, rings = opts.quick ? 64 : 128;
      const Mesh sphere = makeSphere(segs, rings), strips = makeSphereStrips(segs, rings, 8);
      {
        const uint32_t small = 32, smallMaps = opts.quick ? 4 : 16, big = opts.quick ? 512 : 2048, bigMaps = opts.quick ? 4 : 8;
        const Run a = depthRun(sphere, small, smallMaps), a0 = depthRun(flat(makePlane()), small, smallMaps);
        const Run s = d.vertexCache.entries ? depthRun(strips, small, smallMaps) : a;
        const Run b = depthRun(makePlane(), big, bigMaps), b0 = depthRun(flat(makePlane()), big, bigMaps);
        const uint32_t objects = 16;  // empty draws a map, against a0's one
        const Run e16 = depthRun(flat(makePlane()), small, smallMaps, objects);
        const uint32_t medium = opts.quick ? 256 : 512;  // ~6 pixels a triangle: most span a row
        const Run m = depthRun(sphere, medium, smallMaps), m0 = depthRun(flat(makePlane()), medium, smallMaps);
        const uint32_t large = opts.quick ? 1024 : 2048, largeMaps = opts.quick ? 2 : 4;  // ~35 pixels a triangle
        const Run c = depthRun(sphere, large, largeMaps), c0 = depthRun(flat(makePlane()), large, largeMaps);
        d.raster[model::kDepthOnly] = rates("depth-only", a, s, a0, b, b0, double(big) * big * 4 * bigMaps, a, e16, a0,
                                            double(objects - 1) * smallMaps, m, m0, c, c0);
      }
      {
        // The triangle-bound runs draw the sphere once (65k triangles; --quick 16k): a G-buffer pass is one render pass,
        // and lavapipe bins a render pass's triangles into one scene until the scene is full (~150k of these), then
        // rasterizes it on the workers while the next one is binned. Sixteen draws (1M triangles) overlapped binning
        // and rasterizing and read 88 ns a triangle where a single draw, as large as any shipped scene's pass, reads
        // 170-240 (docs/RESULTS.md session 35). The draw cost comes from empty runs of `draws` draws against one.
        const uint32_t small = 64, draws = opts.quick ? 4 : 16, big = opts.quick ? 512 : 1024, bigDraws = 4;
        const Run a = gbufferRun(sphere, small, 1), a0 = gbufferRun(flat(makePlane()), small, 1);
        const Run s = d.vertexCache.entries ? gbufferRun(strips, small, 1) : a;
        const Run b = gbufferRun(makePlane(), big, bigDraws), b0 = gbufferRun(flat(makePlane()), big, bigDraws);
        Mesh away = sphere;  // the camera looks down -y at x, z in about [-1.2, 1.2]: 10 to the side is out of view
        for (auto& p : away.positions) p[0] += 10.0f;
        const Run o = gbufferRun(away, small, 1), eMany = gbufferRun(flat(makePlane()), small, draws);
        const uint32_t medium = opts.quick ? 256 : 512;
        const Run m = gbufferRun(sphere, medium, 1), m0 = gbufferRun(flat(makePlane()), medium, 1);
        const Run c = gbufferRun(sphere, big, 1), c0 = gbufferRun(flat(makePlane()), big, 1);  // ~10 pixels a triangle
        d.raster[model::kGbufferRaster] = rates("G-buffer", a, s, a0, b, b0, double(big) * big * (kGbufFloats * 4 + 4), o,
                                                eMany, a0, double(draws - 1), m, m0, c, c0);
      }
    }
    d.provenance = std::string("shadetwin calibrate") + (opts.quick ? " --quick" : "") + " on this machine (" +
                   std::to_string(d.cores) + " cores): microkernels of src/shaders/calibrate*.comp only; cache from " + cacheSource;
    out << std::setprecision(4);
    for (int c = 0; c < model::kOpClasses; ++c) out << "  " << std::left << std::setw(14) << model::kOpClassNames[c] << ops[size_t(c)] / 1e9 << " Gop/s\n";
    for (int f = 0; f < model::kTexFilters; ++f)
      out << "  " << std::left << std::setw(10) << model::kTexFilterNames[f] << d.lookupsPerSecond[size_t(f)] / 1e6 << " Mlookup/s\n";
    out << "  bandwidth " << d.bandwidthBytesPerSecond / 1e9 << " GB/s (copy), re-read " << d.rereadBytesPerSecond / 1e9 << " GB/s\n  dispatch  " << d.dispatchSeconds * 1e6 << " us\n";
    for (int r = 0; r < model::kRasterPipelines; ++r)
      out << "  " << model::kRasterPipelineNames[r] << ": triangles " << d.raster[size_t(r)].trianglesPerSecond / 1e6
          << " M/s, fragments " << d.raster[size_t(r)].fragmentsPerSecond / 1e6 << " M/s, targets "
          << d.raster[size_t(r)].targetBytesPerSecond / 1e9 << " GB/s (clear + copy-out)\n";
    log << "  round " << round + 1 << "/" << rounds << " (" << std::fixed << std::setprecision(1)
        << std::chrono::duration<double>(std::chrono::steady_clock::now() - roundStart).count() << " s): dispatch "
        << dispatch * 1e6 << " us, bandwidth " << d.bandwidthBytesPerSecond / 1e9 << " GB/s, fadd "
        << ops[model::kFAdd] / 1e9 << " Gop/s, nearest " << d.lookupsPerSecond[model::kNearest] / 1e6
        << " M/s (from the fastest runs so far)" << (inseparable ? ", " + std::to_string(inseparable) + " rate(s) from one run" : "")
        << std::defaultfloat << std::setprecision(6) << std::endl;
    result = d;
  }
  return result;
}

int calibrateCommand(const CalibrateOptions& opts, std::ostream& log) {
  const model::DeviceDesc d = calibrateDevice(opts, log);
  const std::string out = opts.out.empty() ? "devices/" + d.device + ".json" : opts.out;
  model::saveDeviceDesc(d, out);
  log << "wrote " << out << "\n";
  return 0;
}

}  // namespace shadetwin
