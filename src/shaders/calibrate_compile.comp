#version 450
// `shadetwin calibrate`'s compile-cost kernel (issue 19): a pipeline's first dispatch beyond a warm one grows with the
// module the driver compiles then (lavapipe JITs a compute shader's machine code at its first dispatch: 0.3 ms more
// for the 0.4K-word calibrate_group.comp, 0.6 ms for the 6K-word mip_downsample module, 1.0 ms for the 12K-word
// paraboloid module; probes, docs/RESULTS.md session 31). This module is straight-line code of the classes the shared
// code runs (float add and multiply, integer ALU and shifts, conversions, compares and selects, buffer reads and
// texelFetch), with no specialization constants, so its SPIR-V size is what the driver compiles (optimised like the
// shipped modules: add_shader); against calibrate_group.comp it gives the cost per SPIR-V word. Not shared shading
// code: a thin measuring kernel of the host.
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D tex;  // calibrate.comp's layout
layout(std430, set = 0, binding = 1) readonly buffer Src { vec4 src[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Dst { vec4 dst[]; };
layout(push_constant) uniform Push { uint kind, iters, count, pad; float c, lod, step, pad2; } pc;

// One step: every value depends on the previous step's, so nothing folds or dies; a buffer read per step and a
// texelFetch per 16, as the shared code reads its inputs (the sampling code a driver generates is much of its size).
#define STEP                                       \
  x = x * pc.c + src[u & 255u].x;                  \
  u = (u ^ floatBitsToUint(x)) + (u >> 3u);        \
  y = float(int(u & 1023u)) * pc.step - x;         \
  x = x > y ? x - pc.c : y + pc.c;                 \
  u = u < key ? u + key : u ^ key;
#define STEP4 STEP STEP STEP STEP
#define STEP16 STEP4 STEP4 STEP4 STEP4 y = y + texelFetch(tex, ivec2(u & 15u, 0), 0).x;
#define STEP64 STEP16 STEP16 STEP16 STEP16

void main() {
  uint i = gl_GlobalInvocationID.x;
  float x = float(i) * pc.c, y = pc.lod;
  uint u = i * 2654435761u, key = pc.iters;
  STEP64
  if (i < pc.count) dst[i] = vec4(x, y, float(u), 0.0);
}
