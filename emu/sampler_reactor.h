// SwiftShader's texture unit (src/Pipeline/SamplerCore.cpp, Reactor), re-implemented from its
// semantics for the profile strategies that name it (DeviceProfile::TexAddressing::Reactor,
// MipSelection::Reactor, Unorm8Path::Fixed16). Internal to emu/sampler.cpp; one lane at a time,
// since SwiftShader samples explicit-LOD lookups one lane at a time (SpirvShaderSampling.cpp).
#pragma once
#include <array>
#include <cstdint>

#include "emu/sampler.h"

namespace emu::reactor {

/// Reactor's Frac: x - floor(x), clamped below 1 with minps (a NaN result becomes the constant just under 1).
float frac(float x);

/// The LOD after SamplerCore::sampleTexture: lod + sampler bias, clamped to [minLod, maxLod] (both
/// first clamped to [0, kMaxTextureLod] by vk::Sampler), then the level(s): linear mip trunc(lod) and
/// trunc(lod) + 1 with fraction frac(lod) (always blended), nearest rint(lod); levels past the view's
/// last repeat the last one (the descriptor replicates it).
constexpr float kMaxTextureLod = 13.0f;  // sw::MAX_TEXTURE_LOD = MIPMAP_LEVELS - 2, MIPMAP_LEVELS 15 (measured: implicit LODs past 12)
struct Lod {
  float lod;       // clamped
  int32_t l0, l1;  // levels read (l1 only for linear mip)
  float f;         // frac(lod)
};
Lod selectLod(const Texture& t, const SamplerDesc& s, float lod);

/// Float path addressing of one axis (SamplerCore::address, Int4 form). `pointFilter` is
/// FILTER_POINT (x0 = trunc(coord), no wrap afterwards); `offset` is the half-texel shift and the +1
/// step of linear filtering (masked off for the magnified side of mixed filters).
struct Axis {
  int32_t i0, i1;
  float f;
};
Axis addressFloat(float u, int32_t size, AddressMode mode, bool pointFilter, bool offset);

/// 16-bit path addressing (SamplerCore::address, Short4 form): u in 0.16 fixed point.
uint16_t address16(float u, AddressMode mode);

/// RGBA8 through SwiftShader's 16-bit filtering (SamplerCore::sampleFilter / sampleQuad2D): texels as
/// b << 8, bilinear weights as products of 16-bit fractions (MulHigh), the mip blend with a 16-bit
/// truncated fraction, and the result as float(c) * (1.0f / 0xFF00).
Texel4 sampleUnorm16(const Texture& t, const SamplerDesc& s, const Lod& L, uint32_t layer, float u, float v);

}  // namespace emu::reactor
