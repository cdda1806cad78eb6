// What the glints technique's shading pass reads (issue 17, docs/DESIGN.md §12): the normal maps'
// NDF histogram SATs (host-built, one RGBA32UI array for every map of the scene), the bins'
// directions, one record row per material, the lighting table (built by the shared kernel on
// whichever build renders) and the Legendre coefficient table.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "emu/device_profile.h"
#include "emu/texture.h"
#include "inputs/glint_lighting.h"
#include "inputs/ndf_histogram.h"
#include "inputs/normal_map.h"
#include "scene/scene.h"

namespace shadetwin {
namespace vk { class Context; }

struct GlintInputs {
  std::shared_ptr<const emu::Texture> sat;        // RGBA32UI 2D array: the stored rings of every map
  std::shared_ptr<const emu::Texture> binDirs;    // RGBA32F rings x sectors: each bin's tangent-space direction
  std::shared_ptr<const emu::Texture> materials;  // RGBA32F (6 + order + 1) x materials, layout in glints.cpp
  std::shared_ptr<const emu::Texture> lighting;   // RGBA32F (order + 1)^2 x views (inputs/glint_lighting.h), A of
                                                  // coefficient 0: the view's M_light
  std::shared_ptr<const emu::Texture> coef;       // Legendre recurrence coefficients (inputs/sh_legendre.h)
  std::shared_ptr<const emu::Texture> lobes;      // the rotated-lobe table (glintLobeTable), 1 x 1 when unused
  uint32_t lobeRings = 0, lobeSectors = 0;        // its grid (0: the kernel runs the recurrences per bin)
  size_t lobeBytes = 0;
  double lobeMs = 0;
  NdfBinningSpec bins;
  GlintLightingSpec lightingSpec;
  uint32_t mapSize = 0, maps = 0;
  uint32_t order = 0;  // the shading loop's degree: min(table degree, the largest lobe band limit at 1e-6)
  std::vector<uint32_t> lobeBandLimits;   // M_NDF per material at 1e-6, at most `order`
  std::vector<uint32_t> lightBandLimits;  // M_light per table view at 1e-6 (glintLightBandLimits)
  size_t satBytes = 0, lightingBytes = 0;
  double satMs = 0, lightingMs = 0;
};

/// Loop back-edges one invocation of the glints shading kernel may take, at most (every bin of the
/// footprint non-empty): 2 (M + 1)^2 + 2 (M + 1) + T + 9 T G + T P ((M + 1) + (M + 1)(M + 2) / 2) for
/// degree M, T rings, P sectors, G = P / 8 groups (shade/shade_glints.h's loops; the exact-math loops
/// of fixed count are unrolled). A device with a loop limit (emu::DeviceProfile::loopIterationLimit)
/// returns partial sums past it.
/// With the rotated-lobe table a bin takes ceil((M + 1)^2 / 4) + 1 (its loop over texels of four
/// coefficients; the inner loop of fixed count 4 is unrolled) instead of the recurrences'
/// (M + 1) + (M + 1)(M + 2) / 2, so lavapipe runs degree 28 instead of 18 with 9 x 32 bins.
uint64_t glintShadeLoopBound(uint32_t order, uint32_t rings, uint32_t sectors, bool lobeTable = false);

/// A glint material's normal map (generated from its spec or loaded from its file).
NormalMap glintMaterialMap(const Material& m);
/// What makes two materials' normal maps the same map (one SAT in the inputs' array): kind or file, size, seed, spread.
using GlintMapKey = std::tuple<std::string, uint32_t, uint32_t, float>;
inline GlintMapKey glintMapKey(const Material& m) { return {m.glintMap, m.glintMapSize, m.glintMapSeed, m.glintSpread}; }

/// Throws std::invalid_argument naming the material when its map cannot be generated or loaded, or
/// when the scene's maps differ in size (one texture array holds them all).
GlintInputs glintInputsEmu(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev);
GlintInputs glintInputsVulkan(vk::Context& ctx, const Scene& scene, const emu::Texture& env);

}  // namespace shadetwin
