#version 450
// `shadetwin calibrate`'s loop-state kernels (issue 19; the model's loop-state term, model/device_desc.h
// loopStateValues, loopStateSeconds; model/spirv_loops.h): every iteration does the same 128 multiply-adds
// a = a + x * c_j (an fmul and an fadd, 128 distinct constants c_j) into FIXED_CARRIED accumulators, 8 (16 each an
// iteration) or 64 (2 each), x moving by pc.step, so the two modules differ only in how many values the loop carries
// from one iteration to the next (the accumulators, x and the counter: 10 and 66 OpPhi components). Even the 8-value
// kernel's 16-step chains leave the issue rate, not the latency, bounding it (8 chains in flight). Optimised like the
// shading modules (add_shader: spirv-opt -O, every float op NoContraction); operands from the push constants and the
// invocation index, every accumulator ends in the output. Not shared shading code: a thin measuring kernel of the host,
// in calibrate.comp's layout and push constants.
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(std430, set = 0, binding = 1) readonly buffer Src { vec4 src[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Dst { vec4 dst[]; };
layout(push_constant) uniform Push { uint kind, iters, count, pad; float c, lod, step, pad2; } pc;

// Accumulator a<b><d> is number 8 b + d; step (b, d, r) multiplies by its own constant.
#define DIGITS(OP, b, r) OP(b, 0, r) OP(b, 1, r) OP(b, 2, r) OP(b, 3, r) OP(b, 4, r) OP(b, 5, r) OP(b, 6, r) OP(b, 7, r)
#define DECL(b, d, r) float a##b##d = float(i & 7u) + float(8 * b + d);
#define STEP(b, d, r) a##b##d = a##b##d + x * (1.0 + float(8 * b + d + 64 * r) * 1.0e-4);
#define SUM(b, d, r) acc += a##b##d;
#if FIXED_CARRIED == 8
#define BANKS(OP, r) DIGITS(OP, 0, r)
#define ITERATION BANKS(STEP, 0) BANKS(STEP, 1) BANKS(STEP, 2) BANKS(STEP, 3) BANKS(STEP, 4) BANKS(STEP, 5) \
  BANKS(STEP, 6) BANKS(STEP, 7) BANKS(STEP, 8) BANKS(STEP, 9) BANKS(STEP, 10) BANKS(STEP, 11) BANKS(STEP, 12) \
  BANKS(STEP, 13) BANKS(STEP, 14) BANKS(STEP, 15)
#elif FIXED_CARRIED == 64
#define BANKS(OP, r) DIGITS(OP, 0, r) DIGITS(OP, 1, r) DIGITS(OP, 2, r) DIGITS(OP, 3, r) DIGITS(OP, 4, r) \
  DIGITS(OP, 5, r) DIGITS(OP, 6, r) DIGITS(OP, 7, r)
#define ITERATION BANKS(STEP, 0) BANKS(STEP, 1)
#else
#error FIXED_CARRIED must be 8 or 64
#endif

void main() {
  uint i = gl_GlobalInvocationID.x;
  float x = float(i & 1023u) * 0.0009765625;
  BANKS(DECL, 0)
  for (uint n = 0u; n < pc.iters; ++n) {
    x = x + pc.step;
    ITERATION
  }
  float acc = 0.0;
  BANKS(SUM, 0)
  dst[i] = vec4(acc, x, 0.0, 0.0);
}
