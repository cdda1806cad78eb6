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
// (inputs/visibility.h: eigenvalue filter lambda / (lambda^2 + mu^2), the Moore-Penrose inverse as
// mu -> 0, finite for K < 16 or coincident directions).
// Regularisation towards the unoccluded transfer t (a prior, documented): luminance-sampled directions
// cluster around the bright parts of the sky (16 forest directions give rank 13 of 16), so modes the
// samples do not constrain would take any value and the diffuse product (below) would integrate them
// against the whole sphere's lighting. Instead the unoccluded transfer t is taken as known and only the
// occlusion is fitted: c = t + d, d = argmin |Y d - (V - T)|^2 + mu^2 |d|^2, that is
//   c = t + M+ Y^T (V - T) = t + sum_k w_k (V_k - T_k),   w_k = M+ y(omega_k),
// with T_k the unoccluded sample (max(0, n.omega_k), or 1): the residual is -T_k where map k
// occludes and 0 elsewhere, so an unoccluded pixel gets exactly t and occlusion moves only what the
// samples see. t is the SH of max(0, n.w) (V max(0, n.w) fit: band l of y(n) times pi, 2pi/3, pi/4,
// 0; its value at w is tau(c) = 1/4 + c/2 + 5/32 (3c^2 - 1), c = n.w, bands 0-2 of the clamped
// cosine) or of 1 (V fit: sqrt(4 pi) in Y00). The K terms are summed in k order (k = 0 first), so
// every build adds the same floats.
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

// The residual V_k - T_k of map k (uniform) at p, unit normal n: 0 where the map leaves p lit, else
// minus the unoccluded sample T_k (1 for kVisFitV, max(0, n . omega_k) for kVisFitVCos). data row k:
// texels 0-3 the light matrix's columns, 4 omega_k.
Float visResidual(Sampler2DArray maps, Sampler2D data, VisSettings s, int k, Float3 p, Float3 n) {
  Int row = Int(k);
  Float4 m0 = texelFetchUniform(data, 0, k, 0);
  Float4 m1 = texelFetchUniform(data, 1, k, 0);
  Float4 m2 = texelFetchUniform(data, 2, k, 0);
  Float4 m3 = texelFetchUniform(data, 3, k, 0);
  Float4 w = texelFetchUniform(data, 4, k, 0);
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
  Float unoccluded = select(s.fit == kVisFitV, Float(1.0f), max(c, 0.0f));
  return select(lit, Float(0.0f), -unoccluded);
}

// The prior t: the SH of max(0, n.w) (kVisFitVCos) or of the constant 1 (kVisFitV).
Sh16 visPrior(VisSettings s, Float3 n) {
  Sh16 y = sh16Basis(n);
  PRECISE Float4 a = y.a * Float4(3.14159274f, 2.09439516f, 2.09439516f, 2.09439516f);
  PRECISE Float4 b = y.b * 0.785398185f;
  PRECISE Float4 c = y.c * Float4(0.785398185f, 0.0f, 0.0f, 0.0f);
  Float4 zero = Float4(0.0f, 0.0f, 0.0f, 0.0f);
  Float4 one = Float4(3.54490781f, 0.0f, 0.0f, 0.0f);  // sqrt(4 pi) Y00 = 1
  Mask v = s.fit == kVisFitV;
  return Sh16(select(v, one, a), select(v, zero, b), select(v, zero, c), zero);
}

// The per-pixel fit c = t + sum_k w_k (V_k - t(omega_k)) (k = 0 first); data row k, texels 5-8:
// w_k = M+ y(omega_k). nIn: the G-buffer's interpolated normal (normalised here).
Sh16 visFit(Sampler2DArray maps, Sampler2D data, VisSettings s, Float3 p, Float3 nIn) {
  // Background pixels have no normal: +y instead of normalize(0) = NaN, so no NaN reaches min/max
  // (whose NaN operand the C++ prelude and lavapipe resolve differently).
  Float3 n = exNormalize(select(dot(nIn, nIn) > 0.0f, nIn, Float3(0.0f, 1.0f, 0.0f)));
  Sh16 acc = visPrior(s, n);
  FOR (int k = 0; k < int(s.count); k++) {
    Float v = visResidual(maps, data, s, k, p, n);
    Sh16 wk = Sh16(texelFetchUniform(data, 5, k, 0), texelFetchUniform(data, 6, k, 0), texelFetchUniform(data, 7, k, 0),
                   texelFetchUniform(data, 8, k, 0));
    acc = sh16AddScaled(acc, wk, v);
  }
  return acc;
}

// ---- Shading with the fit (shade/shade_fis.h) ----
// Glossy term, per sample direction w (the paper's eval_visibility in L vis f / pdf): for the V fit
// the fitted function at w; for the V max(0, n.w) fit 1 + (fit(w) - tau(n.w)) / max(n.w, 0.05), the
// fitted occlusion over the cosine (exactly 1 where the fit is the prior); clamped to [0, 1]
// (ringing of the truncated series). Diffuse term: with the V max(0, n.w)
// fit, E_vis / pi = (1/pi) sum_i L_i c_i, the double product of the raw lighting SH L (order 4,
// inputs/sh_irradiance.h bands 0-3) and the transfer c (orthonormal basis), clamped to [0, E / pi]
// (0 <= V <= 1); with V
// alone, the unshadowed E / pi times the visibility at the normal (an approximation: the product of
// V and the cosine is not formed).
const uint kFisVisNone = 0u;
const uint kFisVisCos = 1u;  // the fit holds V max(0, n.w)
const uint kFisVisV = 2u;    // the fit holds V

struct VisLighting {
  Sh16 r;
  Sh16 g;
  Sh16 b;
};

Float visAt(uint visMode, Sh16 c, Float3 n, Float3 w) {
  PRECISE Float f = sh16Dot(c, sh16Basis(w));
  PRECISE Float cosW = dot(n, w);
  PRECISE Float tau = 0.25f + 0.5f * cosW + 0.15625f * (3.0f * (cosW * cosW) - 1.0f);
  PRECISE Float occ = 1.0f + exDiv(f - tau, max(cosW, 0.05f));
  Float v = select(visMode == kFisVisCos, occ, f);
  return clamp(v, 0.0f, 1.0f);
}

Float3 visIrradiance(uint visMode, VisLighting L, Sh16 c, Float3 irr, Float3 n) {
  PRECISE Float3 e = Float3(sh16Dot(L.r, c), sh16Dot(L.g, c), sh16Dot(L.b, c)) * 0.318309886f;
  // V <= 1: never above the unshadowed irradiance (the truncated fit can ring above it).
  Float3 product = Float3(min(max(e.x, 0.0f), irr.x), min(max(e.y, 0.0f), irr.y), min(max(e.z, 0.0f), irr.z));
  PRECISE Float3 occluded = irr * visAt(kFisVisV, c, n, n);
  return select(visMode == kFisVisCos, product, occluded);
}

// ---- Spatial filter of the coefficient images (the paper's s5.2: hides shadow-map aliasing) ----
// The mean of the 16 coefficients over the (2r + 1)^2 pixels around (x, y) that hold geometry (G0.w
// != 0) and, with edgeAware, lie on the centre's surface: |n . (q - p)| <= planeTolerance (world
// units) and the normals within about 25 degrees (n_q . n_p >= 0.9 |n_q|, compared squared; G1 is
// not renormalised).
// A box filter as in the paper otherwise. Weights are 0 or 1 and the sum runs dy, then dx, from -r,
// so both builds add the same floats; the mean is one exact division. Pixels without geometry (or
// with no neighbour) keep their own coefficients. coeffs: RGBA32F array, layer j = coefficients
// 4j..4j+3; gbuf: RGBA32F array, layer 0 = G0, layer 1 = G1.
const uint kVisFilterBox = 0u;
const uint kVisFilterEdge = 1u;

Sh16 visFilter(Sampler2DArray coeffs, Sampler2DArray gbuf, Int x, Int y, int width, int height, int radius, uint mode,
               float planeTolerance) {
  Float4 g0 = texelFetchLayer(gbuf, x, y, Int(0), 0);
  Float4 g1 = texelFetchLayer(gbuf, x, y, Int(1), 0);
  Float3 p = Float3(g0.x, g0.y, g0.z);
  Float3 n = exNormalize(select(dot(Float3(g1.x, g1.y, g1.z), Float3(g1.x, g1.y, g1.z)) > 0.0f, Float3(g1.x, g1.y, g1.z),
                                Float3(0.0f, 1.0f, 0.0f)));
  Float4 zero = Float4(0.0f, 0.0f, 0.0f, 0.0f);
  Sh16 acc = Sh16(zero, zero, zero, zero);
  PRECISE Float count = Float(0.0f);
  FOR (int dy = -radius; dy <= radius; dy++) {
    FOR (int dx = -radius; dx <= radius; dx++) {
      Int qx = x + Int(dx);
      Int qy = y + Int(dy);
      Mask inside = qx >= Int(0) && qx < Int(width) && qy >= Int(0) && qy < Int(height);
      Int cx = clamp(qx, Int(0), Int(width - 1));
      Int cy = clamp(qy, Int(0), Int(height - 1));
      Float4 q0 = texelFetchLayer(gbuf, cx, cy, Int(0), 0);
      Float4 q1 = texelFetchLayer(gbuf, cx, cy, Int(1), 0);
      Float3 nq = Float3(q1.x, q1.y, q1.z);
      PRECISE Float plane = abs(dot(n, Float3(q0.x, q0.y, q0.z) - p));
      PRECISE Float d = dot(n, nq);
      PRECISE Float facing = d * d - 0.81f * dot(nq, nq);  // n . n_q >= 0.9 |n_q|, squared (d >= 0)
      Mask same = plane <= planeTolerance && d >= 0.0f && facing >= 0.0f;
      Mask use = inside && q0.w != 0.0f && (Mask(mode == kVisFilterBox) || same);
      Float w = select(use, Float(1.0f), Float(0.0f));
      Sh16 c = Sh16(texelFetchLayer(coeffs, cx, cy, Int(0), 0), texelFetchLayer(coeffs, cx, cy, Int(1), 0),
                    texelFetchLayer(coeffs, cx, cy, Int(2), 0), texelFetchLayer(coeffs, cx, cy, Int(3), 0));
      acc = sh16AddScaled(acc, c, w);
      count = count + w;
    }
  }
  Sh16 self = Sh16(texelFetchLayer(coeffs, x, y, Int(0), 0), texelFetchLayer(coeffs, x, y, Int(1), 0),
                   texelFetchLayer(coeffs, x, y, Int(2), 0), texelFetchLayer(coeffs, x, y, Int(3), 0));
  PRECISE Float inv = exDiv(1.0f, max(count, 1.0f));
  Mask keep = g0.w == 0.0f || count == 0.0f;
  return Sh16(select(keep, self.a, acc.a * inv), select(keep, self.b, acc.b * inv), select(keep, self.c, acc.c * inv),
              select(keep, self.d, acc.d * inv));
}
