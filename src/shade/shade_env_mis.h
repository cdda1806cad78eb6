// Technique kdtree-mis (and its baselines alias-mis, inversion-mis): Monte Carlo shading of a pixel
// with environment samples (shade/env_sampling.h) and BRDF samples combined by multiple importance
// sampling (Veach & Guibas 1995, "Optimally combining sampling techniques for Monte Carlo rendering";
// Veach's thesis ch. 9), no visibility (as FIS and env: the environment lights the surface directly).
//
// Integrand: L(w) f(w) cos theta, f = kd/pi + ks fs (shade/brdf.h), L = the environment at level 0
// (bilinear, as the reference renderer's). Per sample index i, one direction of each strategy:
//   environment  w_e ~ p_e (the map's sampler)
//   BRDF         w_b ~ p_b = P_d cos/pi + (1 - P_d) p_fs,   P_d = lum(kd) / (lum(kd) + lum(ks))
// (the diffuse lobe is sampled too, so p_b covers the hemisphere wherever kd > 0), and
//   F = 1/N sum_i [ w_E(w_e) L f cos / p_e (w_e) + w_B(w_b) L f cos / p_b (w_b) ],
// with weights w_E + w_B = 1 (unbiased where p_e + p_b > 0):
//   balance (Veach eq. 9.9)  w_E / p_e = 1 / (p_e + p_b)
//   power, beta = 2 (9.13)   w_E / p_e = p_e / (p_e^2 + p_b^2)
//   env only, BRDF only      w_E = 1 or 0 (single-strategy baselines; biased where one pdf is 0).
// Random numbers: Philox4x32-10 (shade/philox.h), counter (pixel, i, stream, 0), key (seed, frame):
// stream 0 gives the environment sample's 4 numbers, stream 1 the BRDF sample's (2 for the lobe's
// direction, 1 for the diffuse / glossy choice). Frames with different `frame` are independent, so
// the host averages frames progressively.

const uint kMisBalance = 0u;
const uint kMisPower = 1u;
const uint kMisEnvOnly = 2u;
const uint kMisBrdfOnly = 3u;

// w / p of one strategy's sample: p this strategy's pdf, q the other's, both at the sample's direction
// (one division: the heuristic is uniform).
Float misWeightOverPdf(uint heuristic, Mask envStrategy, Float p, Float q) {
  PRECISE Float num = Float(1.0f);
  PRECISE Float den = p + q;  // balance
  if (heuristic == kMisPower) {
    num = p;
    den = p * p + q * q;
  }
  if (heuristic == kMisEnvOnly || heuristic == kMisBrdfOnly) {
    num = select(envStrategy == Mask(heuristic == kMisEnvOnly), Float(1.0f), Float(0.0f));
    den = p;
  }
  PRECISE Float r = exDiv(num, den);
  return select(p > 0.0f, r, Float(0.0f));
}

Float luminanceOf(Float3 c) {
  PRECISE Float l = (0.2126f * c.x + 0.7152f * c.y) + 0.0722f * c.z;
  return l;
}

// Probability of sampling the diffuse lobe.
Float misDiffuseProbability(Float3 diffuse, Float3 specular) {
  Float d = max(luminanceOf(diffuse), 0.0f);
  Float g = max(luminanceOf(specular), 0.0f);
  Mask any = d + g > 0.0f;
  PRECISE Float p = exDiv(d, select(any, d + g, 1.0f));
  return select(any, p, 0.5f);
}

// p_b of a local direction.
Float misBrdfPdf(BrdfParams brdf, Float pd, Float3 wo, Float3 wi) {
  PRECISE Float p = pd * (max(wi.z, 0.0f) * kBrdfInvPi) + (1.0f - pd) * brdfPdf(brdf, wo, wi);
  return p;
}

// Local direction drawn from p_b: the diffuse lobe (cosine) if u.z < pd, else the glossy lobe (a lobe
// no lane draws is not sampled).
Float3 sampleMisBrdf(BrdfParams brdf, Float pd, Float3 wo, Float4 u) {
  Float2 uv = Float2(u.x, u.y);
  Mask diffuse = u.z < pd;
  Mask glossy = !diffuse;
  Float3 w = Float3(0.0f, 0.0f, 1.0f);
  IF_ANY(diffuse) { w = select(diffuse, drawCosineLobe(Float3(0.0f, 0.0f, 1.0f), 1.0f, uv).w, w); }
  IF_ANY(glossy) { w = select(glossy, sampleBrdfDirection(brdf, wo, uv), w); }
  return w;
}

// L f cos of a world direction (0 below the surface), f = kd/pi + ks fs.
Float3 misIntegrand(Sampler2D env, FisFrame F, BrdfParams brdf, Float3 diffuse, Float3 specular, Float3 dir, Float3 wi) {
  Float4 L = textureLod(env, equirectUv(dir), 0.0f);
  Float fs = brdfEval(brdf, F.wo, wi);
  PRECISE Float3 f = diffuse * kBrdfInvPi + specular * fs;
  PRECISE Float3 c = f * Float3(L.x, L.y, L.z) * max(wi.z, 0.0f);
  return select(wi.z > 0.0f, c, Float3(0.0f, 0.0f, 0.0f));
}

struct MisSettings {
  uint heuristic;    // kMis*
  uint sampleCount;  // N: sample pairs per pixel and frame
  uint frame;        // Philox key word 1
  uint seed;         // Philox key word 0
};

// visMode != kFisVisNone: both strategies' samples times the pixel's SH visibility in their
// direction (shade/visibility.h visAt, issue 16).
Float4 shadeEnvMis(Sampler2D env, Sampler2D table, Sampler2D texels, EnvSampling es, MisSettings ms, Float intensity, Uint pixel,
                   Float4 g0, Float4 g1, Float4 g2, Float3 eye, Float3 ray, Float3 diffuse, Float3 specular, BrdfParams brdf,
                   uint visMode, Sh16 vis) {
  Mask geometry = g0.w != 0.0f;
  PRECISE Float3 sum = Float3(0.0f, 0.0f, 0.0f);
  IF_ANY(geometry) {
    FisFrame F = envFrame(g0, g1, g2, eye);
    Float pd = misDiffuseProbability(diffuse, specular);
    Mask visible = uniformMask(visMode != kFisVisNone);
    FOR (uint i = 0u; i < ms.sampleCount; i++) {
      // Environment strategy.
      Float4 ue = philoxUniform4(philox4x32(Philox4(pixel, Uint(i), Uint(0u), Uint(0u)), Uint(ms.seed), Uint(ms.frame)));
      EnvSample e = sampleEnv(table, texels, es, ue);
      Float3 wie = basisToLocal(F.basis, e.dir);
      Float we = misWeightOverPdf(ms.heuristic, Mask(true), e.pdf, misBrdfPdf(brdf, pd, F.wo, wie));
      Float3 ce = misIntegrand(env, F, brdf, diffuse, specular, e.dir, wie);
      IF_ANY(visible) { ce = select(visible, ce * visAt(visMode, vis, F.basis.n, e.dir), ce); }
      sum = sum + ce * we;
      // BRDF strategy.
      Float4 ub = philoxUniform4(philox4x32(Philox4(pixel, Uint(i), Uint(1u), Uint(0u)), Uint(ms.seed), Uint(ms.frame)));
      Float3 wib = sampleMisBrdf(brdf, pd, F.wo, ub);
      Float3 db = basisToWorld(F.basis, wib);
      Float wb = misWeightOverPdf(ms.heuristic, Mask(false), misBrdfPdf(brdf, pd, F.wo, wib), envPdf(table, texels, es, db));
      Float3 cb = misIntegrand(env, F, brdf, diffuse, specular, db, wib);
      IF_ANY(visible) { cb = select(visible, cb * visAt(visMode, vis, F.basis.n, db), cb); }
      sum = sum + cb * wb;
    }
    PRECISE Float invN = exDiv(1.0f, Float(float(ms.sampleCount)));
    sum = select(geometry, sum * invN, Float3(0.0f, 0.0f, 0.0f));
  }
  return envFinish(env, g0, ray, sum, intensity);
}
