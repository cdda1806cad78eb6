#version 450
// Shadow-map pass, vertex stage: thin entry point around shade/shadow.h (shadowVertex). Depth only.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(location = 0) in vec3 inPos;
struct ObjectGpu { mat4 model; mat4 normal; vec4 material; };  // passes/gbuffer.h ObjectGpu
layout(std430, set = 0, binding = 0) readonly buffer Objects { ObjectGpu objects[]; };
layout(push_constant) uniform Push { mat4 lightViewProj; uint object; } pc;

void main() {
  mat4 m = objects[pc.object].model;
  mat4 l = pc.lightViewProj;
  gl_Position = shadowVertex(m[0], m[1], m[2], m[3], l[0], l[1], l[2], l[3], inPos);
}
