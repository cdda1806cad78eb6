// `shadetwin render`: the main job. Loads a scene, builds the environment's MIP chain with the shared
// kernel, runs the G-buffer and shading passes on the emulator (or a Vulkan device), writes an EXR
// and a tone-mapped PNG, and prints the time of every pass.
#pragma once
#include <cstdint>
#include <ostream>
#include <memory>
#include <string>
#include <vector>

#include "emu/texture.h"

namespace shadetwin {

struct RenderOptions {
  std::string scene = "scenes/bunny.json";
  std::string device = "emu";  // emu | vulkan
  std::string out;             // EXR path; default: <scene name>.exr in the current directory
  uint32_t width = 0, height = 0;  // 0: the scene's size
  std::string profile = "lavapipe";  // device profile the emulator follows
};

/// The environment map as both builds sample it: RGBA32F with its full MIP chain from the shared kernel.
struct EnvironmentMap {
  uint32_t width = 0, height = 0;
  std::vector<std::vector<float>> levels;
  std::unique_ptr<emu::Texture> texture;
  size_t nonFinite = 0, negative = 0;
};
EnvironmentMap loadEnvironment(const std::string& path, std::ostream& log);

int renderCommand(const RenderOptions& opts, std::ostream& log);

}  // namespace shadetwin
