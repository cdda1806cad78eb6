#version 450
// Deferred shading pass, technique glints (issue 17): thin entry point around shade/shade_glints.h.
// One invocation per pixel, local size 64.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D env;
struct GbufFis { vec4 g0; vec4 g1; vec4 g2; vec4 g3; };  // passes/shade_vk.cpp
layout(std430, set = 0, binding = 1) readonly buffer Gbuf { GbufFis gbuf[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Out { vec4 color[]; };
layout(std430, set = 0, binding = 4) readonly buffer Settings { GlintSettings gs; } st;  // passes/shade.h GlintUniforms
layout(set = 0, binding = 5) uniform usampler2DArray sat;  // inputs/glints.h: NDF histogram SATs
layout(set = 0, binding = 6) uniform sampler2D binDirs;
layout(set = 0, binding = 7) uniform sampler2D mats;
layout(set = 0, binding = 8) uniform sampler2D lighting;
layout(set = 0, binding = 9) uniform sampler2D coef;
layout(set = 0, binding = 10) uniform sampler2D lobes;  // the rotated-lobe table (1 x 1 when unused)
layout(push_constant) uniform Push {
  vec4 eye, fwd, right, down;
  float invW, invH, maxLod, intensity;
  uint width, count, materialCount, pad;
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint p = min(i, pc.count - 1u);
  GbufFis g = gbuf[p];
  vec3 ray = cameraRay(pc.fwd.xyz, pc.right.xyz, pc.down.xyz, float(p % pc.width), float(p / pc.width), pc.invW, pc.invH);
  int row = int(materialSlot(g.g0.w, pc.materialCount));
  vec4 c = shadeGlints(sat, binDirs, mats, lighting, coef, lobes, env, st.gs, pc.intensity, g.g0, g.g1, g.g2, g.g3, pc.eye.xyz, ray, row);
  if (i < pc.count) color[i] = c;
}
