// `shadetwin render`: the main job. Loads a scene, builds the environment's MIP chain with the shared
// kernel, runs the G-buffer and shading passes on the emulator (or a Vulkan device), writes an EXR
// and a tone-mapped PNG, and prints the time of every pass.
#pragma once
#include <cstdint>
#include <ostream>
#include <memory>
#include <string>
#include <vector>

#include "inputs/environment.h"

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
  double objectRotate = 0;           // degrees the first object turns about its vertical axis per frame
  std::string technique;             // shading technique (empty: the scene's)
  uint32_t samples = 0;              // samples of the technique (fis / env samples, MIS or G x D pairs; 0: the scene's)
};

int renderCommand(const RenderOptions& opts, std::ostream& log);

}  // namespace shadetwin
