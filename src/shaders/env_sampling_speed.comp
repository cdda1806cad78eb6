#version 450
// Throughput of the environment samplers (shadetwin sweep, issue 5 item 5): each invocation draws
// `perInvocation` directions with shade/env_sampling.h's sampleEnv and looks up envPdf of each (what
// one MIS sample pair needs from the sampler); the sum is written so nothing is optimized away.
// Thin entry point: the C++ side (inputs/env_sampling_speed.cpp) runs the same loop.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D table;  // inputs/env_sampling.h
layout(set = 0, binding = 1) uniform sampler2D texels;
layout(std430, set = 0, binding = 2) readonly buffer Settings { EnvSampling es; } st;  // EnvSamplingUniforms
layout(std430, set = 0, binding = 3) writeonly buffer Out { float sums[]; };
layout(push_constant) uniform Push { uint count, perInvocation, seed, pad; } pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  float s = envSamplingChecksum(table, texels, st.es, i, pc.perInvocation, pc.seed);
  if (i < pc.count) sums[i] = s;
}
