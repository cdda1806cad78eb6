#version 450
// Deferred shading pass (technique "mirror"), compute stage: thin entry point around
// shade/shade_mirror.h. One invocation per pixel, row-major, local size 64 (lavapipe runs 8
// consecutive invocations per SIMD vector: the emulator's SIMD build groups pixels the same way).
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D env;
struct GbufPair { vec4 g0; vec4 g1; };                 // passes/passes_vk ShadeGbufGpu
layout(std430, set = 0, binding = 1) readonly buffer Gbuf { GbufPair gbuf[]; };
struct MaterialGpu { vec4 diffuse; vec4 specular; };  // passes/passes_vk MaterialGpu
layout(std430, set = 0, binding = 2) readonly buffer Materials { MaterialGpu materials[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Out { vec4 color[]; };
layout(push_constant) uniform Push {
  vec4 eye, fwd, right, down;
  float invW, invH, envMaxLod, intensity;
  uint width, count, materialCount, pad;
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint p = min(i, pc.count - 1u);  // the tail of the last vector shades the last pixel again, as the emulator
  vec4 g0 = gbuf[p].g0;
  vec4 g1 = gbuf[p].g1;
  MaterialGpu m = materials[materialSlot(g0.w, pc.materialCount)];
  vec3 ray = cameraRay(pc.fwd.xyz, pc.right.xyz, pc.down.xyz, float(p % pc.width), float(p / pc.width), pc.invW, pc.invH);
  vec4 c = shadeMirror(env, pc.envMaxLod, pc.intensity, g0, g1, pc.eye.xyz, ray, m.diffuse.xyz, m.specular.xyz);
  if (i < pc.count) color[i] = c;
}
