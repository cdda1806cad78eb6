// Pieces of the glints technique (issue 17; Gamboa, Guertin, Nowrouzezahrai 2018): the pixel's
// footprint on the normal map and the FG term. Dialect only.

// ---- Footprint (§6.1) ----
// The G-buffer holds the pixel's uv and its quad derivatives (G3 = du/dx, dv/dx, du/dy, dv/dy). The
// pixel covers, to first order, the parallelogram uv + a duv/dx + b duv/dy, a, b in [-1/2, 1/2];
// its conservative axis-aligned box has half-extents (|du/dx| + |du/dy|) / 2 and (|dv/dx| + |dv/dy|)
// / 2. In texels of a map of `texels` per uv unit (the map's size times the scene's tiling scale),
// the footprint is every texel the box touches: [floor(c - h), floor(c + h)] per axis (a box of zero
// extent is the one texel under uv). Coordinates are not wrapped: the SAT lookups wrap (tiled maps).
// The 16-bit modular SAT is exact below 65,536 texels, so a side longer than 255 texels is cut to
// the 255 texels around its centre (area <= 65,025); with a pixel's footprint that long the NDF of
// 255 texels along that axis stands for it (the cut is reported by `cut`).
struct GlintBox {
  Int x0;
  Int y0;
  Int x1;
  Int y1;
  Mask cut;
};

GlintBox glintFootprint(Float u, Float v, Float4 duv, Float texels) {
  PRECISE Float cu = u * texels;
  PRECISE Float cv = v * texels;
  PRECISE Float hu = 0.5f * ((abs(duv.x) + abs(duv.z)) * texels);
  PRECISE Float hv = 0.5f * ((abs(duv.y) + abs(duv.w)) * texels);
  Int x0 = Int(floor(cu - hu));
  Int x1 = Int(floor(cu + hu));
  Int y0 = Int(floor(cv - hv));
  Int y1 = Int(floor(cv + hv));
  Mask cutX = x1 - x0 > Int(254);
  Mask cutY = y1 - y0 > Int(254);
  Int mx = Int(floor(cu)) - Int(127);
  Int my = Int(floor(cv)) - Int(127);
  return GlintBox(select(cutX, mx, x0), select(cutY, my, y0), select(cutX, mx + Int(254), x1), select(cutY, my + Int(254), y1),
                  cutX || cutY);
}

// ---- FG (appendix A) ----
// Fresnel reflectance of a conductor with complex index of refraction eta + i k (per channel)
// from air, unpolarised: the exact formula (Born & Wolf; pbrt's FrConductor), with
//   t0 = eta^2 - k^2 - sin^2, a2b2 = sqrt(t0^2 + 4 eta^2 k^2), a = sqrt((a2b2 + t0) / 2),
//   Rs = (a2b2 + cos^2 - 2 a cos) / (a2b2 + cos^2 + 2 a cos),
//   Rp = Rs (cos^2 a2b2 + sin^4 - 2 a cos sin^2) / (cos^2 a2b2 + sin^4 + 2 a cos sin^2),  F = (Rs + Rp) / 2.
Float fresnelConductor1(Float cosT, Float eta, Float k) {
  PRECISE Float c = clamp(cosT, 0.0f, 1.0f);
  PRECISE Float c2 = c * c;
  PRECISE Float s2 = 1.0f - c2;
  PRECISE Float t0 = (eta * eta - k * k) - s2;
  PRECISE Float a2b2 = exSqrt(t0 * t0 + 4.0f * (eta * eta) * (k * k));
  PRECISE Float a = exSqrt(max(0.5f * (a2b2 + t0), 0.0f));
  PRECISE Float t1 = a2b2 + c2;
  PRECISE Float t2 = 2.0f * (a * c);
  PRECISE Float rs = exDiv(t1 - t2, t1 + t2);
  PRECISE Float t3 = c2 * a2b2 + s2 * s2;
  PRECISE Float t4 = t2 * s2;
  PRECISE Float rp = rs * exDiv(t3 - t4, t3 + t4);
  return 0.5f * (rs + rp);
}

Float3 fresnelConductor(Float cosT, Float3 eta, Float3 k) {
  return Float3(fresnelConductor1(cosT, eta.x, k.x), fresnelConductor1(cosT, eta.y, k.y), fresnelConductor1(cosT, eta.z, k.z));
}

// Smith's masking G1 for a Beckmann distribution of roughness alpha, Walter et al. 2007's rational
// approximation: a = cos / (alpha sin), G1 = (3.535 a + 2.181 a^2) / (1 + 2.276 a + 2.577 a^2) for
// a < 1.6, else 1 (clamped to 1: just below a = 1.6 the rational form reaches 1.00001); 0 at or
// below the horizon. A Gaussian lobe of angular width sigma is a Beckmann
// lobe of alpha = sqrt(2) sigma (exp(-tan^2 / alpha^2) ~ exp(-theta^2 / (2 sigma^2))).
Float smithG1Beckmann(Float cosT, Float alpha) {
  PRECISE Float c = clamp(cosT, 0.0f, 1.0f);
  PRECISE Float s = exSqrt(max(1.0f - c * c, 0.0f));
  PRECISE Float a = exDiv(c, alpha * max(s, 1e-30f));
  PRECISE Float g = exDiv(a * (3.535f + 2.181f * a), 1.0f + a * (2.276f + 2.577f * a));
  return select(c <= 0.0f, Float(0.0f), select(a < 1.6f, min(g, 1.0f), Float(1.0f)));
}
