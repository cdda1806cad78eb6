// Portable exact math for the shadetwin dialect (GLSL and C++ from this one file).
//
// Built only from float add/sub/mul, comparisons, conversions of exactly representable values, and
// 32-bit integer/bit operations: the operations whose bits Vulkan fixes (correctly rounded) and every
// device agrees on. No '/', sqrt, fma, or builtin transcendental is used. Accuracy against correctly
// rounded results, as measured by tests/exact_math_test.cpp and `shadetwin verify math`, is listed in
// docs/DESIGN.md ("Exact math").
//
// Denormals: exDiv and exSqrt work on integer significands (their float estimates stay normal) and
// honour denormal inputs and outputs in every stage. The polynomial functions use float add/mul, so in
// a stage whose device profile flushes denormals (lavapipe fragment) they flush exactly as the device's
// own float ops do; the emulator runs such a stage with FTZ/DAZ set, which gives the same bits.

// ---------------------------------------------------------------------------------------------
// Integer core shared by exDiv and exSqrt.

struct XmUnpacked {
  Uint m;  // significand with its leading one at bit 23: [2^23, 2^24)
  Int e;   // unbiased exponent: |x| = m * 2^(e - 23)
};

// |x| of a finite, non-zero float given by its magnitude bits (sign cleared); subnormals normalised.
XmUnpacked xmUnpack(Uint ax) {
  PRECISE Uint frac = ax & 0x007fffffu;
  Int eb = Int(ax >> 23u);
  // Leading-one position of a subnormal's fraction from an exact int->float conversion (frac < 2^24).
  Int msb = Int(floatBitsToUint(Float(frac)) >> 23u) - 127;
  Int shift = select(eb == 0, 23 - msb, 0);
  Uint m = select(eb == 0, frac << Uint(shift), frac | 0x00800000u);
  Int e = select(eb == 0, -126 - shift, eb - 127);
  return XmUnpacked(m, e);
}

// Correctly rounded (to nearest, ties to even) float bits of sign * (sig + tail) * 2^e2, where
// sig is in [2^24, 2^27) and `sticky` says whether the tail below sig's last bit is non-zero.
// Covers normal, subnormal, overflow (to inf) and total underflow (to 0).
Uint xmRoundPack(Uint sign, Uint sig, Int e2, Mask sticky) {
  Int p = 24 + select(sig >= 0x02000000u, 1, 0) + select(sig >= 0x04000000u, 1, 0);
  Int s = min(max(p - 23, -149 - e2), 31);  // bits to drop: to 24 bits, or to the 2^-149 quantum
  Uint us = Uint(s);
  Uint kept = sig >> us;
  Uint halfUlp = 1u << (us - 1u);
  Uint tail = sig & ((halfUlp << 1u) - 1u);
  Mask up = tail > halfUlp || (tail == halfUlp && (sticky || (kept & 1u) != 0u));
  kept = kept + select(up, 1u, 0u);
  // kept carries the hidden bit, so adding it to (exponent field - 1) << 23 also handles the carry
  // of a round-up and the subnormal case (field 0).
  Int ef = e2 + s + 149;
  Uint bits = (Uint(max(ef, 0)) << 23u) + kept;
  bits = select(ef > 254 || bits >= 0x7f800000u, 0x7f800000u, bits);
  return sign | bits;
}

// ---------------------------------------------------------------------------------------------
// Division and square root: correctly rounded, from a float estimate and an exact integer residual.
//
// Derivation (division). a/b = (Ma/Mb) 2^(Ea-Eb) with 24-bit significands Ma, Mb in [2^23, 2^24).
// Let k = 24 if Ma < Mb, else 23, so that the integer quotient qa = floor(Ma 2^k / Mb) lies in
// [2^23, 2^24), where float holds every integer exactly. (1) Estimate: R ~ 1/b' for b' = Mb 2^-23 in
// [1, 2) from a bit-trick seed and three Newton steps x(2 - b'x) (mul/sub only; relative error below
// 2^-22.6 on every float of [1, 2.5], tests/exact_math_test.cpp), t = (a' R) 2^k, so
// |t - Ma 2^k/Mb| < 2^24 2^-22.6 + 1/2 (the product's rounding) < 3.2 and qf = floor(t) is within 4 of
// qa (measured: qf - qa in -2..+4). (2) Exact residual: rem = Ma 2^k - qf Mb is a small integer
// (|rem| < 5 Mb < 2^27), so it is exact in wrapping 32-bit integer arithmetic although both terms
// are ~2^47: the low 32 bits of each suffice. (3) One refinement d = floor(rem R 2^-23) (rem/Mb to
// ~10^-6, so floor(rem/Mb) - d is -1, 0 or +1) and (4) one correction each way make rem' in [0, Mb),
// which is the definition of qa: the result is exact whatever the estimate's last bits, so it does
// not depend on how a device rounds the estimate. Then a guard bit (2 rem' >= Mb) and the sticky bit
// (2 rem' - guard Mb != 0) give q = floor(Ma 2^(k+1)/Mb) in [2^24, 2^25) and whether a tail remains:
// xmRoundPack rounds that exactly, subnormal and overflowing quotients included. Every float
// operand and result is in [2^-25, 2^25], never subnormal: the same bits in flushing stages.
// This replaces a 26-step restoring division (issue 19 item 5; docs/RESULTS.md "Exact-math rework"):
// 164 counted operations per division instead of 282, 101 per square root instead of 371. It is
// Markstein's estimate-and-correct scheme with the residual formed by integers instead of an fma or
// Dekker's two-product.
//
// Derivation (square root). x = Mx 2^(e-23); with c = e & 1 let N = Mx 2^(23+c) in [2^46, 2^48), so
// sqrt(x) = sqrt(N) 2^E with E = (e - 46 - c)/2 and r = floor(sqrt(N)) in [2^23, 2^24). Estimate from
// an inverse-square-root seed and three Newton steps on n = N 2^-46 in [1, 4) (relative error below
// 2^-22.5, so within 4 of the root; measured over every input class: -3..+4); the exact residual
// rem = N - r^2 (|rem| < 2^28: again exact in wrapping 32-bit arithmetic), one refinement
// floor(rem / 2 sqrt(N)) and one correction each way give rem in [0, 2r]. sqrt(N) >= r + 1/2 iff
// rem > r (integers; sqrt(N) = r + 1/2 is impossible, so there are no ties), and a square root of a
// float is always a normal float, so the result's bits are ((E + 149) << 23) + r + [rem > r]: the
// carry of r + 1 = 2^24 into the exponent field comes out of the addition.

// 1/d for d in [1, 2.5]: bit-trick seed (relative error <= 0.051), three Newton steps x(2 - dx)
// (mul/sub only); relative error below 2^-22.6 (tests/exact_math_test.cpp: every float in [1, 2.5]).
Float xmRcpApprox(Float d) {
  PRECISE Float x = uintBitsToFloat(0x7ef311c3u - floatBitsToUint(d));
  x = x * (2.0f - d * x);
  x = x * (2.0f - d * x);
  x = x * (2.0f - d * x);
  return x;
}

// 1/sqrt(n) for n in [1, 4]: bit-trick seed, three Newton steps y(3/2 - (n/2) y^2); relative error
// below 2^-22.5 (tests/exact_math_test.cpp: every float in [1, 4]).
Float xmRsqrtApprox(Float n) {
  PRECISE Float h = 0.5f * n;
  PRECISE Float y = uintBitsToFloat(0x5f3759dfu - (floatBitsToUint(n) >> 1u));
  y = y * (1.5f - h * (y * y));
  y = y * (1.5f - h * (y * y));
  y = y * (1.5f - h * (y * y));
  return y;
}

Float exDivPortable(Float a, Float b) {
  Uint ua = floatBitsToUint(a);
  Uint ub = floatBitsToUint(b);
  Uint sign = (ua ^ ub) & 0x80000000u;
  Uint aa = ua & 0x7fffffffu;
  Uint ab = ub & 0x7fffffffu;
  Mask aNan = aa > 0x7f800000u;
  Mask bNan = ab > 0x7f800000u;
  Mask aInf = aa == 0x7f800000u;
  Mask bInf = ab == 0x7f800000u;
  Mask aZero = aa == 0u;
  Mask bZero = ab == 0u;
  XmUnpacked A = xmUnpack(select(aZero || aa >= 0x7f800000u, 0x3f800000u, aa));
  XmUnpacked B = xmUnpack(select(bZero || ab >= 0x7f800000u, 0x3f800000u, ab));
  PRECISE Float an = uintBitsToFloat((A.m & 0x007fffffu) | 0x3f800000u);  // Ma 2^-23 in [1, 2)
  PRECISE Float bn = uintBitsToFloat((B.m & 0x007fffffu) | 0x3f800000u);
  PRECISE Float rcp = xmRcpApprox(bn);
  Mask below = A.m < B.m;
  Uint k = select(below, 24u, 23u);
  PRECISE Float t = (an * rcp) * select(below, 16777216.0f, 8388608.0f);
  Uint q = Uint(Int(floor(t)));
  Uint num = A.m << k;  // low 32 bits of Ma 2^k
  Int rem = Int(num - q * B.m);
  PRECISE Float est = (Float(rem) * rcp) * 1.1920928955078125e-07f;  // rem / Mb (2^-23 R)
  Int d = Int(floor(est));
  q = Uint(Int(q) + d);
  rem = Int(num - q * B.m);
  Mask low = rem < 0;
  q = select(low, q - 1u, q);
  rem = select(low, rem + Int(B.m), rem);
  Mask high = rem >= Int(B.m);
  q = select(high, q + 1u, q);
  rem = select(high, rem - Int(B.m), rem);
  Uint rem2 = Uint(rem) << 1u;
  Mask guard = rem2 >= B.m;
  rem2 = select(guard, rem2 - B.m, rem2);
  Uint r = xmRoundPack(sign, (q << 1u) | select(guard, 1u, 0u), A.e - B.e - Int(k) - 1, rem2 != 0u);
  r = select(aZero || bInf, sign, r);
  r = select(aInf || bZero, sign | 0x7f800000u, r);
  r = select(aNan || bNan || (aZero && bZero) || (aInf && bInf), 0x7fc00000u, r);
  return uintBitsToFloat(r);
}

Float exSqrtPortable(Float x) {
  Uint ux = floatBitsToUint(x);
  Uint ax = ux & 0x7fffffffu;
  Mask nan = ax > 0x7f800000u || ux > 0x80000000u;  // NaN, or negative non-zero (incl. -inf)
  Mask keep = ax == 0u || ux == 0x7f800000u;       // sqrt(+-0) = +-0, sqrt(+inf) = +inf
  XmUnpacked X = xmUnpack(select(keep || nan, 0x3f800000u, ax));
  Int c = X.e & 1;
  Mask odd = c != 0;
  Uint n = X.m << Uint(23 + c);  // low 32 bits of N = Mx 2^(23+c)
  PRECISE Float nf = uintBitsToFloat((X.m & 0x007fffffu) | select(odd, 0x40000000u, 0x3f800000u));  // N 2^-46
  PRECISE Float y = xmRsqrtApprox(nf);
  PRECISE Float t = (nf * y) * 8388608.0f;  // ~ sqrt(N)
  Uint r = Uint(Int(floor(t)));
  Int rem = Int(n - r * r);
  PRECISE Float est = (Float(rem) * y) * 5.9604644775390625e-08f;  // rem / (2 sqrt(N)): 2^-24 y
  r = Uint(Int(r) + Int(floor(est)));
  rem = Int(n - r * r);
  Mask low = rem < 0;
  rem = select(low, rem + Int(r << 1u) - 1, rem);
  r = select(low, r - 1u, r);
  Mask high = rem > Int(r << 1u);
  rem = select(high, rem - Int(r << 1u) - 1, rem);
  r = select(high, r + 1u, r);
  Int E = (X.e - 46 - c) >> 1;
  Uint res = (Uint(E + 149) << 23u) + r + select(rem > Int(r), 1u, 0u);
  res = select(keep, ux, res);
  res = select(nan, 0x7fc00000u, res);
  return uintBitsToFloat(res);
}

Float exDiv(Float a, Float b) {
  NativeResult fast = nativeDiv(a, b);  // C++ builds only: same bits where every lane is normal
  if (fast.ok) return fast.value;
  return exDivPortable(a, b);
}

Float exSqrt(Float x) {
  NativeResult fast = nativeSqrt(x);
  if (fast.ok) return fast.value;
  return exSqrtPortable(x);
}

// 1/sqrt(x) as two correctly rounded steps (<= 1 ulp). -0 -> -inf, +0 -> +inf, +inf -> +0.
Float exInverseSqrt(Float x) { return exDiv(1.0f, exSqrt(x)); }

// v / |v|, scaled by a power of two first so that no component overflows or underflows in the dot.
// A zero (or, in a flushing stage, denormal-only) vector gives NaN, as GPUs' normalize does.
// Every exact-math function returns the canonical NaN 0x7fc00000 for NaN results.
Float3 exNormalize(Float3 v) {
  PRECISE Float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
  Int eb = Int(floatBitsToUint(m) >> 23u);
  Float s = uintBitsToFloat(Uint(clamp(254 - eb, 1, 254)) << 23u);  // 2^(127-eb), exact
  PRECISE Float3 u = v * s;
  PRECISE Float r = exInverseSqrt(dot(u, u));
  PRECISE Float3 n = u * r;
  // NaN payloads depend on operand order (x86 and GPUs alike): return the one canonical NaN.
  Mask nan = n.x != n.x || n.y != n.y || n.z != n.z;
  return select(nan, Float3(uintBitsToFloat(0x7fc00000u)), n);
}

// ---------------------------------------------------------------------------------------------
// Error-free transformations (no fma): Knuth's TwoSum, Veltkamp's split, Dekker's product.

struct XmFF {
  Float hi;
  Float lo;
};

XmFF xmTwoSum(Float a, Float b) {
  PRECISE Float s = a + b;
  PRECISE Float bb = s - a;
  PRECISE Float e = (a - (s - bb)) + (b - bb);
  return XmFF(s, e);
}

XmFF xmSplit(Float a) {  // a = hi + lo, each with at most 12 significant bits (|a| < 2^115)
  PRECISE Float c = a * 4097.0f;
  PRECISE Float hi = c - (c - a);
  return XmFF(hi, a - hi);
}

XmFF xmTwoProduct(Float a, Float b) {  // a*b = hi + lo exactly (no overflow or underflow)
  PRECISE Float p = a * b;
  XmFF A = xmSplit(a);
  XmFF B = xmSplit(b);
  PRECISE Float e = (((A.hi * B.hi - p) + A.hi * B.lo) + A.lo * B.hi) + A.lo * B.lo;
  return XmFF(p, e);
}

// ---------------------------------------------------------------------------------------------
// exp2, exp: reduce x = n + f (|f| <= 1/2), polynomial for 2^f / e^r, scale by 2^n in two exact
// steps so that the only rounding of the scaling is the last multiply (which also produces
// subnormals and overflow correctly). Polynomials: Taylor series of 2^f and e^r truncated where
// the next term is below 2^-30 of the result (|f ln2| <= 0.347).

Float xmExp2Poly(Float f) {  // 2^f, |f| <= 0.55, degree 8
  PRECISE Float p = 1.32154867e-06f;
  p = p * f + 1.52527336e-05f;
  p = p * f + 0.000154035297f;
  p = p * f + 0.00133335579f;
  p = p * f + 0.00961812865f;
  p = p * f + 0.0555041097f;
  p = p * f + 0.240226507f;
  p = p * f + 0.693147182f;
  return 1.0f + p * f;
}

Float xmExpPoly(Float r) {  // e^r, |r| <= 0.36, degree 8
  PRECISE Float p = 2.48015876e-05f;
  p = p * r + 0.000198412701f;
  p = p * r + 0.00138888892f;
  p = p * r + 0.00833333377f;
  p = p * r + 0.0416666679f;
  p = p * r + 0.166666672f;
  p = p * r + 0.5f;
  PRECISE Float q = r + (r * r) * p;
  return 1.0f + q;
}

Float xmScale2(Float p, Float n) {  // p * 2^n for integral n in [-254, 254], one rounding
  Int ni = Int(n);
  Int n1 = ni >> 1;
  Int n2 = ni - n1;
  PRECISE Float t = p * uintBitsToFloat(Uint(n1 + 127) << 23u);
  return t * uintBitsToFloat(Uint(n2 + 127) << 23u);
}

Float exExp2(Float x) {
  Mask nan = x != x;
  PRECISE Float xc = clamp(select(nan, 0.0f, x), -160.0f, 160.0f);
  PRECISE Float n = floor(xc + 0.5f);
  PRECISE Float r = xmScale2(xmExp2Poly(xc - n), n);
  return select(nan, x, r);
}

Float exExp(Float x) {
  Mask nan = x != x;
  PRECISE Float xc = clamp(select(nan, 0.0f, x), -110.0f, 100.0f);
  PRECISE Float n = floor(xc * 1.44269502f + 0.5f);
  // Cody-Waite: ln2 = 0.693145751953125 (15 bits, so n*hi is exact) + 1.42860677e-06.
  PRECISE Float r = (xc - n * 0.693145751953125f) - n * 1.42860677e-06f;
  PRECISE Float v = xmScale2(xmExpPoly(r), n);
  return select(nan, x, v);
}

// ---------------------------------------------------------------------------------------------
// log2, log: x = m 2^e with m in [sqrt(1/2), sqrt(2)], ln m = 2 atanh(t), t = (m-1)/(m+1) (one exact
// division, |t| <= 0.1716), series 2t(1 + t^2/3 + t^4/5 + t^6/7 + t^8/9) (next term < 2^-33).

struct XmLogParts {
  Float e;      // exponent, exact
  Float lnmHi;  // ln(m) = lnmHi + lnmLo (float-float)
  Float lnmLo;
  Mask nan;     // x < 0 or NaN
  Mask zero;    // x == 0 (or flushed)
  Mask inf;     // x == +inf
};

// Derivation: ln m = 2 atanh t, t = (m-1)/(m+1). t = tHi + tLo with tHi = exDiv(m-1, m+1) and
// tLo = (m - 1 - tHi (m+1)) / (m+1), the residual formed exactly (m+1 as a TwoSum, tHi times it by
// Dekker), so ln m = 2 tHi + (2 tLo + 2 tHi w Q(w)) carries ~40 bits; Q's rounding is scaled by w <= 0.03.
XmLogParts xmLogParts(Float x) {
  Uint ux = floatBitsToUint(x);
  Mask nan = x != x || ux > 0x80000000u;
  Mask zero = x == 0.0f;
  Mask inf = ux == 0x7f800000u;
  PRECISE Float xs = select(nan || zero || inf, 1.0f, x);
  Mask sub = xs < 1.17549435e-38f;
  PRECISE Float xn = select(sub, xs * 16777216.0f, xs);  // normalise denormals (flushed where the stage flushes)
  Uint u = floatBitsToUint(xn);
  Uint mb = (u & 0x007fffffu) | 0x3f800000u;
  Mask big = mb > 0x3fb504f3u;  // m > sqrt(2): halve m
  Int e = Int(u >> 23u) - 127 - select(sub, 24, 0) + select(big, 1, 0);
  PRECISE Float m = uintBitsToFloat(select(big, mb - 0x00800000u, mb));
  PRECISE Float num = m - 1.0f;  // exact (Sterbenz)
  XmFF den = xmTwoSum(m, 1.0f);
  PRECISE Float tHi = exDiv(num, den.hi);
  XmFF p = xmTwoProduct(tHi, den.hi);
  PRECISE Float r = ((num - p.hi) - p.lo) - tHi * den.lo;
  PRECISE Float tLo = r * xmRcpApprox(den.hi);
  PRECISE Float w = tHi * tHi;
  PRECISE Float q = w * (0.333333343f + w * (0.200000003f + w * (0.142857149f + w * 0.111111112f)));
  PRECISE Float hi = tHi + tHi;
  PRECISE Float lo = (tLo + tLo) + hi * q;
  XmFF l = xmTwoSum(hi, lo);
  return XmLogParts(Float(e), l.hi, l.lo, nan, zero, inf);
}

// log2(m) = ln(m) * log2(e) as a float-float product; log2 e = 1.44269502 + 1.92596303e-08.
XmFF xmLog2m(XmLogParts L) {
  XmFF p = xmTwoProduct(L.lnmHi, 1.44269502f);
  PRECISE Float lo = p.lo + (L.lnmHi * 1.92596303e-08f + L.lnmLo * 1.44269502f);
  return xmTwoSum(p.hi, lo);
}

Float xmLogSpecial(XmLogParts L, Float v) {
  PRECISE Float r = select(L.zero, uintBitsToFloat(0xff800000u), v);
  r = select(L.inf, uintBitsToFloat(0x7f800000u), r);
  return select(L.nan, uintBitsToFloat(0x7fc00000u), r);
}

Float exLog2(Float x) {
  XmLogParts L = xmLogParts(x);
  XmFF l2 = xmLog2m(L);
  XmFF s = xmTwoSum(L.e, l2.hi);
  PRECISE Float v = s.hi + (s.lo + l2.lo);
  return xmLogSpecial(L, v);
}

Float exLog(Float x) {
  XmLogParts L = xmLogParts(x);
  // ln x = e ln2 + ln m, ln2 = 0.693145751953125 (15 bits: e * hi is exact) + 1.42860677e-06
  XmFF s = xmTwoSum(L.e * 0.693145751953125f, L.lnmHi);
  PRECISE Float v = s.hi + (s.lo + (L.lnmLo + L.e * 1.42860677e-06f));
  return xmLogSpecial(L, v);
}

// pow(x, y) = 2^(y log2 x) for x >= 0 (x < 0 gives NaN; GLSL leaves it undefined); zero bases as C99.
// y*e is formed exactly (Veltkamp split of y times the small integer e), y*log2(m) as a Dekker product
// of y with the float-float log2(m), so the exponent y log2 x carries ~40 bits and the error does not
// grow with |y log2 x| until the result over- or underflows.
Float exPow(Float x, Float y) {
  XmLogParts L = xmLogParts(x);
  PRECISE Float yc = clamp(select(y != y, 0.0f, y), -4294967296.0f, 4294967296.0f);
  XmFF Y = xmSplit(yc);
  XmFF l2 = xmLog2m(L);
  XmFF C = xmTwoProduct(yc, l2.hi);
  XmFF S = xmTwoSum(Y.hi * L.e, C.hi);
  PRECISE Float n = floor(clamp(S.hi, -300.0f, 300.0f) + 0.5f);
  PRECISE Float f = ((S.hi - n) + S.lo) + ((Y.lo * L.e + C.lo) + yc * l2.lo);
  PRECISE Float v = xmScale2(xmExp2Poly(clamp(f, -0.6f, 0.6f)), clamp(n, -254.0f, 254.0f));
  Float inf = uintBitsToFloat(0x7f800000u);
  // C99 for a zero base: +-0 or +-inf, negative only for x = -0 and an odd integer y.
  Mask oddInt = abs(y) < 16777216.0f && floor(y) == y && (Int(y) & 1) != 0;
  Float zeroPow = select(y < 0.0f, inf, 0.0f);
  zeroPow = select(floatBitsToUint(x) == 0x80000000u && oddInt, -zeroPow, zeroPow);
  v = select(L.zero, zeroPow, v);
  v = select(L.inf, select(y < 0.0f, 0.0f, inf), v);
  v = select(L.nan || y != y, uintBitsToFloat(0x7fc00000u), v);
  return select(y == 0.0f || x == 1.0f, 1.0f, v);
}

// ---------------------------------------------------------------------------------------------
// sin, cos: Payne-Hanek reduction for every argument (one path, uniform across lanes).
//
// |x| = M 2^j (M: 24-bit integer). y = |x| 2/pi; only y mod 4 and frac(y) matter. Bits of 2/pi
// above position j-2 contribute multiples of 4 and are skipped; the next 96 bits W (taken from the
// table with two leading zero words, so small j needs no special case) give P = M W, a 120-bit
// integer with y = P 2^-94 + (error < 2^-70). Quadrant = bits 94..95 (+1 if frac >= 1/2), the
// 64 fraction bits become a float-float times pi/2, then Taylor polynomials on [-pi/4, pi/4].
// |x| < 2^-12 returns x (sin) and 1 (cos), which are the correctly rounded values there.

Uint xmTwoOverPiWord(Int k) {  // 32-bit words of 2/pi, after two zero words
  Uint w = 0u;
  w = select(k == 2, 0xa2f9836eu, w);
  w = select(k == 3, 0x4e441529u, w);
  w = select(k == 4, 0xfc2757d1u, w);
  w = select(k == 5, 0xf534ddc0u, w);
  w = select(k == 6, 0xdb629599u, w);
  w = select(k == 7, 0x3c439041u, w);
  w = select(k == 8, 0xfe5163abu, w);
  return w;
}

struct XmTrigReduced {
  Float hi;  // r = hi + lo in [-pi/4, pi/4]
  Float lo;
  Uint q;    // quadrant: |x| = r + q pi/2 (mod 2 pi)
};

XmTrigReduced xmTrigReduce(Float ax) {  // ax finite, >= 2^-12
  Uint u = floatBitsToUint(ax);
  Uint M = (u & 0x007fffffu) | 0x00800000u;
  Int j = Int(u >> 23u) - 150;
  Int g = j + 62;  // first window bit, counted from the top of the zero-padded table
  Int k = g >> 5;
  Uint sh = Uint(g & 31);
  Uint t0 = xmTwoOverPiWord(k);
  Uint t1 = xmTwoOverPiWord(k + 1);
  Uint t2 = xmTwoOverPiWord(k + 2);
  Uint t3 = xmTwoOverPiWord(k + 3);
  Uint w0 = (t0 << sh) | ((t1 >> 1u) >> (31u - sh));
  Uint w1 = (t1 << sh) | ((t2 >> 1u) >> (31u - sh));
  Uint w2 = (t2 << sh) | ((t3 >> 1u) >> (31u - sh));
  // P = M * (w0:w1:w2), limbs L2:L1:L0 (the limb above only holds multiples of 4).
  Uint L0 = M * w2;
  Uint L1a = M * w1;
  Uint L1 = L1a + mulHi(M, w2);
  Uint L2 = M * w0 + mulHi(M, w1) + select(L1 < L1a, 1u, 0u);
  Uint fhi = (L2 << 2u) | (L1 >> 30u);
  Uint flo = (L1 << 2u) | (L0 >> 30u);
  Mask up = fhi >= 0x80000000u;  // frac >= 1/2: next quadrant, negative remainder
  Uint nlo = ~flo + 1u;
  Uint nhi = ~fhi + select(flo == 0u, 1u, 0u);
  Uint mhi = select(up, nhi, fhi);
  Uint mlo = select(up, nlo, flo);
  Uint q = ((L2 >> 30u) + select(up, 1u, 0u)) & 3u;
  // |frac| = mhi 2^-32 + mlo 2^-64 as the exact sum of three floats, then float-float.
  PRECISE Float a = Float(mhi >> 8u) * 5.96046448e-08f;
  PRECISE Float b = Float(((mhi & 0xffu) << 16u) | (mlo >> 16u)) * 3.55271368e-15f;
  PRECISE Float c = Float(mlo & 0xffffu) * 5.42101086e-20f;
  PRECISE Float s = a + b;
  PRECISE Float e1 = (b - (s - a)) + c;
  PRECISE Float fh = s + e1;
  PRECISE Float fl = e1 - (fh - s);
  // r = frac * pi/2, pi/2 = 1.57079637 - 4.37113883e-08
  XmFF P = xmTwoProduct(fh, 1.57079637f);
  PRECISE Float rl = P.lo + (fh * -4.37113883e-08f + fl * 1.57079637f);
  PRECISE Float rh = P.hi + rl;
  rl = rl - (rh - P.hi);
  return XmTrigReduced(select(up, -rh, rh), select(up, -rl, rl), q);
}

Float xmSinPoly(Float rh, Float rl) {  // sin(rh + rl), |r| <= pi/4
  PRECISE Float w = rh * rh;
  PRECISE Float p = w * (-0.166666672f + w * (0.00833333377f + w * (-0.000198412701f + w * (2.75573188e-06f + w * -2.50521079e-08f))));
  return rh + (rh * p + (rl - rl * (0.5f * w)));
}

Float xmCosPoly(Float rh, Float rl) {  // cos(rh + rl), |r| <= pi/4
  PRECISE Float w = rh * rh;
  PRECISE Float hz = 0.5f * w;
  PRECISE Float one = 1.0f - hz;
  PRECISE Float p = (w * w) * (0.0416666679f + w * (-0.00138888892f + w * (2.48015876e-05f + w * (-2.755732e-07f + w * 2.08767559e-09f))));
  return one + (((1.0f - one) - hz) + (p - rh * rl));
}

struct XmSinCos {
  Float s;
  Float c;
};

XmSinCos exSinCos(Float x) {
  Uint ux = floatBitsToUint(x);
  Uint ax = ux & 0x7fffffffu;
  Mask bad = ax >= 0x7f800000u;
  Mask tiny = ax < 0x39800000u;  // 2^-12
  XmTrigReduced R = xmTrigReduce(uintBitsToFloat(select(bad || tiny, 0x3f800000u, ax)));
  PRECISE Float s = xmSinPoly(R.hi, R.lo);
  PRECISE Float c = xmCosPoly(R.hi, R.lo);
  Mask swap = (R.q & 1u) != 0u;
  PRECISE Float sv = select(swap, c, s);
  sv = select((R.q & 2u) != 0u, -sv, sv);
  sv = uintBitsToFloat(floatBitsToUint(sv) ^ (ux & 0x80000000u));
  PRECISE Float cv = select(swap, s, c);
  cv = select(((R.q + 1u) & 2u) != 0u, -cv, cv);
  Float nan = uintBitsToFloat(0x7fc00000u);
  sv = select(bad, nan, select(tiny, x, sv));
  cv = select(bad, nan, select(tiny, 1.0f, cv));
  return XmSinCos(sv, cv);
}

// sin(2 pi u), cos(2 pi u) for finite u (sample angles): u = k/4 + f exactly (|f| <= 1/8), 2 pi f as
// a float-float, the same polynomials on |r| <= pi/4, then the quadrant k mod 4. No Payne-Hanek.
XmSinCos exSinCos2Pi(Float u) {
  PRECISE Float k = floor(u * 4.0f + 0.5f);
  PRECISE Float f = u - k * 0.25f;
  Uint q = Uint(Int(k)) & 3u;
  XmFF P = xmTwoProduct(f, 6.28318548f);
  PRECISE Float rl = P.lo + f * -1.74845553e-07f;  // 2 pi - float(2 pi)
  PRECISE Float rh = P.hi + rl;
  rl = rl - (rh - P.hi);
  PRECISE Float s = xmSinPoly(rh, rl);
  PRECISE Float c = xmCosPoly(rh, rl);
  Mask swap = (q & 1u) != 0u;
  PRECISE Float sv = select(swap, c, s);
  sv = select((q & 2u) != 0u, -sv, sv);
  PRECISE Float cv = select(swap, s, c);
  cv = select(((q + 1u) & 2u) != 0u, -cv, cv);
  return XmSinCos(sv, cv);
}

Float exSin(Float x) { return exSinCos(x).s; }
Float exCos(Float x) { return exSinCos(x).c; }

// ---------------------------------------------------------------------------------------------
// atan2, acos. atan2 reduces to t = mn/mx in [0, 1], then to t' = (mn-mx)/(mn+mx) in [-1/3, 0] when
// mn >= mx/2 (mn - mx is then exact by Sterbenz), so one exact division and a Taylor series on
// |t| <= 1/2 (12 terms, next < 2^-27 relative). Quadrant and sign fix-ups follow C99 atan2,
// including signed zeros and infinities.

Float xmAtanPoly(Float t) {  // atan(t), |t| <= 1/2
  PRECISE Float w = t * t;
  PRECISE Float p = -0.0434782617f;
  p = p * w + 0.0476190485f;
  p = p * w + -0.0526315793f;
  p = p * w + 0.0588235296f;
  p = p * w + -0.0666666701f;
  p = p * w + 0.0769230798f;
  p = p * w + -0.0909090936f;
  p = p * w + 0.111111112f;
  p = p * w + -0.142857149f;
  p = p * w + 0.200000003f;
  p = p * w + -0.333333343f;
  return t + t * (w * p);
}

Float exAtan2(Float y, Float x) {
  Uint uy = floatBitsToUint(y);
  Uint ux = floatBitsToUint(x);
  Mask nan = x != x || y != y;
  PRECISE Float ax = abs(x);
  PRECISE Float ay = abs(y);
  Mask bothInf = ax == uintBitsToFloat(0x7f800000u) && ay == uintBitsToFloat(0x7f800000u);
  ax = select(bothInf || nan, 1.0f, ax);
  ay = select(bothInf || nan, 1.0f, ay);
  Mask swap = ay > ax;
  PRECISE Float mx = max(ax, ay);
  PRECISE Float mn = min(ax, ay);
  Mask huge = mx > 1.0e38f;  // keep mn + mx finite
  mx = select(huge, mx * 0.25f, mx);
  mn = select(huge, mn * 0.25f, mn);
  Mask zero = mx == 0.0f;
  Mask big = mn + mn >= mx && !zero;  // 2 mn is exact (0.5 mx would round for denormal mx)
  PRECISE Float num = select(big, mn - mx, mn);
  PRECISE Float den = select(big, mn + mx, select(zero, 1.0f, mx));
  PRECISE Float a = xmAtanPoly(exDiv(num, den));
  // pi/4 = 0.785398185 - 2.18556941e-08, pi/2 = 1.57079637 - 4.37113883e-08,
  // pi = 3.14159274 - 8.74227766e-08
  PRECISE Float r = select(big, 0.785398185f + (a + -2.18556941e-08f), a);
  r = select(swap, 1.57079637f + (-4.37113883e-08f - r), r);
  r = select((ux & 0x80000000u) != 0u, 3.14159274f + (-8.74227766e-08f - r), r);
  r = uintBitsToFloat((floatBitsToUint(r) & 0x7fffffffu) | (uy & 0x80000000u));
  return select(nan, uintBitsToFloat(0x7fc00000u), r);
}

// acos(x) = atan2(sqrt((1-x)(1+x)), x); |x| > 1 or NaN gives NaN.
Float exAcos(Float x) {
  PRECISE Float s = exSqrt((1.0f - x) * (1.0f + x));
  PRECISE Float r = exAtan2(s, x);
  return select(abs(x) > 1.0f, uintBitsToFloat(0x7fc00000u), r);
}
