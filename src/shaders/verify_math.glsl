#version 450
// Entry point of `shadetwin verify math`: evaluates the shared kernel evalMath (src/shade/) on one
// input per invocation. Built twice: -DSTAGE_COMPUTE and -DSTAGE_FRAGMENT (full-screen triangle).
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(std430, set = 0, binding = 0) readonly buffer Inputs { float inputs[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Outputs { float outputs[]; };
layout(push_constant) uniform Push { int fn; uint count; uint width; } pc;

void run(uint i) {
  if (i >= pc.count) return;
#ifdef FIXED_FN  // benchmarks: one function per module, so the compiler drops the others
  const int fn = FIXED_FN;
#else
  int fn = pc.fn;
#endif
  vec3 r = evalMath(fn, vec3(inputs[3 * i], inputs[3 * i + 1], inputs[3 * i + 2]));
  outputs[3 * i] = r.x;
  outputs[3 * i + 1] = r.y;
  outputs[3 * i + 2] = r.z;
}

#ifdef STAGE_COMPUTE
layout(local_size_x = 64) in;
void main() { run(gl_GlobalInvocationID.x); }
#else
layout(location = 0) out vec4 color;
void main() {
  run(uint(gl_FragCoord.y) * pc.width + uint(gl_FragCoord.x));
  color = vec4(0.0);
}
#endif
