// What a shading pass does, counted (issue 19): the same drivers as the emulator's pass
// (passes/shade_emu_body.inl) over the shared source instantiated with counting lane types (model/op_count.h),
// so the counts are those of the code the GPU runs, vector by vector of 8 pixels. Counting changes no bit:
// the counted pass returns the emulator's image (ShadeCounts.CountingChangesNoBit).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "model/op_count.h"
#include "passes/shade.h"

namespace shadetwin::model {

struct PassCounts {
  std::array<uint64_t, opcount::kKinds> ticks{};  // vector operations (8 lanes) by kind; texture kinds per lane
  uint64_t invocations = 0;                       // work items (pixels, rounded up to whole 8-lane vectors)
  uint64_t bytesRead = 0, bytesWritten = 0;       // buffer traffic (G-buffer in, colour out)
};

/// Runs the shading pass of scene.technique counted, on one thread; `out` (optional) receives its image.
PassCounts countShadePass(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                          const VisibilityImage* vis = nullptr, std::vector<float>* out = nullptr);

}  // namespace shadetwin::model
