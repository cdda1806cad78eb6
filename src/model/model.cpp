#include "model/model.h"
#include "model/spirv_loops.h"

#include <algorithm>
#include <cmath>

namespace shadetwin::model {

namespace {
OpClass classOf(opcount::Kind k) {
  switch (k) {
    case opcount::kFAdd: return kFAdd;
    case opcount::kFMul: return kFMul;
    case opcount::kFCmp: return kFCmp;
    case opcount::kIMul: return kIMul;
    case opcount::kCvt: return kCvt;
    case opcount::kSel: return kSelect;
    case opcount::kShift: return kShift;
    case opcount::kICmp: return kICmp;
    case opcount::kISel: return kISelect;
    case opcount::kPrivRead: return kPrivateRead;
    case opcount::kPrivWrite: return kPrivateWrite;
    case opcount::kExDiv: return kExDiv;
    case opcount::kExSqrt: return kExSqrt;
    default: return kIAlu;  // integer ALU and mask logic
  }
}
}  // namespace

std::array<double, kOpClasses> scalarOps(const PassCounts& c) {
  std::array<double, kOpClasses> o{};
  for (int k = 0; k < opcount::kTexLookup; ++k) o[size_t(classOf(opcount::Kind(k)))] += c.ops[size_t(k)];
  return o;
}

CoreModel coreModel(const DeviceDesc& d) {
  CoreModel m;
  m.on = !d.unitsOverlap;
  m.executeEveryBlock = d.executesEveryBlock;
  m.foldsSpecConstants = d.foldsSpecConstants;
  m.valueNumbering = d.valueNumbering;
  for (int k = 0; k < opcount::kTexLookup; ++k) {
    const OpClass c = classOf(opcount::Kind(k));
    m.interval[size_t(k)] = 8.0 * double(d.cores) / d.opsPerSecond[size_t(c)];  // one 8-lane operation on one core
    m.latency[size_t(k)] = d.latencySeconds[size_t(c)];
  }
  m.window = uint32_t(std::max(1.0, std::round(d.windowOps)));
  // An exact division or square root is many device operations: it holds as many window entries as keep
  // window / slots of them in flight, the overlap calibrate's independent chains reached (interval) against its
  // dependent chain (latency): slots = window x interval / latency, at most the operations its routine counts.
  for (opcount::Kind k : {opcount::kExDiv, opcount::kExSqrt}) {
    const auto mix = exactMathMix(k);
    uint64_t n = 0;
    for (int j = 0; j < opcount::kTexLookup; ++j) n += mix[size_t(j)];
    const double fit = m.latency[size_t(k)] > 0 ? double(m.window) * m.interval[size_t(k)] / m.latency[size_t(k)] : 1.0;
    m.slots[size_t(k)] = uint32_t(std::clamp(std::floor(fit), 1.0, double(std::max<uint64_t>(n, 1))));
  }
  m.cacheLineBytes = uint32_t(std::max(1, d.cacheLineBytes));
  m.cacheBytes = d.cacheBytes;
  m.vertexCache = d.vertexCache;
  return m;
}

double codeSizeFactor(const DeviceDesc& d, uint64_t moduleWords) {
  const std::vector<double>&w = d.codeWords, &s = d.codeSlowdown;
  const double x = double(moduleWords);
  if (w.empty() || x <= w.front()) return 1.0;
  if (x >= w.back()) return s.back();
  const size_t i = size_t(std::upper_bound(w.begin(), w.end(), x) - w.begin());  // w[i - 1] < x < w[i]
  const double t = std::log2(x / w[i - 1]) / std::log2(w[i] / w[i - 1]);
  return s[i - 1] + t * (s[i] - s[i - 1]);
}

double loopStateSeconds(const PassCounts& c, const DeviceDesc& d) {
  double s = 0.0;
  for (int k = 0; k < kLoopDepths; ++k)
    s += c.ops[size_t(opcount::kLoop1 + k)] * std::max(0.0, double(c.loopCarried[size_t(k)]) - d.loopStateValues);
  return s * d.loopStateSeconds;
}

Prediction predict(const PassCounts& c, const DeviceDesc& d) {
  Prediction p;
  const auto ops = scalarOps(c);
  const uint64_t groups = c.triangles ? 0 : c.workgroups ? c.workgroups : (c.invocations + 63) / 64;
  // A compute pass runs its workgroups on the cores (GPU: SMs), a workgroup on one: with fewer workgroups than cores
  // only that many are busy, and the rates, which are every core's together, shrink to theirs (the SH reduction's one
  // workgroup of 16 invocations runs on one of lavapipe's threads). Raster passes spread their bins over every core.
  const double cores = double(std::max(d.cores, 1));
  const double busy = groups ? std::min(double(groups), cores) : cores;
  const double spread = cores / busy;
  for (int k = 0; k < kOpClasses; ++k) p.aluSeconds += ops[size_t(k)] / d.opsPerSecond[size_t(k)];
  p.aluSeconds *= spread;
  // Scheduled on the device's core model: that time, over the busy cores (never below the issue-rate sum above).
  if (!d.unitsOverlap && c.scheduledSeconds > 0) p.aluSeconds = std::max(p.aluSeconds, c.scheduledSeconds / busy);
  // The rates are those of calibrate's small modules: a larger module's machine code runs slower per operation.
  p.codeFactor = codeSizeFactor(d, c.moduleWords);
  p.aluSeconds *= p.codeFactor;
  p.loopStateSeconds = loopStateSeconds(c, d) * spread;
  p.aluSeconds += p.loopStateSeconds;
  p.textureSeconds = c.ops[opcount::kTexNearest] / d.lookupsPerSecond[kNearest] +
                     c.ops[opcount::kTexBilinear] / d.lookupsPerSecond[kBilinear] +
                     c.ops[opcount::kTexTrilinear] / d.lookupsPerSecond[kTrilinear] +
                     c.ops[opcount::kTexUniform] / d.lookupsPerSecond[kUniformFetch] +
                     c.ops[opcount::kTexFetch] / d.lookupsPerSecond[kFetch] +
                     (c.ops[opcount::kTexMiss] - c.ops[opcount::kTexStreamMiss]) * d.textureMissSeconds +
                     c.ops[opcount::kTexStreamMiss] * d.textureStreamSeconds;  // the cache simulation's missed lines
  p.textureSeconds *= spread;
  // Software devices (units that do not overlap) load every storage-buffer element on their busy cores: distinct
  // bytes at calibrate's copy rate, re-reads of cache-resident table rows at its re-read rate (kind 25); their raster
  // rates already hold a raster pass's vertex fetch and fragment writes. A GPU's L1 serves the re-reads, its memory
  // carries the raster bytes, and its memory system is not one SM's (no busy-core share).
  p.memorySeconds = (double(c.bytesRead + c.bytesWritten + (d.unitsOverlap ? c.rasterBytes : 0)) / d.bandwidthBytesPerSecond +
                     double(c.bytesReread) / d.rereadBytesPerSecond) *
                    (d.unitsOverlap ? 1.0 : spread);
  const RasterRates& r = d.raster[size_t(c.rasterPipeline)];
  const uint64_t outside = std::min(c.outsideTriangles, c.triangles);
  p.rasterSeconds = double(c.triangles - outside) / r.trianglesPerSecond + double(outside) * r.outsideTriangleSeconds +
                    double(std::min(c.spanningTriangles, c.triangles - outside)) * r.spanningTriangleSeconds +
                    double(c.fragments) / r.fragmentsPerSecond + double(c.partialBlocks) * r.partialBlockSeconds +
                    double(c.attachmentBytes) / r.targetBytesPerSecond + double(c.vertexRuns) * r.vertexRunSeconds;
  // A raster pass is one submission of its draws: the first costs a dispatch, each further draw the pipeline's draw cost.
  const double submissions = c.triangles ? 1.0 : double(std::max<uint64_t>(c.dispatches, 1));
  const double draws = c.triangles ? double(std::max<uint64_t>(c.dispatches, 1) - 1) : 0.0;
  p.launchSeconds = submissions * d.dispatchSeconds + draws * r.drawSeconds + double(c.pipelines) * d.firstDispatchSeconds +
                    double(c.pipelineWords) * d.compileSecondsPerWord +
                    double(groups) * d.workgroupSeconds;
  const double terms[5] = {p.aluSeconds, p.textureSeconds, p.memorySeconds, p.rasterSeconds, p.launchSeconds};
  const char* names[5] = {"alu", "texture", "memory", "raster", "launch"};
  const int top = int(std::max_element(terms, terms + 5) - terms);
  p.bound = names[top];
  p.seconds = d.unitsOverlap ? std::max({p.aluSeconds, p.textureSeconds, p.memorySeconds, p.rasterSeconds}) + p.launchSeconds
                             : p.aluSeconds + p.textureSeconds + p.memorySeconds + p.rasterSeconds + p.launchSeconds;
  return p;
}

}  // namespace shadetwin::model
