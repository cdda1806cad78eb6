// Real spherical harmonics of any order by normalised associated-Legendre recurrences (glints,
// issue 17; Holmes & Featherstone 2002, "A unified approach to the Clenshaw summation and the
// recursive computation of very high degree and order normalised associated Legendre functions").
// Dialect only.
//
// Conventions (those of shade/sh16.h, extended): polar axis z, no Condon-Shortley phase,
//   Y_l^0 = Pbar_l^0(z),  Y_l^m = sqrt(2) Pbar_l^m(z) cos(m phi),  Y_l^-m = sqrt(2) Pbar_l^m(z) sin(m phi)  (m > 0),
//   Pbar_l^m = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!) P_l^m,
// orthonormal on the unit sphere. Factorials never appear (they overflow double past l + m = 170):
//   Pbar_0^0 = 1 / sqrt(4 pi),
//   Pbar_m^m = sqrt((2m + 1) / (2m)) sin(theta) Pbar_{m-1}^{m-1}                 (sectoral seeds),
//   Pbar_{m+1}^m = sqrt(2m + 3) z Pbar_m^m,
//   Pbar_l^m = a_lm (z Pbar_{l-1}^m - b_lm Pbar_{l-2}^m),
//     a_lm = sqrt((4l^2 - 1) / (l^2 - m^2)),  b_lm = sqrt(((l - 1)^2 - m^2) / (4 (l - 1)^2 - 1)).
// The square roots are uniform constants, computed once on the host in double and read from a table
// (inputs/sh_legendre.h: texel (l, m) = (a_lm or the seed factor, b_lm, 0, 0)), so every build
// multiplies by the same floats.
//
// Underflow. Pbar_m^m ~ sin(theta)^m: in float it underflows (below 2^-126, the smallest normal)
// near the poles long before m = 300 (sin = 0.01 at m = 20), yet Pbar_l^m for l >> m grows back to
// O(1) there — a flushed seed would lose those values. So a recurrence carries its values scaled by
// 2^(32 k): a seed below 2^-32 is multiplied by 2^32 (exact) and k grows; along l, a value above
// 2^32 with k > 0 is multiplied by 2^-32 (both carried values) and k shrinks. The true value is
// p 2^(-32 k), formed once at the end (shLegValue) with one rounding; it is 0 when below the float
// range. A stage that flushes denormals (the device profile's fragment or compute stage) returns 0
// where the true value is below 2^-126; a preserving stage returns the denormal. Neither is ever NaN
// or infinite, at any order (tests/sh_legendre_test.cpp, to l = 300).

struct ShLeg {
  Float p;  // Pbar (current) scaled by 2^(32 k)
  Float q;  // Pbar of the previous degree, same scale
  Int k;
};

// Pbar_0^0.
ShLeg shLegSeed0() { return ShLeg(Float(0.282094792f), Float(0.0f), Int(0)); }

// Pbar_m^m from Pbar_{m-1}^{m-1} (s = sin(theta) >= 0, m >= 1), with the table's seed factor f = texel (m, m).x
// already read (a loop over many directions of one m reads it once: glint_lighting.h).
ShLeg shLegSeedStep(ShLeg s, Float f, Float sinT) {
  PRECISE Float p = s.p * (f * sinT);
  Mask small = abs(p) < 2.3283064e-10f;  // 2^-32
  return ShLeg(select(small, p * 4294967296.0f, p), Float(0.0f), s.k + select(small, Int(1), Int(0)));
}
ShLeg shLegSeedNext(ShLeg s, Sampler2D coef, int m, Float sinT) { return shLegSeedStep(s, texelFetchUniform(coef, m, m, 0).x, sinT); }

// Pbar_l^m from Pbar_{l-1}^m (and Pbar_{l-2}^m), l >= m + 1; z = cos(theta); a, b = texel (l, m).x, .y of the table,
// already read; first: l == m + 1 (no Pbar_{l-2}^m term).
ShLeg shLegStep(ShLeg s, Float a, Float b, Mask first, Float z) {
  PRECISE Float pFirst = a * (z * s.p);
  PRECISE Float general = a * (z * s.p - b * s.q);
  Float p = select(first, pFirst, general);
  Mask big = abs(p) > 4294967296.0f && s.k > Int(0);
  return ShLeg(select(big, p * 2.3283064e-10f, p), select(big, s.p * 2.3283064e-10f, s.p), s.k - select(big, Int(1), Int(0)));
}
ShLeg shLegNext(ShLeg s, Sampler2D coef, int l, int m, Float z) {
  Float4 c = texelFetchUniform(coef, l, m, 0);
  return shLegStep(s, c.x, c.y, Mask(l == m + 1), z);
}

// The unscaled value p 2^(-32 k) (one rounding; 0 below the float range).
Float shLegValue(ShLeg s) {
  Mask zero = s.k > Int(7);
  PRECISE Float v = xmScale2(s.p, Float(-32 * min(s.k, Int(7))));
  return select(zero, Float(0.0f), v);
}

// cos(m phi), sin(m phi) from cos(phi), sin(phi) by rotation, one m at a time.
struct ShAzimuth {
  Float c;
  Float s;
};
ShAzimuth shAzimuthNext(ShAzimuth a, Float cosP, Float sinP) {
  PRECISE Float c = a.c * cosP - a.s * sinP;
  PRECISE Float s = a.s * cosP + a.c * sinP;
  return ShAzimuth(c, s);
}

// The direction's polar terms: z, sin(theta) = |(x, y)| (accurate near the poles, unlike
// sqrt(1 - z^2)), cos(phi), sin(phi) (1, 0 on the axis).
struct ShPolar {
  Float z;
  Float sinT;
  Float cosP;
  Float sinP;
};
ShPolar shPolar(Float3 d) {
  PRECISE Float s = exSqrt(d.x * d.x + d.y * d.y);
  Mask axis = s == 0.0f;
  Float sd = select(axis, Float(1.0f), s);
  return ShPolar(d.z, s, select(axis, Float(1.0f), exDiv(d.x, sd)), select(axis, Float(0.0f), exDiv(d.y, sd)));
}
