#include "passes/shadow.h"

#include <chrono>
#include <cmath>
#include <numbers>

#include <tbb/parallel_for.h>

#include "passes/gbuffer.h"
#include "lanes/instantiate.h"
#include "model/counted.h"
#include "util/pass_log.h"

namespace shadetwin {

std::vector<Vec3> sphereDirections(uint32_t count) {
  // Spherical Fibonacci lattice: z uniform in (-1, 1) at cell centres, azimuth by the golden angle.
  std::vector<Vec3> d(count);
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (uint32_t i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count, r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    d[i] = {float(r * std::cos(phi)), float(z), float(r * std::sin(phi))};
  }
  return d;
}

Mat4 shadowViewProjection(const Scene& scene, const Vec3& dir) {
  const auto [lo, hi] = scene.bounds();
  double c[3], r2 = 0;
  for (int k = 0; k < 3; ++k) {
    c[k] = 0.5 * (double(lo[size_t(k)]) + hi[size_t(k)]);
    const double h = 0.5 * (double(hi[size_t(k)]) - lo[size_t(k)]);
    r2 += h * h;
  }
  const double r = std::max(1.02 * std::sqrt(r2), 1e-6);
  double w[3] = {dir[0], dir[1], dir[2]};
  const double wl = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  for (double& x : w) x /= wl;
  // u = normalize(helper x w), v = w x u: a right-handed frame (u, v, w) for any w.
  const double h[3] = {std::fabs(w[1]) < 0.9 ? 0.0 : 1.0, std::fabs(w[1]) < 0.9 ? 1.0 : 0.0, 0.0};
  double u[3] = {h[1] * w[2] - h[2] * w[1], h[2] * w[0] - h[0] * w[2], h[0] * w[1] - h[1] * w[0]};
  const double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (double& x : u) x /= ul;
  const double v[3] = {w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2], w[0] * u[1] - w[1] * u[0]};
  auto dot = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  Mat4 m{};  // column-major: m[4 * col + row]
  for (int k = 0; k < 3; ++k) {
    m[4 * k + 0] = float(u[k] / r);
    m[4 * k + 1] = float(v[k] / r);
    m[4 * k + 2] = float(-w[k] / (2 * r));
  }
  m[12] = float(-dot(u, c) / r);
  m[13] = float(-dot(v, c) / r);
  m[14] = float(0.5 + dot(w, c) / (2 * r));
  m[15] = 1.0f;
  return m;
}

ShadowMaps shadowEmu(const Scene& scene, const std::vector<Vec3>& directions, uint32_t size,
                     const emu::DeviceProfile& dev, ShadowStats* stats) {
  ShadowMaps sm;
  shadowEmu(scene, directions, size, dev, sm, stats);
  return sm;
}

namespace {
// The driver over either lane build (an instantiation namespace): the scalar build (the emulator's vertex stage) or
// the counting one (the model).
#define SHADOW_LANES(Name, NS)                                                              \
  struct Name {                                                                             \
    using Float = shade::NS::Float;                                                         \
    static auto vertex(auto&&... a) { return shade::NS::shadowVertex(a...); }               \
  };
SHADOW_LANES(ScalarLanes, scalar)
SHADOW_LANES(CountedLanes, counted1)
#undef SHADOW_LANES

template <class L>
void shadowLanes(const Scene& scene, const std::vector<Vec3>& directions, uint32_t size, const emu::DeviceProfile& dev,
                 ShadowMaps& sm, ShadowStats* stats) {
  using V3f = shade::V3<typename L::Float>;
  using V4f = shade::V4<typename L::Float>;
  using opcount::lane0;
  auto col = [](const float* m, int c) { return V4f(m[4 * c], m[4 * c + 1], m[4 * c + 2], m[4 * c + 3]); };
  sm.size = size;
  sm.directions = directions;
  sm.viewProj.clear();
  for (const Vec3& d : directions) sm.viewProj.push_back(shadowViewProjection(scene, d));
  sm.maps.resize(directions.size());
  std::vector<ShadowStats> per(directions.size());
  tbb::parallel_for(size_t(0), directions.size(), [&](size_t di) {
    emu::Framebuffer fb;
    fb.depth.swap(sm.maps[di]);
    fb.reset(size, size, 0);
    const float* l = sm.viewProj[di].data();
    ShadowStats& st = per[di];
    for (uint32_t oi = 0; oi < scene.objects.size(); ++oi) {
      const Mesh& mesh = scene.meshes[scene.objects[oi].mesh];
      const float* m = scene.objects[oi].model.data();
      auto t0 = std::chrono::steady_clock::now();
      // Vertex stage: the shared shadowVertex, scalar build (vertex stage keeps denormals).
      std::vector<float> clip(4 * mesh.positions.size());
      for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const auto& P = mesh.positions[i];
        V4f c = L::vertex(col(m, 0), col(m, 1), col(m, 2), col(m, 3), col(l, 0), col(l, 1), col(l, 2), col(l, 3),
                          V3f(P[0], P[1], P[2]));
        clip[4 * i] = lane0(c.x), clip[4 * i + 1] = lane0(c.y), clip[4 * i + 2] = lane0(c.z), clip[4 * i + 3] = lane0(c.w);
      }
      auto t1 = std::chrono::steady_clock::now();
      emu::DrawInput in;
      in.clip = clip.data();
      in.indices = mesh.indices.data();
      in.triangles = mesh.triangles();
      in.drawId = oi;
      emu::draw(dev, fb, in, emu::FragmentFn(), &st.raster);  // depth only: no fragment shader
      auto t2 = std::chrono::steady_clock::now();
      st.vertexMs += std::chrono::duration<double, std::milli>(t1 - t0).count();
      st.rasterMs += std::chrono::duration<double, std::milli>(t2 - t1).count();
    }
    sm.maps[di].swap(fb.depth);
  });
  if (stats) {
    *stats = {};
    for (auto& s : per) {
      stats->vertexMs += s.vertexMs, stats->rasterMs += s.rasterMs;
      stats->raster += s.raster;
    }
  }
}

}  // namespace

void shadowEmu(const Scene& scene, const std::vector<Vec3>& directions, uint32_t size, const emu::DeviceProfile& dev,
               ShadowMaps& sm, ShadowStats* stats) {
  notePass("shadow");
  shadowLanes<ScalarLanes>(scene, directions, size, dev, sm, stats);
}

ShadowMaps shadowCounted(const Scene& scene, const std::vector<Vec3>& directions, uint32_t size, const emu::DeviceProfile& dev,
                         ShadowStats* stats) {
  ShadowMaps sm;
  shadowLanes<CountedLanes>(scene, directions, size, dev, sm, stats);
  return sm;
}

}  // namespace shadetwin
