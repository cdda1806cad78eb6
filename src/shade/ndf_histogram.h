// The bins of the NDF histogram (Gamboa, Guertin, Nowrouzezahrai 2018, "Scalable Appearance
// Filtering for Complex Lighting Effects", §4.1 and §6.1): a micro-normal n (tangent space, z the
// macro normal) falls in ring t = floor(theta * T / thetaMax) (clamped to T - 1; theta = acos n.z)
// and sector p = floor(phi * P / (2 pi)) (phi = atan2(n.y, n.x) in [0, 2 pi)); its bin is t P + p.
// theta and phi come from the exact-math layer, so every build bins every normal alike (the SAT
// built from the bins is then the same integer table on every build). Dialect only.

struct NdfBinning {
  uint rings;        // T: theta bins
  uint sectors;      // P: phi bins
  float ringScale;   // T / thetaMax
  float sectorScale; // P / (2 pi)
};

Uint ndfBin(NdfBinning b, Float3 n) {
  PRECISE Float theta = exAcos(clamp(n.z, -1.0f, 1.0f));
  PRECISE Float phi = exAtan2(n.y, n.x);
  PRECISE Float phi2 = select(phi < 0.0f, phi + 6.28318548f, phi);
  Int t = clamp(Int(floor(theta * b.ringScale)), Int(0), Int(int(b.rings) - 1));
  Int p = clamp(Int(floor(phi2 * b.sectorScale)), Int(0), Int(int(b.sectors) - 1));
  return Uint(t) * b.sectors + Uint(p);
}

// ---- Box counts from the SAT texture (inputs/ndf_histogram.h ndfSatTexture) ----
// The table as an RGBA32UI 2D array: layer = stored ring, texel (x G + g, y) holds sectors 8g .. 8g + 7
// of map texel (x, y) (G = ceil(P / 8) groups), two 16-bit SAT values per uint (sector 8g + 2j in
// the low half of component j). A box's count is S(x1, y1) - S(x0 - 1, y1) - S(x1, y0 - 1) +
// S(x0 - 1, y0 - 1) modulo 2^16 (exact below 65,536 texels), S = 0 left of or above the map.

// x mod n in [0, n) for |x| < 2^24 (float quotient, then one correction each way), and the quotient.
struct NdfDivMod {
  Int q;
  Int r;
};
NdfDivMod ndfDivMod(Int x, int n, float invN) {
  Int q = Int(floor(Float(x) * invN));
  Int r = x - q * n;
  Int q1 = select(r < Int(0), q - Int(1), select(r >= Int(n), q + Int(1), q));
  return NdfDivMod(q1, x - q1 * n);
}

// An unrolled inclusive range [a, b] of an axis of n texels as map ranges: head [lo0, hi0] once,
// [0, n - 1] `periods` times, tail [0, tailLen - 1] once (tailLen may be 0).
struct NdfAxis {
  Int lo0;
  Int hi0;
  Int periods;
  Int tailLen;
};
NdfAxis ndfAxis(Int a, Int b, int n, float invN) {
  Int len = b - a + Int(1);
  Int s = ndfDivMod(a, n, invN).r;
  Int head = min(len, Int(n) - s);
  NdfDivMod rest = ndfDivMod(len - head, n, invN);
  return NdfAxis(s, s + head - Int(1), rest.q, rest.r);
}

// The SAT's four packed uints of group g at map texel (x, y) of ring layer `layer`; 0 when x or y < 0.
UintTexel4 ndfSatAt(USampler2DArray sat, Int x, Int y, Int layer, int g, int groups) {
  Mask outside = x < Int(0) || y < Int(0);
  UintTexel4 t = texelFetchLayerU(sat, max(x, Int(0)) * groups + Int(g), max(y, Int(0)), layer, 0);
  Uint z = Uint(0u);
  return UintTexel4(select(outside, z, t.x), select(outside, z, t.y), select(outside, z, t.z), select(outside, z, t.w));
}

// acc + m (S11 - S01 - S10 + S00), half by half (each half modulo 2^16 at the end).
struct NdfAcc8 {
  UintTexel4 lo;
  UintTexel4 hi;
};
Uint ndfCornerSum(Uint s11, Uint s01, Uint s10, Uint s00, Uint shift) {
  return (((s11 >> shift) & 0xffffu) - ((s01 >> shift) & 0xffffu) - ((s10 >> shift) & 0xffffu)) + ((s00 >> shift) & 0xffffu);
}
NdfAcc8 ndfAddBox(NdfAcc8 acc, USampler2DArray sat, Int layer, int g, int groups, Int xl, Int xh, Int yl, Int yh, Uint m) {
  UintTexel4 a = ndfSatAt(sat, xh, yh, layer, g, groups);
  UintTexel4 b = ndfSatAt(sat, xl - Int(1), yh, layer, g, groups);
  UintTexel4 c = ndfSatAt(sat, xh, yl - Int(1), layer, g, groups);
  UintTexel4 d = ndfSatAt(sat, xl - Int(1), yl - Int(1), layer, g, groups);
  UintTexel4 lo = UintTexel4(acc.lo.x + m * ndfCornerSum(a.x, b.x, c.x, d.x, 0u), acc.lo.y + m * ndfCornerSum(a.y, b.y, c.y, d.y, 0u),
                             acc.lo.z + m * ndfCornerSum(a.z, b.z, c.z, d.z, 0u), acc.lo.w + m * ndfCornerSum(a.w, b.w, c.w, d.w, 0u));
  UintTexel4 hi = UintTexel4(acc.hi.x + m * ndfCornerSum(a.x, b.x, c.x, d.x, 16u), acc.hi.y + m * ndfCornerSum(a.y, b.y, c.y, d.y, 16u),
                             acc.hi.z + m * ndfCornerSum(a.z, b.z, c.z, d.z, 16u), acc.hi.w + m * ndfCornerSum(a.w, b.w, c.w, d.w, 16u));
  return NdfAcc8(lo, hi);
}

// The counts of sectors 8g .. 8g + 7 of stored ring `layer` over the unrolled inclusive box
// [x0, x1] x [y0, y1] of a tiled map of width x height texels, packed as the table is (sector
// 8g + 2j in the low half of component j). Every piece of the box (head, periods, tail per axis)
// is added with its multiplicity, always all nine (a piece of multiplicity 0 adds 0), so every
// lane runs the same code. invW, invH: 1 / width, 1 / height from the host (a quotient guess only:
// ndfDivMod corrects it, so any rounding of it gives the same result).
UintTexel4 ndfBoxCounts8(USampler2DArray sat, Int layer, int g, int groups, int width, int height, float invW, float invH,
                         Int x0, Int y0, Int x1, Int y1) {
  NdfAxis ax = ndfAxis(x0, x1, width, invW);
  NdfAxis ay = ndfAxis(y0, y1, height, invH);
  Uint xm1 = Uint(ax.periods);
  Uint xm2 = select(ax.tailLen > Int(0), Uint(1u), Uint(0u));
  Uint ym1 = Uint(ay.periods);
  Uint ym2 = select(ay.tailLen > Int(0), Uint(1u), Uint(0u));
  Int xt = ax.tailLen - Int(1);
  Int yt = ay.tailLen - Int(1);
  Int zero = Int(0);
  Int xe = Int(width - 1);
  Int ye = Int(height - 1);
  Uint z = Uint(0u);
  NdfAcc8 acc = NdfAcc8(UintTexel4(z, z, z, z), UintTexel4(z, z, z, z));
  acc = ndfAddBox(acc, sat, layer, g, groups, ax.lo0, ax.hi0, ay.lo0, ay.hi0, Uint(1u));
  acc = ndfAddBox(acc, sat, layer, g, groups, zero, xe, ay.lo0, ay.hi0, xm1);
  acc = ndfAddBox(acc, sat, layer, g, groups, zero, xt, ay.lo0, ay.hi0, xm2);
  acc = ndfAddBox(acc, sat, layer, g, groups, ax.lo0, ax.hi0, zero, ye, ym1);
  acc = ndfAddBox(acc, sat, layer, g, groups, zero, xe, zero, ye, xm1 * ym1);
  acc = ndfAddBox(acc, sat, layer, g, groups, zero, xt, zero, ye, xm2 * ym1);
  acc = ndfAddBox(acc, sat, layer, g, groups, ax.lo0, ax.hi0, zero, yt, ym2);
  acc = ndfAddBox(acc, sat, layer, g, groups, zero, xe, zero, yt, xm1 * ym2);
  acc = ndfAddBox(acc, sat, layer, g, groups, zero, xt, zero, yt, xm2 * ym2);
  return UintTexel4((acc.lo.x & 0xffffu) | ((acc.hi.x & 0xffffu) << 16u), (acc.lo.y & 0xffffu) | ((acc.hi.y & 0xffffu) << 16u),
                    (acc.lo.z & 0xffffu) | ((acc.hi.z & 0xffffu) << 16u), (acc.lo.w & 0xffffu) | ((acc.hi.w & 0xffffu) << 16u));
}
