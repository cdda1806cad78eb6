// `shadetwin model --scene S [--technique T] --device D`: the performance model's prediction of a pass (issue 19,
// first slice: the shading pass) from its counted work (model/shade_counts.h) and the device's description
// (devices/D.json), with the measured time when D is a software device present here, and the check that the
// counted run gives the emulator's bits.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>

namespace shadetwin {

struct ModelOptions {
  std::string scene = "scenes/bunny.json";
  std::string technique;             // default: the scene's
  std::string device = "lavapipe";   // lavapipe, swiftshader, h100, h200
  std::string devicesDir = "devices";
  uint32_t width = 0, height = 0;
  uint32_t samples = 0;              // fis samples (0: the scene's)
  uint32_t repeat = 3;               // timed runs of the measured pass (median)
};

int modelCommand(const ModelOptions& opts, std::ostream& log);

}  // namespace shadetwin
