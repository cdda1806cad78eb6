#include "model/model.h"

#include <algorithm>

namespace shadetwin::model {

std::array<double, kOpClasses> scalarOps(const PassCounts& c) {
  std::array<double, kOpClasses> o{};
  auto t = [&](opcount::Kind k) { return c.ops[size_t(k)]; };
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
  p.textureSeconds = c.ops[opcount::kTexNearest] / d.lookupsPerSecond[kNearest] +
                     c.ops[opcount::kTexBilinear] / d.lookupsPerSecond[kBilinear] +
                     c.ops[opcount::kTexTrilinear] / d.lookupsPerSecond[kTrilinear];
  p.memorySeconds = double(c.bytesRead + c.bytesWritten) / d.bandwidthBytesPerSecond;
  p.rasterSeconds = double(c.triangles) / d.trianglesPerSecond + double(c.fragments) / d.fragmentsPerSecond +
                    double(c.attachmentBytes) / d.attachmentBytesPerSecond;
  p.launchSeconds = double(std::max<uint64_t>(c.dispatches, 1)) * d.dispatchSeconds;
  const double terms[5] = {p.aluSeconds, p.textureSeconds, p.memorySeconds, p.rasterSeconds, p.launchSeconds};
  const char* names[5] = {"alu", "texture", "memory", "raster", "launch"};
  const int top = int(std::max_element(terms, terms + 5) - terms);
  p.bound = names[top];
  p.seconds = d.unitsOverlap ? std::max({p.aluSeconds, p.textureSeconds, p.memorySeconds, p.rasterSeconds}) + p.launchSeconds
                             : p.aluSeconds + p.textureSeconds + p.memorySeconds + p.rasterSeconds + p.launchSeconds;
  return p;
}

}  // namespace shadetwin::model
