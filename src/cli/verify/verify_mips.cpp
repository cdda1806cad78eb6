// verify mips: MIP chains of random textures (odd and even sizes, layers, values outside [0, 1],
// inf/NaN/denormal texels) from the shared kernel in the C++ scalar build, the SIMD build and on the
// Vulkan device; every texel of every level compared bit for bit.
#include <cmath>
#include <cstring>
#include <iomanip>
#include <ostream>
#include <random>

#include "passes/mips.h"
#include "cli/verify/verify.h"
#include "vk/context.h"

namespace shadetwin {

int verifyMips(const VerifyOptions& opts, std::ostream& out) {
  vk::Context ctx({opts.device, opts.validate});
  out << "device: " << ctx.deviceName() << "\n";
  std::mt19937 rng(uint32_t(opts.seed));
  uint64_t identical = 0, total = 0;
  size_t shown = 0;
  for (size_t t = 0; t < opts.count; ++t) {
    const uint32_t w = 1 + rng() % 300, h = 1 + rng() % 200, layers = 1 + rng() % 2;
    std::vector<float> level0(size_t(w) * h * layers * 4);
    for (auto& v : level0) {
      uint32_t pick = rng() % 2000;
      v = pick == 0 ? INFINITY : pick == 1 ? NAN : pick == 2 ? 1e-40f
          : std::uniform_real_distribution<float>(-0.5f, 40000.0f)(rng);
    }
    auto scalar = mipChainCpu(level0, w, h, layers, 1);
    auto simd = mipChainCpu(level0, w, h, layers, 8);
    auto gpu = mipChainGpu(ctx, level0, w, h, layers);
    uint64_t same = 0, n = 0;
    for (size_t l = 1; l < scalar.size(); ++l)
      for (size_t i = 0; i < scalar[l].size(); ++i) {
        ++n;
        bool ok = sameBits(scalar[l][i], simd[l][i]) && sameBits(scalar[l][i], gpu[l][i]);
        same += ok;
        if (!ok && shown < 5) {
          ++shown;
          out << "  diff: " << w << "x" << h << "x" << layers << " level " << l << " float " << i << ": scalar "
              << std::setprecision(9) << scalar[l][i] << " simd " << simd[l][i] << " gpu " << gpu[l][i] << "\n";
        }
      }
    identical += same;
    total += n;
  }
  out << opts.count << " textures, " << total << " texel channels below level 0\n";
  if (ctx.validationEnabled()) out << "validation errors: " << ctx.validationErrors() << "\n";
  UlpTally all{"mip levels 1.. (scalar = simd x8 = device)"};
  all.identical = identical, all.total = total;
  writeVerifyReports(opts, {"mips", ctx.deviceName(), "", 0, {all}, ctx.validationErrors(), ctx.lastValidationMessage}, out);
  out << "mips: " << identical << "/" << total << " bit-identical\n";
  return (identical == total && ctx.validationErrors() == 0) ? 0 : 1;
}

}  // namespace shadetwin
