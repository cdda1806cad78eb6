// The glints technique's SH formulation in double (inputs/glint_tables.*) against its ground truth
// (reference/glints_gxd.*): the decomposition of docs/DESIGN.md §12 converges to the G x D integral
// as the SH order grows, when the map's normals sit at bin centres (no binning error) and the
// environment is smooth.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "inputs/glint_tables.h"
#include "inputs/ndf_histogram.h"
#include "lanes/instantiate.h"
#include "reference/glints_gxd.h"

using shadetwin::reference::D3;

namespace {
constexpr double kPi = std::numbers::pi;
}

TEST(GlintTables, RealShInDoubleAreSh16AtLowDegree) {
  namespace sc = shadetwin::shade::scalar;
  for (const D3 d : {D3{0, 0, 1}, D3{0.6, 0, 0.8}, D3{0.36, -0.48, 0.8}, D3{-0.2, 0.9, -0.38729833}}) {
    const std::vector<double> y = shadetwin::shRealDouble(3, d);
    const sc::Sh16 b = sc::sh16Basis(shadetwin::shade::V3<float>(float(d.x), float(d.y), float(d.z)));
    const float ref[16] = {b.a.x, b.a.y, b.a.z, b.a.w, b.b.x, b.b.y, b.b.z, b.b.w, b.c.x, b.c.y, b.c.z, b.c.w, b.d.x, b.d.y, b.d.z, b.d.w};
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(y[size_t(i)], ref[i], 1e-6) << i;
  }
}

TEST(GlintTables, ShDoubleProductConvergesToTheGxdIntegral) {
  // A 4 x 4 map whose normals are five bin centres (rings 0-2), counted through the SAT; a smooth
  // environment (a sky gradient and a broad warm lobe); the surface faces +y (the environment's
  // up), viewed 30 degrees off the normal; lobes sigma = 0.12. G x D with F G outside (the
  // technique's model, 40,000 sample pairs) against FG / (4 cos_o) * sum Lambda_lm D_lm.
  const shadetwin::NdfBinningSpec bins;
  const uint32_t chosen[5][2] = {{0, 3}, {1, 10}, {1, 20}, {2, 5}, {2, 28}};
  shadetwin::NormalMap m;
  m.width = m.height = 4;
  for (int i = 0; i < 16; ++i) {
    const auto* c = chosen[i % 5];
    const D3 d = shadetwin::ndfBinDirection(bins, c[0], c[1]);
    m.n.insert(m.n.end(), {float(d.x), float(d.y), float(d.z)});
    ASSERT_EQ(shadetwin::ndfBinOf(bins, &m.n[m.n.size() - 3]), c[0] * 32 + c[1]);
  }
  const shadetwin::NdfSat sat = shadetwin::buildNdfSat(m, bins);
  std::vector<uint32_t> counts(288);
  shadetwin::ndfBoxCounts(sat, 0, 0, 3, 3, counts.data());

  const uint32_t W = 128, H = 64;
  std::vector<float> rgba(size_t(W) * H * 4);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const D3 d = shadetwin::reference::Environment::dirOf((x + 0.5) / W, (y + 0.5) / H);
      const double blob = std::exp(-(1.0 - dot(d, normalize(D3{0.4, 0.8, 0.45}))) / 0.08);
      float* p = &rgba[4 * (size_t(y) * W + x)];
      p[0] = float(0.3 + 0.2 * d.y + 4.0 * blob), p[1] = float(0.35 + 0.25 * d.y + 2.5 * blob), p[2] = float(0.5 + 0.3 * d.y + 1.0 * blob);
      p[3] = 1.0f;
    }
  const shadetwin::EnvImage img{W, H, rgba.data()};
  const shadetwin::reference::Environment env(img, 1.0);

  shadetwin::GlintPixel px;
  px.map = &m;
  px.x0 = 0, px.y0 = 0, px.x1 = 3, px.y1 = 3;
  px.t = D3{1, 0, 0}, px.b = D3{0, 0, -1}, px.n = D3{0, 1, 0};
  px.wo = normalize(D3{0.5, 0.866, 0.0});
  px.sigma = 0.12;
  px.fgOutside = true;
  const shadetwin::GxdResult g = shadetwin::glintGxd(px, env, 40000, 3);
  const std::array<double, 3> fg = shadetwin::glintFgOutside(px);
  const double cosO = dot(px.wo, px.n);
  double prev = 1e9;
  for (uint32_t order : {4u, 8u, 16u, 32u}) {
    const std::vector<double> lam = shadetwin::glintLightingShDouble(env, px.wo, order, 256, 128);
    const auto p = shadetwin::glintShDoubleProduct(lam, counts, bins, px.t, px.b, px.n, px.sigma, order);
    double err = 0;
    for (int c = 0; c < 3; ++c) err = std::max(err, std::fabs(fg[size_t(c)] * p[size_t(c)] / (4 * cosO) - g.rgb[c]) / g.rgb[c]);
    RecordProperty("relerr_order_" + std::to_string(order), std::to_string(err));
    if (order >= 16) EXPECT_LT(err, prev * 1.05 + 4 * g.stdErr[0] / g.rgb[0]) << order;
    prev = err;
    if (order == 32)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(fg[size_t(c)] * p[size_t(c)] / (4 * cosO), g.rgb[c], 4 * g.stdErr[c] + 0.01 * g.rgb[c]) << c;
  }
}

TEST(GlintTables, RotatedLobeTableHoldsEachGridDirectionsRealSh) {
  // Four coefficients per texel, one row per direction of the lighting table's grid (poles included):
  // every value the double SH at that direction; the unused tail of the last texel is 0.
  for (uint32_t order : {0u, 3u, 16u}) {
    const uint32_t rings = 5, sectors = 8, nc = (order + 1) * (order + 1);
    const emu::Texture t = shadetwin::glintLobeTable(order, rings, sectors);
    ASSERT_EQ(t.width(), (nc + 3) / 4);
    ASSERT_EQ(t.height(), rings * sectors);
    for (uint32_t j = 0; j < rings; ++j)
      for (uint32_t k = 0; k < sectors; ++k) {
        const double th = kPi * j / (rings - 1), ph = 2 * kPi * k / sectors;
        const D3 d{-std::sin(th) * std::sin(ph), std::cos(th), std::sin(th) * std::cos(ph)};  // equirect (u, v) = (k / P, j / (R - 1))
        const std::vector<double> y = shadetwin::shRealDouble(order, d);
        for (uint32_t i = 0; i < 4 * t.width(); ++i) {
          const emu::Texel4 q = t.loadFloat(0, 0, i / 4, j * sectors + k);
          const float v = i % 4 == 0 ? q.r : i % 4 == 1 ? q.g : i % 4 == 2 ? q.b : q.a;
          // The table's directions are floats (glintViewDirections): a degree-16 value moves ~16 ulps.
          if (i < nc) EXPECT_NEAR(v, y[i], 2e-5 * (1 + std::fabs(y[i]))) << order << " " << j << " " << k << " " << i;
          else EXPECT_EQ(v, 0.0f);
        }
      }
  }
}
