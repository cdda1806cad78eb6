// SH visibility from shadow maps (issue 16): the paper's second half, "filtered importance sampling
// with visibility" — Krivanek & Colbert, "Real-time Shading with Filtered Importance Sampling"
// (EGSR 2008), s5.2, after the GPU Gems 3 chapter 20 "GPU-Based Importance Sampling" (Colbert &
// Krivanek 2007): visibility is sampled in K directions omega_k drawn from the environment's luminance,
// one orthographic shadow map each, and fitted per pixel by an order-4 SH (16 coefficients) in the
// least-squares sense.
//
// Derivation of the fit: with Y the K x 16 matrix Y_ki = y_i(omega_k) and V_k the visibility sample
// (V alone, or V max(0, n . omega_k): the paper's choice, fewer ringing artefacts, and the diffuse term
// becomes a dot product of SH vectors), the coefficients minimising sum_k (sum_i c_i y_i(omega_k) -
// V_k)^2 solve the normal equations M c = Y^T V, M = Y^T Y (16 x 16). The directions are the same for
// every pixel, so the host forms M and its regularised pseudo-inverse M+ once per frame
// (inputs/visibility.h: eigenvalue filter lambda / (lambda^2 + mu^2), mu = 1e-4 lambda_max, which is
// the Moore-Penrose inverse as mu -> 0 and finite for K < 16 or coincident directions), and per pixel
// only c = sum_k w_k V_k with w_k = M+ y(omega_k), the K weight vectors, summed in k order (k = 0
// first), so every build adds the same floats in the same order.
//
// Real SH basis of order 4: shade/sh16.h. Any orthonormal basis gives the same fit.
//
// Shadow test of map k at the world point p (the G-buffer's position), unit normal n: the map's
// light matrix (passes/shadow.h shadowViewProjection, orthographic, w = 1) gives clip (x, y, z);
// texel (floor(x S/2 + S/2), floor(y S/2 + S/2)) clamped to the map (the rasterizer's viewport: row
// 0 at y = -1); lit when z - bias <= the stored depth (the map stores the depth nearest the light).
// Bias = constant + slope-scaled: b0 + b1 min(tan theta, 10), tan theta = sqrt(1 - c^2) / max(|c|,
// 0.1), c = n . omega_k (acne needs more bias at grazing light; the cap keeps peter-panning bounded).

const uint kVisFitVCos = 0u;  // fit V(omega) max(0, n . omega)
const uint kVisFitV = 1u;     // fit V(omega) alone

// Uniform settings of the fit (host: inputs/visibility.h VisibilitySettings).
struct VisSettings {
  uint count;       // K maps (layers of the map array, rows of the data table)
  uint size;        // S: each map is S x S
  uint fit;         // kVisFit*
  float biasConst;  // b0, depth units
  float biasSlope;  // b1, depth units per unit of tan theta
};

// The visibility sample of map k (uniform) at p, unit normal n: 1 or 0 (kVisFitV), times
// max(0, n . omega_k) (kVisFitVCos). data row k: texels 0-3 the light matrix's columns, 4 omega_k.
Float visSample(Sampler2DArray maps, Sampler2D data, VisSettings s, int k, Float3 p, Float3 n) {
  Int row = Int(k);
  Float4 m0 = texelFetch2D(data, Int(0), row, 0);
  Float4 m1 = texelFetch2D(data, Int(1), row, 0);
  Float4 m2 = texelFetch2D(data, Int(2), row, 0);
  Float4 m3 = texelFetch2D(data, Int(3), row, 0);
  Float4 w = texelFetch2D(data, Int(4), row, 0);
  Float4 clip = xformPoint(m0, m1, m2, m3, p);
  PRECISE Float halfSize = 0.5f * float(s.size);
  Int last = Int(int(s.size) - 1);
  Int tx = clamp(Int(floor(clip.x * halfSize + halfSize)), Int(0), last);
  Int ty = clamp(Int(floor(clip.y * halfSize + halfSize)), Int(0), last);
  Float depth = texelFetchLayer(maps, tx, ty, row, 0).x;
  PRECISE Float c = dot(n, Float3(w.x, w.y, w.z));
  PRECISE Float tanTheta = exDiv(exSqrt(max(1.0f - c * c, 0.0f)), max(abs(c), 0.1f));
  PRECISE Float bias = s.biasConst + s.biasSlope * min(tanTheta, 10.0f);
  Mask lit = clip.z - bias <= depth;
  Float weight = select(s.fit == kVisFitV, Float(1.0f), max(c, 0.0f));
  return select(lit, weight, Float(0.0f));
}

// The per-pixel fit c = sum_k w_k V_k (k = 0 first); data row k, texels 5-8: w_k = M+ y(omega_k).
// nIn: the G-buffer's interpolated normal (normalised here).
Sh16 visFit(Sampler2DArray maps, Sampler2D data, VisSettings s, Float3 p, Float3 nIn) {
  Float3 n = exNormalize(nIn);
  Float4 zero = Float4(0.0f, 0.0f, 0.0f, 0.0f);
  Sh16 acc = Sh16(zero, zero, zero, zero);
  for (int k = 0; k < int(s.count); k++) {
    Int row = Int(k);
    Float v = visSample(maps, data, s, k, p, n);
    Sh16 wk = Sh16(texelFetch2D(data, Int(5), row, 0), texelFetch2D(data, Int(6), row, 0),
                   texelFetch2D(data, Int(7), row, 0), texelFetch2D(data, Int(8), row, 0));
    acc = sh16AddScaled(acc, wk, v);
  }
  return acc;
}
