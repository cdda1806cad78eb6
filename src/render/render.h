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
  uint32_t frames = 1;               // frames to render (OUT_NNNN.exr when more than one)
  double envRotate = 0;              // degrees the environment turns about +y per frame
  uint32_t blocks = 0;               // kd-tree blocks of the *-mis techniques (0: the scene's mis.blocks)
};

/// The environment map as both builds sample it: RGBA32F with its full MIP chain from the shared kernel.
struct EnvironmentMap {
  uint32_t width = 0, height = 0;
  std::vector<std::vector<float>> levels;
  std::unique_ptr<emu::Texture> texture;
  size_t nonFinite = 0, negative = 0;
};
EnvironmentMap loadEnvironment(const std::string& path, std::ostream& log);
/// The same from level-0 texels (RGBA, rows top to bottom), with the same NaN/inf policy.
EnvironmentMap environmentFromLevel0(std::vector<float> texels, uint32_t width, uint32_t height);
/// Whole columns an equirectangular map of `width` shifts for a turn of `degrees` about +y (rounded).
uint32_t environmentShift(uint32_t width, double degrees);
/// The environment turned about +y by whole columns (exact: texels move, none is resampled), with
/// its MIP chain rebuilt. Positive degrees turn it right-handedly about +y: a light at azimuth
/// atan2(x, -z) = phi moves to phi - degrees (its column u W to u W - shift).
EnvironmentMap rotateEnvironment(const EnvironmentMap& env, double degrees);
/// RGBA texels of a W x H map with each texel repeated scale x scale times ((W scale) x (H scale)).
std::vector<float> repeatTexels(const float* rgba, uint32_t width, uint32_t height, uint32_t scale);

int renderCommand(const RenderOptions& opts, std::ostream& log);

}  // namespace shadetwin
