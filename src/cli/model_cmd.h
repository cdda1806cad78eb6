// `shadetwin model --scene S [--technique T] --device D`: the performance model's prediction of every pass of a frame
// (issue 19) from its counted work (model/pass_counts.h) and the device's description (devices/D.json), with the
// bound, the measured time when D is a software device present here, and the check that every counted pass gives
// the emulator's bits. `shadetwin model --validate` does that for every shipped scene x technique on every present
// software device and ends with "model: mean abs error E% over N passes (worst W%)".
#pragma once
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace shadetwin {

struct ModelOptions : SceneOverrides {  // the shared scene options (--technique, --samples, --vis-maps, ...)
  std::string scene = "scenes/bunny.json";
  std::string device = "lavapipe";   // lavapipe, swiftshader, h100, h200
  std::string devicesDir = "devices";
  uint32_t repeat = 3;               // timed runs of each measured pass (the fastest is compared)
  // --validate: measurement rounds. Each round measures every scene x technique again after all the others (the
  // counting runs once); a pass's fastest over the rounds is compared, as calibrate keeps its kernels' fastest over
  // its rounds: runs minutes apart see different states of a shared host, back-to-back runs the same one.
  uint32_t rounds = 1;
  bool validate = false;             // every shipped scene x technique x software device
  std::vector<std::string> scenes;   // --validate: the scenes (default: every file in scenes/)
  std::vector<std::string> devices;  // --validate: the devices (default: lavapipe, swiftshader)
  std::string csv;                   // --validate: one row per pass
  // --validate: calibrate each device (writing <devicesDir>/<device>.json) just before its passes are measured, so
  // the prediction and the measurement see the same state of a shared host (its speed drifts 15-35% over minutes).
  bool calibrate = false;
  int calibrateRounds = 0;  // calibrate's rounds (0: its default)
  bool calibrateQuick = false;  // calibrate's --quick (short runs: for tests of the path, not for shipped files)
};

int modelCommand(const ModelOptions& opts, std::ostream& log);

}  // namespace shadetwin
