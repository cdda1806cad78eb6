#include "passes/gbuffer.h"

#include <cmath>

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "inputs/material.h"
#include "lanes/instantiate.h"
#include "model/counted.h"
#include "util/pass_log.h"
#include "util/timer.h"

namespace shadetwin {

std::vector<VertexGpu> interleave(const Mesh& m) {
  std::vector<VertexGpu> v(m.positions.size());
  for (size_t i = 0; i < v.size(); ++i) {
    std::memcpy(v[i].pos, m.positions[i].data(), 12);
    std::memcpy(v[i].normal, m.normals[i].data(), 12);
    std::memcpy(v[i].tangent, m.tangents[i].data(), 16);
    std::memcpy(v[i].uv, m.uvs[i].data(), 8);
  }
  return v;
}

ObjectGpu objectGpu(const Object& o) {
  ObjectGpu g{};
  std::memcpy(g.model, o.model.data(), 64);
  Mat4 n = normalMatrix(o.model);
  std::memcpy(g.normal, n.data(), 64);
  g.materialId = float(o.material);
  return g;
}

namespace {
// The driver over either lane build (an instantiation namespace): the scalar build (the emulator's vertex and
// fragment stages) or the counting one (the model).
#define GBUFFER_LANES(Name, NS)                                                             \
  struct Name {                                                                             \
    using Float = shade::NS::Float;                                                         \
    static auto vertex(auto&&... a) { return shade::NS::gbufferVertex(a...); }              \
    static auto fragment(auto&&... a) { return shade::NS::gbufferFragment(a...); }          \
  };
GBUFFER_LANES(ScalarLanes, scalar)
GBUFFER_LANES(CountedLanes, counted1)
#undef GBUFFER_LANES

template <class L>
void gbufferLanes(const Scene& scene, const emu::DeviceProfile& dev, GBuffer& g, GbufferStats* stats) {
  using V2f = shade::V2<typename L::Float>;
  using V3f = shade::V3<typename L::Float>;
  using V4f = shade::V4<typename L::Float>;
  using opcount::lane0;
  auto col = [](const float* m, int c) { return V4f(m[4 * c], m[4 * c + 1], m[4 * c + 2], m[4 * c + 3]); };
  emu::Framebuffer fb;
  fb.color.swap(g.texels);
  fb.depth.swap(g.depth);
  fb.reset(scene.width, scene.height, kGbufFloats);
  const Mat4 vp = scene.viewProjection();
  GbufferStats local;
  for (uint32_t oi = 0; oi < scene.objects.size(); ++oi) {
    const Object& obj = scene.objects[oi];
    const Mesh& mesh = scene.meshes[obj.mesh];
    const ObjectGpu og = objectGpu(obj);
    // Vertex stage: the shared gbufferVertex, scalar build, vertex-stage denormal mode (preserve).
    auto t0 = std::chrono::steady_clock::now();
    const size_t nv = mesh.positions.size();
    std::vector<float> clip(4 * nv), vary(kGbufVaryings * nv);
    tbb::parallel_for(size_t(0), nv, [&](size_t i) {
      auto& P = mesh.positions[i];
      auto& N = mesh.normals[i];
      auto& T = mesh.tangents[i];
      auto& U = mesh.uvs[i];
      auto o = L::vertex(col(og.model, 0), col(og.model, 1), col(og.model, 2), col(og.model, 3),
                                            col(og.normal, 0), col(og.normal, 1), col(og.normal, 2), col(vp.data(), 0),
                                            col(vp.data(), 1), col(vp.data(), 2), col(vp.data(), 3), V3f(P[0], P[1], P[2]),
                                            V3f(N[0], N[1], N[2]), V4f(T[0], T[1], T[2], T[3]), V2f(U[0], U[1]));
      float* c = &clip[4 * i];
      c[0] = lane0(o.clip.x), c[1] = lane0(o.clip.y), c[2] = lane0(o.clip.z), c[3] = lane0(o.clip.w);
      float* v = &vary[kGbufVaryings * i];
      const float vals[kGbufVaryings] = {lane0(o.worldPos.x), lane0(o.worldPos.y), lane0(o.worldPos.z), lane0(o.normal.x),
                                         lane0(o.normal.y),   lane0(o.normal.z),   lane0(o.tangent.x),  lane0(o.tangent.y),
                                         lane0(o.tangent.z),  lane0(o.tangent.w),  lane0(o.uv.x),       lane0(o.uv.y)};
      std::memcpy(v, vals, sizeof vals);
    });
    local.vertexMs += msSince(t0);
    // Raster + fragment stage: the shared gbufferFragment per pixel, derivatives from the quad.
    t0 = std::chrono::steady_clock::now();
    emu::DrawInput in;
    in.clip = clip.data();
    in.varyings = vary.data();
    in.numVaryings = kGbufVaryings;
    in.indices = mesh.indices.data();
    in.triangles = mesh.triangles();
    in.drawId = oi;
    const float materialId = og.materialId;
    emu::draw(dev, fb, in, [&](const emu::Quad& q, float (*out)[4]) {
      float dudx[4], dudy[4], dvdx[4], dvdy[4];
      emu::quadDerivatives(dev, q.v[10], dudx, dudy);
      emu::quadDerivatives(dev, q.v[11], dvdx, dvdy);
      for (int i = 0; i < 4; ++i) {
        auto g = L::fragment(V3f(q.v[0][i], q.v[1][i], q.v[2][i]), V3f(q.v[3][i], q.v[4][i], q.v[5][i]),
                                                V4f(q.v[6][i], q.v[7][i], q.v[8][i], q.v[9][i]), V2f(q.v[10][i], q.v[11][i]),
                                                V2f(dudx[i], dvdx[i]), V2f(dudy[i], dvdy[i]), materialId);
        const V4f att[4] = {g.g0, g.g1, g.g2, g.g3};
        for (int a = 0; a < 4; ++a) {
          out[4 * a][i] = lane0(att[a].x);
          out[4 * a + 1][i] = lane0(att[a].y);
          out[4 * a + 2][i] = lane0(att[a].z);
          out[4 * a + 3][i] = lane0(att[a].w);
        }
      }
    }, &local.raster);
    local.rasterMs += msSince(t0);
  }
  if (stats) *stats = local;
  g.width = scene.width;
  g.height = scene.height;
  g.texels.swap(fb.color);
  g.depth.swap(fb.depth);
}
}  // namespace

GBuffer gbufferEmu(const Scene& scene, const emu::DeviceProfile& dev, GbufferStats* stats) {
  GBuffer g;
  gbufferEmu(scene, dev, g, stats);
  return g;
}

void gbufferEmu(const Scene& scene, const emu::DeviceProfile& dev, GBuffer& g, GbufferStats* stats) {
  notePass("gbuffer");
  gbufferLanes<ScalarLanes>(scene, dev, g, stats);
}

GBuffer gbufferCounted(const Scene& scene, const emu::DeviceProfile& dev, GbufferStats* stats) {
  GBuffer g;
  gbufferLanes<CountedLanes>(scene, dev, g, stats);
  return g;
}

}  // namespace shadetwin
