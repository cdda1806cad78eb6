// The reference renderer (src/reference/): BRDF sampling matches its pdf, white-furnace and
// analytic albedo cases, the mirror lobe, convergence (error halves when spp quadruples),
// determinism across thread counts.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <sstream>

#include "util/compare.h"
#include "reference/reference.h"
#include "reference/reference_brdf.h"
#include "inputs/environment.h"
#include "scene/scene.h"

namespace {

using shadetwin::reference::D3;
using shadetwin::reference::Lobe;
using shadetwin::reference::RefBrdf;

RefBrdf glossyOnly(Lobe lobe) {
  RefBrdf b;
  b.lobe = lobe;
  for (int k = 0; k < 3; ++k) b.kd[k] = 0, b.ks[k] = 1;
  b.exponent = 20;
  b.ax = 0.3, b.ay = lobe == Lobe::Ward ? 0.5 : 0.3;
  // Lafortune: a 60%-normalized Phong-like lobe about the mirror direction plus a broad
  // forward-leaning lobe (Cx, Cy > 0) of exponent 4.
  b.lobes[0] = {{-1, -1, 1}, 20, 0.6 * 22 / (2 * std::numbers::pi)};
  b.lobes[1] = {{0.5, 0.5, 0.8}, 4, 0.5};
  return b;
}

/// Midpoint quadrature over the upper hemisphere in (cos theta, phi): dw = dz dphi.
template <class F> double hemisphere(F f, int n = 1200) {
  double s = 0;
  const double dz = 1.0 / n, dp = 2 * std::numbers::pi / (2 * n);
  for (int i = 0; i < n; ++i) {
    const double z = (i + 0.5) * dz, r = std::sqrt(1 - z * z);
    for (int j = 0; j < 2 * n; ++j) {
      const double p = (j + 0.5) * dp;
      s += f(D3{r * std::cos(p), r * std::sin(p), z});
    }
  }
  return s * dz * dp;
}

TEST(ReferenceBrdf, SamplingMatchesPdfAndAlbedo) {
  // For each lobe and two view directions: (a) the pdf integrates to at most 1 over the upper
  // hemisphere, and to 1 at normal incidence for the lobes whose mass all lies above it; (b) the
  // Monte Carlo albedo E[f cos / pdf] with sample() equals the quadrature of f cos (so sample()
  // draws from pdf()); (c) energy conservation: albedo <= 1.
  const D3 views[2] = {{0, 0, 1}, {std::sin(0.8), 0, std::cos(0.8)}};
  for (Lobe lobe : {Lobe::Phong, Lobe::Blinn, Lobe::Ggx, Lobe::Ward, Lobe::Lafortune}) {
    const RefBrdf b = glossyOnly(lobe);
    for (const D3& wo : views) {
      const double pdfMass = hemisphere([&](D3 wi) { return b.glossyPdf(wi, wo); });
      const double albedo = hemisphere([&](D3 wi) { return b.glossy(wi, wo) * wi.z; });
      EXPECT_LE(pdfMass, 1.0 + 2e-3) << int(lobe);
      if (wo.z == 1.0 && lobe != Lobe::Ggx && lobe != Lobe::Ward && lobe != Lobe::Lafortune) {
        EXPECT_NEAR(pdfMass, 1.0, 3e-3) << int(lobe);
      }
      // The (e + 8) / (8 pi) Blinn-Phong normalization is the usual approximation: it reflects a
      // little more than it receives away from normal incidence (1.061 at 46 degrees, e = 20).
      EXPECT_LE(albedo, lobe == Lobe::Blinn ? 1.07 : 1.0 + 2e-3) << int(lobe);
      EXPECT_GT(albedo, 0.3) << int(lobe);
      std::mt19937_64 rng(7);
      std::uniform_real_distribution<double> U(0, 1);
      double est = 0;
      const int n = 400000;
      for (int i = 0; i < n; ++i) {
        const D3 wi = b.sample(wo, U(rng), U(rng), U(rng));
        const double p = b.pdf(wi, wo);
        if (wi.z > 0 && p > 0) est += b.glossy(wi, wo) * wi.z / p;
      }
      est /= n;
      EXPECT_NEAR(est, albedo, 0.01 * albedo) << "lobe " << int(lobe) << " view z " << wo.z;
    }
  }
  // Normalized Phong seen head-on reflects exactly its ks: integral of (e+2)/(2 pi) cos^(e+1) = 1.
  const RefBrdf p = glossyOnly(Lobe::Phong);
  EXPECT_NEAR(hemisphere([&](D3 wi) { return p.glossy(wi, {0, 0, 1}) * wi.z; }), 1.0, 2e-3);
}

struct TestScene {
  shadetwin::Scene scene;
  std::vector<float> env;
  shadetwin::EnvImage img() const { return {64, 32, env.data()}; }
};

/// A unit sphere filling the middle of a 32 x 32 image, under a constant environment of radiance 1.
TestScene furnace(const std::string& brdf, float kd, float ks) {
  TestScene t;
  t.scene.width = t.scene.height = 32;
  t.scene.camera.eye = {0, 0, 4};
  t.scene.camera.fovY = 40;
  t.scene.meshes.push_back(shadetwin::makeSphere(128, 64));
  shadetwin::Material m;
  m.brdf = brdf;
  m.diffuse = {kd, kd, kd};
  m.specular = {ks, ks, ks};
  m.exponent = 50;
  t.scene.materials.push_back(m);
  shadetwin::Object o;
  o.model = shadetwin::identity();
  t.scene.objects.push_back(o);
  t.env.assign(64 * 32 * 4, 1.0f);
  return t;
}

TEST(Reference, WhiteFurnaceLambert) {
  TestScene t = furnace("phong", 1.0f, 0.0f);
  shadetwin::ReferenceOptions o;
  o.spp = 64;
  std::vector<float> img = shadetwin::renderReference(t.scene, t.img(), o);
  // Every pixel (sphere or background) must be 1: kd = 1 reflects all of a uniform radiance 1.
  double sum = 0, worst = 0;
  for (size_t p = 0; p < 32 * 32; ++p) {
    sum += img[4 * p];
    worst = std::max(worst, std::fabs(img[4 * p] - 1.0));
  }
  EXPECT_NEAR(sum / 1024, 1.0, 3e-3);
  EXPECT_LT(worst, 0.2);  // single pixels: 64 samples of a two-strategy estimator
}

TEST(Reference, PhongHeadOnReflectsKs) {
  TestScene t = furnace("phong", 0.0f, 1.0f);
  shadetwin::ReferenceOptions o;
  o.spp = 256;
  std::vector<float> img = shadetwin::renderReference(t.scene, t.img(), o);
  // The centre pixels see the sphere head-on (n = wo): L_o = ks * 1.
  for (int y = 15; y <= 16; ++y)
    for (int x = 15; x <= 16; ++x) EXPECT_NEAR(img[4 * (size_t(y) * 32 + size_t(x))], 1.0, 0.03);
}

TEST(Reference, MirrorLobeIsTheEnvironmentAlongTheReflection) {
  TestScene t = furnace("mirror", 0.0f, 0.5f);
  shadetwin::ReferenceOptions o;
  o.spp = 4;
  std::vector<float> img = shadetwin::renderReference(t.scene, t.img(), o);
  // Sphere pixels are exactly ks * 1 (kd = 0: no sampled part), background pixels exactly 1.
  int sphere = 0, background = 0;
  for (size_t p = 0; p < 32 * 32; ++p) {
    sphere += img[4 * p] == 0.5f;
    background += img[4 * p] == 1.0f;
  }
  EXPECT_EQ(sphere + background, 32 * 32);
  EXPECT_GT(sphere, 250);  // the sphere covers about a third of the image
}

TEST(Reference, ErrorHalvesWhenSppQuadruples) {
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/spheres.json");
  s.width = 128, s.height = 48;
  shadetwin::ImageRGBA env = shadetwin::loadImageRGBA(s.environment);
  const shadetwin::EnvImage e{env.width, env.height, env.texels.data()};
  auto render = [&](uint32_t spp, uint64_t seed) {
    shadetwin::ReferenceOptions o;
    o.spp = spp;
    o.seed = seed;
    return shadetwin::ImageRGBA{s.width, s.height, shadetwin::renderReference(s, e, o)};
  };
  const shadetwin::ImageRGBA truth = render(2048, 99);
  double rmse[3];
  const uint32_t spp[3] = {4, 16, 64};
  for (int i = 0; i < 3; ++i) rmse[i] = shadetwin::compareImages(render(spp[i], 1), truth).rmse;
  // RMSE ~ spp^(-1/2): quadrupling the samples halves the error (loosely: 1.6 .. 2.5).
  EXPECT_GT(rmse[0] / rmse[1], 1.6);
  EXPECT_LT(rmse[0] / rmse[1], 2.5);
  EXPECT_GT(rmse[1] / rmse[2], 1.6);
  EXPECT_LT(rmse[1] / rmse[2], 2.5);
}

TEST(Reference, DeterministicAcrossThreadCounts) {
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/teapot.json");
  s.width = 64, s.height = 48;
  shadetwin::ImageRGBA env = shadetwin::loadImageRGBA(s.environment);
  shadetwin::ReferenceOptions o;
  o.spp = 8;
  o.visibility = true;
  std::vector<float> ref;
  for (int threads : {1, 2, 16}) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(threads));
    auto img = shadetwin::renderReference(s, {env.width, env.height, env.texels.data()}, o);
    if (ref.empty()) {
      ref = img;
    } else {
      ASSERT_EQ(0, std::memcmp(ref.data(), img.data(), ref.size() * 4)) << threads;
    }
  }
  o.seed = 2;
  auto other = shadetwin::renderReference(s, {env.width, env.height, env.texels.data()}, o);
  EXPECT_NE(0, std::memcmp(ref.data(), other.data(), ref.size() * 4));
}

TEST(Reference, LafortuneWithoutLobesNamesTheMaterial) {
  TestScene t = furnace("lafortune", 0.5f, 0.5f);
  t.scene.materials[0].name = "lf";
  try {
    shadetwin::renderReference(t.scene, t.img(), {});
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'lf'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("lobes"), std::string::npos) << e.what();
  }
}

TEST(Reference, LafortunePhongLobeMatchesPhong) {
  // One Lafortune lobe with C = (-1, -1, 1), n = e, rho = (e + 2) / (2 pi) is normalized Phong: the two
  // reference images agree to their Monte Carlo noise (same seed, same sample stream).
  TestScene a = furnace("phong", 0.2f, 0.8f), b = furnace("lafortune", 0.2f, 0.8f);
  a.scene.materials[0].exponent = 30;
  b.scene.materials[0].lobes = {{{-1, -1, 1}, 30, float(32 / (2 * std::numbers::pi))}};
  for (TestScene* t : {&a, &b})
    for (size_t i = 0; i < t->env.size(); i += 4) t->env[i] = 1.0f + float(i % 256) / 64;  // varying red
  shadetwin::ReferenceOptions o;
  o.spp = 64;
  const auto ia = shadetwin::renderReference(a.scene, a.img(), o), ib = shadetwin::renderReference(b.scene, b.img(), o);
  double worst = 0;
  for (size_t i = 0; i < ia.size(); ++i) worst = std::max(worst, double(std::fabs(ia[i] - ib[i])) / (1e-3 + std::fabs(ia[i])));
  EXPECT_LT(worst, 1e-4);
}

TEST(Compare, Metrics) {
  shadetwin::ImageRGBA a{2, 1, {1, 1, 1, 1, 2, 2, 2, 1}}, b = a;
  shadetwin::ImageMetrics m = shadetwin::compareImages(a, b);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_TRUE(std::isinf(m.psnr));
  for (int k = 0; k < 3; ++k) a.texels[size_t(k)] += 0.1f;  // pixel 0 off by 0.1 in R, G, B
  m = shadetwin::compareImages(a, b);
  EXPECT_NEAR(m.rmse, std::sqrt(0.01 / 2), 1e-6);
  EXPECT_NEAR(m.relMse, 0.01 / (1 + 0.01) / 2, 1e-6);
  EXPECT_NEAR(m.psnr, 10 * std::log10(4.0 / 0.005), 1e-4);
  a.texels[0] = std::nanf("");
  EXPECT_EQ(shadetwin::compareImages(a, b).nonFinite, 1u);
  shadetwin::ImageRGBA c{1, 2, std::vector<float>(8, 1.0f)};
  EXPECT_THROW(shadetwin::compareImages(a, c), std::invalid_argument);
}

}  // namespace
