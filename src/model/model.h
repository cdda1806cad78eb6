// The performance model (issue 19): a pass's counted work (model/pass_counts.h) over a device's measured or
// published rates (model/device_desc.h) gives its predicted time and what bounds it.
#pragma once
#include <string>

#include "model/device_desc.h"
#include "model/pass_counts.h"

namespace shadetwin::model {

struct Prediction {
  double aluSeconds = 0, textureSeconds = 0, memorySeconds = 0, rasterSeconds = 0, launchSeconds = 0;
  double codeFactor = 1;  // the ALU time's factor for the pass's module size (codeSizeFactor), in aluSeconds
  double loopStateSeconds = 0;  // what its loops' carried values beyond the device's baseline cost (in aluSeconds)
  double seconds = 0;   // sum of the terms (software devices) or the largest plus launch (GPUs); launch = dispatches x cost
  std::string bound;    // alu, texture, memory, raster or launch: the largest term
};

/// Scalar (lane) operations of each model class from a pass's counts (mask logic is integer ALU).
std::array<double, kOpClasses> scalarOps(const PassCounts& c);
/// On a software device, a pass's 8-lane operations are also scheduled on one core (opcount::Scheduler): latency,
/// dependencies and the window count, and the ALU term is that time over the cores; a GPU hides latency across warps
/// and stays throughput-bound (the model is off).
CoreModel coreModel(const DeviceDesc& d);
Prediction predict(const PassCounts& c, const DeviceDesc& d);
/// The ALU time's factor for a module of `moduleWords` SPIR-V words: d's measured points (codeWords, codeSlowdown),
/// linear in log2 of the size between two, 1 at or below the first, the last one's beyond it.
double codeSizeFactor(const DeviceDesc& d, uint64_t moduleWords);
/// The loop-state term before the busy-core share: per loop depth, the pass's invocation-iterations x the values its
/// module's loops of that depth carry beyond d.loopStateValues x d.loopStateSeconds.
double loopStateSeconds(const PassCounts& c, const DeviceDesc& d);

}  // namespace shadetwin::model
