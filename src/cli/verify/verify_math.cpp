// verify math: every exact-math function on N inputs (random + edge cases) in the C++ scalar build,
// the C++ SIMD build (8 lanes) and the Vulkan build, compute stage and fragment stage. The fragment
// stage is compared with the C++ build run under the profile's fragment denormal mode.
#include <cmath>
#include <cstring>
#include <iomanip>
#include <ostream>
#include <random>
#include <vector>

#include "emu/device_profile.h"
#include "lanes/kernels.h"
#include "cli/verify/verify.h"
#include "vk/context.h"

namespace shadetwin {

namespace {
#include "verify_math_comp.inc"
#include "verify_math_frag.inc"
#include "fullscreen_vert.inc"

float bitsToFloat(uint32_t b) {
  float f;
  std::memcpy(&f, &b, 4);
  return f;
}

const float kEdge[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 2.0f, 1e-45f, -1e-45f, 1.1754942e-38f, 1.17549435e-38f,
                       -1.17549435e-38f, 3.4028235e38f, -3.4028235e38f, INFINITY, -INFINITY, NAN, 3.14159274f,
                       1.57079637f, 0.785398185f, 1e10f, 1e-10f, 88.7228394f, 88.7228470f, -103.972084f, -87.3365479f,
                       128.0f, -149.0f, -150.0f, 1.0000001f, 0.99999994f, 1e30f, 7.0f, 100.0f, -100.0f, 0.25f,
                       16777216.0f, 8388608.5f, 2.0e-38f, 5.877472e-39f};

// Typical ranges per function, so the random half of the inputs exercises the useful domain.
float typical(int fn, std::mt19937& rng, int arg) {
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  float r = U(rng);
  float wide = r * std::exp2(float(int(rng() % 60) - 30));
  switch (fn) {
    case 4: return r * 90.0f;                                  // exp
    case 5: return r * 130.0f;                                 // exp2
    case 6: case 7: case 1: case 2: return std::fabs(wide);    // log, log2, sqrt, inversesqrt
    case 8: return arg == 0 ? std::fabs(r) * 4.0f : r * 30.0f; // pow
    case 9: case 10: return r * ((rng() & 1) ? 10.0f : 1e5f);  // sin, cos
    case 12: return r;                                         // acos
    default: return wide;
  }
}

double reference(int fn, double a, double b, double c) {
  switch (fn) {
    case 0: return a / b;
    case 1: return std::sqrt(a);
    case 2: return 1.0 / std::sqrt(a);
    case 3: return a / std::sqrt(a * a + b * b + c * c);
    case 4: return std::exp(a);
    case 5: return std::exp2(a);
    case 6: return std::log(a);
    case 7: return std::log2(a);
    case 8: return a < 0 ? std::nan("") : std::pow(a, b);
    case 9: return std::sin(a);
    case 10: return std::cos(a);
    case 11: return std::atan2(a, b);
    default: return std::acos(a);
  }
}
}  // namespace

int64_t ulpDistance(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return (std::isnan(a) && std::isnan(b)) ? 0 : (int64_t(1) << 32);
  auto ord = [](float f) {
    int32_t i;
    std::memcpy(&i, &f, 4);
    return i < 0 ? int64_t(INT32_MIN) - i : int64_t(i);
  };
  int64_t d = ord(a) - ord(b);
  return d < 0 ? -d : d;
}

bool sameBits(float a, float b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  return std::memcmp(&a, &b, 4) == 0;
}

int verifyMath(const VerifyOptions& opts, std::ostream& out) {
  vk::Context ctx({opts.device, opts.validate});
  emu::DeviceProfile profile = emu::profileForDevice(ctx.deviceName());
  for (const std::string& kv : opts.profileSet) {  // e.g. denormFragment=preserve: what the profile's mode is worth
    emu::setProfileField(profile, kv);
    out << "profile override: " << kv << "\n";
  }
  const bool fragFlush = profile.denorm(emu::Stage::Fragment) == emu::DenormMode::Flush;
  const bool compFlush = profile.denorm(emu::Stage::Compute) == emu::DenormMode::Flush;
  out << "device: " << ctx.deviceName() << " (profile " << profile.name << (profile.verified ? "" : ", unverified")
      << "; compute denormals " << (compFlush ? "flushed" : "preserved") << ", fragment denormals " << (fragFlush ? "flushed" : "preserved")
      << ")\n";
  const VkDescriptorType layout[] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel comp(ctx, vk::Stage::Compute, kSpv_verify_math_comp, layout, 12);
  vk::Kernel frag(ctx, vk::Stage::Fragment, kSpv_verify_math_frag, layout, 12, kSpv_fullscreen_vert);
  const size_t n = opts.count;
  vk::Buffer inBuf(ctx, n * 12), outBuf(ctx, n * 12);
  std::vector<float> in(3 * n), scalar(3 * n), simd(3 * n), scalarFlush(3 * n), gpuComp(3 * n), gpuFrag(3 * n);
  uint64_t stageSame[2][2] = {{0, 0}, {0, 0}};  // [compute, fragment][preserve, flush]: each stage against either C++ mode
  const size_t nEdge = sizeof(kEdge) / sizeof(kEdge[0]);
  uint64_t identical = 0, total = 0;
  std::vector<UlpTally> tallies;  // one per function, for --junit / --json
  out << std::left << std::setw(12) << "function" << std::right << std::setw(22) << "identical/total" << std::setw(14)
      << "max ulp" << std::setw(12) << "NaN vs num"
      << std::setw(22) << "compute P / F" << std::setw(22) << "fragment P / F"
      << "   (identical: scalar = simd x8 = vulkan compute, and C++ = vulkan fragment, each under its stage's mode;"
         " P / F: the stage against C++ with denormals preserved / flushed)\n";
  for (int fn = 0; fn < mathKernelCount(); ++fn) {
    std::mt19937 rng(uint32_t(opts.seed * 1000003u + uint64_t(fn)));
    for (size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) {
        float f;
        if (i < nEdge * nEdge && k < 2) f = kEdge[k == 0 ? i % nEdge : i / nEdge];  // all pairs of edge cases
        else if (i % 4 == 0) f = bitsToFloat(uint32_t(rng()));                    // any bit pattern
        else f = typical(fn, rng, k);
        in[3 * i + k] = f;
      }
    evalMathKernel(fn, in.data(), scalar.data(), n, 1, false);
    evalMathKernel(fn, in.data(), simd.data(), n, 8, false);
    evalMathKernel(fn, in.data(), scalarFlush.data(), n, 1, true);
    std::memcpy(inBuf.data(), in.data(), n * 12);
    struct { int32_t fn; uint32_t count, width; } push{fn, uint32_t(n), 1024};
    const vk::Binding binds[] = {{layout[0], inBuf.handle()}, {layout[1], outBuf.handle()}};
    comp.run(binds, &push, uint32_t(n));
    std::memcpy(gpuComp.data(), outBuf.data(), n * 12);
    std::memset(outBuf.data(), 0, n * 12);
    frag.run(binds, &push, uint32_t(n), 1024);
    std::memcpy(gpuFrag.data(), outBuf.data(), n * 12);
    uint64_t same = 0, nanDiff = 0, st[2][2] = {{0, 0}, {0, 0}};
    UlpTally tally{mathKernelName(fn)};
    int64_t maxUlp = 0;
    for (size_t i = 0; i < n; ++i) {
      bool ok = true, s[2][2] = {{true, true}, {true, true}};
      for (int k = 0; k < 3; ++k) {
        size_t j = 3 * i + k;
        s[0][0] = s[0][0] && sameBits(scalar[j], gpuComp[j]), s[0][1] = s[0][1] && sameBits(scalarFlush[j], gpuComp[j]);
        s[1][0] = s[1][0] && sameBits(scalar[j], gpuFrag[j]), s[1][1] = s[1][1] && sameBits(scalarFlush[j], gpuFrag[j]);
        ok = ok && sameBits(scalar[j], simd[j]);
      }
      ok = ok && s[0][compFlush] && s[1][fragFlush];
      same += ok;
      if (!ok) {  // the reports' first difference: the first component and comparison that differ
        const float* stageOut[2] = {gpuComp.data(), gpuFrag.data()};
        const float* cpp[2] = {compFlush ? scalarFlush.data() : scalar.data(), fragFlush ? scalarFlush.data() : scalar.data()};
        bool noted = false;
        for (int k = 0; k < 3 && !noted; ++k)
          for (int st = 0; st < 2 && !noted; ++st)
            if (!sameBits(cpp[st][3 * i + k], stageOut[st][3 * i + k]))
              tally.noteDifference(int64_t(i), cpp[st][3 * i + k], stageOut[st][3 * i + k]), noted = true;
        for (int k = 0; k < 3 && !noted; ++k)
          if (!sameBits(scalar[3 * i + k], simd[3 * i + k]))
            tally.noteDifference(int64_t(i), scalar[3 * i + k], simd[3 * i + k]), noted = true;
      }
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) st[a][b] += s[a][b];
      double ref = reference(fn, in[3 * i], in[3 * i + 1], in[3 * i + 2]);
      float rf = float(ref);
      if (std::isnan(rf) != std::isnan(scalar[3 * i])) ++nanDiff;  // domain conventions, see DESIGN.md
      else maxUlp = std::max(maxUlp, ulpDistance(scalar[3 * i], rf));
    }
    identical += same;
    total += n;
    tally.identical = same, tally.total = n;
    tallies.push_back(tally);
    out << std::left << std::setw(12) << mathKernelName(fn) << std::right << std::setw(10) << same << "/" << std::setw(11)
        << std::left << n << std::right << std::setw(10) << maxUlp << std::setw(12) << nanDiff << std::setw(12) << st[0][0] << " / "
        << std::setw(7) << st[0][1] << std::setw(12) << st[1][0] << " / " << std::setw(7) << st[1][1] << "\n";
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) stageSame[a][b] += st[a][b];
  }
  out << "stages: compute " << stageSame[0][0] << " / " << stageSame[0][1] << ", fragment " << stageSame[1][0] << " / "
      << stageSame[1][1] << " of " << total + 0 << " identical with denormals preserved / flushed\n";
  if (ctx.validationEnabled())
    out << "validation errors: " << ctx.validationErrors() << (ctx.validationErrors() ? " (" + ctx.lastValidationMessage + ")" : "") << "\n";
  writeVerifyReports(opts, {"math", ctx.deviceName(), "", 0, tallies, ctx.validationErrors(), ctx.lastValidationMessage}, out);
  out << "math: " << identical << "/" << total << " bit-identical\n";
  return (identical == total && ctx.validationErrors() == 0) ? 0 : 1;
}

}  // namespace shadetwin
