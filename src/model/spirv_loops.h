// The loops of a SPIR-V module and the values each carries from one iteration to the next (issue 19's loop-state term):
// per loop header (a block with OpLoopMerge), its nesting depth among the function's loops and the scalar components of
// its OpPhi results. A software device keeps a value that lives across the loop's back edge in a register only while
// the host has one free: SwiftShader's Subzero ran 96 multiply-adds an iteration 2.3x slower into 48 accumulators than
// into 8 (probes, docs/RESULTS.md session 44), lavapipe ~1.1-1.7x. The model charges what a carried value beyond the
// device's measured baseline costs per iteration (DeviceDesc loopStateValues, loopStateSeconds).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace shadetwin::model {

struct SpirvLoop {
  uint32_t depth = 1;    // 1: outermost loop of its function; a loop inside another one level more
  uint32_t carried = 0;  // scalar components of the header's OpPhi results (a vec3 counts 3, a struct its members')
};

/// The module's loops in layout order. A loop's blocks are those between its header and its merge block in the
/// function's layout (structured control flow, as glslang and spirv-opt emit it). Throws std::runtime_error on a module
/// that is not SPIR-V (magic number, truncated instruction).
std::vector<SpirvLoop> spirvLoops(std::span<const uint32_t> module);

/// Per nesting depth 1..kLoopDepths (the last pools every deeper loop): the most values any loop at that depth carries.
inline constexpr int kLoopDepths = 3;
std::vector<uint32_t> carriedByDepth(std::span<const uint32_t> module);

}  // namespace shadetwin::model
