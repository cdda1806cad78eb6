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
#include "scene/scene.h"

namespace shadetwin {

struct RenderOptions : SceneOverrides {  // the shared scene options (--technique, --samples, --width, ...)
  std::string scene = "scenes/bunny.json";
  std::string device = "emu";  // emu | vulkan
  std::string out;             // EXR path; default: <scene name>.exr in the current directory
  std::string profile = "lavapipe";  // device profile the emulator follows
  uint32_t frames = 1;               // frames to render (OUT_NNNN.exr when more than one)
  double envRotate = 0;              // degrees the environment turns about +y per frame
  double objectRotate = 0;           // degrees the first object turns about its vertical axis per frame
};

int renderCommand(const RenderOptions& opts, std::ostream& log);

}  // namespace shadetwin
