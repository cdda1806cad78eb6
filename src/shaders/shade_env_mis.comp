#version 450
// Deferred shading pass (techniques kdtree-mis, alias-mis, inversion-mis: environment and BRDF
// samples combined by MIS), compute stage: thin entry point around shade/shade_env_mis.h. One
// invocation per pixel, local size 64.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D env;
struct GbufFis { vec4 g0; vec4 g1; vec4 g2; vec4 g3; };  // passes/shade_vk.cpp
layout(std430, set = 0, binding = 1) readonly buffer Gbuf { GbufFis gbuf[]; };
struct MaterialGpu { vec4 diffuse; vec4 specular; vec4 brdf; uvec4 kind; vec4 lobe0; vec4 lobe1; vec4 rho; uvec4 maps; };  // inputs/material.h
layout(std430, set = 0, binding = 2) readonly buffer Materials { MaterialGpu materials[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Out { vec4 color[]; };
// passes/shade_vk.cpp MisSettingsGpu: the shared structs themselves (std430, 32 + 16 bytes), then the
// SH visibility mode (x) and, with visibility, each pixel's 16 fit coefficients (4 vec4 per pixel).
layout(std430, set = 0, binding = 4) readonly buffer Settings { EnvSampling es; MisSettings ms; uvec4 visMode; vec4 vis[]; } st;
layout(set = 0, binding = 5) uniform sampler2DArray maps;  // inputs/material.h
layout(set = 0, binding = 6) uniform sampler2D table;      // inputs/env_sampling.h
layout(set = 0, binding = 7) uniform sampler2D texels;
layout(push_constant) uniform Push {
  vec4 eye, fwd, right, down;
  float invW, invH, maxLod, intensity;
  uint width, count, materialCount, pad;
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint p = min(i, pc.count - 1u);
  GbufFis g = gbuf[p];
  MaterialGpu r = materials[materialSlot(g.g0.w, pc.materialCount)];
  SurfaceMaterial m = surfaceMaterial(maps, r.diffuse.xyz, r.specular.xyz, brdfParamsPacked(r.kind.x, r.brdf, r.lobe0, r.lobe1, r.rho),
                                      r.maps.x, r.maps.y, r.maps.z, g.g1, g.g2, g.g3);
  vec3 ray = cameraRay(pc.fwd.xyz, pc.right.xyz, pc.down.xyz, float(p % pc.width), float(p / pc.width), pc.invW, pc.invH);
  Sh16 vis = Sh16(vec4(0.0f), vec4(0.0f), vec4(0.0f), vec4(0.0f));
  if (st.visMode.x != kFisVisNone) vis = Sh16(st.vis[4u * p], st.vis[4u * p + 1u], st.vis[4u * p + 2u], st.vis[4u * p + 3u]);
  vec4 c = shadeEnvMis(env, table, texels, st.es, st.ms, pc.intensity, p, g.g0, g.g1, g.g2, pc.eye.xyz, ray, m.diffuse, m.specular, m.brdf,
                       st.visMode.x, vis);
  if (i < pc.count) color[i] = c;
}
