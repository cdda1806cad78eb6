#version 450
// Microkernels of `shadetwin calibrate` (issue 19): each runs `iters` iterations of 4 x 8 independent chain
// steps of one operation class per invocation (unrolled so the loop's own cost is small), so a device's throughput for that class is ops / time once the chains
// hide the latency. The operands come from the push constants and the invocation index, so nothing folds at
// compile time; every chain ends in the output, so nothing is dead. Not shared shading code: a thin
// measuring kernel of the host, like bench_native_math.glsl.
//   kind 0 fadd   x = x + c                       1 fadd per chain-iteration
//   kind 1 fmul   x = x * c                       1 fmul
//   kind 2 ialu   u = (u ^ (u >> 3)) + k          3 integer ALU (shift, xor, add)
//   kind 3 imul   u = u * k                       1 integer multiply
//   kind 4 cvt    x = float(int(x * c))           2 conversions + 1 fmul (c just above 1: |x| grows slowly)
//   kind 5 select x = mix(x + c, x - c, x > c)    1 compare + 1 select + 2 fadd (OpSelect)
//   kind 6 tex    textureLod at a moving (u, v): `filter` picked by the sampler the host binds; 1 lookup
//   kind 7 copy   dst = src * c over a large buffer, 16 vec4 per invocation (bandwidth)
//   kind 8 empty  nothing (launch cost)
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(std430, set = 0, binding = 1) readonly buffer Src { vec4 src[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Dst { vec4 dst[]; };
// The kind is a specialization constant: one pipeline per kind, the other kinds' code removed before the JIT
// (SwiftShader's Subzero takes minutes on the whole shader).
layout(constant_id = 0) const uint KIND = 0u;
layout(push_constant) uniform Push {
  uint kind, iters, count, pad;  // kind: the host's record of the pipeline (the shader reads KIND)
  float c, lod, step, pad2;
} pc;

// Eight named scalars per class (no arrays: a JIT without scalar replacement would measure memory).
#define ALL8(OP) OP(0) OP(1) OP(2) OP(3) OP(4) OP(5) OP(6) OP(7)
#define DECL_X(k) float x##k = float(i & 1023u) * 0.0009765625 + float(k) + 1.0;
#define DECL_U(k) uint u##k = i * 2654435761u + uint(k);
#define FADD(k) x##k = x##k + pc.c;
#define FMUL(k) x##k = x##k * pc.c;
#define IALU(k) u##k = (u##k ^ (u##k >> 3u)) + key;
#define IMUL(k) u##k = u##k * key;
#define CVT(k) x##k = float(int(x##k * pc.c));
#define SEL(k) x##k = mix(x##k + pc.c, x##k - pc.c, x##k > pc.c);  /* OpSelect, not a branch */
#define SUM_X(k) acc.x += x##k;
#define SUM_U(k) acc.y += float(u##k & 255u);
#define STEPS(OP) ALL8(OP) ALL8(OP) ALL8(OP) ALL8(OP)

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  ALL8(DECL_X)
  ALL8(DECL_U)
  uint key = floatBitsToUint(pc.c) | 1u;
  vec4 acc = vec4(0.0);
  if (KIND == 0u) {
    for (uint n = 0u; n < pc.iters; ++n) { STEPS(FADD) }
  } else if (KIND == 1u) {
    for (uint n = 0u; n < pc.iters; ++n) { STEPS(FMUL) }
  } else if (KIND == 2u) {
    for (uint n = 0u; n < pc.iters; ++n) { STEPS(IALU) }
  } else if (KIND == 3u) {
    for (uint n = 0u; n < pc.iters; ++n) { STEPS(IMUL) }
  } else if (KIND == 4u) {
    for (uint n = 0u; n < pc.iters; ++n) { STEPS(CVT) }
  } else if (KIND == 5u) {
    for (uint n = 0u; n < pc.iters; ++n) { STEPS(SEL) }
  } else if (KIND == 6u) {
    vec2 p = vec2(float(i & 255u), float((i >> 8u) & 255u)) * (1.0 / 256.0);
    for (uint n = 0u; n < pc.iters; ++n) {
      acc += textureLod(tex, p, pc.lod);
      p = fract(p + vec2(pc.step, pc.step * 0.5));
    }
  } else if (KIND == 7u) {  // 16 vec4 per invocation, each pass over the buffer contiguous across invocations
    for (uint r = 0u; r < 16u; ++r) dst[i + r * pc.count] = src[i + r * pc.count] * pc.c;
    return;
  } else {
    return;
  }
  ALL8(SUM_X)
  ALL8(SUM_U)
  dst[i] = acc;
}
