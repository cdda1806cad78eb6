// Low-discrepancy points and frames shared by the sampling techniques (shared dialect).
//
// Hammersley set of N points (Hammersley 1964; the FIS paper, Colbert & Krivanek 2007, s2.2):
//   x_i = ((i + 1/2) / N, Phi_2(i)),  i = 0 .. N-1,
// Phi_2 = base-2 radical inverse (bit reversal). The first coordinate is shifted by half a cell so
// no point sits at 0, where a lobe's pdf can vanish (u^(1/(e+1)) = 0). Phi_2 keeps 24 bits so that
// the integer-to-float conversion is exact on every device.

// Base-2 radical inverse of i in 24 bits: the bit-reversed integer scaled by 2^-24 (exact).
Float radicalInverse2(Uint i) {
  Uint x = (i << 16) | (i >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
  PRECISE Float r = Float(x >> 8) * 5.96046448e-08f;  // 2^-24
  return r;
}

// Point i of the N-point Hammersley set (i < N <= 2^24).
Float2 hammersley(Uint i, Uint n) {
  PRECISE Float u = exDiv(Float(i) + 0.5f, Float(n));
  return Float2(u, radicalInverse2(i));
}

// Integer hash of 32 bits (C. Wellons' "lowbias32", 2018: xorshift-multiply rounds, bias 0.17 of a
// random permutation); shared integer code, so every build draws the same numbers.
Uint hashLowbias32(Uint v) {
  Uint x = v ^ (v >> 16);
  x = x * 0x7feb352du;
  x = x ^ (x >> 15);
  x = x * 0x846ca68bu;
  x = x ^ (x >> 16);
  return x;
}

// Per-pixel offset in [0, 1)^2 (24 bits each, exact) for a Cranley-Patterson rotation.
Float2 pixelOffset(Uint pixel) {
  Uint a = hashLowbias32(pixel * 2u);
  Uint b = hashLowbias32(pixel * 2u + 1u);
  PRECISE Float2 r = Float2(Float(a >> 8) * 5.96046448e-08f, Float(b >> 8) * 5.96046448e-08f);
  return r;
}

// Cranley-Patterson rotation (Cranley & Patterson 1976): u + r modulo 1 (a point at 0 keeps its weight
// rules: the samplers treat pdf = 0 as a lost sample).
Float2 rotatePoint(Float2 u, Float2 r) {
  PRECISE Float x = u.x + r.x;
  PRECISE Float y = u.y + r.y;
  x = select(x >= 1.0f, x - 1.0f, x);
  y = select(y >= 1.0f, y - 1.0f, y);
  return Float2(x, y);
}

// Orthonormal basis (t, b, n) about a unit vector n, branch-free (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited", JCGT 6(1)); right-handed: cross(t, b) = n.
struct Basis {
  Float3 t;
  Float3 b;
  Float3 n;
};

Basis basisAbout(Float3 n) {
  PRECISE Float s = select(n.z >= 0.0f, 1.0f, -1.0f);
  PRECISE Float a = exDiv(-1.0f, s + n.z);
  PRECISE Float c = n.x * n.y * a;
  PRECISE Float3 t = Float3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
  PRECISE Float3 b = Float3(c, s + n.y * n.y * a, -n.y);
  return Basis(t, b, n);
}

// Local (x, y, z) -> world: x t + y b + z n, summed in that order.
Float3 basisToWorld(Basis f, Float3 v) {
  PRECISE Float3 r = f.t * v.x + f.b * v.y;
  r = r + f.n * v.z;
  return r;
}

Float3 basisToLocal(Basis f, Float3 v) { return Float3(dot(v, f.t), dot(v, f.b), dot(v, f.n)); }

// 1 - 2^z for z <= 0 without cancellation near 0: the polar sine of a narrow lobe comes from it
// (sin^2 = (1 - c)(1 + c)); with 1 - c taken from a rounded c, a Phong lobe of exponent 10^5
// would be quantized to a few hundred distinct angles. |z ln 2| < 0.18: Taylor series of
// -expm1 to degree 8 (next term < 2^-34 relative); else 1 - 2^z (c <= 0.85, little cancellation).
Float oneMinusExp2(Float z) {
  PRECISE Float x = z * 0.693147182f;
  PRECISE Float p = x * (1.0f + x * (0.5f + x * (0.166666672f + x * (0.0416666679f + x * (0.00833333377f +
                    x * (0.00138888892f + x * (1.98412701e-04f + x * 2.48015876e-05f)))))));
  return select(z > -0.25f, -p, 1.0f - exExp2(z));
}

// Unit vector at polar cosine c (sine s) and azimuth 2 pi u about +z.
Float3 sphericalDirection(Float s, Float c, Float u) {
  XmSinCos p = exSinCos2Pi(u);
  PRECISE Float3 d = Float3(s * p.c, s * p.s, c);
  return d;
}
