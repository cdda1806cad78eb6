// Shared BRDF samplers (src/shade/brdf.h) through the C++ scalar build, the way pbrt and Mitsuba
// test their samplers: pdf integrates to the sampler's valid fraction (quadrature), sampled
// directions pass a chi-square goodness-of-fit test against the pdf, weight = f cos / pdf, the
// definitions equal the reference renderer's (double) ones, and the SIMD build agrees bit for bit.
// Also the Hammersley points and exSinCos2Pi.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "reference/reference_brdf.h"
#include "chi_square.h"
#include "lanes/instantiate.h"
#include "cli/verify/verify.h"

namespace sc = shadetwin::shade::scalar;
namespace x8 = shadetwin::shade::x8;
using V3f = shadetwin::shade::V3<float>;
using V2f = shadetwin::shade::V2<float>;

namespace {

constexpr double kPi = std::numbers::pi;

struct Case {
  std::string name;
  sc::BrdfParams p;
  double thetaO;  // view polar angle (radians)
  double scale;   // angular width of the lobe, for the chi-square bins
};

sc::BrdfParams params(uint32_t kind, float e = 0, float ax = 0, float ay = 0) {
  sc::BrdfParams p{};
  p.kind = kind, p.e = e, p.ax = ax, p.ay = ay;
  p.c0 = V3f(0, 0, 0), p.c1 = V3f(0, 0, 0);
  p.n0 = p.n1 = 1, p.rho0 = p.rho1 = 0;
  return p;
}

sc::BrdfParams lafortune(V3f c0, float n0, float rho0, V3f c1 = V3f(0, 0, 0), float n1 = 1, float rho1 = 0) {
  sc::BrdfParams p = params(sc::kBrdfLafortune);
  p.c0 = c0, p.n0 = n0, p.rho0 = rho0, p.c1 = c1, p.n1 = n1, p.rho1 = rho1;
  return p;
}

std::vector<Case> cases() {
  std::vector<Case> c;
  for (double th : {0.3, 1.2, 1.5}) {  // 17, 69 and 86 degrees (grazing)
    const std::string t = "_th" + std::to_string(int(th * 180 / kPi + 0.5));
    c.push_back({"phong10" + t, params(sc::kBrdfPhong, 10), th, 0.4});
    c.push_back({"phong1000" + t, params(sc::kBrdfPhong, 1000), th, 0.04});
    c.push_back({"phong1e5" + t, params(sc::kBrdfPhong, 1e5f), th, 0.004});
    c.push_back({"blinn50" + t, params(sc::kBrdfBlinn, 50), th, 0.3});
    c.push_back({"blinn5000" + t, params(sc::kBrdfBlinn, 5000), th, 0.04});
    c.push_back({"ward_iso" + t, params(sc::kBrdfWard, 0, 0.2f, 0.2f), th, 0.4});
    c.push_back({"ward_aniso" + t, params(sc::kBrdfWard, 0, 0.05f, 0.4f), th, 0.4});
    c.push_back({"ggx0.3" + t, params(sc::kBrdfGgx, 0, 0.3f, 0.3f), th, 0.6});
    c.push_back({"ggx0.02" + t, params(sc::kBrdfGgx, 0, 0.02f, 0.02f), th, 0.05});
    c.push_back({"lafortune1" + t, lafortune(V3f(-1, -1, 1), 30, 5), th, 0.3});
    c.push_back({"lafortune2" + t, lafortune(V3f(-0.9f, -0.9f, 1), 20, 4, V3f(0.3f, 0.3f, 0.5f), 2, 1), th, 0.8});
  }
  return c;
}

V3f viewDir(double th) { return V3f(float(std::sin(th)), 0.0f, float(std::cos(th))); }

// Lobe axis for the chi-square bins: the mirror direction (the lobes here peak near it).
shadetwin::reference::D3 mirrorAxis(double th) { return {-std::sin(th), 0, std::cos(th)}; }

// Chi-square bins. Phong and Lafortune lobes are binned in wi about the mirror axis. Half-vector
// samplers (Blinn, Ward, GGX) are binned in h = normalize(wi + wo) about the normal, where their
// density is smooth: a wi-bin near -wo would hold the integrable 1/(4 wo.h) singularity, which a
// midpoint rule cannot integrate. The expected mass of an h-bin is the integral of
// brdfPdf(reflect(wo, h)) * 4 (wo.h) dh, so the pdf function itself is still what is tested.
struct Bins {
  bool halfVector = false;
  V3f wo;
  shadetwin::reference::D3 a, t, b;  // frame about the axis
  int nt = 24, np = 16;
  double scale;
  // theta edge k of nt: scale * 2x/(1-x) with x = k/nt, the last edge at pi.
  double edge(int k) const {
    if (k >= nt) return kPi;
    const double x = double(k) / nt;
    return std::min(kPi, scale * 2 * x / (1 - x));
  }
  int index(V3f wi) const {
    V3f w = wi;
    if (halfVector) {
      const double hx = double(wi.x) + wo.x, hy = double(wi.y) + wo.y, hz = double(wi.z) + wo.z;
      const double l = std::sqrt(hx * hx + hy * hy + hz * hz);
      w = V3f(float(hx / l), float(hy / l), float(hz / l));
    }
    const double x = w.x * t.x + w.y * t.y + w.z * t.z, y = w.x * b.x + w.y * b.y + w.z * b.z,
                 z = w.x * a.x + w.y * a.y + w.z * a.z;
    const double th = std::acos(std::clamp(z, -1.0, 1.0));
    double ph = std::atan2(y, x);
    if (ph < 0) ph += 2 * kPi;
    int k = 0;
    while (k + 1 < nt && th >= edge(k + 1)) ++k;
    const int j = std::min(np - 1, int(ph / (2 * kPi) * np));
    return k * np + j;
  }
  V3f dir(double th, double ph) const {
    const double s = std::sin(th), c = std::cos(th);
    return V3f(float(s * std::cos(ph) * t.x + s * std::sin(ph) * b.x + c * a.x),
               float(s * std::cos(ph) * t.y + s * std::sin(ph) * b.y + c * a.y),
               float(s * std::cos(ph) * t.z + s * std::sin(ph) * b.z + c * a.z));
  }
};

Bins binsFor(const Case& c) {
  Bins B;
  B.halfVector = c.p.kind == sc::kBrdfBlinn || c.p.kind == sc::kBrdfWard || c.p.kind == sc::kBrdfGgx;
  B.wo = viewDir(c.thetaO);
  B.a = B.halfVector ? shadetwin::reference::D3{0, 0, 1} : mirrorAxis(c.thetaO);
  shadetwin::reference::RefBrdf::frame(B.a, B.t, B.b);
  B.scale = B.halfVector ? 0.5 * c.scale : c.scale;
  return B;
}

// pdf density in the bins' domain at direction d (wi, or h for half-vector bins).
double binDensity(const Case& c, const Bins& B, V3f d) {
  if (!B.halfVector) return sc::brdfPdf(c.p, B.wo, d);
  const double oh = double(B.wo.x) * d.x + double(B.wo.y) * d.y + double(B.wo.z) * d.z;
  if (oh <= 0) return 0;
  const V3f wi(float(2 * oh * d.x - B.wo.x), float(2 * oh * d.y - B.wo.y), float(2 * oh * d.z - B.wo.z));
  return double(sc::brdfPdf(c.p, B.wo, wi)) * 4 * oh;
}

// Integral of the pdf over each bin: midpoint rule on a sub-grid, in each bin's own (theta, phi).
std::vector<double> binIntegrals(const Case& c, const Bins& B, int sub) {
  std::vector<double> out(size_t(B.nt * B.np), 0.0);
  for (int k = 0; k < B.nt; ++k) {
    const double t0 = B.edge(k), t1 = B.edge(k + 1);
    for (int j = 0; j < B.np; ++j) {
      double sum = 0;
      for (int a = 0; a < sub; ++a) {
        const double th = t0 + (t1 - t0) * (a + 0.5) / sub;
        for (int q = 0; q < sub; ++q) {
          const double ph = 2 * kPi * (j + (q + 0.5) / sub) / B.np;
          sum += binDensity(c, B, B.dir(th, ph)) * std::sin(th);
        }
      }
      out[size_t(k * B.np + j)] = sum * (t1 - t0) / sub * (2 * kPi / B.np) / sub;
    }
  }
  return out;
}

struct GoF {
  double pValue = 0, validFraction = 0, pdfIntegral = 0;
  int dof = 0;
};

// Chi-square test of `samples` draws of `sampler` against the pdf of case c (bins pooled below 5 expected).
GoF goodnessOfFit(const Case& c, const sc::BrdfParams& samplerParams, int samples, uint32_t seed) {
  const Bins B = binsFor(c);
  const std::vector<double> mass = binIntegrals(c, B, 12);
  std::vector<double> observed(mass.size(), 0.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  const V3f wo = viewDir(c.thetaO);
  int valid = 0;
  for (int i = 0; i < samples; ++i) {
    const V2f u(U(rng), U(rng));
    const sc::BrdfSample s = sc::sampleBrdf(samplerParams, wo, u);
    if (!(s.pdf > 0.0f)) continue;  // a lost sample (reflected below the half-vector's hemisphere)
    ++valid;
    observed[size_t(B.index(s.wi))] += 1;
  }
  GoF g;
  g.validFraction = double(valid) / samples;
  for (double m : mass) g.pdfIntegral += m;
  const shadetwin::test::ChiSquare c2 = shadetwin::test::pooledChiSquare(mass, observed, samples);
  g.dof = c2.dof;
  g.pValue = c2.pValue;
  return g;
}

}  // namespace

TEST(Brdf, PdfIntegratesToTheValidFraction) {
  // The pdf integrates to 1 over the sphere, less the samples a half-vector sampler loses at grazing
  // views (h drawn in the upper hemisphere but wo.h < 0): the integral equals the sampler's valid fraction.
  for (const Case& c : cases()) {
    const Bins B = binsFor(c);
    double integral = 0;
    for (double m : binIntegrals(c, B, 16)) integral += m;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    int valid = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) valid += sc::sampleBrdf(c.p, viewDir(c.thetaO), V2f(U(rng), U(rng))).pdf > 0.0f;
    const double frac = double(valid) / n;
    EXPECT_NEAR(integral, frac, 0.012) << c.name;
    if (c.thetaO < 1.0) {
      EXPECT_NEAR(integral, 1.0, 0.01) << c.name;
    }
  }
}

TEST(Brdf, SamplesPassChiSquareAgainstThePdf) {
  const auto all = cases();
  const double alpha = 0.01 / double(all.size());  // Bonferroni over the cases
  for (size_t i = 0; i < all.size(); ++i) {
    const GoF g = goodnessOfFit(all[i], all[i].p, 100000, uint32_t(100 + i));
    EXPECT_GT(g.pValue, alpha) << all[i].name << " dof " << g.dof;
    EXPECT_GT(g.dof, 30) << all[i].name;  // the bins resolve the lobe
  }
}

TEST(Brdf, ChiSquareRejectsAWrongSampler) {
  // Negative control: samples of a slightly different lobe (exponent or roughness 15% off) against the pdf.
  for (const Case& c : cases()) {
    if (c.thetaO > 1.0) continue;
    sc::BrdfParams wrong = c.p;
    wrong.e *= 1.15f, wrong.ax *= 1.15f, wrong.ay *= 1.15f, wrong.n0 *= 1.15f, wrong.n1 *= 1.15f;
    const GoF g = goodnessOfFit(c, wrong, 100000, 7);
    EXPECT_LT(g.pValue, 1e-6) << c.name;
  }
}

TEST(Brdf, WeightIsEvalTimesCosineOverPdf) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  for (const Case& c : cases()) {
    const V3f wo = viewDir(c.thetaO);
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
      const sc::BrdfSample s = sc::sampleBrdf(c.p, wo, V2f(U(rng), U(rng)));
      if (!(s.weight > 0.0f)) continue;
      const double f = sc::brdfEval(c.p, wo, s.wi), pdf = sc::brdfPdf(c.p, wo, s.wi);
      ASSERT_GT(pdf, 0.0) << c.name;
      // Evaluating cos^e at a float direction carries ~e * 2^-23 relative error (cos is rounded to
      // 24 bits); the sampler's own pdf comes from u and does not.
      const double tol = 2e-3 + 4 * double(std::max(c.p.e, c.p.n0)) * 1.2e-7;
      EXPECT_NEAR(s.pdf / pdf, 1.0, tol) << c.name;
      EXPECT_NEAR(s.weight / (f * s.wi.z / pdf), 1.0, tol) << c.name;
      ++checked;
    }
    EXPECT_GT(checked, 100) << c.name;
  }
}

TEST(Brdf, DefinitionsMatchTheReferenceRenderer) {
  using shadetwin::reference::D3;
  using shadetwin::reference::Lobe;
  using shadetwin::reference::RefBrdf;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  struct Pair {
    sc::BrdfParams p;
    RefBrdf r;
  };
  auto ref = [](Lobe lobe, double e, double ax, double ay) {
    RefBrdf r;
    r.lobe = lobe, r.exponent = e, r.ax = ax, r.ay = ay;
    return r;
  };
  // Lafortune, two lobes: the scene's lobes reach both through the same parameters.
  RefBrdf lf = ref(Lobe::Lafortune, 0, 0, 0);
  lf.lobes[0] = {{-0.9, -0.9, 1.0}, 20, 4};
  lf.lobes[1] = {{0.3, 0.3, 0.5}, 2, 1};
  const Pair pairs[] = {{params(sc::kBrdfPhong, 40), ref(Lobe::Phong, 40, 0, 0)},
                        {params(sc::kBrdfBlinn, 40), ref(Lobe::Blinn, 40, 0, 0)},
                        {params(sc::kBrdfWard, 0, 0.1f, 0.3f), ref(Lobe::Ward, 0, 0.1, 0.3)},
                        {params(sc::kBrdfGgx, 0, 0.25f, 0.25f), ref(Lobe::Ggx, 0, 0.25, 0.25)},
                        {lafortune(V3f(-0.9f, -0.9f, 1), 20, 4, V3f(0.3f, 0.3f, 0.5f), 2, 1), lf}};
  for (const Pair& q : pairs) {
    int n = 0;
    for (int i = 0; i < 3000; ++i) {
      const double ct = U(rng), st = std::sqrt(1 - ct * ct), ph = 2 * kPi * U(rng);
      const double co = 0.05 + 0.95 * U(rng), so = std::sqrt(1 - co * co);
      const D3 wi{st * std::cos(ph), st * std::sin(ph), ct}, wo{so, 0, co};
      const V3f wif(float(wi.x), float(wi.y), float(wi.z)), wof(float(wo.x), float(wo.y), float(wo.z));
      const double fr = q.r.glossy(wi, wo), pr = q.r.glossyPdf(wi, wo);
      if (fr < 1e-3 || pr < 1e-3) continue;  // compare where the values are well conditioned in float
      EXPECT_NEAR(sc::brdfEval(q.p, wof, wif) / fr, 1.0, 1e-3) << int(q.r.lobe);
      EXPECT_NEAR(sc::brdfPdf(q.p, wof, wif) / pr, 1.0, 1e-3) << int(q.r.lobe);
      ++n;
    }
    EXPECT_GT(n, 200);
  }
}

TEST(Brdf, SimdBuildAgreesWithScalarBitForBit) {
  // Lanes of mixed kinds (the dispatch selects per lane; IF_ANY only skips kinds no lane has).
  const auto all = cases();
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  using F = emu::F32<8>;
  using U8 = emu::U32<8>;
  for (int rep = 0; rep < 400; ++rep) {
    sc::BrdfParams ps[8];
    V3f wos[8];
    V2f us[8];
    x8::BrdfParams P{};
    shadetwin::shade::V3<F> wo(F(0.0f), F(0.0f), F(0.0f));
    shadetwin::shade::V2<F> u(F(0.0f), F(0.0f));
    U8 kind(0u);
    for (int l = 0; l < 8; ++l) {
      const Case& c = all[rng() % all.size()];
      ps[l] = c.p, wos[l] = viewDir(c.thetaO), us[l] = V2f(U(rng), U(rng));
      kind.set(l, c.p.kind);
      P.e.set(l, c.p.e), P.ax.set(l, c.p.ax), P.ay.set(l, c.p.ay);
      P.c0.x.set(l, c.p.c0.x), P.c0.y.set(l, c.p.c0.y), P.c0.z.set(l, c.p.c0.z);
      P.c1.x.set(l, c.p.c1.x), P.c1.y.set(l, c.p.c1.y), P.c1.z.set(l, c.p.c1.z);
      P.n0.set(l, c.p.n0), P.n1.set(l, c.p.n1), P.rho0.set(l, c.p.rho0), P.rho1.set(l, c.p.rho1);
      wo.x.set(l, wos[l].x), wo.y.set(l, wos[l].y), wo.z.set(l, wos[l].z);
      u.x.set(l, us[l].x), u.y.set(l, us[l].y);
    }
    P.kind = kind;
    const x8::BrdfSample s = x8::sampleBrdf(P, wo, u);
    const F pdf = x8::brdfPdf(P, wo, s.wi);
    const shadetwin::shade::V3<F> dir = x8::sampleBrdfDirection(P, wo, u);
    for (int l = 0; l < 8; ++l) {
      const sc::BrdfSample r = sc::sampleBrdf(ps[l], wos[l], us[l]);
      ASSERT_TRUE(shadetwin::sameBits(r.wi.x, s.wi.x[l]) && shadetwin::sameBits(r.wi.y, s.wi.y[l]) &&
                  shadetwin::sameBits(r.wi.z, s.wi.z[l]));
      // The direction-only sampler (the MIS techniques' BRDF strategy) draws the same direction, both builds.
      const V3f d = sc::sampleBrdfDirection(ps[l], wos[l], us[l]);
      ASSERT_TRUE(shadetwin::sameBits(r.wi.x, d.x) && shadetwin::sameBits(r.wi.y, d.y) && shadetwin::sameBits(r.wi.z, d.z));
      ASSERT_TRUE(shadetwin::sameBits(r.wi.x, dir.x[l]) && shadetwin::sameBits(r.wi.y, dir.y[l]) &&
                  shadetwin::sameBits(r.wi.z, dir.z[l]));
      ASSERT_TRUE(shadetwin::sameBits(r.pdf, s.pdf[l]));
      ASSERT_TRUE(shadetwin::sameBits(r.weight, s.weight[l]));
      ASSERT_TRUE(shadetwin::sameBits(sc::brdfPdf(ps[l], wos[l], r.wi), pdf[l]));
    }
  }
}

TEST(Sampling, HammersleyPoints) {
  EXPECT_EQ(sc::radicalInverse2(0u), 0.0f);
  EXPECT_EQ(sc::radicalInverse2(1u), 0.5f);
  EXPECT_EQ(sc::radicalInverse2(2u), 0.25f);
  EXPECT_EQ(sc::radicalInverse2(3u), 0.75f);
  EXPECT_EQ(sc::radicalInverse2(6u), 0.375f);
  // The N points stratify both axes: each of N intervals [k/N, (k+1)/N) holds exactly one coordinate.
  for (uint32_t n : {16u, 64u, 1024u}) {
    std::vector<int> cx(n, 0), cy(n, 0);
    for (uint32_t i = 0; i < n; ++i) {
      const V2f p = sc::hammersley(i, n);
      cx[size_t(p.x * float(n))]++;
      cy[size_t(p.y * float(n))]++;
    }
    for (uint32_t k = 0; k < n; ++k) ASSERT_TRUE(cx[k] == 1 && cy[k] == 1) << n << " " << k;
  }
}

TEST(Sampling, SinCos2PiWithinTwoUlp) {
  // Dense sweep of u in [-2, 2] (every 2^-20) and random u in [0, 1): |error| <= 2 ULP (or 1e-7
  // absolute near the zeros of sin / cos, where ULPs of the result vanish).
  auto check = [](float u) {
    const sc::XmSinCos r = sc::exSinCos2Pi(u);
    const double s = std::sin(2 * kPi * double(u)), c = std::cos(2 * kPi * double(u));
    const bool sOk = shadetwin::ulpDistance(r.s, float(s)) <= 2 || std::fabs(r.s - s) < 1e-7;
    const bool cOk = shadetwin::ulpDistance(r.c, float(c)) <= 2 || std::fabs(r.c - c) < 1e-7;
    return sOk && cOk;
  };
  for (int i = -(2 << 20); i <= (2 << 20); ++i) ASSERT_TRUE(check(float(i) * 9.5367431640625e-07f)) << i;
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  for (int i = 0; i < 1000000; ++i) {
    const float u = U(rng);
    ASSERT_TRUE(check(u)) << u;
  }
  // Exact at the quarter turns.
  EXPECT_EQ(sc::exSinCos2Pi(0.25f).s, 1.0f);
  EXPECT_EQ(sc::exSinCos2Pi(0.5f).c, -1.0f);
}

TEST(Sampling, PixelOffsetsAreUniformAndRotationStaysInTheUnitSquare) {
  // The stochastic baseline's per-pixel Cranley-Patterson offsets: chi-square of 64 x 64 cells over
  // 2^18 pixels (4095 dof: mean 4095, sd 90.5; bound mean + 5 sd), rotated points in [0, 1), and the
  // SIMD build equal to the scalar one.
  const int cells = 64, n = 1 << 18;
  std::vector<int> hist(cells * cells, 0);
  for (uint32_t p = 0; p < uint32_t(n); ++p) {
    const V2f r = sc::pixelOffset(p);
    ASSERT_TRUE(r.x >= 0.0f && r.x < 1.0f && r.y >= 0.0f && r.y < 1.0f) << p;
    ++hist[int(r.y * cells) * cells + int(r.x * cells)];
    const V2f u = sc::rotatePoint(sc::hammersley(p % 256u, 256u), r);
    ASSERT_TRUE(u.x >= 0.0f && u.x < 1.0f && u.y >= 0.0f && u.y < 1.0f) << p;
  }
  const double expect = double(n) / (cells * cells);
  double chi2 = 0;
  for (int h : hist) chi2 += (h - expect) * (h - expect) / expect;
  EXPECT_LT(chi2, 4095 + 5 * 90.5);
  EXPECT_GT(chi2, 4095 - 5 * 90.5);  // not suspiciously regular either
  EXPECT_EQ(sc::rotatePoint(V2f(0.75f, 0.5f), V2f(0.25f, 0.75f)).x, 0.0f);
  emu::U32<8> px;
  for (int l = 0; l < 8; ++l) px.set(l, uint32_t(1000003 * l + 7));
  const auto r8 = x8::pixelOffset(px);
  for (int l = 0; l < 8; ++l) {
    const V2f r = sc::pixelOffset(uint32_t(1000003 * l + 7));
    EXPECT_EQ(r.x, r8.x[l]);
    EXPECT_EQ(r.y, r8.y[l]);
  }
}
