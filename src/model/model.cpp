#include "model/model.h"

#include <algorithm>

namespace shadetwin::model {

std::array<double, kOpClasses> scalarOps(const PassCounts& c) {
  std::array<double, kOpClasses> o{};
  auto t = [&](opcount::Kind k) { return 8.0 * double(c.ticks[size_t(k)]); };
  o[kFAdd] = t(opcount::kFAdd);
  o[kFMul] = t(opcount::kFMul);
  o[kFCmp] = t(opcount::kFCmp);
  o[kIAlu] = t(opcount::kIAlu) + t(opcount::kMaskOp);
  o[kIMul] = t(opcount::kIMul);
  o[kCvt] = t(opcount::kCvt);
  o[kSelect] = t(opcount::kSel);
  return o;
}

Prediction predict(const PassCounts& c, const DeviceDesc& d) {
  Prediction p;
  const auto ops = scalarOps(c);
  for (int k = 0; k < kOpClasses; ++k) p.aluSeconds += ops[size_t(k)] / d.opsPerSecond[size_t(k)];
  p.textureSeconds = double(c.ticks[opcount::kTexNearest]) / d.lookupsPerSecond[kNearest] +
                     double(c.ticks[opcount::kTexBilinear]) / d.lookupsPerSecond[kBilinear] +
                     double(c.ticks[opcount::kTexTrilinear]) / d.lookupsPerSecond[kTrilinear];
  p.memorySeconds = double(c.bytesRead + c.bytesWritten) / d.bandwidthBytesPerSecond;
  p.launchSeconds = d.dispatchSeconds;
  const double terms[4] = {p.aluSeconds, p.textureSeconds, p.memorySeconds, p.launchSeconds};
  const char* names[4] = {"alu", "texture", "memory", "launch"};
  const int top = int(std::max_element(terms, terms + 4) - terms);
  p.bound = names[top];
  p.seconds = d.unitsOverlap ? std::max({p.aluSeconds, p.textureSeconds, p.memorySeconds}) + p.launchSeconds
                             : p.aluSeconds + p.textureSeconds + p.memorySeconds + p.launchSeconds;
  return p;
}

}  // namespace shadetwin::model
