// Dual-paraboloid environment map (Heidrich & Seidel 1998), as FIS uses it (Colbert & Krivanek,
// GPU Gems 3 ch. 20: "the dual-paraboloid map ... scaled by b = 1.2 so that bilinear filtering
// near the rim stays inside the map").
//
// Face coordinates of a unit direction d:  front (d.z >= 0): p = ( d.x, d.y) / (1 + d.z)
//                                          back  (d.z <  0): p = (-d.x, d.y) / (1 - d.z)
// |p| <= 1 is the face's hemisphere; p up to b = 1.2 continues into the other hemisphere, so the
// texels beyond the rim hold real environment radiance and filtered lookups near z = 0 are correct.
// Inverse: d = (2 p.x, 2 p.y, 1 - |p|^2) / (1 + |p|^2) (x and z negated on the back face).
//
// Both faces share one texture (an atlas, 2S x S): front in u in [0, 1/2], back in [1/2, 1],
// s = (p.x / b + 1) / 2 within a face, t = (p.y / b + 1) / 2. Mirroring x on the back face makes
// the atlas seam join directions with the same sign of d.x (the two sides of the seam are mirror
// images in z, |z| <= 0.48 at the corners), so a coarse MIP level blends nearby directions there.
//
// Jacobian (the r(z)): on a face, dw = (1 + |z|)^2 dp_x dp_y (1 + z = 2 / (1 + |p|^2) and
// dw = 4 / (1 + |p|^2)^2 dp), and dp = 2b ds, 2b dt, so dw = 4 b^2 (1 + |z|)^2 ds dt: a texel of a
// face of S x S texels subtends r(z) / S^2 with r(z) = 4 b^2 (1 + |z|)^2.

const float kParaboloidB = 1.2f;
const float kParaboloidInvB = 0.833333313f;  // float(1 / 1.2)

Float paraboloidJacobian(Float z) {
  PRECISE Float a = 1.0f + abs(z);
  PRECISE Float r = (4.0f * kParaboloidB * kParaboloidB) * (a * a);
  return r;
}

// Atlas texture coordinates of a unit direction.
Float2 paraboloidUv(Float3 d) {
  Mask front = d.z >= 0.0f;
  PRECISE Float k = exDiv(1.0f, 1.0f + abs(d.z));
  PRECISE Float px = select(front, d.x, -d.x) * k;
  PRECISE Float py = d.y * k;
  PRECISE Float s = (px * kParaboloidInvB + 1.0f) * 0.25f;
  PRECISE Float t = (py * kParaboloidInvB + 1.0f) * 0.5f;
  return Float2(select(front, s, s + 0.5f), t);
}

// Direction of an atlas texel centre (i, j) of an atlas 2S x S (resampling kernel).
Float3 paraboloidTexelDirection(Int i, Int j, Int faceSize) {
  Mask back = i >= faceSize;
  Int fi = select(back, i - faceSize, i);
  PRECISE Float inv = exDiv(1.0f, Float(faceSize));
  PRECISE Float px = ((Float(fi) + 0.5f) * inv * 2.0f - 1.0f) * kParaboloidB;
  PRECISE Float py = ((Float(j) + 0.5f) * inv * 2.0f - 1.0f) * kParaboloidB;
  PRECISE Float q = px * px + py * py;
  PRECISE Float k = exDiv(1.0f, 1.0f + q);
  PRECISE Float3 d = Float3(2.0f * px * k, 2.0f * py * k, (1.0f - q) * k);
  return select(back, Float3(-d.x, d.y, -d.z), d);
}

// Resampling kernel: atlas texel (i, j) from the equirectangular map `env`, one trilinear lookup
// whose LOD matches the texel's solid angle to the source texels' (both from their Jacobians):
//   paraboloid texel  r(z) / S^2,   equirect texel  (2 pi / W)(pi / H) sin(theta),
//   lod = max(0, 1/2 log2(paraboloid / equirect)).
Float4 paraboloidResample(Sampler2D env, Float envWidth, Float envHeight, Int i, Int j, Int faceSize) {
  Float3 d = paraboloidTexelDirection(i, j, faceSize);
  PRECISE Float fs = Float(faceSize);
  PRECISE Float sinTheta = exSqrt(max(1.0f - d.y * d.y, 0.0f));
  PRECISE Float omegaP = exDiv(paraboloidJacobian(d.z), fs * fs);
  PRECISE Float omegaE = exDiv(19.7392082f * max(sinTheta, 1.0e-4f), envWidth * envHeight);  // 2 pi^2 sin / (W H)
  PRECISE Float lod = max(0.5f * exLog2(exDiv(omegaP, omegaE)), 0.0f);
  return textureLod(env, equirectUv(d), lod);
}
