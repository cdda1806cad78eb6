// Environment-map importance sampling with the environment as directional lights: the baseline
// "env" of the FIS error study (Colbert & Krivanek 2008 compare FIS against it, sec. 5; the
// lights are N samples of the environment's luminance, Agarwal et al. 2003 style).
//
// The host (inputs/env_lights.cpp) draws N directions w_j from the piecewise-constant pdf of the
// equirectangular map (texel probability P_t proportional to max(luminance, 0) sin(theta_t),
// solid-angle pdf p_j = P_t W H / (2 pi^2 sin(theta_t))) at the Hammersley points, and gives each
// light the weight W_j = L_t / (N p_j) (its radiance over N times its pdf). Then per pixel
//   c = sum_j (kd / pi + ks fs(w_j, wo)) max(cos theta_j, 0) W_j,
// the Monte Carlo estimate of the rendering equation without visibility (as FIS). Every pixel uses
// the same N lights: the error is structured (banding) rather than noise.
//
// The loop over lights is the entry points' (GLSL src/shaders/shade_env.comp, C++ passes/shade_emu.cpp:
// a light list is a buffer there), light 0 first, each step one envAddLight: the same order in both
// builds.

// sum + the contribution of one light (direction `dir`, weight `weight`, world space) to a pixel.
Float3 envAddLight(Float3 sum, FisFrame F, BrdfParams brdf, Float3 diffuse, Float3 specular, Float3 dir, Float3 weight) {
  Float3 wi = basisToLocal(F.basis, dir);
  Float fs = brdfEval(brdf, F.wo, wi);
  PRECISE Float3 f = diffuse * kBrdfInvPi + specular * fs;
  PRECISE Float3 c = f * (max(wi.z, 0.0f)) * weight;
  return shAdd3(sum, select(wi.z > 0.0f, c, Float3(0.0f, 0.0f, 0.0f)));
}

// The pixel's shading frame (as FIS) for the light loop.
FisFrame envFrame(Float4 g0, Float4 g1, Float4 g2, Float3 eye) {
  Float3 p = Float3(g0.x, g0.y, g0.z);
  Float3 v = exNormalize(eye - p);
  return fisFrame(Float3(g1.x, g1.y, g1.z), Float3(g2.x, g2.y, g2.z), v);
}

// Final colour: the light sum on geometry, the environment (level 0) along the ray elsewhere.
Float4 envFinish(Sampler2D env, Float4 g0, Float3 ray, Float3 sum, Float intensity) {
  Mask geometry = g0.w != 0.0f;
  Float4 bg = textureLod(env, equirectUv(ray), 0.0f);
  PRECISE Float3 c = select(geometry, sum, Float3(bg.x, bg.y, bg.z));
  c = c * intensity;
  return Float4(c.x, c.y, c.z, 1.0f);
}
