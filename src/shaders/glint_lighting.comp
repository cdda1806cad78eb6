#version 450
// The glints lighting table (shade/glint_lighting.h glintLightingColumn), compute stage: invocation
// i = m views + view computes column m of one view (local size 64; m-major, so a vector of
// invocations shares m, as the emulator's lanes do). Writes the column's 6 (order + 1) floats
// (l = m .. order used); tail invocations compute the last one again and store nothing.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D env;   // RGBA32F with its MIP chain
layout(set = 0, binding = 1) uniform sampler2D dirs;  // RGBA32F: direction, solid angle per texel of the level
layout(set = 0, binding = 2) uniform sampler2D coef;  // RGBA32F: Legendre recurrence coefficients
layout(std430, set = 0, binding = 3) readonly buffer Views { vec4 views[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Out { float cols[]; };
layout(push_constant) uniform Push { int envW, y0, y1, level, order; uint views, count; } pc;  // inputs/glint_lighting.cpp

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint j = min(i, pc.count - 1u);
  int m = int(j / pc.views);
  GlintColumn c = glintLightingColumn(env, dirs, coef, pc.envW, pc.y0, pc.y1, pc.level, pc.order, m, views[j % pc.views].xyz);
  uint stride = uint(6 * (pc.order + 1));
  if (i < pc.count)
    for (int k = 0; k < 6 * (pc.order + 1); ++k) cols[i * stride + uint(k)] = c.c[k];
}
