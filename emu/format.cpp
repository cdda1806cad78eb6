#include "emu/format.h"

#include <cctype>
#include <cstring>
#include <stdexcept>
#include <string>

namespace emu {

const FormatInfo& formatInfo(Format f) {
  static const FormatInfo infos[] = {{"rgba32f", 16, 4}, {"rgba16f", 8, 4}, {"rgba8", 4, 4}, {"r32f", 4, 1}, {"rgba32ui", 16, 4}};
  return infos[static_cast<int>(f)];
}

Format parseFormat(std::string_view name) {
  std::string s(name);
  for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (Format f : kAllFormats)
    if (s == formatInfo(f).name) return f;
  if (s == formatInfo(Format::RGBA32UI).name) return Format::RGBA32UI;
  throw std::invalid_argument("unknown texture format '" + std::string(name) + "' (expected rgba32f, rgba16f, rgba8, r32f or rgba32ui)");
}

float halfToFloat(uint16_t h) {
  uint32_t sign = uint32_t(h & 0x8000u) << 16, exp = (h >> 10) & 0x1fu, man = h & 0x3ffu, bits;
  if (exp == 0x1f) {
    bits = sign | 0x7f800000u | (man << 13);
  } else if (exp != 0) {
    bits = sign | ((exp + 112) << 23) | (man << 13);
  } else if (man == 0) {
    bits = sign;
  } else {  // subnormal half: normalise
    int e = -1;
    do { man <<= 1; ++e; } while (!(man & 0x400u));
    bits = sign | uint32_t(112 - e) << 23 | ((man & 0x3ffu) << 13);
  }
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

uint16_t floatToHalf(float f) {
  uint32_t x;
  std::memcpy(&x, &f, 4);
  uint32_t sign = (x >> 16) & 0x8000u, ax = x & 0x7fffffffu;
  if (ax > 0x7f800000u) return uint16_t(sign | 0x7e00u);
  if (ax >= 0x477ff000u) return uint16_t(sign | 0x7c00u);  // rounds to inf
  if (ax < 0x38800000u) {                                 // half subnormal or zero
    float a;
    std::memcpy(&a, &ax, 4);
    float scaled = a * 16777216.0f;                        // exact: units of 2^-24
    uint32_t q = uint32_t(scaled), r = 0;
    float rem = scaled - float(q);
    r = (rem > 0.5f || (rem == 0.5f && (q & 1))) ? 1 : 0;
    return uint16_t(sign | (q + r));
  }
  uint32_t m = ax + 0xc8000000u;  // rebias 127 -> 15
  uint32_t rounded = (m + 0xfffu + ((m >> 13) & 1u)) >> 13;
  return uint16_t(sign | rounded);
}

}  // namespace emu
