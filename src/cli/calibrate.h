// `shadetwin calibrate --device D`: measures a software Vulkan device with microkernels only
// (src/shaders/calibrate.comp: one operation class, one texture filter, a large copy or an empty dispatch per
// run) and writes its description for the performance model (src/model/device_desc.h, devices/D.json).
// Never runs a pass the model predicts: the model's validation would otherwise be fitted to its answer.
#pragma once
#include <ostream>
#include <string>

#include "model/device_desc.h"

namespace shadetwin {

struct CalibrateOptions {
  std::string device = "lavapipe";  // Vulkan device substring (lavapipe, swiftshader)
  std::string out;                  // default devices/<device>.json
  bool quick = false;               // short runs (tests): rates are then rough
  int rounds = 0;                   // rounds of every microkernel, each value the best of its rounds (0: 3, quick 1)
};

/// Runs the microkernels and returns the description (also printed, one rate per line).
model::DeviceDesc calibrateDevice(const CalibrateOptions& opts, std::ostream& log);
int calibrateCommand(const CalibrateOptions& opts, std::ostream& log);

}  // namespace shadetwin
