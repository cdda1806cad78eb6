#version 450
// Spatial filter of the SH visibility coefficients (shade/visibility.h visFilter), compute stage: one
// invocation per pixel, local size 64; tail invocations filter the last pixel again and store nothing,
// as the emulator's tail lanes (passes/visibility_emu.cpp).
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2DArray coeffs;  // layer j: coefficients 4j..4j+3
layout(set = 0, binding = 1) uniform sampler2DArray gbuf;    // layer 0: G0, layer 1: G1
layout(std430, set = 0, binding = 2) writeonly buffer Out { vec4 filtered[]; };
layout(push_constant) uniform Push {
  int width, height, radius;
  uint mode, pixels;
  float planeTolerance;
} pc;  // passes/visibility_vk.cpp

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint p = min(i, pc.pixels - 1u);
  Sh16 c = visFilter(coeffs, gbuf, int(p % uint(pc.width)), int(p / uint(pc.width)), pc.width, pc.height, pc.radius, pc.mode,
                     pc.planeTolerance);
  if (i < pc.pixels) {
    filtered[4u * i + 0u] = c.a;
    filtered[4u * i + 1u] = c.b;
    filtered[4u * i + 2u] = c.c;
    filtered[4u * i + 3u] = c.d;
  }
}
