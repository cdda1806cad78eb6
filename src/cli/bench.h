// `shadetwin bench`: the same passes on the emulator and on a Vulkan device in one run, median of
// --repeat runs each, and the ratio emu/vulkan of their summed medians (last line of the output).
// Emulator times are the pass functions end to end (allocation and clear of their targets included);
// Vulkan times are submit-to-fence of the recorded pass including the copy of its targets into
// host-visible memory (pipelines, targets and buffers are built once, outside the timing).
// With the shading pass, the run also checks that both builds produce the same frame bits (each
// build's G-buffer, then its shading pass) and prints `frame: I/T bit-identical` before the ratio.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>

#include "scene/scene.h"

namespace shadetwin {

struct BenchOptions : SceneOverrides {  // the shared scene options; a --technique makes passes default to gbuffer,shade
  std::string scene = "scenes/bunny.json";
  std::string passes = "gbuffer,shadow";  // comma-separated: gbuffer, shadow, shade
  uint32_t repeat = 5;
  uint32_t directions = 16, shadowSize = 1024;
  std::string device;  // Vulkan device substring; empty = lavapipe
};

int benchCommand(const BenchOptions& opts, std::ostream& log);

}  // namespace shadetwin
