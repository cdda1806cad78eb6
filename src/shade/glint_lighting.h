// The glints lighting table (issue 17, docs/DESIGN.md §12): per view direction wo, the SH coefficients
// of the half-vector lighting Lambda(wh; wo) = L(wi(wh)) 4 (wo.wh),
//   Lambda_lm(wo) = integral Lambda Y_lm dwh = integral L(wi) Y_lm(normalize(wo + wi)) dwi
// (the substitution wh -> wi, dwh = dwi / (4 wo.wh), cancels the Jacobian), summed over the texels of
// one level of the environment: direction and solid angle from a host table (`dirs`, RGBA32F: xyz,
// dOmega, so every build adds the same terms), radiance by texelFetch. SH of any order with the
// scaled recurrences of sh_legendre.h, polar axis z in world space. One call computes one column m
// (every l = m .. order, the Y_l^m and Y_l^-m parts, RGB) for one view, texels in row-major order,
// so the sum's order is the same on every build. Dialect only.

const int kGlintMaxOrder = 64;

// Column m of one view: c[6 (l - m) + 0..2] the RGB coefficient of Y_l^m, c[6 (l - m) + 3..5] of Y_l^-m
// (0 for m = 0).
struct GlintColumn {
  Float c[6 * (kGlintMaxOrder + 1)];
};

// The recurrence's table entries of column m (they depend on l and m only, never on the texel): read once per call
// instead of once per texel (36,864 uniform fetches an invocation at order 16 over 64 x 32 texels, now 4,112). Seed
// factors of k = 1 .. m, and a, b of l = m + 1 .. order at index l - m. Every build multiplies by the same floats in
// the same order as before, so the table's bits do not change. Measured (docs/RESULTS.md, session 32): the emulator
// 1.23x and SwiftShader 1.06x faster; lavapipe not, since it reads an array at a loop-variable index with a scalar
// load per lane (as it reads and writes col.c below), which costs it about what the uniform fetch did.
struct GlintCoefs {
  Float seed[kGlintMaxOrder + 1];
  Float a[kGlintMaxOrder + 1];
  Float b[kGlintMaxOrder + 1];
};
GlintCoefs glintColumnCoefs(Sampler2D coef, int order, int m) {
  GlintCoefs g;
  FOR (int k = 1; k <= m; ++k) arraySet(g.seed, k, texelFetchUniform(coef, k, k, 0).x);
  FOR (int l = m + 1; l <= order; ++l) {
    Float4 c = texelFetchUniform(coef, l, m, 0);
    arraySet(g.a, l - m, c.x);
    arraySet(g.b, l - m, c.y);
  }
  return g;
}

// Rows y0 .. y1 - 1 of the level (a band: the host adds the bands in order; lavapipe stops every loop
// of an invocation after 65,535 back-edges, so the drivers keep a band's loops below that).
GlintColumn glintLightingColumn(Sampler2D env, Sampler2D dirs, Sampler2D coef, int envW, int y0, int y1, int level, int order,
                                int m, Float3 wo) {
  GlintColumn col;
  FOR (int i = 0; i < 6 * (kGlintMaxOrder + 1); ++i) arraySet(col.c, i, Float(0.0f));
  GlintCoefs g = glintColumnCoefs(coef, order, m);
  float mScale = m == 0 ? 1.0f : 1.41421356f;  // sqrt(2) for the m > 0 pair
  FOR (int y = y0; y < y1; ++y) {
    FOR (int x = 0; x < envW; ++x) {
      Float4 L = texelFetchUniform(env, x, y, level);
      Float4 d = texelFetchUniform(dirs, x, y, 0);
      PRECISE Float3 h = wo + Float3(d.x, d.y, d.z);
      PRECISE Float len2 = dot(h, h);
      Mask ok = len2 > 1e-12f;
      PRECISE Float3 hn = h * exInverseSqrt(select(ok, len2, Float(1.0f)));
      ShPolar pol = shPolar(hn);
      ShLeg s = shLegSeed0();
      ShAzimuth az = ShAzimuth(Float(1.0f), Float(0.0f));
      FOR (int k = 1; k <= m; ++k) {
        s = shLegSeedStep(s, arrayGet(g.seed, k), pol.sinT);
        az = shAzimuthNext(az, pol.cosP, pol.sinP);
      }
      PRECISE Float w = select(ok, d.w * mScale, Float(0.0f));
      PRECISE Float3 wl = Float3(L.x * w, L.y * w, L.z * w);
      FOR (int l = m; l <= order; ++l) {
        if (l > m) s = shLegStep(s, arrayGet(g.a, l - m), arrayGet(g.b, l - m), Mask(l == m + 1), pol.z);
        PRECISE Float p = shLegValue(s);
        PRECISE Float pc = p * az.c;
        PRECISE Float ps = p * az.s;
        int i = 6 * (l - m);
        arraySet(col.c, i + 0, arrayGet(col.c, i + 0) + wl.x * pc);
        arraySet(col.c, i + 1, arrayGet(col.c, i + 1) + wl.y * pc);
        arraySet(col.c, i + 2, arrayGet(col.c, i + 2) + wl.z * pc);
        arraySet(col.c, i + 3, arrayGet(col.c, i + 3) + wl.x * ps);
        arraySet(col.c, i + 4, arrayGet(col.c, i + 4) + wl.y * ps);
        arraySet(col.c, i + 5, arrayGet(col.c, i + 5) + wl.z * ps);
      }
    }
  }
  return col;
}
