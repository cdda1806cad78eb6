// `shadetwin verify ...`: differential tests of the emulator and the C++ builds against a Vulkan device.
#pragma once
#include <cstdint>
#include <iosfwd>
#include <string>

namespace shadetwin {

struct VerifyOptions {
  size_t count = 100000;
  uint64_t seed = 1;
  std::string device;     // Vulkan device name substring; empty = lavapipe
  bool validate = false;  // Vulkan validation layers on (errors fail the run)
  bool finiteTexels = false;  // texture: no inf, NaN or denormal texels
  std::string filters;        // texture: comma-separated filter cases to run (empty = all)
  std::string stages;         // texture: "compute", "fragment" or both (empty = both)
  std::string image;          // texture: sample this image file (MIP chain from the shared kernel) instead of random textures
  std::string scene;          // raster: scene file
  uint32_t width = 0, height = 0;  // raster: override the scene's image size
};

/// Returns the process exit status: 0 when everything is bit-identical, 1 otherwise.
int verifyMath(const VerifyOptions& opts, std::ostream& out);
int verifyTexture(const VerifyOptions& opts, std::ostream& out);
int verifyMips(const VerifyOptions& opts, std::ostream& out);
/// G-buffer pass, emulator vs Vulkan build: coverage, depth and every G-buffer channel, bit for bit.
int verifyRaster(const VerifyOptions& opts, std::ostream& out);

/// Distance in units in the last place between two floats (NaN vs NaN = 0, NaN vs number = huge).
int64_t ulpDistance(float a, float b);
/// Bitwise equality, treating all NaNs as one value (Vulkan does not define NaN payloads).
bool sameBits(float a, float b);

}  // namespace shadetwin
