// SwiftShader's texture unit, re-implemented from the semantics of src/Pipeline/SamplerCore.cpp
// (read with the project's search tool, not copied): see emu/sampler_reactor.h and docs/DESIGN.md s3.
#include "emu/sampler_reactor.h"

#include "emu/x86_float.h"

#include <cmath>
#include <cstring>

namespace emu::reactor {

namespace {
float fromBits(uint32_t b) {
  float f;
  std::memcpy(&f, &b, 4);
  return f;
}
const float kJustUnderOne = fromBits(0x3F7FFFFFu);  // SamplerCore::address: oneBits

int32_t mini(int32_t a, int32_t b) { return a < b ? a : b; }
int32_t maxi(int32_t a, int32_t b) { return a > b ? a : b; }
uint16_t mulHigh(uint16_t a, uint16_t b) { return uint16_t((uint32_t(a) * b) >> 16); }
}  // namespace

float frac(float x) {
  const float r = x - std::floor(x);
  return x86::minps(r, kJustUnderOne);
}

Lod selectLod(const Texture& t, const SamplerDesc& s, float lod) {
  auto clampLod = [](float x) { return x < 0.0f ? 0.0f : (x > kMaxTextureLod ? kMaxTextureLod : x); };
  const int32_t last = int32_t(t.levelCount()) - 1;
  float minLod = clampLod(s.minLod), maxLod = clampLod(s.maxLod);
  // A one-level view whose filtering does not depend on the LOD (mag = min filter) is sampled at LOD 0:
  // the sampler state's LOD range becomes [0, 0] and the LOD computation is skipped (measured: a
  // 16-bit mip blend with weight 0 on one-level RGBA8 views, verify texture --seeds 30).
  if (last == 0 && s.magFilter == s.minFilter) minLod = maxLod = 0.0f;
  float l = minLod == maxLod ? minLod : lod + s.lodBias;
  l = x86::maxps(l, minLod);
  l = x86::minps(l, maxLod);
  Lod r{l, 0, 0, 0.0f};
  if (s.mipmapMode == MipmapMode::Nearest) {
    r.l0 = r.l1 = mini(x86::cvtps2dq(l), last);
  } else {
    const int32_t i = x86::cvttps2dq(l);
    r.l0 = mini(i, last);
    r.l1 = mini(i + 1, last);
    r.f = frac(l);
  }
  return r;
}

Axis addressFloat(float u, int32_t size, AddressMode mode, bool pointFilter, bool offset) {
  float c = u;
  switch (mode) {
    case AddressMode::ClampToEdge:
      c = x86::minps(x86::maxps(c, 0.0f), kJustUnderOne);
      break;
    case AddressMode::MirroredRepeat: {  // 2 |u/2 - rint(u/2)|, below 1
      const float h = c * 0.5f;
      c = 2.0f * std::fabs(h - std::nearbyint(h));
      c = x86::minps(c, kJustUnderOne);
      break;
    }
    case AddressMode::Repeat:
      c = frac(c);
      break;
  }
  c = c * float(size);
  Axis r{};
  if (pointFilter) {  // FILTER_POINT: coordinates are in [0, size), so the cast is the floor
    r.i0 = r.i1 = x86::cvttps2dq(c);
    return r;
  }
  c = c - (offset ? 0.5f : 0.0f);
  const float fl = std::floor(c);
  r.i0 = x86::cvttps2dq(fl);
  r.f = c - fl;
  r.i1 = r.i0 + (offset ? 1 : 0);
  if (mode == AddressMode::Repeat) {
    r.i0 = r.i0 < 0 ? size - 1 : r.i0;
    r.i1 = r.i1 < size ? r.i1 : 0;
  } else {
    r.i0 = maxi(r.i0, 0);
    r.i1 = mini(r.i1, size - 1);
  }
  return r;
}

uint16_t address16(float u, AddressMode mode) {
  switch (mode) {
    case AddressMode::ClampToEdge:
      return uint16_t(x86::cvttps2dq(x86::minps(x86::maxps(u, 0.0f), 65535.0f / 65536.0f) * 65536.0f));
    case AddressMode::MirroredRepeat: {
      int32_t c = x86::cvttps2dq(u * 65536.0f);
      const int32_t m = int32_t(uint32_t(c) << 15) >> 31;  // bit 16: an odd period runs backwards
      return uint16_t(c ^ m);
    }
    case AddressMode::Repeat:
      break;
  }
  return uint16_t(x86::cvttps2dq(u * 65536.0f));
}

namespace {
using Short4 = std::array<uint16_t, 4>;

Short4 loadUnorm16(const Texture& t, int32_t level, uint32_t layer, uint16_t u, uint16_t v) {
  const uint32_t w = t.levelWidth(uint32_t(level)), h = t.levelHeight(uint32_t(level));
  const uint32_t x = mulHigh(u, uint16_t(w)), y = mulHigh(v, uint16_t(h));
  const auto b = t.loadBytes(uint32_t(level), layer, x, y);
  return {uint16_t(b[0] << 8), uint16_t(b[1] << 8), uint16_t(b[2] << 8), uint16_t(b[3] << 8)};
}

// One level of sampleQuad2D. halfMask: the half-texel offsets apply (off for the point side of mixed
// filters, SamplerCore::offsetSample).
Short4 sampleLevel16(const Texture& t, const SamplerDesc& s, int32_t level, uint32_t layer, float u, float v, bool point,
                     bool halfMask) {
  const uint16_t uu = address16(u, s.addressU), vv = address16(v, s.addressV);
  if (point) return loadUnorm16(t, level, layer, uu, vv);
  const uint32_t w = t.levelWidth(uint32_t(level)), h = t.levelHeight(uint32_t(level));
  auto offsets = [&](uint16_t c, uint32_t size, AddressMode mode, uint16_t& c0, uint16_t& c1) {
    const uint16_t half = halfMask ? uint16_t(0x8000u / size) : uint16_t(0);
    if (mode == AddressMode::Repeat) {
      c0 = uint16_t(c - half);
      c1 = uint16_t(c + half);
    } else {  // unsigned saturating
      c0 = c > half ? uint16_t(c - half) : uint16_t(0);
      c1 = uint32_t(c) + half > 0xFFFFu ? uint16_t(0xFFFF) : uint16_t(c + half);
    }
  };
  uint16_t u0, u1, v0, v1;
  offsets(uu, w, s.addressU, u0, u1);
  offsets(vv, h, s.addressV, v0, v1);
  const Short4 c00 = loadUnorm16(t, level, layer, u0, v0), c10 = loadUnorm16(t, level, layer, u1, v0);
  const Short4 c01 = loadUnorm16(t, level, layer, u0, v1), c11 = loadUnorm16(t, level, layer, u1, v1);
  const uint16_t f0u = uint16_t(u0 * w), f0v = uint16_t(v0 * h);
  const uint16_t f1u = uint16_t(~f0u), f1v = uint16_t(~f0v);
  const uint16_t w00 = mulHigh(f1u, f1v), w10 = mulHigh(f0u, f1v), w01 = mulHigh(f1u, f0v), w11 = mulHigh(f0u, f0v);
  Short4 c;
  for (int k = 0; k < 4; ++k)
    c[size_t(k)] = uint16_t(uint16_t(mulHigh(c00[k], w00) + mulHigh(c10[k], w10)) +
                            uint16_t(mulHigh(c01[k], w01) + mulHigh(c11[k], w11)));
  return c;
}
}  // namespace

Texel4 sampleUnorm16(const Texture& t, const SamplerDesc& s, const Lod& L, uint32_t layer, float u, float v) {
  const bool point = s.magFilter == Filter::Nearest && s.minFilter == Filter::Nearest;
  bool halfMask = true;  // FILTER_LINEAR
  if (s.magFilter == Filter::Nearest && s.minFilter == Filter::Linear) halfMask = L.lod > 0.0f;
  if (s.magFilter == Filter::Linear && s.minFilter == Filter::Nearest) halfMask = L.lod <= 0.0f;
  Short4 c = sampleLevel16(t, s, L.l0, layer, u, v, point, halfMask);
  if (s.mipmapMode == MipmapMode::Linear) {
    const Short4 cc = sampleLevel16(t, s, L.l1, layer, u, v, point, halfMask);
    const uint16_t utri = uint16_t(x86::cvttps2dq(L.lod * 65536.0f)), rest = uint16_t(~utri);
    for (size_t k = 0; k < 4; ++k) c[k] = uint16_t(mulHigh(c[k], rest) + mulHigh(cc[k], utri));
  }
  const float scale = 1.0f / float(0xFF00);
  return {float(c[0]) * scale, float(c[1]) * scale, float(c[2]) * scale, float(c[3]) * scale};
}

}  // namespace emu::reactor
