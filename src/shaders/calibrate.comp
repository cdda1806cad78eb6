#version 450
// Microkernels of `shadetwin calibrate` (issue 19): each runs `iters` iterations of 16 x 8 independent chain
// steps of one operation class per invocation, so a device's throughput for that class is ops / time once the chains
// hide the latency. Unrolled 128 steps deep so the loop's own cost is small: SwiftShader carries each chain from one
// iteration to the next through memory (a phi), and at 32 steps per iteration (4 per chain) that read fadd at 22 Gop/s
// where straight-line code runs 47-57 (probes of 1024-65536 steps, docs/RESULTS.md session 22). The operands come
// from the push constants and the invocation index, so nothing folds at compile time; every chain ends in the output,
// so nothing is dead. Not shared shading code: a thin
// measuring kernel of the host, like bench_native_math.glsl.
//   kind 0 fadd   x = x + c                       1 fadd per chain-iteration
//   kind 1 fmul   x = x * c                       1 fmul
//   kind 2 ialu   u = (u ^ k) + k                 2 integer ALU (xor, add)
//   kind 3 imul   u = u * u                       1 integer multiply
//   kind 4 cvt    x = float(int(x * c))           2 conversions + 1 fmul (c just above 1: |x| grows slowly)
//   kind 5 select x = mix(x + c, x - c, x > c)    1 compare + 1 select + 2 fadd (OpSelect)
//   kind 6 tex    textureLod at a moving (u, v): `filter` picked by the sampler the host binds; 1 lookup
//   kind 7 copy   dst = src * c over a large buffer, `iters` passes of 16 vec4 per invocation (bandwidth)
//   kind 8 empty  nothing (launch cost)
//   kind 9 window iterations that are independent of each other, each a chain of 64 dependent fadds: how much of the
//                 next chain the core overlaps with this one (its reorder window, in these operations)
//   kind 10 branch the fadd kernel's steps inside an `if` on a per-lane value no lane takes (x0 < lod, lod = -1): about
//                 the fadd kernel's time when the device runs every block under a mask, about nothing when it skips
//   kind 11 branch the same, the `if` around the whole loop: a loop whose lanes are all inactive may exit at once
//   kind 12 branch kind 10 with the block's steps in a loop of a literal 16 iterations (a compiler may unroll it)
//   kind 15 stream texelFetch along the rows: invocation i reads texels i*iters .. (i+1)*iters - 1 of the texture in
//                 row-major order (a prefetcher's streams; against a cache-resident texture: a streamed line's cost)
//   kind 16 shift  u = u + (u >> 3)               1 shift + 1 integer add (SwiftShader's Subzero scalarizes vector
//                 shifts: a shift costs it ~6 fadds, an add or xor less than one; lavapipe shifts at the add rate)
//   kind 17 icmp   u = mix(u + k, u ^ k, u < k)   1 integer compare + 1 integer select + 2 integer ALU (add, xor)
//   kind 18 iselect u = mix(u + k, u ^ k, x < c), x = x + c   1 fcmp + 1 integer select + 2 integer ALU + 1 fadd
//                 (the shared code's integer selects and compares: exact-math rounding, min/max, masks)
//   kind 19 private read   x_k = x_k + a[i]: a local array of 256 floats read at 32 indices an iteration (the loop
//                 counter's, not literals: (32 n + j) & 255), 1 private read + 1 fadd
//   kind 20 private write  a[i] = a[i] + c at the same indices: 1 private read + 1 fadd + 1 private write (the glints
//                 kernels' accumulation, shade/glint_lighting.h)
//   kind 23 shared blocks  each iteration: a = (((x + c) + c) + c) + c under one mask (x0 < lod), b the same
//                 expression under the complementary one, x = (a + b) * 0.5: the second block repeats the first's 32
//                 fadds on the same operands, which a compiler that numbers values across the blocks it flattened
//                 computes once. Each block's sums are one expression whose partial sums are temporaries, as the
//                 shared source's functions are (a variable written step by step would be a register that gallivm
//                 writes under the mask at every step: no two steps of the blocks would then be the same value).
//   kind 24 distinct blocks  the same with step in place of c in b (pc.step: not the same expression): both run
//   kind 25 re-read  16 vec4 loads an iteration of a 64-entry storage-buffer table (src's first 64 elements, cache
//                 resident) at indices every lane shares (the iteration's base + 0..15), summed pairwise (16 vec4
//                 fadds): the entry points' re-reads of a table row (a material record, the SH lighting, env's lights
//                 in its loop), which a software device loads one lane at a time where a GPU's cache serves them
//   kind 26 fetch  texelFetch at kind 6's moving coordinates (the texel its nearest lookup reads, at integer
//                 coordinates: no sampler scaling, wrapping or level selection); 1 fetch
// DEPENDENT runs kinds 0-5 and 16-18 on one chain: time per step is the latency, not the issue rate.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_integer_mix : require

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(std430, set = 0, binding = 1) readonly buffer Src { vec4 src[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Dst { vec4 dst[]; };
// The kind is fixed when the module is built (FIXED_KIND; CMakeLists.txt builds one module per kind, the other kinds'
// branches removed by spirv-opt): a driver that does not fold specialization constants (SwiftShader) ran every other
// kind's code under a false mask in each dispatch of the one module there was (docs/RESULTS.md, session 41).
const uint KIND = FIXED_KIND;
// DEPENDENT: the 32 steps of an iteration run on one chain (each step waits for the previous one), so time per
// step is the class's latency rather than its issue rate (the latency kernels of the model's scheduler). Fixed in the
// module too, except for kind 13, whose block behind a false specialization constant is what it measures.
#ifdef FIXED_DEPENDENT
const bool DEPENDENT = FIXED_DEPENDENT;
#else
layout(constant_id = 1) const bool DEPENDENT = false;
#endif
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
#define IALU(k) u##k = (u##k ^ key) + key;
#define SHIFT(k) u##k = u##k + (u##k >> 3u);
// The multiply squares: u * key * key ... would fold into one multiply by a power of key (integer multiplication is
// associative; lavapipe's LLVM did, reading imul at 334 Gop/s, 3.5x its fadd rate).
#define IMUL(k) u##k = u##k * u##k;
#define CVT(k) x##k = float(int(x##k * pc.c));
#define SEL(k) x##k = mix(x##k + pc.c, x##k - pc.c, x##k > pc.c);  /* OpSelect, not a branch */
#define ICMP(k) u##k = mix(u##k + key, u##k ^ key, u##k < key);
#define ISEL(k) u##k = mix(u##k + key, u##k ^ key, x##k < pc.c); x##k = x##k + pc.c;
#define SUM_X(k) acc.x += x##k;
#define SUM_U(k) acc.y += float(u##k & 255u);
#define X4(M, OP) M(OP) M(OP) M(OP) M(OP)
#define STEPS_INDEP(OP) X4(ALL8, OP) X4(ALL8, OP) X4(ALL8, OP) X4(ALL8, OP)
#define ONE8(OP) OP(0) OP(0) OP(0) OP(0) OP(0) OP(0) OP(0) OP(0)
// The chain layout is chosen outside the loop: SwiftShader runs both sides of an `if` under a mask (it would run the
// untaken layout's steps too), but a loop whose lanes are all inactive exits at once.
#define STEPS_DEP(OP) X4(ONE8, OP) X4(ONE8, OP) X4(ONE8, OP) X4(ONE8, OP)
#define LOOP(OP, DOP)                                                          \
  if (DEPENDENT) {                                                             \
    for (uint n = 0u; n < pc.iters; ++n) { STEPS_DEP(DOP) }                    \
  } else {                                                                     \
    for (uint n = 0u; n < pc.iters; ++n) { STEPS_INDEP(OP) }                   \
  }
#define YADD(k) y = y + pc.c;
// Shared / distinct blocks (kinds 23, 24).
#define DECL_AB(k) float a##k = x##k, b##k = x##k;
#define SUMA(k) a##k = (((x##k + pc.c) + pc.c) + pc.c) + pc.c;
#define SUMB(k) b##k = (((x##k + pc.c) + pc.c) + pc.c) + pc.c;
#define SUMB2(k) b##k = (((x##k + pc.step) + pc.step) + pc.step) + pc.step;
#define MERGE(k) x##k = (a##k + b##k) * 0.5;
// Private-array steps (kinds 19, 20): index b + o + k of chain k.
#define PRIVREAD(o, k) x##k = x##k + a[b + o + uint(k)];
#define PRIVRMW(o, k) a[b + o + uint(k)] = a[b + o + uint(k)] + pc.c;
#define PRIV8(OP, o) OP(o, 0) OP(o, 1) OP(o, 2) OP(o, 3) OP(o, 4) OP(o, 5) OP(o, 6) OP(o, 7)

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  ALL8(DECL_X)
  ALL8(DECL_U)
  uint key = floatBitsToUint(pc.c) | 1u;
  vec4 acc = vec4(0.0);
  if (KIND == 0u) {
    LOOP(FADD, FADD)
  } else if (KIND == 1u) {
    LOOP(FMUL, FMUL)
  } else if (KIND == 2u) {
    LOOP(IALU, IALU)
  } else if (KIND == 16u) {
    LOOP(SHIFT, SHIFT)
  } else if (KIND == 3u) {
    LOOP(IMUL, IMUL)
  } else if (KIND == 4u) {
    LOOP(CVT, CVT)
  } else if (KIND == 5u) {
    LOOP(SEL, SEL)
  } else if (KIND == 17u) {
    LOOP(ICMP, ICMP)
  } else if (KIND == 18u) {
    LOOP(ISEL, ISEL)
  } else if (KIND == 6u) {
    vec2 p = vec2(float(i & 255u), float((i >> 8u) & 255u)) * (1.0 / 256.0);
    for (uint n = 0u; n < pc.iters; ++n) {
      acc += textureLod(tex, p, pc.lod);
      p = fract(p + vec2(pc.step, pc.step * 0.5));
    }
  } else if (KIND == 26u) {
    const vec2 size = vec2(textureSize(tex, 0));
    vec2 p = vec2(float(i & 255u), float((i >> 8u) & 255u)) * (1.0 / 256.0);
    for (uint n = 0u; n < pc.iters; ++n) {
      acc += texelFetch(tex, ivec2(p * size), 0);
      p = fract(p + vec2(pc.step, pc.step * 0.5));
    }
  } else if (KIND == 15u) {
    const uint w = uint(textureSize(tex, 0).x), h = uint(textureSize(tex, 0).y), sh = uint(findMSB(w));
    const uint texels = w * h;
    for (uint n = 0u; n < pc.iters; ++n) {
      const uint t = (i * pc.iters + n) & (texels - 1u);  // w and h are powers of two
      acc += texelFetch(tex, ivec2(int(t & (w - 1u)), int(t >> sh)), 0);
    }
  } else if (KIND == 14u) {  // texelFetch at coordinates every lane shares (a table row: shade/prelude.h texelFetchUniform)
    for (uint n = 0u; n < pc.iters; ++n) acc += texelFetch(tex, ivec2(int(n & 7u), int((n >> 3u) & 7u)), 0);
  } else if (KIND == 19u || KIND == 20u) {
    // The indices are uniform (every lane's the same, as the glints kernels' loop counters) and differ within an
    // iteration, so no read of an iteration is the same as another (nothing to share), and the loop is not unrolled
    // (pc.iters): each access is one at a run-time index.
    float a[256];
    for (int k = 0; k < 256; ++k) a[k] = x0 + float(k & 7);
    for (uint n = 0u; n < pc.iters; ++n) {
      const uint b = (n * 32u) & 255u;
      if (KIND == 19u) {
        PRIV8(PRIVREAD, 0u) PRIV8(PRIVREAD, 8u) PRIV8(PRIVREAD, 16u) PRIV8(PRIVREAD, 24u)
      } else {
        PRIV8(PRIVRMW, 0u) PRIV8(PRIVRMW, 8u) PRIV8(PRIVRMW, 16u) PRIV8(PRIVRMW, 24u)
      }
    }
    if (KIND == 20u) acc.w += a[i & 255u] + a[(i + 77u) & 255u];
  } else if (KIND == 9u) {  // window: independent iterations, each one dependent chain of 64 fadds
    for (uint n = 0u; n < pc.iters; ++n) {
      float y = x0 + float(n);
      ALL8(YADD) ALL8(YADD) ALL8(YADD) ALL8(YADD) ALL8(YADD) ALL8(YADD) ALL8(YADD) ALL8(YADD)
      acc.z += y;
    }
  } else if (KIND == 10u) {
    for (uint n = 0u; n < pc.iters; ++n) {
      if (x0 < pc.lod) { STEPS_INDEP(FADD) }
    }
  } else if (KIND == 12u) {
    for (uint n = 0u; n < pc.iters; ++n) {
      if (x0 < pc.lod) {
        for (int r = 0; r < 16; r++) { ALL8(FADD) }
      }
    }
  } else if (KIND == 13u) {  // a block behind a specialization constant inside a loop: DEPENDENT = true removes it
    for (uint n = 0u; n < pc.iters; ++n) {
      if (!DEPENDENT) { STEPS_INDEP(FADD) }
    }
  } else if (KIND == 23u || KIND == 24u) {
    ALL8(DECL_AB)
    for (uint n = 0u; n < pc.iters; ++n) {
      if (x0 < pc.lod) { ALL8(SUMA) }
      if (!(x0 < pc.lod)) {
        if (KIND == 23u) { ALL8(SUMB) } else { ALL8(SUMB2) }
      }
      ALL8(MERGE)
    }
  } else if (KIND == 25u) {
    for (uint n = 0u; n < pc.iters; ++n) {
      const uint b = (n * 16u) & 63u;
      const vec4 s0 = (src[b] + src[b + 1u]) + (src[b + 2u] + src[b + 3u]);
      const vec4 s1 = (src[b + 4u] + src[b + 5u]) + (src[b + 6u] + src[b + 7u]);
      const vec4 s2 = (src[b + 8u] + src[b + 9u]) + (src[b + 10u] + src[b + 11u]);
      const vec4 s3 = (src[b + 12u] + src[b + 13u]) + (src[b + 14u] + src[b + 15u]);
      acc += (s0 + s1) + (s2 + s3);
    }
  } else if (KIND == 11u) {
    if (x0 < pc.lod) {
      for (uint n = 0u; n < pc.iters; ++n) { STEPS_INDEP(FADD) }
    }
  } else if (KIND == 7u) {  // `iters` passes over the buffer, 16 vec4 per invocation each, contiguous across invocations
    for (uint n = 0u; n < pc.iters; ++n) {
      // pass n moves each invocation n workgroups on: every pass copies the whole buffer, and no invocation writes the
      // same element twice (nothing a compiler could prove dead)
      const uint j = (i + n * 64u) % pc.count;
      for (uint r = 0u; r < 16u; ++r) dst[j + r * pc.count] = src[j + r * pc.count] * pc.c;
    }
    return;
  } else {
    return;
  }
  ALL8(SUM_X)
  ALL8(SUM_U)
  dst[i] = acc;
}
