// `shadetwin sweep`: speed against error of the shading techniques (issue 4, item 5). For each
// technique and sample count: the emulator's frame (shading pass timed; G-buffer rendered once),
// the same frame on a Vulkan device (shading pass timed, submit to read-back) with the count of
// bit-identical values, and its error against the reference renderer (Embree, MIS, no visibility)
// over the pixels the G-buffer covers (the techniques differ only there). Writes sweep.csv and two
// log-log plots (error vs samples, error vs emulator time). For the MIS techniques (issue 5) the
// count is the sample pairs per pixel, and the sweep adds the sampler study, env_sampling.csv: per
// map (at its size and at 2x2 its size, the paper's 2048 x 1024) and sampler, the kd-tree's fitted
// alpha and L1 misfit, build time, table memory and compression against the inversion tables, and
// samples per second of the C++ scalar, C++ 8-lane and Vulkan builds from one run. With --vis-maps the
// reference traces visibility and the sweep adds the SH visibility study, visibility.csv: per map count
// K the shadow-map, fit, filter and shading times of both builds, the bits, and the error.
#pragma once
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "emu/device_profile.h"
#include "passes/gbuffer.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace shadetwin {

// The shared scene options it takes: --width, --height, --blocks (its --technique, --samples and --vis-maps are lists,
// the sweep's axes).
struct SweepOptions : SceneOverrides {
  std::string scene = "scenes/spheres.json";
  std::string techniques = "fis,unfiltered,stochastic,env";
  std::string samples = "4,8,16,32,64,128,256";
  std::string reference;         // EXR of the reference; empty: render it (referenceSpp per pixel)
  uint32_t referenceSpp = 512;
  std::string out = "sweep";     // output folder: sweep.csv, rmse_vs_samples.png, rmse_vs_time.png, reference.exr
  std::string device;            // Vulkan device substring; empty = lavapipe
  bool vulkan = true;            // --no-vulkan: emulator only
  std::string maps = "forest,courtyard,studio,city";  // sampler study (with a *-mis technique)
  // SH visibility study (issue 16): comma-separated map counts K (0 = no visibility) of technique fis
  // at the scene's sample count, against a reference with visibility; writes visibility.csv.
  std::string visMapCounts;
  uint32_t visRays = 10000;  // the per-pixel Embree SH fit (the best an order-4 SH can do); 0: skip
  // Glints study (issue 17, --technique glints): SH degrees of the technique; --samples is then the
  // G x D baseline's sample ladder and --reference-spp its reference (cli/sweep_glints.cpp).
  std::string glintOrders = "4,8,16,20";
  // ... and histogram binnings RINGSxSECTORS@THETAMAX_DEGREES (e.g. 9x32@40,18x32@40) at the scene's degree.
  std::string glintBins;
  // ... and lighting-table view grids RINGSxSECTORS (e.g. 9x16,33x64,65x128) at the scene's degree (Fig. 17).
  std::string glintViews;
  // ... and rotated-lobe tables RINGSxSECTORS instead of the recurrences (Fig. 16), at the scene's degree.
  std::string glintLobes;
  // ... and temporal stability: frames of a camera orbiting the target by glintOrbit degrees per frame;
  // glints, G x D at glints' time (fixed and per-frame seeds) against the reference's frame-to-frame change.
  uint32_t glintFrames = 0;
  double glintOrbit = 0.25;
};

/// Comma-separated counts in [lo, hi]; throws std::invalid_argument "FLAG: 'S' is not a NOUN in [lo, hi]".
std::vector<uint32_t> parseCounts(const std::string& list, const char* flag, const char* noun, uint32_t lo, uint32_t hi);

/// The builds a sweep compares: the device profile (lavapipe's, or the Vulkan device's), the Vulkan
/// context and its G-buffer (with opts.vulkan), the emulator's G-buffer and which pixels have
/// geometry (the techniques differ only there; the metrics' mask). Logs the device and the count.
struct SweepBuilds {
  const emu::DeviceProfile* dev = nullptr;
  std::unique_ptr<vk::Context> ctx;
  GBuffer gv, g;
  std::vector<uint8_t> covered;
};
SweepBuilds sweepBuilds(const SweepOptions& opts, const Scene& scene, std::ostream& log);

/// The glints study (sweep --technique glints): glints per degree and G x D per sample count against a
/// G x D reference; glints.csv, rmse_vs_time.png, the line "glints speed-up at equal error: Sx".
int glintsSweep(const SweepOptions& opts, std::ostream& log);

int sweepCommand(const SweepOptions& opts, std::ostream& log);

}  // namespace shadetwin
