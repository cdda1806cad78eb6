#include "inputs/visibility.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

#include "inputs/env_lights.h"
#include "inputs/sh_irradiance.h"
#include "passes/shadow.h"

namespace shadetwin {

std::array<double, 16> sh16BasisDouble(const Vec3& v) {
  const double x = v[0], y = v[1], z = v[2], xx = x * x, yy = y * y, zz = z * z;
  return {0.282094792, 0.488602512 * y, 0.488602512 * z, 0.488602512 * x, 1.09254843 * x * y, 1.09254843 * y * z,
          0.315391565 * (3 * zz - 1), 1.09254843 * x * z, 0.546274215 * (xx - yy), 0.590043604 * y * (3 * xx - yy),
          2.89061141 * x * y * z, 0.457045794 * y * (5 * zz - 1), 0.373176336 * z * (5 * zz - 3),
          0.457045794 * x * (5 * zz - 1), 1.44530571 * z * (xx - yy), 0.590043604 * x * (xx - 3 * yy)};
}

std::array<double, 256> sh16PseudoInverse(const std::vector<Vec3>& dirs, double muRelative, uint32_t* rank) {
  Eigen::Matrix<double, 16, 16> M = Eigen::Matrix<double, 16, 16>::Zero();
  for (const Vec3& d : dirs) {
    const std::array<double, 16> y = sh16BasisDouble(d);
    const Eigen::Map<const Eigen::Matrix<double, 16, 1>> Y(y.data());
    M += Y * Y.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 16, 16>> eig(M);
  const auto& lambda = eig.eigenvalues();
  const double lmax = std::max(lambda.maxCoeff(), 0.0), mu = muRelative * lmax;
  Eigen::Matrix<double, 16, 16> P = Eigen::Matrix<double, 16, 16>::Zero();
  uint32_t r = 0;
  for (int i = 0; i < 16; ++i) {
    const double l = lambda[i];
    if (!(l > 0)) continue;  // numerically zero or negative: no contribution (no division)
    if (l > mu) ++r;
    P += (l / (l * l + mu * mu)) * eig.eigenvectors().col(i) * eig.eigenvectors().col(i).transpose();
  }
  if (rank) *rank = r;
  std::array<double, 256> out;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) out[size_t(16 * i + j)] = P(i, j);
  return out;
}

VisibilitySettings visibilitySettings(const Scene& scene) {
  VisibilitySettings s;
  s.maps = scene.visMaps;
  s.size = scene.visSize;
  s.fitCosine = scene.visFitCosine;
  s.biasTexels = scene.visBias;
  s.biasSlopeTexels = scene.visSlopeBias;
  s.filterRadius = scene.visFilterRadius;
  s.filterEdgeAware = scene.visFilterEdge;
  return s;
}

std::array<float, 48> visibilityLighting(const ShIrradiance& sh) {
  std::array<float, 48> L{};
  for (int ch = 0; ch < 3; ++ch)
    for (int k = 0; k < 16; ++k) {
      const float unscale = k == 0 ? 1.0f : k < 4 ? 1.5f : 4.0f;
      L[size_t(16 * ch + k)] = k < 9 ? sh.c[size_t(3 * k + ch)] * unscale : sh.band3[size_t(3 * (k - 9) + ch)];
    }
  return L;
}

VisibilitySetup visibilitySetup(const Scene& scene, const emu::Texture& env, const VisibilitySettings& s) {
  if (s.maps == 0) throw std::invalid_argument("visibility: maps must be at least 1");
  if (s.size == 0) throw std::invalid_argument("visibility: the map size must be at least 1");
  VisibilitySetup v;
  v.settings = s;
  const EnvLights lights = envLights(env, s.maps);
  if (lights.count == s.maps) {
    for (uint32_t k = 0; k < s.maps; ++k) {
      const float* d = &lights.data[8 * size_t(k)];
      const double l = std::sqrt(double(d[0]) * d[0] + double(d[1]) * d[1] + double(d[2]) * d[2]);
      v.directions.push_back({float(d[0] / l), float(d[1] / l), float(d[2] / l)});
    }
  } else {
    v.directions = sphereDirections(s.maps);
    v.uniformFallback = true;
  }
  v.pinv = sh16PseudoInverse(v.directions, s.muRelative, &v.rank);
  v.biasConst = s.biasTexels / float(s.size);
  v.biasSlope = s.biasSlopeTexels / float(s.size);
  const auto [lo, hi] = scene.bounds();
  double r2 = 0;
  for (int k = 0; k < 3; ++k) r2 += 0.25 * (double(hi[size_t(k)]) - lo[size_t(k)]) * (double(hi[size_t(k)]) - lo[size_t(k)]);
  v.planeTolerance = float(s.planeTolerance * std::sqrt(r2));
  std::vector<float> table(size_t(9) * 4 * s.maps, 0.0f);
  for (uint32_t k = 0; k < s.maps; ++k) {
    const Mat4 m = shadowViewProjection(scene, v.directions[k]);
    v.viewProj.push_back(m);
    float* row = &table[size_t(k) * 36];
    for (int i = 0; i < 16; ++i) row[i] = m[size_t(i)];  // columns 0..3 (column-major)
    for (int i = 0; i < 3; ++i) row[16 + i] = v.directions[k][size_t(i)];
    const std::array<double, 16> y = sh16BasisDouble(v.directions[k]);
    for (int i = 0; i < 16; ++i) {
      double w = 0;
      for (int j = 0; j < 16; ++j) w += v.pinv[size_t(16 * i + j)] * y[size_t(j)];
      row[20 + i] = float(w);
    }
  }
  v.data = std::make_shared<emu::Texture>(emu::floatTexture(emu::Format::RGBA32F, 9, s.maps, table.data()));
  return v;
}

}  // namespace shadetwin
