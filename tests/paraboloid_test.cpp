// Dual-paraboloid atlas (src/shade/paraboloid.h, src/inputs/paraboloid.*): the mapping and its
// inverse, the Jacobian r(z) = 4 b^2 (1 + |z|)^2 against the measured solid angle of texels, the
// seam layout, and the resampling of a constant environment. Emulator-vs-GPU bits: ctest
// verify_paraboloid_*.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "emu/device_profile.h"
#include "passes/mips.h"
#include "inputs/paraboloid.h"
#include "lanes/instantiate.h"

namespace sc = shadetwin::shade::scalar;
using V3f = shadetwin::shade::V3<float>;

namespace {
struct D3 {
  double x, y, z;
};
D3 dirOf(const V3f& v) { return {v.x, v.y, v.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
// Solid angle of the spherical triangle (a, b, c) (Van Oosterom & Strackee 1983).
double triangleSolidAngle(D3 a, D3 b, D3 c) {
  return 2 * std::atan2(std::fabs(dot(a, cross(b, c))), 1 + dot(a, b) + dot(b, c) + dot(c, a));
}
// Direction of face point p (front: z >= 0 hemisphere for |p| <= 1), in double.
D3 facePoint(double px, double py, bool back) {
  const double q = px * px + py * py;
  D3 d{2 * px / (1 + q), 2 * py / (1 + q), (1 - q) / (1 + q)};
  if (back) d.x = -d.x, d.z = -d.z;
  return d;
}
}  // namespace

TEST(Paraboloid, TexelCentresRoundTrip) {
  const int S = 64;
  int checked = 0;
  for (int j = 0; j < S; ++j)
    for (int i = 0; i < 2 * S; ++i) {
      const V3f d = sc::paraboloidTexelDirection(i, j, S);
      EXPECT_NEAR(dot(dirOf(d), dirOf(d)), 1.0, 1e-6);
      const double px = ((i % S + 0.5) / S * 2 - 1) * 1.2, py = ((j + 0.5) / S * 2 - 1) * 1.2;
      if (px * px + py * py > 1.0) continue;  // beyond the rim the direction belongs to the other face
      const auto uv = sc::paraboloidUv(d);
      EXPECT_NEAR(uv.x * 2 * S, i + 0.5, 2e-3) << i << "," << j;
      EXPECT_NEAR(uv.y * S, j + 0.5, 2e-3) << i << "," << j;
      ++checked;
    }
  EXPECT_GT(checked, int(2 * 0.5 * S * S));  // pi / (4 b^2) of each face is inside the rim
}

TEST(Paraboloid, JacobianMatchesTexelSolidAngles) {
  // Solid angle of texels measured from their corner directions against r(z) / S^2 at the centre,
  // and the two faces' texels inside the rim summing to 4 pi.
  const int S = 128;
  double total = 0, worst = 0;
  for (int back = 0; back < 2; ++back)
    for (int j = 0; j < S; ++j)
      for (int i = 0; i < S; ++i) {
        auto p = [&](int k) { return (double(k) / S * 2 - 1) * 1.2; };
        const double cx = (p(i) + p(i + 1)) / 2, cy = (p(j) + p(j + 1)) / 2;
        if (cx * cx + cy * cy > 1.0) continue;
        const D3 a = facePoint(p(i), p(j), back), b = facePoint(p(i + 1), p(j), back), c = facePoint(p(i + 1), p(j + 1), back),
                 d = facePoint(p(i), p(j + 1), back);
        const double measured = triangleSolidAngle(a, b, c) + triangleSolidAngle(a, c, d);
        const V3f centre = sc::paraboloidTexelDirection(i + back * S, j, S);
        const double model = double(sc::paraboloidJacobian(centre.z)) / (double(S) * S);
        worst = std::max(worst, std::fabs(measured / model - 1));
        total += model;
      }
  EXPECT_LT(worst, 2e-4);
  // The rim cuts texels in half; the sum of whole texels inside approaches 4 pi to within the rim's share.
  EXPECT_NEAR(total / (4 * std::numbers::pi), 1.0, 0.02);
  EXPECT_EQ(sc::paraboloidJacobian(1.0f), 4.0f * 1.2f * 1.2f * 4.0f);
}

TEST(Paraboloid, FacesAndSeam) {
  // +z lands at the centre of the front face, -z at the centre of the back face; the horizon
  // z = 0 lies on the unit circle of both, and x > 0 meets the seam from both sides.
  auto uv = [](float x, float y, float z) { return sc::paraboloidUv(V3f(x, y, z)); };
  EXPECT_FLOAT_EQ(uv(0, 0, 1).x, 0.25f);
  EXPECT_FLOAT_EQ(uv(0, 0, -1).x, 0.75f);
  EXPECT_FLOAT_EQ(uv(0, 0, 1).y, 0.5f);
  const float rim = (1.0f / 1.2f + 1.0f) * 0.25f;  // s of p.x = 1 on the front face
  EXPECT_NEAR(uv(1, 0, 0).x, rim, 1e-6);
  EXPECT_NEAR(uv(1, 0, -1e-7f).x, 0.5f + (0.5f - rim), 1e-6);  // just behind: back face, mirrored
  EXPECT_LT(uv(1, 0, 0).x, 0.5f);
  EXPECT_GT(uv(1, 0, -1e-7f).x, 0.5f);
}

TEST(Paraboloid, ConstantEnvironmentStaysConstant) {
  // Bilinear / trilinear of equal texels is that value exactly, and so is every MIP level.
  const uint32_t W = 64, H = 32;
  std::vector<float> level0(size_t(W) * H * 4, 0.7f);
  const auto chain = shadetwin::mipChainCpu(level0, W, H, 1, 8);
  const emu::Texture env = shadetwin::packTexture(emu::Format::RGBA32F, W, H, 1, chain);
  const auto atlas = shadetwin::paraboloidAtlasEmu(env, emu::lavapipeProfile(), 16);
  ASSERT_EQ(atlas.size(), size_t(32) * 16 * 4);
  for (float v : atlas) ASSERT_EQ(v, 0.7f);
  EXPECT_THROW(shadetwin::paraboloidAtlasEmu(env, emu::lavapipeProfile(), 2), std::invalid_argument);
}
