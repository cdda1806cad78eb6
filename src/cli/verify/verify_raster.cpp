// verify raster: the G-buffer pass of a scene on the emulator (device profile of the Vulkan device)
// and on the Vulkan build; coverage, depth and every G-buffer channel compared bit for bit.
#include <array>
#include <cstring>
#include <cmath>
#include <iomanip>

#include "util/heatmap.h"

#include "emu/device_profile.h"
#include "passes/passes_vk.h"
#include "scene/scene.h"
#include "cli/verify/verify.h"
#include "vk/context.h"

namespace shadetwin {
void UlpTally::add(float a, float b) {
  ++total;
  if (sameBits(a, b)) {
    ++identical;
    return;
  }
  noteDifference(int64_t(total - 1), a, b);
  int64_t u = ulpDistance(a, b);
  hist[u <= 1 ? 0 : u <= 3 ? 1 : u <= 15 ? 2 : u <= 255 ? 3 : 4]++;
  if (diffs.size() < kMaxDiffs)
    diffs.push_back({uint32_t(total - 1), (std::isnan(a) != std::isnan(b) || u >= int64_t(kHeatNotANumber)) ? kHeatNotANumber : uint32_t(u)});
  else diffsTruncated = true;
}

void UlpTally::noteDifference(int64_t i, float a, float b) {
  if (firstDiff < 0) firstDiff = i, firstA = a, firstB = b;
}

void UlpTally::addSame(bool same) {
  ++total;
  if (same) {
    ++identical;
    return;
  }
  if (firstDiff < 0) firstDiff = int64_t(total - 1);
  if (diffs.size() < kMaxDiffs) diffs.push_back({uint32_t(total - 1), kHeatNotANumber});
  else diffsTruncated = true;
}

std::array<size_t, 2> printTallies(const std::vector<UlpTally>& t, std::ostream& out) {
  out << std::left << std::setw(20) << "channel" << std::setw(22) << "identical/total"
      << "differing by ULP: 1 | 2-3 | 4-15 | 16-255 | >=256\n";
  size_t I = 0, T = 0;
  for (auto& x : t) {
    std::string it = std::to_string(x.identical) + "/" + std::to_string(x.total);
    out << std::setw(20) << x.name << std::setw(22) << it;
    for (size_t h : x.hist) out << h << " ";
    out << "\n";
    I += x.identical;
    T += x.total;
  }
  return {I, T};
}

int verifyRaster(const VerifyOptions& opts, std::ostream& out) {
  Scene scene = loadScene(opts.scene, opts);
  vk::ContextOptions co;
  co.device = opts.device;
  co.validation = opts.validate;
  vk::Context ctx(co);
  emu::DeviceProfile dev = emu::profileForDevice(ctx.deviceName());
  for (const std::string& kv : opts.profileSet) {
    emu::setProfileField(dev, kv);
    out << "profile override: " << kv << "\n";
  }
  out << "scene " << opts.scene << ": " << scene.width << "x" << scene.height << ", " << scene.triangles()
      << " triangles; device: " << ctx.deviceName() << " (profile " << dev.name << ")\n";
  GbufferStats st;
  GBuffer e = gbufferEmu(scene, dev, &st);
  GBuffer g = gbufferVulkan(ctx, scene);
  if (st.raster.trianglesClipped)
    out << "clipped: " << st.raster.trianglesClipped << " triangles have a vertex outside a clip plane ("
        << (dev.raster.clip == emu::DeviceProfile::Raster::Clip::DrawModule ? "x/y, near and far: draw-module clipper"
                                                                             : "near and far: guard band")
        << ")\n";
  std::vector<UlpTally> t;
  t.push_back({"coverage"});
  t.push_back({"depth"});
  const char* names[4] = {"G0 position+id", "G1 normal+u", "G2 tangent+v", "G3 uv derivs"};
  for (int a = 0; a < kGbufAttachments; ++a)
    for (int c = 0; c < 4; ++c) t.push_back({std::string(names[a]) + "." + "xyzw"[c]});
  const size_t n = size_t(scene.width) * scene.height;
  for (size_t p = 0; p < n; ++p) {
    const bool ce = e.texels[p * kGbufFloats + 3] != 0.0f, cg = g.texels[p * kGbufFloats + 3] != 0.0f;
    t[0].addSame(ce == cg);
    t[1].add(e.depth[p], g.depth[p]);
    for (int k = 0; k < kGbufFloats; ++k) t[size_t(2 + k)].add(e.texels[p * kGbufFloats + size_t(k)], g.texels[p * kGbufFloats + size_t(k)]);
  }
  const auto [I, T] = printTallies(t, out);
  writeVerifyReports(opts, {"raster", ctx.deviceName(), opts.scene, scene.width, t, uint32_t(ctx.validationErrors()),
                            ctx.lastValidationMessage}, out);
  if (opts.validate && ctx.validationErrors()) {
    out << "validation errors: " << ctx.validationErrors() << " (last: " << ctx.lastValidationMessage << ")\n";
    return 1;
  }
  out << "raster: " << I << "/" << T << " bit-identical\n";
  return I == T ? 0 : 1;
}

}  // namespace shadetwin
