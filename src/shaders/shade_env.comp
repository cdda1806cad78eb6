#version 450
// Deferred shading pass (technique "env": environment importance sampling as directional lights),
// compute stage: thin entry point around shade/shade_env.h; the light loop in the order of
// passes/shade_emu.cpp (light 0 first, one envAddLight each). One invocation per pixel, local size 64.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D env;
struct GbufFis { vec4 g0; vec4 g1; vec4 g2; vec4 g3; };  // passes/shade_vk.cpp
layout(std430, set = 0, binding = 1) readonly buffer Gbuf { GbufFis gbuf[]; };
struct MaterialGpu { vec4 diffuse; vec4 specular; vec4 brdf; uvec4 kind; vec4 lobe0; vec4 lobe1; vec4 rho; uvec4 maps; };  // inputs/material.h
layout(std430, set = 0, binding = 2) readonly buffer Materials { MaterialGpu materials[]; };
layout(set = 0, binding = 5) uniform sampler2DArray maps;  // inputs/material.h
layout(std430, set = 0, binding = 3) writeonly buffer Out { vec4 color[]; };
struct EnvLight { vec4 dir; vec4 weight; };  // inputs/env_lights.h
layout(std430, set = 0, binding = 4) readonly buffer Lights { EnvLight lights[]; };
layout(push_constant) uniform Push {
  vec4 eye, fwd, right, down;
  float invW, invH, maxLod, intensity;
  uint width, count, materialCount, lightCount;
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint p = min(i, pc.count - 1u);
  GbufFis g = gbuf[p];
  MaterialGpu r = materials[materialSlot(g.g0.w, pc.materialCount)];
  SurfaceMaterial m = surfaceMaterial(maps, r.diffuse.xyz, r.specular.xyz, brdfParamsPacked(r.kind.x, r.brdf, r.lobe0, r.lobe1, r.rho),
                                      r.maps.x, r.maps.y, r.maps.z, g.g1, g.g2, g.g3);
  vec3 ray = cameraRay(pc.fwd.xyz, pc.right.xyz, pc.down.xyz, float(p % pc.width), float(p / pc.width), pc.invW, pc.invH);
  vec3 sum = vec3(0.0f);
  if (g.g0.w != 0.0f) {
    FisFrame F = envFrame(g.g0, g.g1, g.g2, pc.eye.xyz);
    for (uint j = 0u; j < pc.lightCount; j++)
      sum = envAddLight(sum, F, m.brdf, m.diffuse, m.specular, lights[j].dir.xyz, lights[j].weight.xyz);
  }
  vec4 c = envFinish(env, g.g0, ray, sum, pc.intensity);
  if (i < pc.count) color[i] = c;
}
