#version 450
// One MIP level from the previous one (float4 texels in buffers, layer-major). Thin entry point
// around shade/mip.h: fetch the 3x3 footprint, filter rows, then the column.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(std430, set = 0, binding = 0) readonly buffer Src { vec4 src[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Dst { vec4 dst[]; };
layout(push_constant) uniform Push { int srcW; int srcH; int layers; } pc;
layout(local_size_x = 64) in;

vec4 srcTexel(int layer, int x, int y) {
  int cx = min(x, pc.srcW - 1);
  int cy = min(y, pc.srcH - 1);
  return src[(layer * pc.srcH + cy) * pc.srcW + cx];
}

void main() {
  int dstW = max(1, pc.srcW >> 1);
  int dstH = max(1, pc.srcH >> 1);
  int i = int(gl_GlobalInvocationID.x);
  if (i >= dstW * dstH * pc.layers) return;
  int x = i % dstW;
  int y = (i / dstW) % dstH;
  int layer = i / (dstW * dstH);
  MipTaps tx = mipTaps(x, pc.srcW);
  MipTaps ty = mipTaps(y, pc.srcH);
  vec4 r0 = mipCombine(srcTexel(layer, tx.i0, ty.i0), srcTexel(layer, tx.i0 + 1, ty.i0), srcTexel(layer, tx.i0 + 2, ty.i0), tx);
  vec4 r1 = mipCombine(srcTexel(layer, tx.i0, ty.i0 + 1), srcTexel(layer, tx.i0 + 1, ty.i0 + 1), srcTexel(layer, tx.i0 + 2, ty.i0 + 1), tx);
  vec4 r2 = mipCombine(srcTexel(layer, tx.i0, ty.i0 + 2), srcTexel(layer, tx.i0 + 1, ty.i0 + 2), srcTexel(layer, tx.i0 + 2, ty.i0 + 2), tx);
  dst[i] = mipCombine(r0, r1, r2, ty);
}
