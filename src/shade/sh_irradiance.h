// Order-3 spherical-harmonic irradiance (bands l <= 2, 9 coefficients per colour channel):
// Ramamoorthi & Hanrahan, "An Efficient Representation for Irradiance Environment Maps",
// SIGGRAPH 2001. The diffuse term of technique "fis" (shade/shade_fis.h).
//
// Projection (their eq. 10): L_lm = integral over the sphere of L(w) Y_lm(w) dw, summed here over
// the texels of the equirectangular map (level 0, texelFetch: the stored bits, no filtering):
//   texel (x, y) of a W x H map: centre u = (x + 1/2)/W, v = (y + 1/2)/H, azimuth 2 pi (u - 1/2),
//   polar angle theta = pi v (the inverse of shade_mirror.h equirectUv), so
//   w = (-sin(theta) sin(2 pi u), cos(theta), sin(theta) cos(2 pi u)),
//   and its exact solid angle dw = (2 pi / W)(cos(pi y / H) - cos(pi (y + 1) / H))
//   = (2 pi / W) 2 sin(theta) sin(pi / 2H) (product form: no cancellation near the poles; the
//   texels of a row sum to the band's area, all rows to 4 pi up to rounding).
// Real basis (their eq. 3; up = y): Y00 = 0.282095; Y1m = 0.488603 (y, z, x);
//   Y2-2 = 1.092548 xy, Y2-1 = 1.092548 yz, Y20 = 0.315392 (3 z^2 - 1), Y21 = 1.092548 xz,
//   Y22 = 0.546274 (x^2 - y^2). (Any orthonormal real basis of each band gives the same E.)
// Irradiance (their eq. 7-8): E(n) = sum_lm A_l L_lm Y_lm(n), A_0 = pi, A_1 = 2 pi / 3,
// A_2 = pi / 4. The shading pass needs E / pi (Lambert: outgoing radiance kd E / pi), so the
// reduction ends by scaling band l by A_l / pi = 1, 2/3, 1/4 (shIrradianceScale).
// Negative irradiance (ringing of the truncated series behind a strong sun) is clamped to 0.
// Band 3 (shade/sh16.h, 7 more coefficients) is projected in the same row loop and kept as raw
// radiance L_3m (A_3 = 0 for Lambert: E does not use it): the lighting vector of SH visibility's
// diffuse product (issue 16, shade/visibility.h).
//
// Fixed summation order, so the emulator and every GPU produce the same bits:
//   1. one invocation per row y (shProjectRow): the row's texels summed left to right;
//   2. one invocation per coefficient k: the H row sums reduced by a pairwise tree, stride
//      s = 1, 2, 4, ...: row[i] += row[i + s] for i = 0, 2s, 4s, ... while i + s < H (shAdd3),
//      then the band scale. The tree is written out in the reduce entry points (GLSL
//      src/shaders/sh_reduce.comp, C++ inputs/sh_irradiance.cpp), both tested for identical bits.

const float kShY0 = 0.282094792f;  // 1 / (2 sqrt(pi))
const float kShY1 = 0.488602512f;  // sqrt(3 / (4 pi))
const float kShY2 = 1.09254843f;   // sqrt(15 / (4 pi))
const float kShY20 = 0.315391565f; // sqrt(5 / (16 pi))
const float kShY22 = 0.546274215f; // sqrt(15 / (16 pi))

// The 9 RGB coefficients, k = 0..8 in the order Y00, Y1-1, Y10, Y11, Y2-2, Y2-1, Y20, Y21, Y22.
struct ShRgb {
  Float3 c0;
  Float3 c1;
  Float3 c2;
  Float3 c3;
  Float3 c4;
  Float3 c5;
  Float3 c6;
  Float3 c7;
  Float3 c8;
};

struct ShBasis {
  Float y0;
  Float y1;
  Float y2;
  Float y3;
  Float y4;
  Float y5;
  Float y6;
  Float y7;
  Float y8;
};

ShBasis shBasis(Float3 d) {
  PRECISE Float zz = d.z * d.z;
  PRECISE Float b20 = kShY20 * (3.0f * zz - 1.0f);
  PRECISE Float b22 = kShY22 * (d.x * d.x - d.y * d.y);
  return ShBasis(Float(kShY0), kShY1 * d.y, kShY1 * d.z, kShY1 * d.x, kShY2 * (d.x * d.y),
                 kShY2 * (d.y * d.z), b20, kShY2 * (d.x * d.z), b22);
}

Float3 shAdd3(Float3 a, Float3 b) {
  PRECISE Float3 r = a + b;
  return r;
}

// acc + Y(d) * L, coefficient by coefficient.
ShRgb shAccumulate(ShRgb acc, Float3 d, Float3 L) {
  ShBasis Y = shBasis(d);
  ShRgb r = ShRgb(acc.c0 + L * Y.y0, acc.c1 + L * Y.y1, acc.c2 + L * Y.y2, acc.c3 + L * Y.y3,
                          acc.c4 + L * Y.y4, acc.c5 + L * Y.y5, acc.c6 + L * Y.y6, acc.c7 + L * Y.y7,
                          acc.c8 + L * Y.y8);
  return r;
}

// Band 3's 7 RGB coefficients, k = 9..15 in shade/sh16.h order.
struct ShBand3 {
  Float3 c9;
  Float3 c10;
  Float3 c11;
  Float3 c12;
  Float3 c13;
  Float3 c14;
  Float3 c15;
};

ShBand3 shAccumulateBand3(ShBand3 acc, Float3 d, Float3 L) {
  Sh16 Y = sh16Basis(d);
  return ShBand3(acc.c9 + L * Y.c.y, acc.c10 + L * Y.c.z, acc.c11 + L * Y.c.w, acc.c12 + L * Y.d.x, acc.c13 + L * Y.d.y,
                 acc.c14 + L * Y.d.z, acc.c15 + L * Y.d.w);
}

struct ShRow {
  ShRgb low;     // bands 0-2
  ShBand3 high;  // band 3
};

// Step 1: the projection of row y of the equirectangular map `env` (width x height, level 0).
ShRow shProjectRow(Sampler2D env, Int y, int width, int height) {
  PRECISE Float invW = exDiv(1.0f, Float(float(width)));
  PRECISE Float inv2H = exDiv(1.0f, Float(float(2 * height)));
  XmSinCos mid = exSinCos2Pi((Float(y) + 0.5f) * inv2H);  // theta = pi (y + 1/2) / H = 2 pi (.. / 2H)
  XmSinCos halfStep = exSinCos2Pi(0.5f * inv2H);                // pi / 2H
  PRECISE Float dw = (2.0f * mid.s) * halfStep.s * (6.28318548f * invW);
  Float3 zero = Float3(0.0f, 0.0f, 0.0f);
  ShRgb acc = ShRgb(zero, zero, zero, zero, zero, zero, zero, zero, zero);
  ShBand3 hi = ShBand3(zero, zero, zero, zero, zero, zero, zero);
  FOR (int x = 0; x < width; x++) {
    XmSinCos az = exSinCos2Pi((Float(float(x)) + 0.5f) * invW);
    PRECISE Float3 d = Float3(-(mid.s * az.s), mid.c, mid.s * az.c);
    Float4 t = texelFetch2D(env, Int(x), y, 0);
    PRECISE Float3 L = Float3(t.x, t.y, t.z) * dw;
    acc = shAccumulate(acc, d, L);
    hi = shAccumulateBand3(hi, d, L);
  }
  return ShRow(acc, hi);
}

// Step 2's last operation: band scale A_l / pi of coefficient k (uniform or per invocation); band 3
// (k >= 9) stays raw radiance.
Float3 shIrradianceScale(Uint k, Float3 sum) {
  Float s = select(k == 0u, 1.0f, select(k < 4u, 0.666666687f, select(k < 9u, 0.25f, 1.0f)));
  PRECISE Float3 r = sum * s;
  return r;
}

// E(n) / pi for the unit normal n, clamped at 0, summed in coefficient order.
Float3 shIrradiance(ShRgb c, Float3 n) {
  ShBasis Y = shBasis(n);
  PRECISE Float3 e = c.c0 * Y.y0 + c.c1 * Y.y1;
  e = e + c.c2 * Y.y2;
  e = e + c.c3 * Y.y3;
  e = e + c.c4 * Y.y4;
  e = e + c.c5 * Y.y5;
  e = e + c.c6 * Y.y6;
  e = e + c.c7 * Y.y7;
  e = e + c.c8 * Y.y8;
  return Float3(max(e.x, 0.0f), max(e.y, 0.0f), max(e.z, 0.0f));
}
