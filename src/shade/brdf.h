// BRDF sampling, pdf and evaluation for the sampling techniques (shared dialect: the FIS shading
// pass of both builds and the C++ tests run this one source).
//
// Conventions. Local shading frame: n = +z. wo = unit direction to the viewer, wi = to the light.
// The glossy lobe is f = ks * fs(wi, wo); these functions handle fs (ks is applied by the caller).
// A sampler returns wi, the pdf it drew wi with (solid angle, over the whole sphere: a lobe is
// sampled as a whole and samples below the horizon simply carry weight 0) and
//   weight = fs(wi, wo) cos(theta_i) / pdf          (0 when wi or wo is below the horizon),
// the Monte Carlo weight of the sample. Definitions match src/reference/reference_brdf.h (double
// precision, the ground truth) so that errors measured against the reference are the technique's.
//
// Phong (normalized; Lafortune & Willems 1994). alpha = angle(wi, r), r = reflect(wo) = (-x, -y, z):
//   fs = (e+2)/(2pi) cos^e(alpha);  sample cos(alpha) = u^(1/(e+1)), phi = 2 pi v about r;
//   pdf = (e+1)/(2pi) cos^e(alpha) = (e+1)/(2pi) u^(e/(e+1));  weight = (e+2)/(e+1) cos(theta_i).
// Blinn-Phong (normalized, Akenine-Moller et al.): fs = (e+8)/(8pi) cos^e(theta_h);
//   h drawn with pdf_h = (e+1)/(2pi) cos^e(theta_h) (cos theta_h = u^(1/(e+1))), wi = reflect(-wo, h),
//   pdf = pdf_h / (4 wo.h) (Jacobian of the reflection, Walter et al. 2007 eq. 14);
//   weight = (e+8)/(e+1) (wo.h) cos(theta_i).
// Ward anisotropic (Ward 1992, sampling of Walter 2005 "Notes on the Ward BRDF"):
//   fs = exp(-tan^2(theta_h)(cos^2 phi_h/ax^2 + sin^2 phi_h/ay^2)) / (4 pi ax ay sqrt(cos_i cos_o)).
//   tan(phi_h) = ay/ax tan(2 pi v): (cos, sin)(phi_h) = (ax cos 2pi v, ay sin 2pi v) / L, and then
//   cos^2 phi_h/ax^2 + sin^2 phi_h/ay^2 = 1/L^2, so tan^2(theta_h) = -ln(u) L^2 and the exponential
//   of pdf_h equals u:  pdf_h = u / (pi ax ay cos^3 theta_h), pdf = pdf_h / (4 wo.h),
//   weight = (wo.h) cos^3(theta_h) sqrt(cos_i / cos_o).
// GGX / Trowbridge-Reitz (Walter et al. 2007), isotropic alpha a:
//   D = a^2 / (pi cos^4 theta_h (a^2 + tan^2 theta_h)^2), G1(c) = 2c / (c + sqrt(c^2 + a^2 (1 - c^2))),
//   fs = D G1(cos_i) G1(cos_o) / (4 cos_i cos_o); tan^2 theta_h = a^2 u / (1 - u) draws
//   pdf_h = D cos theta_h; pdf = pdf_h / (4 wo.h); weight = G1(cos_i) G1(cos_o) (wo.h) / (cos_o cos theta_h).
// Lafortune (Lafortune et al. 1997), up to two generalized cosine lobes k:
//   fs = sum_k rho_k max(s_k . wi, 0)^n_k, s_k = (Cx wo.x, Cy wo.y, Cz wo.z) (rho_k carries the
//   normalization). Lobe k is a Phong lobe of exponent n_k about s_k/|s_k| scaled by
//   rho_k |s_k|^n_k; its integral over the sphere is m_k = rho_k |s_k|^n_k 2pi/(n_k+1). A lobe is
//   picked with probability P_k = m_k / (m_0 + m_1) (u rescaled into the chosen interval), then
//   sampled as Phong; pdf = sum_k P_k (n_k+1)/(2pi) max(a_k . wi, 0)^n_k, weight = fs cos_i / pdf.

const uint kBrdfPhong = 0u;
const uint kBrdfBlinn = 1u;
const uint kBrdfWard = 2u;
const uint kBrdfLafortune = 3u;
const uint kBrdfGgx = 4u;
const float kBrdfInvTwoPi = 0.159154943f;
const float kBrdfInvPi = 0.318309886f;

struct BrdfParams {
  Uint kind;   // kBrdf*
  Float e;     // Phong / Blinn-Phong exponent
  Float ax;    // Ward alpha_x, GGX alpha
  Float ay;    // Ward alpha_y
  Float3 c0;   // Lafortune lobe 0: (Cx, Cy, Cz), exponent, rho
  Float n0;
  Float rho0;
  Float3 c1;   // Lafortune lobe 1 (rho1 = 0: absent)
  Float n1;
  Float rho1;
};

// Parameters of a Phong / Blinn-Phong / Ward / GGX material (no Lafortune lobes: rho = 0).
BrdfParams brdfParams(Uint kind, Float e, Float ax, Float ay) {
  Float3 zero = Float3(0.0f, 0.0f, 0.0f);
  return BrdfParams(kind, e, ax, ay, zero, Float(1.0f), Float(0.0f), zero, Float(1.0f), Float(0.0f));
}

struct BrdfSample {
  Float3 wi;
  Float pdf;
  Float weight;
};

BrdfSample selectSample(Mask m, BrdfSample a, BrdfSample b) {
  return BrdfSample(select(m, a.wi, b.wi), select(m, a.pdf, b.pdf), select(m, a.weight, b.weight));
}

Float3 reflectAbout(Float3 wo, Float3 h, Float oh) {
  PRECISE Float3 r = h * (2.0f * oh) - wo;
  return r;
}

// A Phong lobe of exponent e about the unit axis a: direction with cos(angle to a) = u^(1/(e+1)),
// sine from 1 - c without cancellation (oneMinusExp2), and pdf = (e+1)/(2pi) u^(e/(e+1)).
struct LobeSample {
  Float3 w;
  Float pdf;
};

// The draw is split from its pdf so that a caller that needs only the direction (the MIS techniques' BRDF strategy,
// which weighs a direction by brdfPdf) computes only that: the split changes no bit of either.
struct LobeDraw {
  Float3 w;
  Float lu;  // log2(u.x)
  Float e1;  // e + 1
};

LobeDraw drawCosineLobe(Float3 a, Float e, Float2 u) {
  PRECISE Float e1 = e + 1.0f;
  PRECISE Float lu = exLog2(u.x);
  PRECISE Float z = exDiv(lu, e1);
  PRECISE Float c = exExp2(z);
  PRECISE Float omc = oneMinusExp2(z);
  PRECISE Float s = exSqrt(omc * (2.0f - omc));
  Float3 w = basisToWorld(basisAbout(a), sphericalDirection(s, c, u.y));
  return LobeDraw(w, lu, e1);
}

Float drawnLobePdf(LobeDraw d, Float e) {
  PRECISE Float pdf = d.e1 * kBrdfInvTwoPi * exExp2(exDiv(d.lu * e, d.e1));
  return pdf;
}

LobeSample sampleCosineLobe(Float3 a, Float e, Float2 u) {
  LobeDraw d = drawCosineLobe(a, e, u);
  return LobeSample(d.w, drawnLobePdf(d, e));
}

Float cosineLobePdf(Float3 a, Float e, Float3 w) {
  PRECISE Float c = max(dot(a, w), 0.0f);
  PRECISE Float p = (e + 1.0f) * kBrdfInvTwoPi * exPow(c, e);
  return p;
}

Float3 phongAxis(Float3 wo) { return Float3(-wo.x, -wo.y, wo.z); }

// ---- Phong ----
BrdfSample samplePhong(Float3 wo, Float e, Float2 u) {
  LobeSample l = sampleCosineLobe(phongAxis(wo), e, u);
  PRECISE Float w = exDiv(e + 2.0f, e + 1.0f) * l.w.z;
  w = select(l.w.z > 0.0f && wo.z > 0.0f, w, 0.0f);
  return BrdfSample(l.w, l.pdf, w);
}

Float phongPdf(Float3 wo, Float e, Float3 wi) { return cosineLobePdf(phongAxis(wo), e, wi); }

Float phongEval(Float3 wo, Float e, Float3 wi) {
  PRECISE Float f = (e + 2.0f) * kBrdfInvTwoPi * exPow(max(dot(phongAxis(wo), wi), 0.0f), e);
  return select(wi.z > 0.0f && wo.z > 0.0f, f, 0.0f);
}

// ---- Blinn-Phong ----
struct BlinnDraw {
  Float3 wi;
  Float oh;  // wo.h
  LobeDraw h;
};

BlinnDraw drawBlinn(Float3 wo, Float e, Float2 u) {
  LobeDraw h = drawCosineLobe(Float3(0.0f, 0.0f, 1.0f), e, u);
  PRECISE Float oh = dot(wo, h.w);
  return BlinnDraw(reflectAbout(wo, h.w, oh), oh, h);
}

BrdfSample sampleBlinn(Float3 wo, Float e, Float2 u) {
  BlinnDraw d = drawBlinn(wo, e, u);
  Float3 wi = d.wi;
  Float oh = d.oh;
  Mask ok = oh > 0.0f;
  PRECISE Float pdf = exDiv(drawnLobePdf(d.h, e), 4.0f * oh);
  PRECISE Float w = exDiv(e + 8.0f, e + 1.0f) * oh * wi.z;
  w = select(ok && wi.z > 0.0f && wo.z > 0.0f, w, 0.0f);
  return BrdfSample(wi, select(ok, pdf, 0.0f), w);
}

Float3 halfVector(Float3 wo, Float3 wi) { return exNormalize(wo + wi); }

Float blinnPdf(Float3 wo, Float e, Float3 wi) {
  Float3 h = halfVector(wo, wi);
  PRECISE Float oh = dot(wo, h);
  PRECISE Float p = exDiv(cosineLobePdf(Float3(0.0f, 0.0f, 1.0f), e, h), 4.0f * oh);
  return select(oh > 0.0f, p, 0.0f);
}

Float blinnEval(Float3 wo, Float e, Float3 wi) {
  Float3 h = halfVector(wo, wi);
  PRECISE Float f = (e + 8.0f) * (0.125f * kBrdfInvPi) * exPow(max(h.z, 0.0f), e);
  return select(wi.z > 0.0f && wo.z > 0.0f, f, 0.0f);
}

// ---- Ward ----
struct HalfDraw {
  Float3 wi;
  Float ch;  // cos(theta_h)
  Float oh;  // wo.h
  Float t2;  // tan^2(theta_h)
};

HalfDraw drawWard(Float3 wo, Float ax, Float ay, Float2 u) {
  XmSinCos sc = exSinCos2Pi(u.y);
  PRECISE Float X = ax * sc.c;
  PRECISE Float Y = ay * sc.s;
  PRECISE Float L2 = X * X + Y * Y;
  PRECISE Float invL = exInverseSqrt(L2);
  PRECISE Float t2 = -exLog(u.x) * L2;
  PRECISE Float ch = exInverseSqrt(1.0f + t2);
  PRECISE Float sh = exSqrt(t2) * ch;
  PRECISE Float3 h = Float3(sh * (X * invL), sh * (Y * invL), ch);
  PRECISE Float oh = dot(wo, h);
  return HalfDraw(reflectAbout(wo, h, oh), ch, oh, t2);
}

BrdfSample sampleWard(Float3 wo, Float ax, Float ay, Float2 u) {
  HalfDraw d = drawWard(wo, ax, ay, u);
  Float3 wi = d.wi;
  Float ch = d.ch;
  Float oh = d.oh;
  Mask ok = oh > 0.0f;
  PRECISE Float ch3 = ch * ch * ch;
  PRECISE Float pdf = exDiv(u.x, 4.0f * 3.14159274f * ax * ay * ch3 * oh);
  PRECISE Float w = oh * ch3 * exSqrt(exDiv(max(wi.z, 0.0f), wo.z));
  w = select(ok && wi.z > 0.0f && wo.z > 0.0f, w, 0.0f);
  return BrdfSample(wi, select(ok, pdf, 0.0f), w);
}

// exp(-(hx^2/ax^2 + hy^2/ay^2) / hz^2) = exp(-tan^2(theta_h)(cos^2 phi_h/ax^2 + sin^2 phi_h/ay^2)).
Float wardExp(Float3 h, Float ax, Float ay) {
  PRECISE Float q = exDiv(exDiv(h.x * h.x, ax * ax) + exDiv(h.y * h.y, ay * ay), h.z * h.z);
  return exExp(-q);
}

Float wardPdf(Float3 wo, Float ax, Float ay, Float3 wi) {
  Float3 h = halfVector(wo, wi);
  PRECISE Float oh = dot(wo, h);
  PRECISE Float p = exDiv(wardExp(h, ax, ay), 4.0f * 3.14159274f * ax * ay * h.z * h.z * h.z * oh);
  return select(oh > 0.0f && h.z > 0.0f, p, 0.0f);
}

Float wardEval(Float3 wo, Float ax, Float ay, Float3 wi) {
  Float3 h = halfVector(wo, wi);
  PRECISE Float f = exDiv(wardExp(h, ax, ay), 4.0f * 3.14159274f * ax * ay * exSqrt(max(wi.z * wo.z, 0.0f)));
  return select(wi.z > 0.0f && wo.z > 0.0f, f, 0.0f);
}

// ---- GGX ----
Float ggxG1(Float a2, Float c) {
  PRECISE Float r = exDiv(2.0f * c, c + exSqrt(c * c + a2 * (1.0f - c * c)));
  return r;
}

Float ggxD(Float a2, Float ch) {
  PRECISE Float c2 = ch * ch;
  PRECISE Float t2 = exDiv(1.0f - c2, c2);
  PRECISE Float k = a2 + t2;
  PRECISE Float d = exDiv(a2, 3.14159274f * c2 * c2 * k * k);
  return d;
}

HalfDraw drawGgx(Float3 wo, Float a, Float2 u) {
  PRECISE Float a2 = a * a;
  PRECISE Float t2 = exDiv(a2 * u.x, 1.0f - u.x);
  PRECISE Float ch = exInverseSqrt(1.0f + t2);
  PRECISE Float sh = exSqrt(t2) * ch;
  Float3 h = sphericalDirection(sh, ch, u.y);
  PRECISE Float oh = dot(wo, h);
  return HalfDraw(reflectAbout(wo, h, oh), ch, oh, t2);
}

BrdfSample sampleGgx(Float3 wo, Float a, Float2 u) {
  PRECISE Float a2 = a * a;
  HalfDraw d = drawGgx(wo, a, u);
  Float3 wi = d.wi;
  Float ch = d.ch;
  Float oh = d.oh;
  Float t2 = d.t2;
  Mask ok = oh > 0.0f;
  PRECISE Float k = a2 + t2;
  PRECISE Float c2 = ch * ch;
  // D cos(theta_h) / (4 wo.h) with D = a^2 / (pi cos^4 (a^2 + tan^2)^2)
  PRECISE Float pdf = exDiv(a2, 4.0f * 3.14159274f * c2 * ch * k * k * oh);
  PRECISE Float w = exDiv(ggxG1(a2, max(wi.z, 0.0f)) * ggxG1(a2, wo.z) * oh, wo.z * ch);
  w = select(ok && wi.z > 0.0f && wo.z > 0.0f, w, 0.0f);
  return BrdfSample(wi, select(ok, pdf, 0.0f), w);
}

Float ggxPdf(Float3 wo, Float a, Float3 wi) {
  Float3 h = halfVector(wo, wi);
  PRECISE Float oh = dot(wo, h);
  PRECISE Float p = exDiv(ggxD(a * a, h.z) * h.z, 4.0f * oh);
  return select(oh > 0.0f && h.z > 0.0f, p, 0.0f);
}

Float ggxEval(Float3 wo, Float a, Float3 wi) {
  Float3 h = halfVector(wo, wi);
  PRECISE Float a2 = a * a;
  PRECISE Float f = exDiv(ggxD(a2, h.z) * ggxG1(a2, wi.z) * ggxG1(a2, wo.z), 4.0f * wi.z * wo.z);
  return select(wi.z > 0.0f && wo.z > 0.0f && h.z > 0.0f, f, 0.0f);
}

// ---- Lafortune ----
struct LafortuneLobes {
  Float3 a0;  // unit lobe axes
  Float3 a1;
  Float p0;   // probability of lobe 0
  Mask valid;
};

Float3 lafortuneS(Float3 c, Float3 wo) { return Float3(c.x * wo.x, c.y * wo.y, c.z * wo.z); }

LafortuneLobes lafortuneLobes(BrdfParams p, Float3 wo) {
  Float3 s0 = lafortuneS(p.c0, wo);
  Float3 s1 = lafortuneS(p.c1, wo);
  PRECISE Float l0 = exSqrt(dot(s0, s0));
  PRECISE Float l1 = exSqrt(dot(s1, s1));
  PRECISE Float m0 = exDiv(p.rho0 * exPow(l0, p.n0), p.n0 + 1.0f);
  PRECISE Float m1 = exDiv(p.rho1 * exPow(l1, p.n1), p.n1 + 1.0f);
  m0 = select(l0 > 0.0f, m0, 0.0f);
  m1 = select(l1 > 0.0f, m1, 0.0f);
  PRECISE Float total = m0 + m1;
  Mask valid = total > 0.0f;
  PRECISE Float p0 = exDiv(m0, select(valid, total, 1.0f));
  Float3 a0 = exNormalize(select(l0 > 0.0f, s0, Float3(0.0f, 0.0f, 1.0f)));
  Float3 a1 = exNormalize(select(l1 > 0.0f, s1, Float3(0.0f, 0.0f, 1.0f)));
  return LafortuneLobes(a0, a1, p0, valid);
}

Float lafortuneEval(BrdfParams p, Float3 wo, Float3 wi) {
  PRECISE Float f = p.rho0 * exPow(max(dot(lafortuneS(p.c0, wo), wi), 0.0f), p.n0);
  f = f + p.rho1 * exPow(max(dot(lafortuneS(p.c1, wo), wi), 0.0f), p.n1);
  return select(wi.z > 0.0f && wo.z > 0.0f, f, 0.0f);
}

Float lafortunePdfOf(LafortuneLobes L, BrdfParams p, Float3 wi) {
  PRECISE Float q = L.p0 * cosineLobePdf(L.a0, p.n0, wi);
  q = q + (1.0f - L.p0) * cosineLobePdf(L.a1, p.n1, wi);
  return select(L.valid, q, 0.0f);
}

Float lafortunePdf(BrdfParams p, Float3 wo, Float3 wi) { return lafortunePdfOf(lafortuneLobes(p, wo), p, wi); }

Float3 drawLafortune(LafortuneLobes L, BrdfParams p, Float2 u) {
  Mask second = u.x >= L.p0;
  // u rescaled into the chosen interval: [0, p0) -> [0, 1), [p0, 1) -> [0, 1)
  PRECISE Float ux = exDiv(select(second, u.x - L.p0, u.x), select(second, 1.0f - L.p0, L.p0));
  ux = min(ux, 0.99999994f);
  return drawCosineLobe(select(second, L.a1, L.a0), select(second, p.n1, p.n0), Float2(ux, u.y)).w;
}

BrdfSample sampleLafortune(BrdfParams p, Float3 wo, Float2 u) {
  LafortuneLobes L = lafortuneLobes(p, wo);
  Float3 wi = drawLafortune(L, p, u);
  PRECISE Float pdf = lafortunePdfOf(L, p, wi);
  PRECISE Float w = exDiv(lafortuneEval(p, wo, wi) * wi.z, select(pdf > 0.0f, pdf, 1.0f));
  w = select(L.valid && pdf > 0.0f, w, 0.0f);
  return BrdfSample(wi, pdf, w);
}

// ---- dispatch on the per-lane kind (IF_ANY skips kinds no lane has; on the GPU a kind absent from
// the scene, kSceneBrdfKinds, is compiled out) ----
Mask brdfKindIs(Uint kind, uint k) { return kind == k && specMask((kSceneBrdfKinds & (1u << k)) != 0u); }

BrdfSample sampleBrdf(BrdfParams p, Float3 wo, Float2 u) {
  BrdfSample r = BrdfSample(Float3(0.0f, 0.0f, 1.0f), 0.0f, 0.0f);
  Mask m = brdfKindIs(p.kind, kBrdfPhong);
  IF_ANY(m) { r = selectSample(m, samplePhong(wo, p.e, u), r); }
  m = brdfKindIs(p.kind, kBrdfBlinn);
  IF_ANY(m) { r = selectSample(m, sampleBlinn(wo, p.e, u), r); }
  m = brdfKindIs(p.kind, kBrdfWard);
  IF_ANY(m) { r = selectSample(m, sampleWard(wo, p.ax, p.ay, u), r); }
  m = brdfKindIs(p.kind, kBrdfLafortune);
  IF_ANY(m) { r = selectSample(m, sampleLafortune(p, wo, u), r); }
  m = brdfKindIs(p.kind, kBrdfGgx);
  IF_ANY(m) { r = selectSample(m, sampleGgx(wo, p.ax, u), r); }
  return r;
}

// The direction sampleBrdf draws, without its pdf and weight (the same bits as sampleBrdf(p, wo, u).wi).
Float3 sampleBrdfDirection(BrdfParams p, Float3 wo, Float2 u) {
  Float3 r = Float3(0.0f, 0.0f, 1.0f);
  Mask m = brdfKindIs(p.kind, kBrdfPhong);
  IF_ANY(m) { r = select(m, drawCosineLobe(phongAxis(wo), p.e, u).w, r); }
  m = brdfKindIs(p.kind, kBrdfBlinn);
  IF_ANY(m) { r = select(m, drawBlinn(wo, p.e, u).wi, r); }
  m = brdfKindIs(p.kind, kBrdfWard);
  IF_ANY(m) { r = select(m, drawWard(wo, p.ax, p.ay, u).wi, r); }
  m = brdfKindIs(p.kind, kBrdfLafortune);
  IF_ANY(m) { r = select(m, drawLafortune(lafortuneLobes(p, wo), p, u), r); }
  m = brdfKindIs(p.kind, kBrdfGgx);
  IF_ANY(m) { r = select(m, drawGgx(wo, p.ax, u).wi, r); }
  return r;
}

Float brdfPdf(BrdfParams p, Float3 wo, Float3 wi) {
  Float r = 0.0f;
  Mask m = brdfKindIs(p.kind, kBrdfPhong);
  IF_ANY(m) { r = select(m, phongPdf(wo, p.e, wi), r); }
  m = brdfKindIs(p.kind, kBrdfBlinn);
  IF_ANY(m) { r = select(m, blinnPdf(wo, p.e, wi), r); }
  m = brdfKindIs(p.kind, kBrdfWard);
  IF_ANY(m) { r = select(m, wardPdf(wo, p.ax, p.ay, wi), r); }
  m = brdfKindIs(p.kind, kBrdfLafortune);
  IF_ANY(m) { r = select(m, lafortunePdf(p, wo, wi), r); }
  m = brdfKindIs(p.kind, kBrdfGgx);
  IF_ANY(m) { r = select(m, ggxPdf(wo, p.ax, wi), r); }
  return r;
}

Float brdfEval(BrdfParams p, Float3 wo, Float3 wi) {
  Float r = 0.0f;
  Mask m = brdfKindIs(p.kind, kBrdfPhong);
  IF_ANY(m) { r = select(m, phongEval(wo, p.e, wi), r); }
  m = brdfKindIs(p.kind, kBrdfBlinn);
  IF_ANY(m) { r = select(m, blinnEval(wo, p.e, wi), r); }
  m = brdfKindIs(p.kind, kBrdfWard);
  IF_ANY(m) { r = select(m, wardEval(wo, p.ax, p.ay, wi), r); }
  m = brdfKindIs(p.kind, kBrdfLafortune);
  IF_ANY(m) { r = select(m, lafortuneEval(p, wo, wi), r); }
  m = brdfKindIs(p.kind, kBrdfGgx);
  IF_ANY(m) { r = select(m, ggxEval(wo, p.ax, wi), r); }
  return r;
}
