// `shadetwin verify ...`: differential tests of the emulator and the C++ builds against a Vulkan device.
#pragma once
#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace shadetwin {

struct VerifyOptions : SceneOverrides {  // the shared scene options of the suites that take a scene
  size_t count = 100000;
  uint64_t seed = 1;
  std::string device;     // Vulkan device name substring; empty = lavapipe
  bool validate = false;  // Vulkan validation layers on (errors fail the run)
  bool finiteTexels = false;  // texture: no inf, NaN or denormal texels
  std::string filters;        // texture: comma-separated filter cases to run (empty = all)
  std::string stages;         // texture: "compute", "fragment" or both (empty = both)
  bool implicitLod = false;   // texture: fragment-stage texture() with the LOD from quad derivatives
  uint64_t seeds = 1;         // texture: run the seeds seed .. seed + seeds - 1
  std::vector<std::string> profileSet;  // every suite (math: the denormal modes): KEY=VALUE overrides of the device profile (emu::setProfileField)
  std::string image;          // texture: sample this image file (MIP chain from the shared kernel) instead of random textures
  std::string junit, json;    // every suite: --junit FILE (JUnit XML), --json FILE (the same as data)
  std::string heatmap;        // image suites: --heatmap FILE.png, a ULP heat map of every differing channel
  std::string scene;          // raster/shadow/shade/frame: scene file
  uint32_t directions = 16;   // shadow: number of directions (spherical Fibonacci)
  uint32_t shadowSize = 512;  // shadow: map resolution
  uint32_t faceSize = 256;    // paraboloid: face size S of the 2S x S atlas
  bool visibilityV = false;   // visibility: fit V alone (default V max(0, n . w))
  std::string mapKind = "flakes";  // ndf: generated normal map kind
  uint32_t mapSize = 256;          // ndf: its size
  uint32_t glintOrder = 16;        // glint-lighting: SH degree
  uint32_t glintRings = 65, glintSectors = 128;  // glint-lighting: view grid
  int glintLevel = -1;             // glint-lighting: environment level summed (-1: the first at most 64 wide)
};

/// Returns the process exit status: 0 when everything is bit-identical, 1 otherwise.
int verifyMath(const VerifyOptions& opts, std::ostream& out);
int verifyTexture(const VerifyOptions& opts, std::ostream& out);
int verifyMips(const VerifyOptions& opts, std::ostream& out);
/// G-buffer pass, emulator vs Vulkan build: coverage, depth and every G-buffer channel, bit for bit.
int verifyRaster(const VerifyOptions& opts, std::ostream& out);

/// Shadow-map passes, emulator vs Vulkan build: every depth value of every direction.
int verifyShadow(const VerifyOptions& opts, std::ostream& out);

/// Dual-paraboloid atlas of the scene's environment (resampling kernel and its MIP chain), emulator vs Vulkan build.
int verifyParaboloid(const VerifyOptions& opts, std::ostream& out);
/// Order-3 SH irradiance of the scene's environment (projection rows + reduction tree), emulator vs Vulkan build.
int verifyShIrradiance(const VerifyOptions& opts, std::ostream& out);
/// SH visibility fit (issue 16) of both builds on the same G-buffer and shadow maps: 16 coefficients per pixel.
int verifyVisibility(const VerifyOptions& opts, std::ostream& out);
/// Shading pass of both builds on the same G-buffer (the Vulkan build's, read back): every channel.
int verifyShade(const VerifyOptions& opts, std::ostream& out);
/// Whole frames: emulator (G-buffer + shading) vs Vulkan build (G-buffer + shading).
int verifyFrame(const VerifyOptions& opts, std::ostream& out);

/// NDF histogram box counts (issue 17): the shared SAT lookup on both builds against the host's exact counts.
int verifyNdf(const VerifyOptions& opts, std::ostream& out);

/// The glints lighting table (issue 17) of the scene's environment on both builds: every coefficient of every view.
int verifyGlintLighting(const VerifyOptions& opts, std::ostream& out);

/// Per-channel tally of a bit-for-bit comparison: identical/total and a ULP histogram of what differs.
struct UlpTally {
  std::string name;
  size_t identical = 0, total = 0;
  std::array<size_t, 5> hist{};  // ULP 1, 2-3, 4-15, 16-255, >= 256 (or NaN vs number)
  int64_t firstDiff = -1;        // the first differing element's index (-1: none)
  float firstA = 0, firstB = 0;  // ... its two values, emulator and device
  /// Every difference as (element, ULP distance; kHeatNotANumber for NaN vs a number or a comparison not of floats),
  /// for the heat map (--heatmap); at most kMaxDiffs, `diffsTruncated` past them.
  std::vector<std::pair<uint32_t, uint32_t>> diffs;
  bool diffsTruncated = false;
  static constexpr size_t kMaxDiffs = size_t(1) << 24;
  void add(float a, float b);
  /// Records element `i` (values a, b) as the first difference unless one is recorded.
  void noteDifference(int64_t i, float a, float b);
  /// A comparison that is not of floats (coverage): counts a difference at the current element.
  void addSame(bool same);
};

/// What --junit / --json write: one case per tally (stage and channel group) plus the validation layers.
struct VerifyReport {
  std::string suite, device, scene;
  uint32_t width = 0;  // pixels per row when the tallies' elements are pixels (first difference as (x, y)), else 0
  std::vector<UlpTally> cases;
  uint32_t validationErrors = 0;
  std::string lastValidationMessage;
};
/// Writes opts.junit (JUnit XML, tests/junit.xsd) and opts.json (tests/verify_report.schema.json) when set, each
/// through an OutputFile (a temporary renamed when complete), and opts.heatmap (util/heatmap.h) when a case of an image
/// comparison (width > 0) differs; says on `out` what it wrote or why no heat map.
void writeVerifyReports(const VerifyOptions& opts, const VerifyReport& r, std::ostream& out);
/// Prints one row per tally and returns {identical, total} summed over all of them.
std::array<size_t, 2> printTallies(const std::vector<UlpTally>& t, std::ostream& out);

/// Distance in units in the last place between two floats (NaN vs NaN = 0, NaN vs number = huge).
int64_t ulpDistance(float a, float b);
/// Bitwise equality, treating all NaNs as one value (Vulkan does not define NaN payloads).
bool sameBits(float a, float b);

}  // namespace shadetwin
