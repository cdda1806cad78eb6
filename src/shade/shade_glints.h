// Technique glints (issue 17; Gamboa, Guertin, Nowrouzezahrai 2018; docs/DESIGN.md §12): per pixel,
// the footprint's NDF histogram from the SAT, as SH (every non-empty bin's Gaussian lobe, rotated to
// the bin's direction in world space through the pixel's tangent frame: D_lm += (count / area) k_l
// Y_lm(d_b)), dotted with the half-vector lighting's SH interpolated between the four table views
// around wo, times F G / (4 cos_o) at the macro normal:
//   L_o = F(wo.n) G1(wo) G1(r) / (4 cos_o) * max(0, sum_lm Lambda_lm(wo) D_lm),   r = reflect(wo, n).
// Adaptive band limit (docs/DESIGN.md §12): each lane sums bands up to M* = min(M_NDF, M_light), M_NDF
// its material's lobe band limit at 1e-6 (material row texel 6, .y), M_light the largest of the four
// table views' lighting band limits (lighting texel (0, view), .w; glintLightBandLimits); k_l is 0
// beyond M*, and bands no lane of the vector needs are skipped (IF_ANY), so a lane's sum is the same
// whichever lanes share its vector. Loops run to the frame's degree `order`. Bins no lane of the
// vector has are skipped (IF_ANY). Background pixels: the environment along the camera ray. Dialect only.

const int kGlintShadeMaxOrder = 64;
// The D_lm array's length: (64 + 1)^2 in C++; on a device the host sets it to the frame's (order + 1)^2
// (specialization constant 1), since a private array's size is paid per invocation (lavapipe: 1.8x the
// pass time at degree 16 with 4,225 floats instead of 289).
SPEC_INT(kGlintShadeCoeffs, 1, 4225)
// Which ways to the bins' SH a pipeline holds: bit 0 the recurrences, bit 1 the rotated-lobe table. The
// host sets the one the frame uses (specialization constant 2): lavapipe executes both sides of a branch
// even when it is uniform, so a pipeline with both paid for both (1.5x at degree 16). C++: both.
SPEC_INT(kGlintShadePaths, 2, 3)

struct GlintSettings {
  uint order;        // shading degree (<= kGlintShadeMaxOrder)
  uint rings;        // NDF bins in theta
  uint sectors;      // NDF bins in phi (a multiple of 8)
  uint mapW;         // normal map size (texels)
  uint mapH;
  float invW;        // 1 / mapW, 1 / mapH (host-rounded quotient guesses for ndfDivMod)
  float invH;
  uint viewRings;    // lighting table views
  uint viewSectors;
  uint lobeRings;    // rotated-lobe table directions (0: the recurrences at each bin's direction)
  uint lobeSectors;
};

// The four grid points around direction d of a (rings x sectors) equirectangular grid whose row j is
// v = j / (rings - 1) (poles included) and column k is u = k / sectors (the lighting table's views and
// the lobe table's directions), and the bilinear weights (theta clamped, phi wrapping).
struct GlintGridTap {
  Int v00;
  Int v01;
  Int v10;
  Int v11;
  Float ax;
  Float ay;
};
GlintGridTap glintGridTap(Float3 d, uint rings, uint sectors) {
  Float2 uv = equirectUv(d);
  PRECISE Float fx = uv.x * float(sectors);
  PRECISE Float fy = uv.y * float(rings - 1u);
  Int x0 = Int(floor(fx));
  PRECISE Float ax = fx - floor(fx);
  x0 = select(x0 >= Int(int(sectors)), x0 - Int(int(sectors)), x0);
  Int x1 = select(x0 + Int(1) >= Int(int(sectors)), Int(0), x0 + Int(1));
  Int y0 = clamp(Int(floor(fy)), Int(0), Int(int(rings) - 2));
  PRECISE Float ay = clamp(fy - Float(y0), 0.0f, 1.0f);
  Int vs = Int(int(sectors));
  return GlintGridTap(y0 * vs + x0, y0 * vs + x1, (y0 + Int(1)) * vs + x0, (y0 + Int(1)) * vs + x1, ax, ay);
}

// Bilinear at a tap of a table whose row v holds a direction's values (texel x of row v).
Float4 glintGridLerp(Sampler2D t, int x, GlintGridTap k) {
  Float4 a = texelFetch2D(t, Int(x), k.v00, 0);
  Float4 b = texelFetch2D(t, Int(x), k.v01, 0);
  Float4 c = texelFetch2D(t, Int(x), k.v10, 0);
  Float4 d = texelFetch2D(t, Int(x), k.v11, 0);
  PRECISE Float4 top = a * (1.0f - k.ax) + b * k.ax;
  PRECISE Float4 bot = c * (1.0f - k.ax) + d * k.ax;
  PRECISE Float4 r = top * (1.0f - k.ay) + bot * k.ay;
  return r;
}

Float4 shadeGlints(USampler2DArray sat, Sampler2D binDirs, Sampler2D mats, Sampler2D lighting, Sampler2D coef, Sampler2D lobes, Sampler2D env,
                   GlintSettings s, Float intensity, Float4 g0, Float4 g1, Float4 g2, Float4 g3, Float3 eye, Float3 ray, Int row) {
  Mask geometry = g0.w != 0.0f;
  PRECISE Float3 up = Float3(Float(0.0f), Float(0.0f), Float(1.0f));
  PRECISE Float3 n = exNormalize(select(geometry, Float3(g1.x, g1.y, g1.z), up));
  PRECISE Float3 tg = Float3(g2.x, g2.y, g2.z);
  PRECISE Float3 tp = tg - n * dot(n, tg);
  // A degenerate tangent (none, or along n): any perpendicular (the map's orientation is then arbitrary).
  PRECISE Float3 alt = select(abs(n.x) < 0.9f, Float3(Float(0.0f), -n.z, n.y), Float3(-n.z, Float(0.0f), n.x));
  PRECISE Float3 t = exNormalize(select(dot(tp, tp) > 1e-12f, tp, alt));
  PRECISE Float3 b = cross(n, t) * select(g0.w < 0.0f, Float(-1.0f), Float(1.0f));
  PRECISE Float3 wo = exNormalize(select(geometry, eye - Float3(g0.x, g0.y, g0.z), up));
  PRECISE Float cosO = dot(n, wo);
  Mask lit = geometry && cosO > 0.0f;
  Float4 m0 = texelFetch2D(mats, Int(0), row, 0);  // eta, sigma
  Float4 m1 = texelFetch2D(mats, Int(1), row, 0);  // k, texels per uv
  GlintBox box = glintFootprint(g1.w, g2.w, g3, m1.w);
  PRECISE Float area = Float(box.x1 - box.x0 + Int(1)) * Float(box.y1 - box.y0 + Int(1));
  PRECISE Float invArea = exDiv(1.0f, area);
  int order = int(s.order);
  int nc = (order + 1) * (order + 1);
  // Lambda(wo): bilinear between the four table views around wo.
  GlintGridTap view = glintGridTap(wo, s.viewRings, s.viewSectors);
  // M* = min(M_NDF, M_light), the lighting's limit the largest of the four views' (any bilinear
  // weight may be the whole).
  Float4 k0 = texelFetch2D(mats, Int(6), row, 0);
  Float lightMax = max(max(texelFetch2D(lighting, Int(0), view.v00, 0).w, texelFetch2D(lighting, Int(0), view.v01, 0).w),
                       max(texelFetch2D(lighting, Int(0), view.v10, 0).w, texelFetch2D(lighting, Int(0), view.v11, 0).w));
  Int mstar = min(Int(k0.y), Int(lightMax));
  Float kl[kGlintShadeMaxOrder + 1];
  FOR (int l = 0; l <= order; ++l)
    arraySet(kl, l, select(Int(l) <= mstar, texelFetch2D(mats, Int(6 + l), row, 0).x, Float(0.0f)));
  Float D[kGlintShadeCoeffs];
  FOR (int i = 0; i < nc; ++i) arraySet(D, i, Float(0.0f));
  int groups = int(s.sectors) / 8;
  FOR (int r = 0; r < int(s.rings); ++r) {
    Float4 slots = texelFetch2D(mats, Int(2 + r / 4), row, 0);
    Float slotF = slots.x;
    if (r % 4 == 1) slotF = slots.y;
    if (r % 4 == 2) slotF = slots.z;
    if (r % 4 == 3) slotF = slots.w;
    Mask has = lit && slotF >= 0.0f;
    Int layer = Int(max(slotF, 0.0f));
    IF_ANY(has) {
      FOR (int g = 0; g < groups; ++g) {
        UintTexel4 c8 = ndfBoxCounts8(sat, layer, g, groups, int(s.mapW), int(s.mapH), s.invW, s.invH, box.x0, box.y0, box.x1, box.y1);
        for (int j = 0; j < 8; ++j) {
          Uint word = c8.x;
          if (j / 2 == 1) word = c8.y;
          if (j / 2 == 2) word = c8.z;
          if (j / 2 == 3) word = c8.w;
          Uint cnt = (word >> uint(16 * (j % 2))) & 0xffffu;
          Mask on = has && cnt > Uint(0u);
          IF_ANY(on) {
            PRECISE Float w = select(on, Float(cnt) * invArea, Float(0.0f));
            Float4 dt = texelFetchUniform(binDirs, 8 * g + j, r, 0);
            PRECISE Float3 d = t * dt.x + b * dt.y + n * dt.z;
            if ((kGlintShadePaths & 2) != 0 && s.lobeRings > 0u) {
              // The rotated-lobe table: Y_lm at the bin's direction, bilinear between the four grid
              // directions around it; four coefficients (index 4 q .. 4 q + 3) per texel.
              GlintGridTap lt = glintGridTap(d, s.lobeRings, s.lobeSectors);
              int lq = 0;  // the degree of coefficient 4 q
              FOR (int q = 0; q < (nc + 3) / 4; ++q) {
                if ((lq + 1) * (lq + 1) <= 4 * q) ++lq;
                if ((lq + 1) * (lq + 1) <= 4 * q) ++lq;  // q = 1: from degree 0 to 2
                IF_ANY(Int(lq) <= mstar) {
                  Float4 y4 = glintGridLerp(lobes, q, lt);
                  int l4 = lq;
                  for (int j = 0; j < 4; ++j) {
                    int i = 4 * q + j;
                    if (i < nc) {
                      if ((l4 + 1) * (l4 + 1) <= i) ++l4;
                      Float y = y4.x;
                      if (j == 1) y = y4.y;
                      if (j == 2) y = y4.z;
                      if (j == 3) y = y4.w;
                      arraySet(D, i, arrayGet(D, i) + w * (y * arrayGet(kl, l4)));
                    }
                  }
                }
              }
            }
            if ((kGlintShadePaths & 1) != 0 && s.lobeRings == 0u) {
            // The recurrences at the bin's direction (exact up to float rounding).
            ShPolar pol = shPolar(d);
            ShLeg seed = shLegSeed0();
            ShAzimuth az = ShAzimuth(Float(1.0f), Float(0.0f));
            FOR (int m = 0; m <= order; ++m) {
              // Past its M* a lane's k_l are 0: what it adds there is +-0.
              IF_ANY(Int(m) <= mstar) {
                if (m > 0) {
                  seed = shLegSeedNext(seed, coef, m, pol.sinT);
                  az = shAzimuthNext(az, pol.cosP, pol.sinP);
                }
                PRECISE Float wc = select(Mask(m == 0), w, w * 1.41421356f) * az.c;
                PRECISE Float ws = (w * 1.41421356f) * az.s;
                ShLeg sl = seed;
                FOR (int l = m; l <= order; ++l) {
                  IF_ANY(Int(l) <= mstar) {
                    if (l > m) sl = shLegNext(sl, coef, l, m, pol.z);
                    PRECISE Float p = shLegValue(sl) * arrayGet(kl, l);
                    arraySet(D, l * l + l + m, arrayGet(D, l * l + l + m) + wc * p);
                    if (m > 0) arraySet(D, l * l + l - m, arrayGet(D, l * l + l - m) + ws * p);
                  }
                }
              }
            }
            }
          }
        }
      }
    }
  }
  PRECISE Float3 sum = Float3(Float(0.0f), Float(0.0f), Float(0.0f));
  FOR (int l = 0; l <= order; ++l) {
    IF_ANY(Int(l) <= mstar) {  // D is 0 past M*: L * 0 adds +-0
      FOR (int i = l * l; i < (l + 1) * (l + 1); ++i) {
        Float4 L = glintGridLerp(lighting, i, view);
        sum = sum + Float3(L.x, L.y, L.z) * arrayGet(D, i);
      }
    }
  }
  PRECISE Float alpha = m0.w * 1.41421356f;
  // r = reflect(wo, n) makes the same angle with n as wo: G1(r) = G1(wo).
  PRECISE Float3 F = fresnelConductor(cosO, Float3(m0.x, m0.y, m0.z), Float3(m1.x, m1.y, m1.z));
  PRECISE Float g1o = smithG1Beckmann(cosO, alpha);
  PRECISE Float G = g1o * g1o;
  PRECISE Float scale = exDiv(G, 4.0f * max(cosO, 1e-6f));
  // The truncated series of a narrow lobe against a sun rings below zero (order 16 against a lobe
  // that needs ~100 at 1e-6): radiance is clamped at 0, the ringing stays visible as dark patches.
  PRECISE Float3 rad = Float3(max(sum.x * F.x, 0.0f), max(sum.y * F.y, 0.0f), max(sum.z * F.z, 0.0f)) * scale;
  Float4 bg = textureLod(env, equirectUv(ray), 0.0f);
  PRECISE Float3 col = select(geometry, select(lit, rad, Float3(Float(0.0f), Float(0.0f), Float(0.0f))), Float3(bg.x, bg.y, bg.z));
  col = col * intensity;
  return Float4(col.x, col.y, col.z, 1.0f);
}
