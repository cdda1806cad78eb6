#version 450
// SH irradiance, step 1 (shade/sh_irradiance.h shProjectRow): one invocation per row of the
// equirectangular environment, local size 64; writes the row's 16 RGB coefficients (vec4, w = 0):
// bands 0-2, then band 3.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D env;
layout(std430, set = 0, binding = 1) writeonly buffer Rows { vec4 rows[]; };  // 16 per row
layout(push_constant) uniform Push { int width; int height; } pc;  // inputs/sh_irradiance.cpp

void main() {
  int y = min(int(gl_GlobalInvocationID.x), pc.height - 1);  // tail invocations repeat the last row
  ShRow r = shProjectRow(env, y, pc.width, pc.height);
  ShRgb s = r.low;
  ShBand3 h = r.high;
  if (int(gl_GlobalInvocationID.x) < pc.height) {
    uint o = uint(y) * 16u;
    rows[o + 0u] = vec4(s.c0, 0.0f);
    rows[o + 1u] = vec4(s.c1, 0.0f);
    rows[o + 2u] = vec4(s.c2, 0.0f);
    rows[o + 3u] = vec4(s.c3, 0.0f);
    rows[o + 4u] = vec4(s.c4, 0.0f);
    rows[o + 5u] = vec4(s.c5, 0.0f);
    rows[o + 6u] = vec4(s.c6, 0.0f);
    rows[o + 7u] = vec4(s.c7, 0.0f);
    rows[o + 8u] = vec4(s.c8, 0.0f);
    rows[o + 9u] = vec4(h.c9, 0.0f);
    rows[o + 10u] = vec4(h.c10, 0.0f);
    rows[o + 11u] = vec4(h.c11, 0.0f);
    rows[o + 12u] = vec4(h.c12, 0.0f);
    rows[o + 13u] = vec4(h.c13, 0.0f);
    rows[o + 14u] = vec4(h.c14, 0.0f);
    rows[o + 15u] = vec4(h.c15, 0.0f);
  }
}
