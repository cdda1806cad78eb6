// MIP chain generation, shared by the C++ builds and the GPU (src/shaders/mip_downsample.glsl), so
// both produce the same bits for every level.
//
// Filter: separable polyphase box (the exact area average of the source footprint of each
// destination texel). Destination size n' = max(1, n >> 1).
//   n even:  dst x = (src 2x + src 2x+1) / 2                  weights 1/2, 1/2
//   n odd:   dst x covers src [2x, 2x+3) partially, n' = (n-1)/2:
//            weights (n'-x)/n, n'/n, (x+1)/n  (they sum to 1; each exDiv-rounded)
//   n == 1:  the texel itself
// Taps with weight 0 are not read, so an inf/NaN neighbour does not leak into a texel.

struct MipTaps {
  Int i0;    // first source texel
  Float w0;  // weights of i0, i0+1, i0+2
  Float w1;
  Float w2;
};

MipTaps mipTaps(Int x, Int srcSize) {
  Int n2 = srcSize >> 1;
  Mask odd = (srcSize & 1) != 0;
  Float n = Float(srcSize);
  PRECISE Float a = exDiv(Float(n2 - x), n);
  PRECISE Float b = exDiv(Float(n2), n);
  PRECISE Float c = exDiv(Float(x + 1), n);
  Mask one = srcSize == 1;
  MipTaps t = MipTaps(2 * x, select(odd, a, 0.5f), select(odd, b, 0.5f), select(odd, c, 0.0f));
  t.i0 = select(one, 0, t.i0);
  t.w0 = select(one, 1.0f, t.w0);
  t.w1 = select(one, 0.0f, t.w1);
  t.w2 = select(one, 0.0f, t.w2);
  return t;
}

// Weighted sum of three taps in a fixed order; zero-weight taps contribute exactly nothing.
Float4 mipCombine(Float4 p, Float4 q, Float4 r, MipTaps t) {
  PRECISE Float4 s = p * t.w0;
  s = select(t.w1 != 0.0f, s + q * t.w1, s);
  s = select(t.w2 != 0.0f, s + r * t.w2, s);
  return s;
}
