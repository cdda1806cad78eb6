// Philox4x32-10, the counter-based random number generator of Salmon, Moraes, Dror & Shaw,
// "Parallel Random Numbers: As Easy as 1, 2, 3" (SC 2011; the Random123 library), in shared integer
// code: output = a bijection of a 128-bit counter keyed by 64 bits, so a pixel's numbers depend only
// on (pixel, sample, frame, seed) and every build (C++ scalar / SIMD, GLSL on any device) draws the
// same bits. Ten rounds of
//   (hi0, lo0) = 0xD2511F53 * c0,  (hi1, lo1) = 0xCD9E8D57 * c2   (32 x 32 -> 64-bit products)
//   c = (hi1 ^ c1 ^ k0, lo1, hi0 ^ c3 ^ k1, lo0),  then k += (0x9E3779B9, 0xBB67AE85) (Weyl key schedule).
// Checked against the Random123 known-answer vectors (tests/philox_test.cpp).

struct Philox4 {
  Uint x;
  Uint y;
  Uint z;
  Uint w;
};

Philox4 philoxRound(Philox4 c, Uint k0, Uint k1) {
  Uint hi0 = mulHi(Uint(0xD2511F53u), c.x);
  Uint lo0 = c.x * Uint(0xD2511F53u);
  Uint hi1 = mulHi(Uint(0xCD9E8D57u), c.z);
  Uint lo1 = c.z * Uint(0xCD9E8D57u);
  return Philox4(hi1 ^ c.y ^ k0, lo1, hi0 ^ c.w ^ k1, lo0);
}

Philox4 philox4x32(Philox4 counter, Uint key0, Uint key1) {
  Philox4 c = counter;
  Uint k0 = key0;
  Uint k1 = key1;
  for (uint r = 0u; r < 10u; r++) {
    c = philoxRound(c, k0, k1);
    k0 = k0 + Uint(0x9E3779B9u);
    k1 = k1 + Uint(0xBB67AE85u);
  }
  return c;
}

// The top 24 bits of r as a float in [0, 1) (exact: a multiple of 2^-24).
Float unitFloat24(Uint r) {
  PRECISE Float u = Float(r >> 8) * 5.96046448e-08f;
  return u;
}

// Four uniform numbers in [0, 1) from one Philox block.
Float4 philoxUniform4(Philox4 r) { return Float4(unitFloat24(r.x), unitFloat24(r.y), unitFloat24(r.z), unitFloat24(r.w)); }
