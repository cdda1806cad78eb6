#version 450
// `shadetwin calibrate`'s exact-math kernels (issue 19): the shared exDiv and exSqrt (shade/exact_math.h, the routines
// every shading module inlines) in chains, so a device's rate for one correctly rounded division or square root is
// measured on the code it runs (the model's ex_div and ex_sqrt classes, model/device_desc.h). Optimised like the
// shading modules (add_shader: spirv-opt -O, every float op NoContraction). Operands come from the push constants and
// the invocation index, so nothing folds; every chain ends in the output. Not shared shading code: a thin measuring
// kernel of the host, in calibrate.comp's layout and push constants.
//   KIND 0 ex_div   x = exDiv(y, x), y = exDiv(x, y): both operands vary (with a uniform numerator the compiler
//                   hoists its unpacking out of the loop: a third of the routine), and (x, y) returns to itself every
//                   third pair of steps (y/x, 1/x; 1/y, x/y; x, y), so the values stay normal
//   KIND 1 ex_sqrt  x = exSqrt(x) + c  x stays in [1, 3) (c = 0.25: the fixed point of sqrt(x) + c is ~1.6)
// Each iteration runs 16 steps: 8 independent chains of 2 (the issue rate) or, DEPENDENT, one chain of 16 (the
// latency). The kernels exist in the module as the shading code has them: inlined, straight-line.
// FIXED_UNROLL (1, 2, 4, 8 or 16; the independent division kernel only): the iteration's 16 steps written out that many times,
// the same work per step in a module that many times the size, so calibrate reads what a larger module costs the device
// per operation (the model's code-size term, model/device_desc.h codeWords, codeSlowdown).
#extension GL_GOOGLE_include_directive : require
#include "shade/prelude.h"
#include "shade/exact_math.h"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(std430, set = 0, binding = 1) readonly buffer Src { vec4 src[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Dst { vec4 dst[]; };
// One module per kind and chain layout (CMakeLists.txt: FIXED_KIND, FIXED_DEPENDENT), as calibrate.comp's. constant_id
// 0 is the prelude's kSceneBrdfKinds (unused here): the host passes ~0u.
const uint KIND = FIXED_KIND;
const bool DEPENDENT = FIXED_DEPENDENT;
layout(push_constant) uniform Push { uint kind, iters, count, pad; float c, lod, step, pad2; } pc;

#define ALL8(OP) OP(0) OP(1) OP(2) OP(3) OP(4) OP(5) OP(6) OP(7)
#define ONE8(OP) OP(0) OP(0) OP(0) OP(0) OP(0) OP(0) OP(0) OP(0)
#define DECL_X(k) float x##k = float(i & 1023u) * 0.0009765625 + float(k) * 0.125 + 1.0; float y##k = x##k * pc.c + 0.5;
#define DIV2(k) x##k = exDiv(y##k, x##k); y##k = exDiv(x##k, y##k);
#define SQRT2(k) x##k = exSqrt(x##k) + pc.c; x##k = exSqrt(x##k) + pc.c;
#define SUM_X(k) acc += x##k + y##k;
#ifndef FIXED_UNROLL
#define FIXED_UNROLL 1
#endif
#if FIXED_UNROLL == 1
#define BODY(X) X
#elif FIXED_UNROLL == 2
#define BODY(X) X X
#elif FIXED_UNROLL == 4
#define BODY(X) X X X X
#elif FIXED_UNROLL == 8
#define BODY(X) X X X X X X X X
#elif FIXED_UNROLL == 16
#define BODY(X) X X X X X X X X X X X X X X X X
#else
#error FIXED_UNROLL must be 1, 2, 4, 8 or 16
#endif
// Two steps of chain k per STEP2(k): of all eight chains (8 independent chains) or of chain 0 eight times (one chain).
#define LOOP(STEP2)                                                            \
  if (DEPENDENT) {                                                             \
    for (uint n = 0u; n < pc.iters; ++n) { ONE8(STEP2) }                       \
  } else {                                                                     \
    for (uint n = 0u; n < pc.iters; ++n) { BODY(ALL8(STEP2)) }                 \
  }

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  ALL8(DECL_X)
  if (KIND == 0u) {
    LOOP(DIV2)
  } else {
    LOOP(SQRT2)
  }
  float acc = 0.0;
  ALL8(SUM_X)
  dst[i] = vec4(acc);
}
