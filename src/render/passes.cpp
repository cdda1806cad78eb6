#include "render/gbuffer.h"

#include <cmath>

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "shade/instantiate.h"

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
using V2f = shade::V2<float>;
using V3f = shade::V3<float>;
using V4f = shade::V4<float>;
V4f col(const float* m, int c) { return V4f(m[4 * c], m[4 * c + 1], m[4 * c + 2], m[4 * c + 3]); }
double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

GBuffer gbufferEmu(const Scene& scene, const emu::DeviceProfile& dev, GbufferStats* stats) {
  GBuffer g;
  gbufferEmu(scene, dev, g, stats);
  return g;
}

void gbufferEmu(const Scene& scene, const emu::DeviceProfile& dev, GBuffer& g, GbufferStats* stats) {
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
      auto o = shade::scalar::gbufferVertex(col(og.model, 0), col(og.model, 1), col(og.model, 2), col(og.model, 3),
                                            col(og.normal, 0), col(og.normal, 1), col(og.normal, 2), col(vp.data(), 0),
                                            col(vp.data(), 1), col(vp.data(), 2), col(vp.data(), 3), V3f(P[0], P[1], P[2]),
                                            V3f(N[0], N[1], N[2]), V4f(T[0], T[1], T[2], T[3]), V2f(U[0], U[1]));
      float* c = &clip[4 * i];
      c[0] = o.clip.x, c[1] = o.clip.y, c[2] = o.clip.z, c[3] = o.clip.w;
      float* v = &vary[kGbufVaryings * i];
      const float vals[kGbufVaryings] = {o.worldPos.x, o.worldPos.y, o.worldPos.z, o.normal.x,  o.normal.y,  o.normal.z,
                                         o.tangent.x,  o.tangent.y,  o.tangent.z,  o.tangent.w, o.uv.x, o.uv.y};
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
        auto g = shade::scalar::gbufferFragment(V3f(q.v[0][i], q.v[1][i], q.v[2][i]), V3f(q.v[3][i], q.v[4][i], q.v[5][i]),
                                                V4f(q.v[6][i], q.v[7][i], q.v[8][i], q.v[9][i]), V2f(q.v[10][i], q.v[11][i]),
                                                V2f(dudx[i], dvdx[i]), V2f(dudy[i], dvdy[i]), materialId);
        const V4f att[4] = {g.g0, g.g1, g.g2, g.g3};
        for (int a = 0; a < 4; ++a) {
          out[4 * a][i] = att[a].x;
          out[4 * a + 1][i] = att[a].y;
          out[4 * a + 2][i] = att[a].z;
          out[4 * a + 3][i] = att[a].w;
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

std::vector<float> shadeEmu(const Scene& scene, const GBuffer& g, const emu::Texture& env, const emu::DeviceProfile& dev) {
  std::vector<float> out;
  shadeEmu(scene, g, env, dev, out);
  return out;
}

BrdfGpu brdfOf(const Material& m) {
  if (m.brdf == "phong") return {shade::scalar::kBrdfPhong, m.exponent, 0, 0};
  if (m.brdf == "blinn") return {shade::scalar::kBrdfBlinn, m.exponent, 0, 0};
  if (m.brdf == "ward") return {shade::scalar::kBrdfWard, 0, m.roughness, m.roughnessY};
  if (m.brdf == "ggx") return {shade::scalar::kBrdfGgx, 0, m.roughness, m.roughness};
  throw std::invalid_argument("material '" + m.name + "': BRDF '" + m.brdf +
                              "' cannot be importance-sampled by fis (phong, blinn, ward or ggx)");
}

float fisLevelConstant(const Scene& scene) {
  const double S = scene.fisFaceSize;
  return float(std::log2(double(scene.fisK) * S * S / double(scene.fisSamples)));
}

namespace {
void shadeFisEmu(const Scene& scene, const GBuffer& g, const emu::Texture& atlas, const emu::DeviceProfile& dev,
                 std::vector<float>& out) {
  using F = emu::F32<8>;
  using U = emu::U32<8>;
  using V3 = shade::V3<F>;
  using V4 = shade::V4<F>;
  const size_t n = size_t(g.width) * g.height;
  out.resize(4 * n);
  const CameraRays cam = cameraRays(scene);
  shade::Sampler2D s;
  s.tex = &atlas;
  s.dev = &dev;
  s.desc.addressU = emu::AddressMode::ClampToEdge;
  s.desc.addressV = emu::AddressMode::ClampToEdge;
  const float maxLod = float(atlas.levelCount() - 1), levelC = fisLevelConstant(scene);
  const float invW = 1.0f / float(g.width), invH = 1.0f / float(g.height);
  std::vector<BrdfGpu> brdfs;
  for (const Material& m : scene.materials) brdfs.push_back(brdfOf(m));
  if (brdfs.empty()) brdfs.push_back(brdfOf(Material{}));
  const size_t blocks = (n + 7) / 8;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks, 16), [&](const tbb::blocked_range<size_t>& r) {
    emu::DenormalScope mode(dev.denormCompute == emu::DenormMode::Flush);
    for (size_t b = r.begin(); b != r.end(); ++b) {
      V4 g0, g1, g2;
      V3 dif, spec;
      F px, py;
      shade::x8::BrdfParams bp{};
      U kind(0u);
      for (int l = 0; l < 8; ++l) {
        const size_t i = std::min(b * 8 + size_t(l), n - 1);
        const float* t = g.texels.data() + i * kGbufFloats;
        g0.x.set(l, t[0]), g0.y.set(l, t[1]), g0.z.set(l, t[2]), g0.w.set(l, t[3]);
        g1.x.set(l, t[4]), g1.y.set(l, t[5]), g1.z.set(l, t[6]), g1.w.set(l, t[7]);
        g2.x.set(l, t[8]), g2.y.set(l, t[9]), g2.z.set(l, t[10]), g2.w.set(l, t[11]);
        const uint32_t slot = shade::scalar::materialSlot(t[3], uint32_t(brdfs.size()));
        const Material& m = scene.materials.empty() ? Material{} : scene.materials[slot];
        dif.x.set(l, m.diffuse[0]), dif.y.set(l, m.diffuse[1]), dif.z.set(l, m.diffuse[2]);
        spec.x.set(l, m.specular[0]), spec.y.set(l, m.specular[1]), spec.z.set(l, m.specular[2]);
        kind.set(l, brdfs[slot].kind);
        bp.e.set(l, brdfs[slot].e), bp.ax.set(l, brdfs[slot].ax), bp.ay.set(l, brdfs[slot].ay);
        px.set(l, float(i % g.width));
        py.set(l, float(i / g.width));
      }
      bp.kind = kind;
      const V3 zero(F(0.0f), F(0.0f), F(0.0f));
      bp.c0 = zero, bp.c1 = zero, bp.n0 = F(1.0f), bp.n1 = F(1.0f), bp.rho0 = F(0.0f), bp.rho1 = F(0.0f);
      V3 ray = shade::x8::cameraRay(V3(F(cam.fwd[0]), F(cam.fwd[1]), F(cam.fwd[2])),
                                    V3(F(cam.right[0]), F(cam.right[1]), F(cam.right[2])),
                                    V3(F(cam.down[0]), F(cam.down[1]), F(cam.down[2])), px, py, F(invW), F(invH));
      V4 c = shade::x8::shadeFis(s, F(maxLod), F(levelC), scene.fisSamples, F(scene.environmentIntensity), g0, g1, g2,
                                 V3(F(cam.eye[0]), F(cam.eye[1]), F(cam.eye[2])), ray, dif, spec, bp);
      for (int l = 0; l < 8 && b * 8 + size_t(l) < n; ++l) {
        float* o = &out[4 * (b * 8 + size_t(l))];
        o[0] = c.x[l], o[1] = c.y[l], o[2] = c.z[l], o[3] = c.w[l];
      }
    }
  });
}
}  // namespace

void shadeEmu(const Scene& scene, const GBuffer& g, const emu::Texture& env, const emu::DeviceProfile& dev,
              std::vector<float>& out) {
  if (scene.technique == "fis") return shadeFisEmu(scene, g, env, dev, out);
  using F = emu::F32<8>;
  using V3 = shade::V3<F>;
  using V4 = shade::V4<F>;
  const size_t n = size_t(g.width) * g.height;
  out.resize(4 * n);
  const CameraRays cam = cameraRays(scene);
  shade::Sampler2D envS;
  envS.tex = &env;
  envS.dev = &dev;
  envS.desc.addressU = emu::AddressMode::Repeat;
  envS.desc.addressV = emu::AddressMode::ClampToEdge;
  const float maxLod = float(env.levelCount() - 1);
  const float invW = 1.0f / float(g.width), invH = 1.0f / float(g.height);
  const size_t blocks = (n + 7) / 8;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks, 64), [&](const tbb::blocked_range<size_t>& r) {
    emu::DenormalScope mode(dev.denormCompute == emu::DenormMode::Flush);
    for (size_t b = r.begin(); b != r.end(); ++b) {
      V4 g0, g1;
      V3 dif, spec;
      F px, py;
      for (int l = 0; l < 8; ++l) {
        const size_t i = std::min(b * 8 + size_t(l), n - 1);
        const float* t = g.texels.data() + i * kGbufFloats;
        g0.x.set(l, t[0]), g0.y.set(l, t[1]), g0.z.set(l, t[2]), g0.w.set(l, t[3]);
        g1.x.set(l, t[4]), g1.y.set(l, t[5]), g1.z.set(l, t[6]), g1.w.set(l, t[7]);
        const Material& m = scene.materials[shade::scalar::materialSlot(t[3], uint32_t(scene.materials.size()))];
        dif.x.set(l, m.diffuse[0]), dif.y.set(l, m.diffuse[1]), dif.z.set(l, m.diffuse[2]);
        spec.x.set(l, m.specular[0]), spec.y.set(l, m.specular[1]), spec.z.set(l, m.specular[2]);
        px.set(l, float(i % g.width));
        py.set(l, float(i / g.width));
      }
      V3 ray = shade::x8::cameraRay(V3(F(cam.fwd[0]), F(cam.fwd[1]), F(cam.fwd[2])),
                                    V3(F(cam.right[0]), F(cam.right[1]), F(cam.right[2])),
                                    V3(F(cam.down[0]), F(cam.down[1]), F(cam.down[2])), px, py, F(invW), F(invH));
      V4 c = shade::x8::shadeMirror(envS, F(maxLod), F(scene.environmentIntensity), g0, g1,
                                    V3(F(cam.eye[0]), F(cam.eye[1]), F(cam.eye[2])), ray, dif, spec);
      for (int l = 0; l < 8 && b * 8 + size_t(l) < n; ++l) {
        float* o = &out[4 * (b * 8 + size_t(l))];
        o[0] = c.x[l], o[1] = c.y[l], o[2] = c.z[l], o[3] = c.w[l];
      }
    }
  });
}

}  // namespace shadetwin
