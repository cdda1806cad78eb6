// Kernels of `shadetwin verify math`: one shared entry that evaluates exact-math function `fn` on
// (a, b, c). The GLSL entry (src/shaders/verify_math.glsl) and the C++ scalar and SIMD builds all
// call this, so the three builds run the same source. `fn` is uniform (a push constant).
const int kMathDiv = 0;
const int kMathSqrt = 1;
const int kMathInverseSqrt = 2;
const int kMathNormalize = 3;
const int kMathExp = 4;
const int kMathExp2 = 5;
const int kMathLog = 6;
const int kMathLog2 = 7;
const int kMathPow = 8;
const int kMathSin = 9;
const int kMathCos = 10;
const int kMathAtan2 = 11;
const int kMathAcos = 12;
const int kMathCount = 13;

Float3 evalMath(int fn, Float3 v) {
  PRECISE Float3 r = Float3(0.0f);
  if (fn == kMathDiv) r = Float3(exDiv(v.x, v.y), 0.0f, 0.0f);
  if (fn == kMathSqrt) r = Float3(exSqrt(v.x), 0.0f, 0.0f);
  if (fn == kMathInverseSqrt) r = Float3(exInverseSqrt(v.x), 0.0f, 0.0f);
  if (fn == kMathNormalize) r = exNormalize(v);
  if (fn == kMathExp) r = Float3(exExp(v.x), 0.0f, 0.0f);
  if (fn == kMathExp2) r = Float3(exExp2(v.x), 0.0f, 0.0f);
  if (fn == kMathLog) r = Float3(exLog(v.x), 0.0f, 0.0f);
  if (fn == kMathLog2) r = Float3(exLog2(v.x), 0.0f, 0.0f);
  if (fn == kMathPow) r = Float3(exPow(v.x, v.y), 0.0f, 0.0f);
  if (fn == kMathSin) r = Float3(exSin(v.x), 0.0f, 0.0f);
  if (fn == kMathCos) r = Float3(exCos(v.x), 0.0f, 0.0f);
  if (fn == kMathAtan2) r = Float3(exAtan2(v.x, v.y), 0.0f, 0.0f);
  if (fn == kMathAcos) r = Float3(exAcos(v.x), 0.0f, 0.0f);
  return r;
}
