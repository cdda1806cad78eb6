// Environment-map importance sampling on the device (issue 5): three samplers of the equirectangular
// map with their solid-angle pdfs, sampleX / xPdf pairs in shared code (the host builds the tables:
// inputs/env_sampling.h). All three draw a texel region and then a uniform point in it in (u, v), so
//   pdf(omega) = P_region / (area_uv(region) 2 pi^2 sin theta)        (d omega = 2 pi^2 sin theta du dv,
// u = phi / 2 pi, v = theta / pi, equirectangular; PBRT-v3 s14.2.4). The tables store
// P_region / area_uv / (2 pi^2) per region ("uv pdf"), so a pdf costs one division by sin theta.
//
// kEnvKdTree  Ergun, Kurt & Ozturk, "Real-time kd-tree based importance sampling of environment maps"
//             (SCCG 2012): the kd-tree blocks (inputs/env_kdtree.h) ranked by mean, rank k drawn from the
//             fitted density p(x) = 1/(log(1 + n/alpha)(alpha + x)) by x = alpha((1 + n/alpha)^xi - 1)
//             = alpha (2^(xi log2(1 + n/alpha)) - 1), k = floor(x): O(1), one table lookup. The pdf of an
//             arbitrary direction (MIS) is O(1) too: a texel -> rank texture, then the rank's record.
// kEnvAlias   the same blocks drawn with their exact probabilities sum_k / total by Walker's alias method
//             (Vose 1991): k = floor(xi0 n), keep k if xi1 < q_k else take alias_k. O(1).
// kEnvInversion the baseline: texel by inversion of the marginal CDF over rows and the row's conditional
//             CDF (binary searches of a uniform count of steps: ceil(log2 H) and ceil(log2 W) texel
//             fetches), the pdf from the CDF differences (the probabilities the searches realize).
//
// Tables (sampler2D read with texelFetch, stored values exact):
//   kd-tree, alias: `table` holds 2 RGBA32F texels per block (rank order), block k at
//     (2 (k mod 1024) + j, k / 1024): j = 0: (x0, y0, w, h) in texels; j = 1: (uv pdf with the fitted
//     P_k, uv pdf with the exact P_k, alias threshold q_k, alias index). `texels`: R32F, W x H, the
//     rank of the block holding each texel.
//   inversion: `table` R32F H x 1, marginal CDF M(y) = P(row <= y) (M(H-1) = 1); `texels` R32F W x H,
//     conditional CDFs C_y(x) = P(column <= x | row y) (C_y(W-1) = 1).

const uint kEnvKdTree = 0u;
const uint kEnvAlias = 1u;
const uint kEnvInversion = 2u;

// Uniform settings of a sampler (host: inputs/env_sampling.h envSamplingUniforms).
struct EnvSampling {
  uint method;     // kEnv*
  uint count;      // blocks (kd-tree, alias)
  uint width;      // map size in texels
  uint height;
  float alpha;     // kd-tree fit
  float log2Span;  // log2(1 + count / alpha)
  float invWidth;  // 1 / width, 1 / height (host-rounded)
  float invHeight;
};

struct EnvSample {
  Float3 dir;  // world direction (the environment's frame)
  Float pdf;   // solid angle; 0: a lost sample (weight 0)
};

// Inverse of equirectUv (shade_mirror.h): phi = 2 pi (u - 1/2), theta = pi v;
// direction (sin theta sin phi, cos theta, -sin theta cos phi) = (-st sin 2pi u, ct, st cos 2pi u).
struct EquirectDir {
  Float3 dir;
  Float sinTheta;
};
EquirectDir equirectDirection(Float u, Float v) {
  XmSinCos a = exSinCos2Pi(u);
  XmSinCos t = exSinCos2Pi(0.5f * v);
  PRECISE Float3 d = Float3(-t.s * a.s, t.c, t.s * a.c);
  return EquirectDir(d, t.s);
}

// uv pdf / sin theta, 0 where sin theta = 0 (the poles, measure zero).
Float envSolidAnglePdf(Float uvPdf, Float sinTheta) {
  Mask ok = sinTheta > 0.0f;
  PRECISE Float p = exDiv(uvPdf, select(ok, sinTheta, 1.0f));
  return select(ok, p, 0.0f);
}

Float4 envBlockRecord(Sampler2D table, Uint k, uint j) {
  return texelFetch2D(table, Int(((k & Uint(1023u)) << 1) + Uint(j)), Int(k >> 10), 0);
}

// 2^z - 1 for z >= 0 without cancellation near 0 (oneMinusExp2's series below 0.2).
Float exp2Minus1(Float z) {
  PRECISE Float e = exExp2(z) - 1.0f;
  return select(z < 0.2f, -oneMinusExp2(min(z, 0.2f)), e);
}

// Rank drawn from the fitted density: floor(alpha (2^(xi log2Span) - 1)), clamped to count - 1.
Uint sampleEnvKdRank(EnvSampling s, Float xi) {
  PRECISE Float x = s.alpha * exp2Minus1(xi * s.log2Span);
  return min(Uint(max(x, 0.0f)), Uint(s.count - 1u));
}

// Block drawn by the kd-tree fit (u.x) or the alias table (u.x, u.y), then a uniform point in it (u.z, u.w).
EnvSample sampleEnvBlocks(Sampler2D table, EnvSampling s, Float4 u) {
  Uint k = Uint(0u);
  Mask kd = uniformMask(s.method == kEnvKdTree), alias = uniformMask(s.method == kEnvAlias);
  IF_ANY(kd) { k = select(kd, sampleEnvKdRank(s, u.x), k); }
  IF_ANY(alias) {
    PRECISE Float x = u.x * float(s.count);
    Uint i = min(Uint(x), Uint(s.count - 1u));
    Float4 a = envBlockRecord(table, i, 1u);
    k = select(alias, select(u.y < a.z, i, Uint(a.w)), k);
  }
  Float4 r = envBlockRecord(table, k, 0u);
  Float4 q = envBlockRecord(table, k, 1u);
  PRECISE Float bu = (r.x + u.z * r.z) * s.invWidth;
  PRECISE Float bv = (r.y + u.w * r.w) * s.invHeight;
  EquirectDir d = equirectDirection(bu, bv);
  Float uvPdf = select(s.method == kEnvKdTree, q.x, q.y);
  return EnvSample(d.dir, envSolidAnglePdf(uvPdf, d.sinTheta));
}

// The texel (x, y) under a direction, and sin theta there.
struct EnvTexel {
  Int x;
  Int y;
  Float sinTheta;
};
EnvTexel envTexelOf(EnvSampling s, Float3 dir) {
  Float2 uv = equirectUv(dir);
  Int x = clamp(Int(uv.x * float(s.width)), Int(0), Int(int(s.width) - 1));
  Int y = clamp(Int(uv.y * float(s.height)), Int(0), Int(int(s.height) - 1));
  PRECISE Float st = exSqrt(dir.x * dir.x + dir.z * dir.z);
  return EnvTexel(x, y, st);
}

Float envBlocksPdf(Sampler2D table, Sampler2D texels, EnvSampling s, Float3 dir) {
  EnvTexel t = envTexelOf(s, dir);
  Uint k = Uint(texelFetch2D(texels, t.x, t.y, 0).x);
  Float4 q = envBlockRecord(table, k, 1u);
  return envSolidAnglePdf(select(s.method == kEnvKdTree, q.x, q.y), t.sinTheta);
}

// First index i in [0, n) of a non-decreasing CDF stored along x (row `row` of `cdf`) with
// cdf(i) > u, given cdf(n - 1) = 1 > u: the number of leading entries <= u, found by descending powers
// of two (pos grows by 2^j while entry pos + 2^j - 1 is still <= u): floor(log2 n) + 1 uniform steps.
Int cdfSearch(Sampler2D cdf, Int row, uint n, Float u) {
  uint top = 1u;
  while (top * 2u <= n) top = top * 2u;
  Int pos = Int(0);
  FOR (uint stride = top; stride > 0u; stride = stride >> 1) {
    Int probe = pos + Int(int(stride) - 1);
    Mask inside = probe < Int(int(n));
    Float c = texelFetch2D(cdf, min(probe, Int(int(n) - 1)), row, 0).x;
    pos = select(inside && c <= u, pos + Int(int(stride)), pos);
  }
  return min(pos, Int(int(n) - 1));
}

// P(index = i) = cdf(i) - cdf(i - 1) (cdf(-1) = 0).
Float cdfMass(Sampler2D cdf, Int row, Int i) {
  Float hi = texelFetch2D(cdf, i, row, 0).x;
  Float lo = texelFetch2D(cdf, max(i - Int(1), Int(0)), row, 0).x;
  PRECISE Float m = hi - select(i > Int(0), lo, 0.0f);
  return m;
}

// uv pdf of texel (x, y): P(row) P(column | row) W H / (2 pi^2).
Float envInversionUvPdf(Sampler2D marginal, Sampler2D conditional, EnvSampling s, Int x, Int y) {
  PRECISE Float p = cdfMass(marginal, Int(0), y) * cdfMass(conditional, y, x);
  p = p * (float(s.width) * float(s.height) * 0.0506605918f);  // 1 / (2 pi^2)
  return p;
}

EnvSample sampleEnvInversion(Sampler2D marginal, Sampler2D conditional, EnvSampling s, Float4 u) {
  Int y = cdfSearch(marginal, Int(0), s.height, u.x);
  Int x = cdfSearch(conditional, y, s.width, u.y);
  PRECISE Float bu = (Float(x) + u.z) * s.invWidth;
  PRECISE Float bv = (Float(y) + u.w) * s.invHeight;
  EquirectDir d = equirectDirection(bu, bv);
  return EnvSample(d.dir, envSolidAnglePdf(envInversionUvPdf(marginal, conditional, s, x, y), d.sinTheta));
}

Float envInversionPdf(Sampler2D marginal, Sampler2D conditional, EnvSampling s, Float3 dir) {
  EnvTexel t = envTexelOf(s, dir);
  return envSolidAnglePdf(envInversionUvPdf(marginal, conditional, s, t.x, t.y), t.sinTheta);
}

// The method's sampler and pdf (s.method is uniform: a GPU runs one branch, a software device both, the other under a
// false mask; uniformMask).
EnvSample sampleEnv(Sampler2D table, Sampler2D texels, EnvSampling s, Float4 u) {
  Float3 dir = Float3(0.0f, 1.0f, 0.0f);
  Float pdf = Float(0.0f);
  Mask inversion = uniformMask(s.method == kEnvInversion), blocks = !inversion;
  IF_ANY(inversion) {
    EnvSample e = sampleEnvInversion(table, texels, s, u);
    dir = select(inversion, e.dir, dir);
    pdf = select(inversion, e.pdf, pdf);
  }
  IF_ANY(blocks) {
    EnvSample e = sampleEnvBlocks(table, s, u);
    dir = select(blocks, e.dir, dir);
    pdf = select(blocks, e.pdf, pdf);
  }
  return EnvSample(dir, pdf);
}

Float envPdf(Sampler2D table, Sampler2D texels, EnvSampling s, Float3 dir) {
  Float p = Float(0.0f);
  Mask inversion = uniformMask(s.method == kEnvInversion), blocks = !inversion;
  IF_ANY(inversion) { p = select(inversion, envInversionPdf(table, texels, s, dir), p); }
  IF_ANY(blocks) { p = select(blocks, envBlocksPdf(table, texels, s, dir), p); }
  return p;
}

// Throughput probe (inputs/env_sampling_speed.cpp, src/shaders/env_sampling_speed.comp): n directions
// of stream `index` drawn and their pdfs looked up; returns sum(pdf + dir.x) so no work is dead.
Float envSamplingChecksum(Sampler2D table, Sampler2D texels, EnvSampling s, Uint index, uint n, uint seed) {
  PRECISE Float sum = Float(0.0f);
  FOR (uint j = 0u; j < n; j++) {
    Float4 u = philoxUniform4(philox4x32(Philox4(index, Uint(j), Uint(2u), Uint(0u)), Uint(seed), Uint(0u)));
    EnvSample e = sampleEnv(table, texels, s, u);
    sum = sum + envPdf(table, texels, s, e.dir) + e.dir.x;
  }
  return sum;
}
