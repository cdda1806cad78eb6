// Filtered importance sampling (Colbert & Krivanek, "Real-time Shading with Filtered Importance
// Sampling", EGSR 2008 / GPU Gems 3 ch. 20), the deferred shading pass of technique "fis".
//
// Glossy term: N deterministic samples per pixel, the same Hammersley set everywhere (points i of
// N, shade/sampling.h), drawn from the pixel's BRDF (shade/brdf.h) in its shading frame. Each
// sample reads the dual-paraboloid atlas (shade/paraboloid.h) with trilinear textureLod at
//   l = max(1/2 log2(K w h / (N p r(z))), 0) = max(1/2 (log2(K w h / N) - log2(p r(z))), 0),
// the level whose texel solid angle r(z)/(w h 4^-l) matches the sample's share 1/(N p) of the
// sphere, times K (paper eq. 7-8; w h = S^2 texels per face), plus levelBias: 0 in the paper's
// form (K = 4 there), 1 in the book chapter's form l = max(1/2 log2(w h / N) - 1/2 log2(p d), 0) + 1
// (GPU Gems 3 eq. 20-13, with K = 1). The estimate is (1/N) sum_i L(wi) weight_i,
// weight_i = fs cos / p (shade/brdf.h), times ks.
// Diffuse term: kd * E(n) / pi from the order-3 SH irradiance of the environment
// (shade/sh_irradiance.h; the coefficients already carry A_l / pi).
// Visibility (issue 16, visMode != kFisVisNone): each sample's weight times the pixel's SH visibility
// at its direction, and the diffuse term from the lighting-visibility product (shade/visibility.h).
//
// Background pixels (G0.w = 0) show the environment along the camera ray: the equirectangular map, bilinear at
// level 0, as the other techniques do (kFisBackgroundEnvironment; issue 22: the atlas's 256^2 faces have about
// half the map's angular resolution), or the atlas at level 0 (kFisBackgroundAtlas, "fis": {"background": "atlas"}).
//
// Baselines of the error study (issue 4, item 4), the same pass with a mode:
//   kFisUnfiltered   the same deterministic samples read at level 0 (no filtering: aliasing);
//   kFisStochastic   the Hammersley set rotated per pixel (Cranley-Patterson, hashed pixel index),
//                    read at level 0: plain Monte Carlo BRDF sampling, noise instead of aliasing.

const uint kFisFiltered = 0u;
const uint kFisUnfiltered = 1u;
const uint kFisStochastic = 2u;

const uint kFisBackgroundEnvironment = 0u;
const uint kFisBackgroundAtlas = 1u;

struct FisFrame {
  Basis basis;  // world shading frame: t, b, n
  Float3 wo;    // view direction in it
};

// Shading frame from the G-buffer normal and tangent (Gram-Schmidt; handedness from G0.w's sign is
// irrelevant to these isotropic-or-aligned lobes: b = n x t).
FisFrame fisFrame(Float3 nIn, Float3 tIn, Float3 v) {
  Float3 n = exNormalize(nIn);
  PRECISE Float3 t = tIn - n * dot(n, tIn);
  t = exNormalize(select(dot(t, t) > 1.0e-12f, t, basisAbout(n).t));
  Float3 b = cross(n, t);
  Basis B = Basis(t, b, n);
  return FisFrame(B, basisToLocal(B, v));
}

Float4 shadeFis(Sampler2D atlas, Sampler2D env, uint background, uint mode, Float maxLod, Float log2KwhOverN, Float levelBias, uint sampleCount,
                Float intensity, ShRgb sh, Uint pixel, Float4 g0, Float4 g1, Float4 g2, Float3 eye, Float3 ray, Float3 diffuse, Float3 specular,
                BrdfParams brdf, uint visMode, Sh16 vis, VisLighting visLight) {
  Mask geometry = g0.w != 0.0f;
  Float3 p = Float3(g0.x, g0.y, g0.z);
  Float3 v = exNormalize(eye - p);
  FisFrame F = fisFrame(Float3(g1.x, g1.y, g1.z), Float3(g2.x, g2.y, g2.z), v);
  PRECISE Float3 sum = Float3(0.0f, 0.0f, 0.0f);
  // Background pixels skip the samples (a vector or invocation with no geometry does no work; the
  // lanes that run them without geometry are discarded by the select below).
  Mask visible = uniformMask(visMode != kFisVisNone);
  IF_ANY(geometry) {
    Float2 offset = pixelOffset(pixel);
    Mask stochastic = uniformMask(mode == kFisStochastic);
    FOR (uint i = 0u; i < sampleCount; i++) {
      Float2 u = hammersley(Uint(i), Uint(sampleCount));
      IF_ANY(stochastic) { u = select(stochastic, rotatePoint(u, offset), u); }
      BrdfSample s = sampleBrdf(brdf, F.wo, u);
      Float3 wi = basisToWorld(F.basis, s.wi);
      PRECISE Float l = 0.5f * (log2KwhOverN - exLog2(s.pdf * paraboloidJacobian(wi.z)));
      l = min(max(l, 0.0f) + levelBias, maxLod);  // pdf = 0 (a lost sample, weight 0) gives +inf: the coarsest level
      if (mode != kFisFiltered) l = Float(0.0f);
      Float4 L = textureLod(atlas, paraboloidUv(wi), l);
      PRECISE Float3 term = Float3(L.x, L.y, L.z) * s.weight;
      IF_ANY(visible) { term = select(visible, term * visAt(visMode, vis, F.basis.n, wi), term); }
      sum = sum + term;
    }
  }
  PRECISE Float invN = exDiv(1.0f, Float(sampleCount));
  Float3 irr = shIrradiance(sh, F.basis.n);
  IF_ANY(visible) { irr = select(visible, visIrradiance(visMode, visLight, vis, irr, F.basis.n), irr); }
  PRECISE Float3 c = sum * invN * specular + irr * diffuse;
  Float4 bg = Float4(0.0f, 0.0f, 0.0f, 0.0f);
  Mask atlasBackground = uniformMask(background == kFisBackgroundAtlas), envBackground = !atlasBackground;
  IF_ANY(atlasBackground) { bg = select(atlasBackground, textureLod(atlas, paraboloidUv(ray), 0.0f), bg); }
  IF_ANY(envBackground) { bg = select(envBackground, textureLod(env, equirectUv(ray), 0.0f), bg); }
  c = select(geometry, c, Float3(bg.x, bg.y, bg.z));
  c = c * intensity;
  return Float4(c.x, c.y, c.z, 1.0f);
}
