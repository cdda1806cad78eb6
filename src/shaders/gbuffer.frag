#version 450
// G-buffer pass, fragment stage: thin entry point around shade/gbuffer.h (gbufferFragment).
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

struct ObjectGpu { mat4 model; mat4 normal; vec4 material; };
layout(std430, set = 0, binding = 0) readonly buffer Objects { ObjectGpu objects[]; };
layout(push_constant) uniform Push { uint object; } pc;
layout(location = 0) in vec3 vWorld;
layout(location = 1) in vec3 vNormal;
layout(location = 2) in vec4 vTangent;
layout(location = 3) in vec2 vUv;
layout(location = 0) out vec4 g0;
layout(location = 1) out vec4 g1;
layout(location = 2) out vec4 g2;
layout(location = 3) out vec4 g3;

void main() {
  GbufTexels t = gbufferFragment(vWorld, vNormal, vTangent, vUv, dFdx(vUv), dFdy(vUv), objects[pc.object].material.x);
  g0 = t.g0;
  g1 = t.g1;
  g2 = t.g2;
  g3 = t.g3;
}
