// Texel formats of the emulated texture unit and their exact decoding.
#pragma once
#include <cstdint>
#include <string_view>

namespace emu {

enum class Format : uint8_t { RGBA32F, RGBA16F, RGBA8_UNORM, R32F, RGBA32UI };

struct FormatInfo {
  const char* name;
  uint32_t texelBytes;
  uint32_t channels;
};

const FormatInfo& formatInfo(Format f);
/// "rgba32f", "rgba16f", "rgba8", "r32f", "rgba32ui" (case-insensitive); throws std::invalid_argument naming the value.
Format parseFormat(std::string_view name);
/// The float formats the sampler filters. RGBA32UI (four 32-bit unsigned integers, GLSL usampler) is
/// read only by texelFetch, exactly (the glints histogram tables).
inline constexpr Format kAllFormats[] = {Format::RGBA32F, Format::RGBA16F, Format::RGBA8_UNORM, Format::R32F};
inline constexpr bool isIntegerFormat(Format f) { return f == Format::RGBA32UI; }

/// IEEE binary16 -> binary32, exact for every input (NaN payload kept, denormals exact).
float halfToFloat(uint16_t h);
/// binary32 -> binary16, round to nearest even (for building test textures).
uint16_t floatToHalf(float f);

}  // namespace emu
