// C++ side of `textureLod` in the shared dialect: a Sampler2D is an emulated texture + sampler +
// device profile, and a lookup runs through the emulated texture unit (emu/sampler.h). In the SIMD
// builds the N lanes are one device vector (lavapipe: 8 invocations), so the per-vector decisions of
// the device's sampler are reproduced; the scalar build is the one-lane model. GLSL: sampler2D.
#pragma once
#include <cstring>

#include "emu/lanes.h"
#include "emu/sampler.h"
#include "lanes/vec.h"

namespace shadetwin::shade {

struct Sampler2D {
  const emu::Texture* tex = nullptr;
  emu::SamplerDesc desc;
  const emu::DeviceProfile* dev = nullptr;
};

inline V4<float> textureLodLanes(const Sampler2D& s, float u, float v, float lod, float layer = 0.0f) {
  emu::Texel4 t = emu::textureLod(*s.tex, s.desc, *s.dev, u, v, layer, lod);
  return V4<float>(t.r, t.g, t.b, t.a);
}

template <int N>
V4<emu::F32<N>> textureLodLanes(const Sampler2D& s, emu::F32<N> u, emu::F32<N> v, emu::F32<N> lod,
                                emu::F32<N> layer = emu::F32<N>(0.0f)) {
  float q[4 * N], out[4 * N];
  for (int i = 0; i < N; ++i) {
    q[4 * i] = u[i];
    q[4 * i + 1] = v[i];
    q[4 * i + 2] = layer[i];
    q[4 * i + 3] = lod[i];
  }
  emu::textureLodVector(*s.tex, s.desc, *s.dev, q, out, N);
  V4<emu::F32<N>> r;
  for (int i = 0; i < N; ++i) {
    r.x.set(i, out[4 * i]);
    r.y.set(i, out[4 * i + 1]);
    r.z.set(i, out[4 * i + 2]);
    r.w.set(i, out[4 * i + 3]);
  }
  return r;
}

/// An integer texture (RGBA32UI) as a GLSL usampler2DArray: texelFetch only, the stored values.
struct USampler2DArray {
  const emu::Texture* tex = nullptr;
};

inline void uintFetchLanes(const USampler2DArray& s, int32_t x, int32_t y, int32_t layer, int level, uint32_t& a,
                           uint32_t& b, uint32_t& c, uint32_t& d) {
  const std::array<uint32_t, 4> v = s.tex->loadUint(uint32_t(level), uint32_t(layer), uint32_t(x), uint32_t(y));
  a = v[0], b = v[1], c = v[2], d = v[3];
}

template <int N>
void uintFetchLanes(const USampler2DArray& s, emu::I32<N> x, emu::I32<N> y, emu::I32<N> layer, int level, emu::U32<N>& a,
                    emu::U32<N>& b, emu::U32<N>& c, emu::U32<N>& d) {
  for (int i = 0; i < N; ++i) {
    const std::array<uint32_t, 4> v = s.tex->loadUint(uint32_t(level), uint32_t(layer[i]), uint32_t(x[i]), uint32_t(y[i]));
    a.set(i, v[0]), b.set(i, v[1]), c.set(i, v[2]), d.set(i, v[3]);
  }
}

/// texelFetch(sampler2D, ivec2(x, y), level) (or of a 2D array at `layer`): the stored texel,
/// converted from its format.
inline V4<float> texelFetchLanes(const Sampler2D& s, int32_t x, int32_t y, int level, int32_t layer = 0) {
  emu::Texel4 t = emu::texelFetch(*s.tex, x, y, layer, level);
  return V4<float>(t.r, t.g, t.b, t.a);
}

template <int N>
V4<emu::F32<N>> texelFetchLanes(const Sampler2D& s, emu::I32<N> x, emu::I32<N> y, int level,
                                emu::I32<N> layer = emu::I32<N>(0)) {
  V4<emu::F32<N>> r;
  if (s.tex->format() == emu::Format::RGBA32F) {  // the common case: direct 16-byte loads, the same bits
    const uint32_t w = s.tex->levelWidth(uint32_t(level)), h = s.tex->levelHeight(uint32_t(level));
    const uint8_t* base = s.tex->levels()[size_t(level)].data();
    for (int i = 0; i < N; ++i) {
      float v[4];
      std::memcpy(v, base + ((size_t(uint32_t(layer[i])) * h + uint32_t(y[i])) * w + uint32_t(x[i])) * 16, 16);
      r.x.set(i, v[0]);
      r.y.set(i, v[1]);
      r.z.set(i, v[2]);
      r.w.set(i, v[3]);
    }
    return r;
  }
  for (int i = 0; i < N; ++i) {
    emu::Texel4 t = emu::texelFetch(*s.tex, x[i], y[i], layer[i], level);
    r.x.set(i, t.r);
    r.y.set(i, t.g);
    r.z.set(i, t.b);
    r.w.set(i, t.a);
  }
  return r;
}

/// texture() with implicit LOD: the lanes are 2x2 quads in groups of four (top-left, top-right,
/// bottom-left, bottom-right), as a fragment stage runs them; each quad's LOD comes from its own
/// coordinates (emu::implicitLod, per the profile), then the N lanes sample as one device vector.
/// There is no scalar form: a lone pixel has no derivatives (using texture() in the scalar build is
/// a compile error).
template <int N>
V4<emu::F32<N>> textureImplicitLanes(const Sampler2D& s, emu::F32<N> u, emu::F32<N> v) {
  static_assert(N % 4 == 0, "texture() needs whole 2x2 quads of lanes");
  emu::F32<N> lod;
  for (int g = 0; g < N; g += 4) {
    const float su[4] = {u[g], u[g + 1], u[g + 2], u[g + 3]}, sv[4] = {v[g], v[g + 1], v[g + 2], v[g + 3]};
    const float l = emu::implicitLod(*s.tex, s.desc, *s.dev, su, sv);
    for (int i = g; i < g + 4; ++i) lod.set(i, l);
  }
  Sampler2D perQuad = s;
  perQuad.desc.lodPerQuad = true;
  return textureLodLanes(perQuad, u, v, lod);
}

}  // namespace shadetwin::shade
