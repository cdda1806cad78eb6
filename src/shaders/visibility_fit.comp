#version 450
// SH visibility fit (shade/visibility.h visFit), compute stage: one invocation per G-buffer pixel,
// local size 64; writes the pixel's 16 coefficients (4 vec4). Tail invocations fit the last pixel
// again and store nothing, as the emulator's tail lanes (passes/visibility_emu.cpp).
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
struct GbufPos { vec4 g0; vec4 g1; };  // passes/visibility_vk.cpp: position, normal
layout(std430, set = 0, binding = 0) readonly buffer Gbuf { GbufPos gbuf[]; };
layout(set = 0, binding = 1) uniform sampler2DArray maps;  // R32F, layer k = map k
layout(set = 0, binding = 2) uniform sampler2D data;       // RGBA32F 9 x K (inputs/visibility.h)
layout(std430, set = 0, binding = 3) writeonly buffer Out { vec4 coeffs[]; };
layout(push_constant) uniform Push {
  uint count, size, fit, pixels;
  float biasConst, biasSlope;
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint p = min(i, pc.pixels - 1u);
  VisSettings s = VisSettings(pc.count, pc.size, pc.fit, pc.biasConst, pc.biasSlope);
  Sh16 c = visFit(maps, data, s, gbuf[p].g0.xyz, gbuf[p].g1.xyz);
  if (i < pc.pixels) {
    coeffs[4u * i + 0u] = c.a;
    coeffs[4u * i + 1u] = c.b;
    coeffs[4u * i + 2u] = c.c;
    coeffs[4u * i + 3u] = c.d;
  }
}
