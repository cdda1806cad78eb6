#version 450
// Deferred shading pass (technique "fis"), compute stage: thin entry point around shade/shade_fis.h.
// One invocation per pixel, row-major, local size 64; tail invocations re-shade the last pixel (the
// emulator's tail lanes do the same, so the 8-invocation vectors hold the same pixels).
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D atlas;
struct GbufFis { vec4 g0; vec4 g1; vec4 g2; vec4 g3; };  // passes/shade_vk.cpp
layout(std430, set = 0, binding = 1) readonly buffer Gbuf { GbufFis gbuf[]; };
struct MaterialGpu { vec4 diffuse; vec4 specular; vec4 brdf; uvec4 kind; vec4 lobe0; vec4 lobe1; vec4 rho; uvec4 maps; };  // inputs/material.h
layout(std430, set = 0, binding = 2) readonly buffer Materials { MaterialGpu materials[]; };
layout(set = 0, binding = 5) uniform sampler2DArray maps;  // inputs/material.h
layout(set = 0, binding = 6) uniform sampler2D env;  // the equirectangular map: the background (kFisBackgroundEnvironment)
layout(std430, set = 0, binding = 3) writeonly buffer Out { vec4 color[]; };
// E/pi coefficients (0-8, inputs/sh_irradiance.cpp); with visibility also the raw lighting SH (9-20:
// r, g, b, 4 vec4 each, inputs/visibility.h) and each pixel's 16 fit coefficients (21 + 4 p ...).
layout(std430, set = 0, binding = 4) readonly buffer Sh { vec4 sh[]; };
layout(push_constant) uniform Push {
  vec4 eye, fwd, right, down;
  float invW, invH, maxLod, intensity;
  uint width, count, materialCount, sampleCount;
  float levelConstant, levelBias; uint mode, visMode;
  uint background;
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint p = min(i, pc.count - 1u);
  GbufFis g = gbuf[p];
  MaterialGpu r = materials[materialSlot(g.g0.w, pc.materialCount)];
  SurfaceMaterial m = surfaceMaterial(maps, r.diffuse.xyz, r.specular.xyz, brdfParamsPacked(r.kind.x, r.brdf, r.lobe0, r.lobe1, r.rho),
                                      r.maps.x, r.maps.y, r.maps.z, g.g1, g.g2, g.g3);
  vec3 ray = cameraRay(pc.fwd.xyz, pc.right.xyz, pc.down.xyz, float(p % pc.width), float(p / pc.width), pc.invW, pc.invH);
  ShRgb e = ShRgb(sh[0].xyz, sh[1].xyz, sh[2].xyz, sh[3].xyz, sh[4].xyz, sh[5].xyz, sh[6].xyz, sh[7].xyz, sh[8].xyz);
  Sh16 vis = Sh16(vec4(0.0f), vec4(0.0f), vec4(0.0f), vec4(0.0f));
  VisLighting vl = VisLighting(vis, vis, vis);
  if (pc.visMode != kFisVisNone) {
    uint o = 21u + 4u * p;
    vis = Sh16(sh[o], sh[o + 1u], sh[o + 2u], sh[o + 3u]);
    vl = VisLighting(Sh16(sh[9], sh[10], sh[11], sh[12]), Sh16(sh[13], sh[14], sh[15], sh[16]), Sh16(sh[17], sh[18], sh[19], sh[20]));
  }
  vec4 c = shadeFis(atlas, env, pc.background, pc.mode, pc.maxLod, pc.levelConstant, pc.levelBias, pc.sampleCount, pc.intensity, e, p, g.g0, g.g1, g.g2,
                    pc.eye.xyz, ray, m.diffuse, m.specular, m.brdf, pc.visMode, vis, vl);
  if (i < pc.count) color[i] = c;
}
