#include "reference/reference.h"

#include <embree3/rtcore.h>
#include "passes/shadow.h"
#include "inputs/visibility.h"
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include "util/image_io.h"
#include "util/output_file.h"
#include "util/memory.h"
#include "inputs/environment.h"
#include "reference/reference_brdf.h"
#include "reference/ref_environment.h"
#include "inputs/env_kdtree.h"
#include "inputs/material.h"
#include "passes/shade.h"
#include "inputs/environment.h"
#include "util/progress.h"
#include "passes/gbuffer.h"
#include "reference/glints_gxd.h"
#include "emu/device_profile.h"

namespace shadetwin {
namespace {

using reference::D3;
using reference::RefBrdf;
constexpr double kPi = std::numbers::pi;


RefBrdf refBrdf(const Material& m) {
  RefBrdf b;
  for (int k = 0; k < 3; ++k) b.kd[k] = m.diffuse[size_t(k)], b.ks[k] = m.specular[size_t(k)];
  b.exponent = m.exponent;
  b.ax = m.roughness;
  b.ay = m.brdf == "ward" ? m.roughnessY : m.roughness;
  if (m.brdf == "phong") b.lobe = reference::Lobe::Phong;
  else if (m.brdf == "blinn") b.lobe = reference::Lobe::Blinn;
  else if (m.brdf == "ggx") b.lobe = reference::Lobe::Ggx;
  else if (m.brdf == "ward") b.lobe = reference::Lobe::Ward;
  else if (m.brdf == "mirror") b.lobe = reference::Lobe::Mirror;
  else if (m.brdf == "lafortune") {
    b.lobe = reference::Lobe::Lafortune;
    if (m.lobes.empty() || m.lobes.size() > 2)
      throw std::invalid_argument("reference: material '" + m.name + "': a lafortune BRDF needs 1 or 2 lobes");
    for (size_t k = 0; k < m.lobes.size(); ++k) {
      for (int i = 0; i < 3; ++i) b.lobes[k].c[i] = m.lobes[k].c[size_t(i)];
      b.lobes[k].n = m.lobes[k].n;
      b.lobes[k].rho = m.lobes[k].rho;
    }
  }
  else throw std::invalid_argument("reference: material '" + m.name + "': BRDF '" + m.brdf + "' has no reference implementation yet");
  return b;
}

struct World {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  // Per geometry (= object): world-space normals and tangents per vertex, and its indices.
  struct Geo {
    std::vector<D3> n, t;
    std::vector<double> handed;
    std::vector<std::array<double, 2>> uv;
    const std::vector<uint32_t>* idx = nullptr;
    uint32_t material = 0;
  };
  std::vector<Geo> geos;
  explicit World(const Scene& s) {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("reference: rtcNewDevice failed");
    scene = rtcNewScene(device);
    for (const Object& o : s.objects) {
      const Mesh& m = s.meshes[o.mesh];
      const Mat4 nm = normalMatrix(o.model);
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      float* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), m.positions.size()));
      uint32_t* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                    3 * sizeof(uint32_t), m.triangles()));
      Geo geo;
      geo.idx = &m.indices;
      geo.material = o.material;
      for (size_t i = 0; i < m.positions.size(); ++i) {
        const auto& p = m.positions[i];
        for (int k = 0; k < 3; ++k)
          vb[3 * i + size_t(k)] = float(double(o.model[size_t(k)]) * p[0] + double(o.model[size_t(4 + k)]) * p[1] +
                                        double(o.model[size_t(8 + k)]) * p[2] + double(o.model[size_t(12 + k)]));
        auto xf = [&](const Mat4& M, double x, double y, double z) {
          return D3{M[0] * x + M[4] * y + M[8] * z, M[1] * x + M[5] * y + M[9] * z, M[2] * x + M[6] * y + M[10] * z};
        };
        const auto& nn = m.normals[i];
        const auto& tt = m.tangents[i];
        geo.n.push_back(xf(nm, nn[0], nn[1], nn[2]));
        geo.t.push_back(xf(o.model, tt[0], tt[1], tt[2]));
        geo.handed.push_back(tt[3]);
        geo.uv.push_back({m.uvs[i][0], m.uvs[i][1]});
      }
      std::copy(m.indices.begin(), m.indices.end(), ib);
      rtcCommitGeometry(g);
      rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
      geos.push_back(std::move(geo));
    }
    rtcCommitScene(scene);
  }
  ~World() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  bool occluded(D3 o, D3 d) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r{};
    r.org_x = float(o.x), r.org_y = float(o.y), r.org_z = float(o.z);
    r.dir_x = float(d.x), r.dir_y = float(d.y), r.dir_z = float(d.z);
    r.tnear = 0.0f;
    r.tfar = std::numeric_limits<float>::infinity();
    r.mask = 0xffffffffu;
    rtcOccluded1(scene, &ctx, &r);
    return r.tfar < 0.0f;
  }
};

}  // namespace

// Material maps for the reference: level 0 of each map, bilinear with repeat addressing at the hit's
// uv (the reference shoots one ray through each pixel centre, so it point-samples the texture's
// reconstruction; the rasterized techniques filter over the pixel's footprint).
struct RefMaps {
  MaterialMapImages images;
  std::vector<std::string> files;
  explicit RefMaps(const Scene& s) : files(materialMapFiles(s)) {
    if (!files.empty()) images = loadMaterialMaps(s);
  }
  int layer(const std::string& f) const {
    for (size_t i = 0; i < files.size(); ++i)
      if (files[i] == f) return int(i);
    return -1;
  }
  void lookup(int layer, double u, double v, double out[3]) const {
    for (int c = 0; c < 3; ++c) out[c] = mapBilinear(images, uint32_t(layer), u, v, c);
  }
  /// The material at uv: kd, ks times their maps; roughness (ward, ggx) times the map's red channel.
  RefBrdf apply(const RefBrdf& b, const Material& m, double u, double v) const {
    RefBrdf r = b;
    double t[3];
    if (!m.diffuseMap.empty()) {
      lookup(layer(m.diffuseMap), u, v, t);
      for (int k = 0; k < 3; ++k) r.kd[k] *= t[k];
    }
    if (!m.specularMap.empty()) {
      lookup(layer(m.specularMap), u, v, t);
      for (int k = 0; k < 3; ++k) r.ks[k] *= t[k];
    }
    if (!m.roughnessMap.empty()) {
      lookup(layer(m.roughnessMap), u, v, t);
      r.ax = std::max(r.ax * t[0], 1e-4);
      r.ay = std::max(r.ay * t[0], 1e-4);
    }
    return r;
  }
};

std::vector<float> renderReference(const Scene& scene, const EnvImage& envImg, const ReferenceOptions& opts) {
  std::vector<RefBrdf> brdfs;
  for (const Material& m : scene.materials) {
    if (m.glints)
      throw std::invalid_argument("material '" + m.name + "' is a glints material: its ground truth is G x D over the pixel's footprint "
                                  "(shadetwin reference on a glints scene, or render --technique glints-gxd)");
    brdfs.push_back(refBrdf(m));
  }
  const RefMaps maps(scene);
  const reference::Environment env(envImg, scene.environmentIntensity);
  const World world(scene);
  const CameraRays cam = cameraRays(scene);
  const uint32_t W = scene.width, H = scene.height;
  std::vector<float> out(size_t(W) * H * 4, 0.0f);
  std::atomic<uint32_t> rowsDone{0};
  std::mutex progressMutex;
  tbb::parallel_for(uint32_t(0), H, [&](uint32_t y) {
    for (uint32_t x = 0; x < W; ++x) {
      const double nx = (x + 0.5) / W * 2 - 1, ny = (y + 0.5) / H * 2 - 1;
      D3 d{cam.fwd[0] + cam.right[0] * nx + cam.down[0] * ny, cam.fwd[1] + cam.right[1] * nx + cam.down[1] * ny,
           cam.fwd[2] + cam.right[2] * nx + cam.down[2] * ny};
      d = reference::normalize(d);
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      RTCRayHit rh{};
      rh.ray.org_x = cam.eye[0], rh.ray.org_y = cam.eye[1], rh.ray.org_z = cam.eye[2];
      rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = std::numeric_limits<float>::infinity();
      rh.ray.mask = 0xffffffffu;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(world.scene, &ctx, &rh);
      float* px = &out[4 * (size_t(y) * W + x)];
      px[3] = 1.0f;
      double L[3];
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        env.radiance(d, L);
        for (int k = 0; k < 3; ++k) px[k] = float(L[k]);
        continue;
      }
      const World::Geo& g = world.geos[rh.hit.geomID];
      const size_t slot = std::min<size_t>(g.material, brdfs.size() - 1);
      const uint32_t* tri = &(*g.idx)[3 * size_t(rh.hit.primID)];
      const double b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
      const Material& mat = scene.materials[slot];
      const RefBrdf brdf = mat.hasMaps() ? maps.apply(brdfs[slot], mat,
                                                      g.uv[tri[0]][0] * b0 + g.uv[tri[1]][0] * b1 + g.uv[tri[2]][0] * b2,
                                                      g.uv[tri[0]][1] * b0 + g.uv[tri[1]][1] * b1 + g.uv[tri[2]][1] * b2)
                                         : brdfs[slot];
      D3 n = reference::normalize(g.n[tri[0]] * b0 + g.n[tri[1]] * b1 + g.n[tri[2]] * b2);
      D3 ng = reference::normalize(D3{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
      const D3 wo = d * -1.0;
      if (reference::dot(n, wo) < 0) n = n * -1.0;  // seen from behind: shade the side facing the camera
      if (reference::dot(ng, wo) < 0) ng = ng * -1.0;
      D3 t = g.t[tri[0]] * b0 + g.t[tri[1]] * b1 + g.t[tri[2]] * b2;
      t = t - n * reference::dot(n, t);
      if (reference::dot(t, t) < 1e-20) {  // degenerate tangent: any frame about n
        D3 unused;
        RefBrdf::frame(n, t, unused);
      }
      t = reference::normalize(t);
      const D3 bt = reference::cross(n, t);
      auto toLocal = [&](D3 v) { return D3{reference::dot(v, t), reference::dot(v, bt), reference::dot(v, n)}; };
      auto toWorld = [&](D3 v) { return t * v.x + bt * v.y + n * v.z; };
      const D3 p{rh.ray.org_x + rh.ray.tfar * rh.ray.dir_x, rh.ray.org_y + rh.ray.tfar * rh.ray.dir_y,
                 rh.ray.org_z + rh.ray.tfar * rh.ray.dir_z};
      const D3 origin = p + ng * 1e-4;
      const D3 woL = toLocal(wo);
      auto visible = [&](D3 wiW) { return !opts.visibility || !world.occluded(origin, wiW); };
      auto fCos = [&](D3 wiL, double f[3]) {
        const double gl = brdf.glossy(wiL, woL), c = std::max(0.0, wiL.z);
        for (int k = 0; k < 3; ++k) f[k] = (brdf.kd[k] / kPi + brdf.ks[k] * gl) * c;
      };
      double sum[3] = {0, 0, 0};
      for (uint32_t s = 0; s < opts.spp; ++s) {
        reference::Rng rng(opts.seed, size_t(y) * W + x, s);
        double f[3];
        // Environment sample, balance heuristic against the BRDF mixture.
        {
          const D3 wiW = env.sample(rng.next(), rng.next(), rng.next(), rng.next());
          const D3 wiL = toLocal(wiW);
          const double pe = env.pdf(wiW), pb = brdf.pdf(wiL, woL);
          if (wiL.z > 0 && pe > 0 && visible(wiW)) {
            fCos(wiL, f);
            env.radiance(wiW, L);
            const double w = pe / (pe + pb);
            for (int k = 0; k < 3; ++k) sum[k] += f[k] * L[k] * w / pe;
          }
        }
        // BRDF sample.
        {
          const double u0 = rng.next(), u1 = rng.next(), u2 = rng.next();
          const D3 wiL = brdf.sample(woL, u0, u1, u2);
          const D3 wiW = toWorld(wiL);
          const double pb = brdf.pdf(wiL, woL), pe = env.pdf(wiW);
          if (wiL.z > 0 && pb > 0 && visible(wiW)) {
            fCos(wiL, f);
            env.radiance(wiW, L);
            const double w = pb / (pe + pb);
            for (int k = 0; k < 3; ++k) sum[k] += f[k] * L[k] * w / pb;
          }
        }
      }
      for (int k = 0; k < 3; ++k) sum[k] /= opts.spp;
      if (brdf.lobe == reference::Lobe::Mirror) {  // delta lobe: ks * L(reflect(wo))
        const D3 r = n * (2 * reference::dot(n, wo)) - wo;
        if (visible(r)) {
          env.radiance(r, L);
          for (int k = 0; k < 3; ++k) sum[k] += brdf.ks[k] * L[k];
        }
      }
      for (int k = 0; k < 3; ++k) px[k] = float(sum[k]);
    }
    const uint32_t done = ++rowsDone;
    if (opts.progress) {
      std::lock_guard<std::mutex> lock(progressMutex);
      opts.progress(double(done) / H);
    }
  });
  return out;
}

std::vector<float> referenceVisibilitySh(const Scene& scene, const std::vector<float>& gbuffer, uint32_t width,
                                         uint32_t height, uint32_t rays, bool cosine) {
  const World world(scene);
  const std::vector<Vec3> dirs = sphereDirections(rays);
  std::vector<std::array<double, 16>> Y;
  for (const Vec3& d : dirs) Y.push_back(sh16BasisDouble(d));
  const size_t n = size_t(width) * height;
  std::vector<float> out(n * 16, 0.0f);
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    const float* t = &gbuffer[i * 16];
    D3 nrm{t[4], t[5], t[6]};
    const bool geometry = t[3] != 0.0f && reference::dot(nrm, nrm) > 0;
    nrm = geometry ? reference::normalize(nrm) : D3{0, 1, 0};
    const D3 origin = D3{t[0], t[1], t[2]} + nrm * 1e-4;
    double c[16] = {};
    for (size_t j = 0; j < dirs.size(); ++j) {
      const D3 w{dirs[j][0], dirs[j][1], dirs[j][2]};
      const double weight = cosine ? std::max(0.0, reference::dot(nrm, w)) : 1.0;
      if (weight == 0.0 || (geometry && world.occluded(origin, w))) continue;
      for (int k = 0; k < 16; ++k) c[k] += weight * Y[j][size_t(k)];
    }
    for (int k = 0; k < 16; ++k) out[i * 16 + size_t(k)] = float(c[k] * 4 * kPi / double(dirs.size()));
  });
  return out;
}

int referenceCommand(const ReferenceCommandOptions& opts, std::ostream& log) {
  Scene scene = loadScene(opts.scene, opts);
  const std::string out = opts.out.empty() ? std::filesystem::path(opts.scene).stem().string() + "_ref.exr" : opts.out;
  checkWritable(out);  // before the render: a missing output folder costs nothing
  {
    // What the reference holds beside the scene: the image (and its EXR/PNG copies), the environment (its file's
    // channels and RGBA32F while loading, its sampling tables), Embree's BVH over the triangles.
    const ImageHeader eh = imageHeader(scene.environment);
    const double px = double(scene.width) * scene.height, texels = double(eh.width) * eh.height;
    checkMemoryBudget(opts.scene, {{"image", px * 36.0},
                                   {"environment", texels * (4.0 * eh.channels + 16.0 + 16.0)},
                                   {"BVH", double(scene.triangles()) * 128.0}});
  }
  ImageRGBA img = loadImageRGBA(scene.environment);
  const auto [nonFinite, negative] = sanitizeTexels(img.texels, scene.envClampNegative);  // the renderer's policy
  log << "reference " << opts.scene << ": " << scene.width << "x" << scene.height << ", " << opts.render.spp
      << " spp (x2 directions, MIS), visibility " << (opts.render.visibility ? "on" : "off") << ", seed " << opts.render.seed
      << "\n";
  if (nonFinite) log << "  environment: " << nonFinite << " non-finite texel values replaced by 0\n";
  if (negative && scene.envClampNegative) log << "  environment: " << negative << " negative texel values clamped to 0\n";
  ProgressBar bar(std::cerr, "reference");
  ReferenceOptions ro = opts.render;
  ro.progress = [&](double f) { bar.update(f); };
  auto t0 = std::chrono::steady_clock::now();
  std::vector<float> image;
  if (std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.glints; })) {
    // A glints scene: G x D (exact F G) over each pixel's footprint, whose uv derivatives come from the
    // emulated G-buffer (a ray through the pixel centre has none); Embree is not used.
    setTechnique(scene, "glints-gxd");
    log << "  glints scene: G x D over the emulated G-buffer's footprints, " << ro.spp << " sample pairs per pixel\n";
    const GBuffer g = gbufferEmu(scene, emu::lavapipeProfile());
    GlintGxdOptions go;
    go.samples = ro.spp, go.seed = ro.seed;
    image = glintGxdImage(scene, g.texels.data(), g.width, g.height,
                          reference::Environment(EnvImage{img.width, img.height, img.texels.data()}, scene.environmentIntensity), go);
  } else {
    image = renderReference(scene, EnvImage{img.width, img.height, img.texels.data()}, ro);
  }
  bar.finish();
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string png = std::filesystem::path(out).replace_extension(".png").string();
  writeExr(out, scene.width, scene.height, image);
  writePngToneMapped(png, scene.width, scene.height, image);
  log << std::fixed << std::setprecision(2) << "  rendered in " << sec << " s ("
      << double(scene.width) * scene.height * opts.render.spp * 2 / sec / 1e6 << " M directions/s)\n";
  log << "wrote " << out << " and " << png << "\n";
  return 0;
}

}  // namespace shadetwin
