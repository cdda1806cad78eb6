// Host side of the device's environment samplers (shade/env_sampling.h, issue 5): the tables of the
// kd-tree (fitted block distribution), the alias table over the same blocks, and the inversion
// method's CDFs, built in double precision from the level-0 texels and stored as the textures the
// shading kernels read (the same objects for the emulator and the Vulkan build).
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "emu/texture.h"
#include "inputs/env_kdtree.h"
#include "lanes/instantiate.h"

namespace shadetwin {

/// kEnvKdTree / kEnvAlias / kEnvInversion for technique kdtree-mis / alias-mis / inversion-mis.
uint32_t envMethodOf(const std::string& technique);

/// The uniforms of shade/env_sampling.h's EnvSampling, field for field.
struct EnvSamplingUniforms {
  uint32_t method = 0, count = 0, width = 0, height = 0;
  float alpha = 1, log2Span = 0, invWidth = 0, invHeight = 0;
};

/// The uniforms as the EnvSampling of a lane instantiation (shade::scalar::EnvSampling, shade::x8::...).
template <class EnvSampling>
EnvSampling toEnvSampling(const EnvSamplingUniforms& u) {
  return EnvSampling{u.method, u.count, u.width, u.height, u.alpha, u.log2Span, u.invWidth, u.invHeight};
}

struct EnvSamplingTables {
  EnvSamplingUniforms uniforms;                // the kernels' uniforms (count: blocks made; 0 for inversion)
  std::shared_ptr<const emu::Texture> table;   // blocks (RGBA32F) or marginal CDF (R32F)
  std::shared_ptr<const emu::Texture> texels;  // rank per texel or conditional CDFs (R32F, W x H)
  BlockFit fit;                                // kd-tree: alpha and its L1 misfit
  /// Bytes the sampler needs to draw directions (kd-tree: the block records; alias: + the alias
  /// table; inversion: both CDFs), and the bytes the pdf of an arbitrary direction adds (kd-tree,
  /// alias: the texel -> rank texture; inversion: nothing).
  size_t samplingBytes = 0, pdfBytes = 0;
  double buildMs = 0;
};

/// Tables of `method` for the RGBA32F equirectangular map `env` (level 0), `blocks` kd-tree blocks.
/// An environment without positive luminance is sampled uniformly over the sphere.
EnvSamplingTables envSamplingTables(const emu::Texture& env, uint32_t method, uint32_t blocks);

/// Bytes of the paper's packed kd-tree (4 x 16-bit block corners per block, alpha) and of the
/// inversion method's float CDFs (W H conditional + H marginal), for the compression ratio.
inline size_t packedKdTreeBytes(uint32_t blocks) { return size_t(blocks) * 8 + 4; }
inline size_t inversionTableBytes(uint32_t width, uint32_t height) { return (size_t(width) * height + height) * 4; }

}  // namespace shadetwin
