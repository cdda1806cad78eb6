// The emulated sampler: textureLod and texelFetch as a device profile says the device does them.
// Stages of the model (SwiftShader-style split): LOD (bias, min/max clamp, level choice),
// addressing (wrap per mode, per filter), texel decode (emu/format.h), filtering (float path or the
// 8-bit fixed-point path).
#pragma once
#include <cstdint>

#include "emu/device_profile.h"
#include "emu/texture.h"

namespace emu {

enum class Filter : uint8_t { Nearest, Linear };
enum class MipmapMode : uint8_t { Nearest, Linear };
enum class AddressMode : uint8_t { ClampToEdge, Repeat, MirroredRepeat };

struct SamplerDesc {
  Filter magFilter = Filter::Linear;
  Filter minFilter = Filter::Linear;
  MipmapMode mipmapMode = MipmapMode::Linear;
  AddressMode addressU = AddressMode::ClampToEdge;
  AddressMode addressV = AddressMode::ClampToEdge;
  float lodBias = 0.0f;
  float minLod = 0.0f;
  float maxLod = 1000.0f;
  // How the LOD arrives, not sampler state: true for texture() with implicit LOD, whose LOD lavapipe
  // computes once per 2x2 quad. That lets its 8-bit AoS path run mixed mag/min filters (the min/mag
  // choice is then per quad); with a per-pixel explicit LOD mixed filters take the float path.
  bool lodPerQuad = false;
};

const char* addressName(AddressMode a);

/// textureLod(sampler2DArray, vec3(u, v, layer), lod), as one lane deciding alone. Devices that decide
/// mip lerping or mixed mag/min filtering per SIMD vector (lavapipe) can differ for lanes whose
/// neighbours decide otherwise: use textureLodBatch with the stage's lane grouping for exact bits.
Texel4 textureLod(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, float u, float v, float layer, float lod);
/// The LOD texture() derives for one 2x2 quad (pixels 0 top-left, 1 top-right, 2 bottom-left,
/// 3 bottom-right) from its normalized coordinates s, t, before sampler bias and min/max clamps (it
/// then goes through them like an explicit LOD). Per the profile's implicitLod model. Where the
/// profile's implicitNearestShortcut applies to sampler s, the value returned is the equivalent
/// explicit LOD: the shortcut's integer level, and 0.25 for level 0 when rho^2 > 1 (minified).
/// (Not modelled: rho^2 = NaN there, level 64 but magnified, with mixed mag/min filters.)
float implicitLod(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, const float su[4],
                  const float tv[4]);

/// texelFetch(sampler2DArray, ivec3(x, y, layer), level); coordinates must be in range.
Texel4 texelFetch(const Texture& tex, int32_t x, int32_t y, int32_t layer, int32_t level);

/// Batch form: n queries of (u, v, layer, lod), results as 4 floats each, run on 8-lane SIMD blocks
/// (float path, equal mag/min filters) and TBB threads, under the stage's denormal mode. vectorOf[i]
/// names the device SIMD vector query i runs in (DeviceProfile::computeVectorLanes /
/// fragmentVector*); lanes of one vector share the "need lerp" / "need linear" decisions. nullptr:
/// every query decides alone. Results do not depend on the thread count.
void textureLodBatch(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, Stage stage, const float* query,
                     float* out, size_t n, const uint32_t* vectorOf = nullptr);

/// One device vector: n <= 16 queries of (u, v, layer, lod) that run together in one SIMD vector of
/// the device (the per-vector "need lerp" / "need linear" decisions are taken over all n lanes). Runs
/// on the calling thread under its current denormal mode (the caller's stage). Used by the C++ SIMD
/// builds of shared shading code, whose lanes are the device's lanes.
void textureLodVector(const Texture& tex, const SamplerDesc& s, const DeviceProfile& dev, const float* query, float* out,
                      int n);

}  // namespace emu
