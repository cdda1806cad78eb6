// Materials as the shading kernels read them: one 128-byte record per material slot (the std430
// struct MaterialGpu of shade_fis.comp / shade_env.comp; shade_mirror.comp reads its first 32 bytes)
// and the material maps of a scene as the layers of one 2D array texture (shade/material.h).
// Both builds read the same records and the same texels.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "emu/texture.h"
#include "scene/scene.h"

namespace shadetwin {
namespace vk { class Context; }

struct MaterialGpu {
  float diffuse[4], specular[4];
  float brdf[4];       // e, alpha_x, alpha_y, -
  uint32_t kind[4];    // kBrdf*, -, -, -
  float lobe0[4];      // Lafortune lobe 0: Cx, Cy, Cz, n
  float lobe1[4];      // lobe 1
  float rho[4];        // rho_0, rho_1 (0: lobe absent), -, -
  uint32_t maps[4];    // layer + 1 of the diffuse, specular and roughness maps (0: none), -
};
static_assert(sizeof(MaterialGpu) == 128 && offsetof(MaterialGpu, brdf) == 32 && offsetof(MaterialGpu, lobe0) == 64 &&
                  offsetof(MaterialGpu, maps) == 112,
              "MaterialGpu must match the std430 struct of shade_fis.comp / shade_env.comp");

/// The distinct map files of a scene in order of first use: layer i of the maps texture.
std::vector<std::string> materialMapFiles(const Scene& scene);

/// One record per material slot (a scene without materials has one default slot). withBrdf: the
/// sampling techniques' BRDF parameters; throws std::invalid_argument naming the material for a BRDF
/// they cannot sample (mirror).
std::vector<MaterialGpu> materialRecords(const Scene& scene, bool withBrdf);

/// The BRDF kinds the records use, bit k for kind k: the kSceneBrdfKinds specialization constant of
/// the shading kernels (shade/prelude.h), so kinds no material has are compiled out on the GPU.
uint32_t brdfKindsOf(const std::vector<MaterialGpu>& records);

/// Level 0 of the maps texture: every map file as float RGBA, one layer each (the files must share one
/// size; throws FileError naming the file otherwise, or for a non-finite texel). No maps: one white
/// 1x1 layer (kernels bind something; records then name no layer).
struct MaterialMapImages {
  uint32_t width = 1, height = 1, layers = 1;
  std::vector<float> texels{1.0f, 1.0f, 1.0f, 1.0f};
};
MaterialMapImages loadMaterialMaps(const Scene& scene);
/// Channel `c` of layer `layer` at (u, v), bilinear at level 0 with repeat addressing, in double
/// precision (texel centres at (i + 1/2) / w, rows top to bottom): the reference renderer's lookup.
double mapBilinear(const MaterialMapImages& maps, uint32_t layer, double u, double v, int c);

/// The maps texture (RGBA32F, full MIP chain from the shared downsampling kernel) built by the
/// emulator (SIMD build) or on a Vulkan device; the two chains are bit-identical (tests/mips_test).
emu::Texture materialMapsEmu(const MaterialMapImages& images);
emu::Texture materialMapsVulkan(vk::Context& ctx, const MaterialMapImages& images);

}  // namespace shadetwin
