#version 450
// G-buffer pass, vertex stage: thin entry point around shade/gbuffer.h (gbufferVertex).
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(location = 0) in vec3 inPos;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;
struct ObjectGpu { mat4 model; mat4 normal; vec4 material; };  // passes/gbuffer.h ObjectGpu
layout(std430, set = 0, binding = 0) readonly buffer Objects { ObjectGpu objects[]; };
layout(std430, set = 0, binding = 1) readonly buffer Frame { mat4 viewProj; } frame;
layout(push_constant) uniform Push { uint object; } pc;
layout(location = 0) out vec3 vWorld;
layout(location = 1) out vec3 vNormal;
layout(location = 2) out vec4 vTangent;
layout(location = 3) out vec2 vUv;

void main() {
  mat4 m = objects[pc.object].model;
  mat4 n = objects[pc.object].normal;
  mat4 vp = frame.viewProj;
  GbufVertex v = gbufferVertex(m[0], m[1], m[2], m[3], n[0], n[1], n[2], vp[0], vp[1], vp[2], vp[3], inPos, inNormal,
                               inTangent, inUv);
  gl_Position = v.clip;
  vWorld = v.worldPos;
  vNormal = v.normal;
  vTangent = v.tangent;
  vUv = v.uv;
}
