// The memory a frame of a scene would need, estimated from the scene and its environment's header before anything is
// allocated (issue 20 item 6): render and reference refuse a run that would need more than the machine has, naming the
// parts (docs/RESULTS.md "Stress" compares the estimate with the measured peak).
#pragma once
#include <cstdint>
#include <vector>

#include "scene/scene.h"
#include "util/memory.h"

namespace shadetwin {

/// Which build renders: the emulator, or a Vulkan device whose memory is host memory (lavapipe, SwiftShader: every
/// device image and its read-back buffer count as well).
enum class FrameBuild { Emu, Vulkan };

/// The largest allocations of one frame of `scene` (its technique, image size, visibility block, glint tables) over an
/// environment of envWidth x envHeight with envChannels channels in its file, and the per-frame accumulation of a
/// progressive technique, and the passes' transformed geometry (per triangle, measured). The loaded meshes are not
/// included (they come with the scene, so the process already holds them), nor material maps (their size is known when
/// loaded). Byte counts per part, not a bound: docs/RESULTS.md "Stress" compares them with measured peaks.
std::vector<MemoryNeed> frameMemory(const Scene& scene, uint32_t envWidth, uint32_t envHeight, uint32_t envChannels,
                                    FrameBuild build);

}  // namespace shadetwin
