#version 450
// Resampling of the equirectangular environment into the dual-paraboloid atlas (2S x S), compute
// stage: thin entry point around shade/paraboloid.h (paraboloidResample). One invocation per atlas
// texel, row-major, local size 64 (8 consecutive invocations per lavapipe SIMD vector, as the
// emulator groups its lanes).
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D env;
layout(std430, set = 0, binding = 1) writeonly buffer Out { vec4 texels[]; };
layout(push_constant) uniform Push { float envW; float envH; int faceSize; uint count; } pc;  // inputs/paraboloid.cpp

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint p = min(i, pc.count - 1u);
  uint w = uint(2 * pc.faceSize);
  vec4 c = paraboloidResample(env, pc.envW, pc.envH, int(p % w), int(p / w), pc.faceSize);
  if (i < pc.count) texels[i] = c;
}
