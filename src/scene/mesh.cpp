#include "scene/mesh.h"

#include <nlohmann/json.hpp>
// Same configuration as src/scene/tinygltf_impl.cpp (no image decoding).
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>
#include <limits>
#include <fstream>
#include <numbers>
#include <sstream>

namespace shadetwin {
namespace {

using v3::F3;
using v3::normalized;
using v3::sub;

// Any unit vector orthogonal to n.
F3 orthogonal(F3 n) {
  F3 a = std::fabs(n[0]) < 0.9f ? F3{1, 0, 0} : F3{0, 1, 0};
  F3 t = v3::cross(a, n);
  return normalized(v3::cross(n, t), {1, 0, 0});
}

}  // namespace

F3 v3::normalized(F3 a, F3 fallback) {
  double l = std::sqrt(dot(a, a));
  if (!(l > 1e-30)) return fallback;
  return {float(a[0] / l), float(a[1] / l), float(a[2] / l)};
}

std::array<F3, 2> meshBounds(const Mesh& m) {
  F3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (auto& p : m.positions)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  return {lo, hi};
}

Mesh makeSphere(uint32_t segments, uint32_t rings) {
  Mesh m;
  m.name = "sphere";
  const double pi = std::numbers::pi;
  for (uint32_t r = 0; r <= rings; ++r) {
    double v = double(r) / rings, theta = v * pi;
    for (uint32_t s = 0; s <= segments; ++s) {
      double u = double(s) / segments, phi = u * 2 * pi;
      F3 p{float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(-std::sin(theta) * std::sin(phi))};
      m.positions.push_back(p);
      m.normals.push_back(p);
      m.uvs.push_back({float(u), float(v)});
      m.tangents.push_back({float(-std::sin(phi)), 0.0f, float(-std::cos(phi)), 1.0f});
    }
  }
  for (uint32_t r = 0; r < rings; ++r)
    for (uint32_t s = 0; s < segments; ++s) {
      uint32_t a = r * (segments + 1) + s, b = a + segments + 1;
      if (r != 0) m.indices.insert(m.indices.end(), {a, b, a + 1});
      if (r + 1 != rings) m.indices.insert(m.indices.end(), {a + 1, b, b + 1});
    }
  return m;
}

Mesh makeSphereStrips(uint32_t segments, uint32_t rings, uint32_t w) {
  const Mesh s = makeSphere(segments, rings);
  Mesh m;
  m.name = "sphere-strips";
  for (uint32_t s0 = 0; s0 < segments; s0 += w) {
    const uint32_t cols = std::min(w, segments - s0), base = uint32_t(m.positions.size());
    for (uint32_t r = 0; r <= rings; ++r)
      for (uint32_t c = 0; c <= cols; ++c) {
        const uint32_t v = r * (segments + 1) + s0 + c;
        m.positions.push_back(s.positions[v]), m.normals.push_back(s.normals[v]);
        m.tangents.push_back(s.tangents[v]), m.uvs.push_back(s.uvs[v]);
      }
    for (uint32_t r = 0; r < rings; ++r)
      for (uint32_t c = 0; c < cols; ++c) {
        const uint32_t a = base + r * (cols + 1) + c, b = a + cols + 1;
        if (r != 0) m.indices.insert(m.indices.end(), {a, b, a + 1});
        if (r + 1 != rings) m.indices.insert(m.indices.end(), {a + 1, b, b + 1});
      }
  }
  return m;
}

Mesh makePlane() {
  Mesh m;
  m.name = "plane";
  m.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  m.normals.assign(4, {0, 1, 0});
  m.tangents.assign(4, {1, 0, 0, 1});
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 2, 1, 0, 3, 2};
  return m;
}

Mesh makeTorus(float major, float minor, uint32_t segments, uint32_t sides) {
  Mesh m;
  m.name = "torus";
  const double pi = std::numbers::pi;
  for (uint32_t i = 0; i <= segments; ++i) {
    double u = double(i) / segments, a = u * 2 * pi;
    for (uint32_t j = 0; j <= sides; ++j) {
      double v = double(j) / sides, b = v * 2 * pi;
      double r = major + minor * std::cos(b);
      m.positions.push_back({float(r * std::cos(a)), float(minor * std::sin(b)), float(-r * std::sin(a))});
      m.normals.push_back({float(std::cos(b) * std::cos(a)), float(std::sin(b)), float(-std::cos(b) * std::sin(a))});
      m.uvs.push_back({float(u), float(v)});
      m.tangents.push_back({float(-std::sin(a)), 0.0f, float(-std::cos(a)), 1.0f});
    }
  }
  for (uint32_t i = 0; i < segments; ++i)
    for (uint32_t j = 0; j < sides; ++j) {
      uint32_t a = i * (sides + 1) + j, b = a + sides + 1;
      m.indices.insert(m.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
    }
  return m;
}

namespace {

// Bits of a float with -0 read as +0 (positions that compare equal weld).
uint32_t weldBits(float x) {
  if (x == 0.0f) x = 0.0f;
  uint32_t b;
  std::memcpy(&b, &x, 4);
  return b;
}

struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) {
    for (size_t i = 0; i < n; ++i) parent[i] = uint32_t(i);
  }
  uint32_t find(uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(uint32_t a, uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the smallest corner is a set's root
  }
};

}  // namespace

WeldStats weldNormals(Mesh& m, float creaseDegrees) {
  const size_t n = m.positions.size(), corners = m.indices.size() - m.indices.size() % 3;
  // Position classes: vertices at the same position (bitwise, -0 = +0) are one point of the surface.
  std::vector<uint32_t> cls(n);
  std::map<std::array<uint32_t, 3>, uint32_t> classOf;
  for (size_t i = 0; i < n; ++i) {
    const auto& p = m.positions[i];
    cls[i] = classOf.emplace(std::array<uint32_t, 3>{weldBits(p[0]), weldBits(p[1]), weldBits(p[2])}, uint32_t(classOf.size()))
                 .first->second;
  }
  WeldStats st;
  st.positionClasses = classOf.size();
  // Face normals: f = (b - a) x (c - a), |f| = twice the area (the weight); unit normals in double for the angle test.
  const size_t faces = corners / 3;
  std::vector<F3> f(faces);
  std::vector<std::array<double, 3>> u(faces);
  std::vector<char> flat(faces);
  for (size_t t = 0; t < faces; ++t) {
    const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
    f[t] = v3::cross(sub(m.positions[b], m.positions[a]), sub(m.positions[c], m.positions[a]));
    const double l = std::sqrt(v3::dot(f[t], f[t]));
    flat[t] = !(l > 1e-30);
    u[t] = flat[t] ? std::array<double, 3>{0, 0, 0} : std::array<double, 3>{f[t][0] / l, f[t][1] / l, f[t][2] / l};
  }
  // Smoothing groups of corners. The corners of one vertex index are one group (the mesh shares that vertex: it asked
  // for one normal there). Corners of two different vertices at one position join across each edge their faces share
  // (the same two position classes) unless the faces meet at more than the crease angle: a duplicated vertex is either
  // a patch border (the teapot: join) or an authored hard edge (a cube of 24 vertices: keep). Zero-area faces decide
  // nothing (a sliver along a crease would join both sides).
  UnionFind groups(corners);
  {
    std::vector<uint32_t> firstCorner(n, UINT32_MAX);
    for (size_t c = 0; c < corners; ++c) {
      uint32_t& fc = firstCorner[m.indices[c]];
      if (fc == UINT32_MAX) fc = uint32_t(c);
      else groups.join(fc, uint32_t(c));
    }
  }
  const double cosCrease = std::cos(double(creaseDegrees) * std::numbers::pi / 180.0);
  struct Spoke {
    uint32_t at, to, corner;
  };
  std::vector<Spoke> spokes;
  spokes.reserve(2 * corners);
  for (size_t c = 0; c < corners; ++c) {
    const size_t t = c / 3, k = c % 3;
    const uint32_t at = cls[m.indices[c]];
    for (size_t o : {(k + 1) % 3, (k + 2) % 3}) {
      const uint32_t to = cls[m.indices[3 * t + o]];
      if (to != at) spokes.push_back({at, to, uint32_t(c)});
    }
  }
  std::sort(spokes.begin(), spokes.end(), [](const Spoke& x, const Spoke& y) {
    return std::tie(x.at, x.to, x.corner) < std::tie(y.at, y.to, y.corner);
  });
  for (size_t i = 0; i < spokes.size();) {
    size_t j = i;
    while (j < spokes.size() && spokes[j].at == spokes[i].at && spokes[j].to == spokes[i].to) ++j;
    for (size_t a = i; a < j; ++a)
      for (size_t b = a + 1; b < j; ++b) {  // an edge has two faces on a manifold, a few on others
        const uint32_t ca = spokes[a].corner, cb = spokes[b].corner;
        const size_t fa = ca / 3, fb = cb / 3;
        if (m.indices[ca] == m.indices[cb] || flat[fa] || flat[fb]) continue;
        const double d = u[fa][0] * u[fb][0] + u[fa][1] * u[fb][1] + u[fa][2] * u[fb][2];
        if (d >= cosCrease) groups.join(ca, cb);
        else ++st.creaseEdges;
      }
    i = j;
  }
  // A group's normal: the area-weighted sum of its faces, in face order and in float (a vertex no duplicate touches
  // gets the bits the per-index sum gave: the group is its corners).
  std::vector<F3> sum(corners, F3{0, 0, 0});
  std::vector<char> root(corners, 0);
  for (size_t c = 0; c < corners; ++c) {
    const uint32_t g = groups.find(uint32_t(c));
    root[g] = 1;
    for (int k = 0; k < 3; ++k) sum[g][k] += f[c / 3][k];
  }
  for (char r : root) st.groups += size_t(r);
  m.normals.assign(n, F3{0, 1, 0});  // a vertex no triangle uses keeps the fallback
  for (size_t c = 0; c < corners; ++c) m.normals[m.indices[c]] = normalized(sum[groups.find(uint32_t(c))], {0, 1, 0});
  return st;
}

void completeMesh(Mesh& m, float creaseDegrees) {
  if (m.normals.size() != m.positions.size()) weldNormals(m, creaseDegrees);
  const size_t n = m.positions.size();
  if (m.uvs.size() != n) {  // spherical about the bounding-box centre
    const auto [lo, hi] = meshBounds(m);
    F3 c{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    m.uvs.resize(n);
    for (size_t i = 0; i < n; ++i) {
      F3 d = normalized(sub(m.positions[i], c), {0, 1, 0});
      m.uvs[i] = {float(0.5 + std::atan2(-d[2], d[0]) / (2 * std::numbers::pi)),
                  float(std::acos(std::clamp(double(d[1]), -1.0, 1.0)) / std::numbers::pi)};
    }
  }
  if (m.tangents.size() != n) {  // UV-gradient tangents (Lengyel), orthogonalised
    // Accumulated per weld class (position, normal and UV all equal): vertices a patch border duplicated share one
    // tangent, a UV seam or a crease keeps its own.
    std::vector<uint32_t> weld(n);
    {
      std::map<std::array<uint32_t, 8>, uint32_t> classOf;
      for (size_t i = 0; i < n; ++i) {
        const auto &p = m.positions[i], &nn = m.normals[i];
        const auto& uv = m.uvs[i];
        weld[i] = classOf
                      .emplace(std::array<uint32_t, 8>{weldBits(p[0]), weldBits(p[1]), weldBits(p[2]), weldBits(nn[0]),
                                                       weldBits(nn[1]), weldBits(nn[2]), weldBits(uv[0]), weldBits(uv[1])},
                               uint32_t(i))
                      .first->second;
      }
    }
    std::vector<F3> t(n, F3{0, 0, 0}), b(n, F3{0, 0, 0});
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
      uint32_t v[3] = {weld[m.indices[i]], weld[m.indices[i + 1]], weld[m.indices[i + 2]]};
      F3 e1 = sub(m.positions[v[1]], m.positions[v[0]]), e2 = sub(m.positions[v[2]], m.positions[v[0]]);
      float du1 = m.uvs[v[1]][0] - m.uvs[v[0]][0], dv1 = m.uvs[v[1]][1] - m.uvs[v[0]][1];
      float du2 = m.uvs[v[2]][0] - m.uvs[v[0]][0], dv2 = m.uvs[v[2]][1] - m.uvs[v[0]][1];
      float det = du1 * dv2 - du2 * dv1;
      if (!(std::fabs(det) > 1e-20f)) continue;
      float r = 1.0f / det;
      F3 sdir{(e1[0] * dv2 - e2[0] * dv1) * r, (e1[1] * dv2 - e2[1] * dv1) * r, (e1[2] * dv2 - e2[2] * dv1) * r};
      F3 tdir{(e2[0] * du1 - e1[0] * du2) * r, (e2[1] * du1 - e1[1] * du2) * r, (e2[2] * du1 - e1[2] * du2) * r};
      for (uint32_t k : v)
        for (int c = 0; c < 3; ++c) t[k][c] += sdir[c], b[k][c] += tdir[c];
    }
    m.tangents.resize(n);
    for (size_t i = 0; i < n; ++i) {
      F3 nn = m.normals[i];
      const F3 &ti = t[weld[i]], &bi = b[weld[i]];
      double d = v3::dot(nn, ti);
      F3 tt{float(ti[0] - nn[0] * d), float(ti[1] - nn[1] * d), float(ti[2] - nn[2] * d)};
      tt = normalized(tt, orthogonal(nn));
      float w = v3::dot(v3::cross(nn, tt), bi) < 0.0 ? -1.0f : 1.0f;
      m.tangents[i] = {tt[0], tt[1], tt[2], w};
    }
  }
}

void validateMesh(const Mesh& m, const std::string& what) {
  if (m.positions.empty() || m.indices.empty()) throw MeshError(what + ": mesh has no triangles");
  if (m.indices.size() % 3) throw MeshError(what + ": index count is not a multiple of 3");
  for (uint32_t i : m.indices)
    if (i >= m.positions.size())
      throw MeshError(what + ": index " + std::to_string(i) + " out of range (" + std::to_string(m.positions.size()) +
                      " vertices)");
  for (auto& p : m.positions)
    for (float c : p)
      if (!std::isfinite(c)) throw MeshError(what + ": non-finite vertex position");
}

Mesh loadNpmMesh(const std::string& path) {
  std::ifstream f(path);
  if (!f)
    throw MeshError(path + ": cannot open mesh file (fetch the npm meshes with: bash scripts/setup.sh)");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  auto arrayAfter = [&](const std::string& key) {
    size_t k = text.find(key);
    if (k == std::string::npos) throw MeshError(path + ": no `" + key + "` in this module");
    size_t b = text.find('[', k);
    int depth = 0;
    size_t e = b;
    for (; e < text.size(); ++e) {
      if (text[e] == '[') ++depth;
      if (text[e] == ']' && --depth == 0) break;
    }
    if (b == std::string::npos || e >= text.size()) throw MeshError(path + ": unterminated array after `" + key + "`");
    try {
      return nlohmann::json::parse(text.substr(b, e - b + 1));
    } catch (const std::exception& ex) {
      throw MeshError(path + ": `" + key + "` is not a JSON array: " + ex.what());
    }
  };
  nlohmann::json pos = arrayAfter("exports.positions"), cells = arrayAfter("exports.cells");
  Mesh m;
  m.name = path;
  try {
    // Each value checked before its conversion (a float cannot hold 1e39, an index is a non-negative integer).
    for (auto& p : pos) {
      std::array<float, 3> v{};
      for (int k = 0; k < 3; ++k) {
        const double d = p.at(size_t(k)).get<double>();
        if (!(std::fabs(d) <= double(std::numeric_limits<float>::max())))
          throw MeshError(path + ": position " + std::to_string(m.positions.size()) + " is not finite: " + p.dump());
        v[size_t(k)] = float(d);
      }
      m.positions.push_back(v);
    }
    for (auto& c : cells) {
      if (!c.is_array() || c.size() != 3) throw MeshError(path + ": a cell is not a triangle: " + c.dump());
      for (int k = 0; k < 3; ++k) {
        const nlohmann::json& i = c.at(size_t(k));
        if (!i.is_number_unsigned() || i.get<uint64_t>() > 0xffffffffu)
          throw MeshError(path + ": cell " + std::to_string(m.indices.size() / 3) + ": expected vertex indices, got " + c.dump());
        m.indices.push_back(uint32_t(i.get<uint64_t>()));
      }
    }
  } catch (const nlohmann::json::exception& ex) {
    throw MeshError(path + ": malformed positions/cells: " + ex.what());
  }
  validateMesh(m, path);
  completeMesh(m);
  return m;
}

namespace {

using Mat = std::array<double, 16>;  // column-major
Mat mul(const Mat& a, const Mat& b) {
  Mat r{};
  for (int c = 0; c < 4; ++c)
    for (int rr = 0; rr < 4; ++rr)
      for (int k = 0; k < 4; ++k) r[c * 4 + rr] += a[k * 4 + rr] * b[c * 4 + k];
  return r;
}
Mat nodeMatrix(const tinygltf::Node& n) {
  Mat m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (n.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i) m[i] = n.matrix[i];
    return m;
  }
  Mat t = m, r = m, s = m;
  if (n.translation.size() == 3) t[12] = n.translation[0], t[13] = n.translation[1], t[14] = n.translation[2];
  if (n.rotation.size() == 4) {
    double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
    r = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0, 2 * (x * y - z * w), 1 - 2 * (x * x + z * z),
         2 * (y * z + x * w), 0, 2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0, 0, 0, 0, 1};
  }
  if (n.scale.size() == 3) s[0] = n.scale[0], s[5] = n.scale[1], s[10] = n.scale[2];
  return mul(t, mul(r, s));
}

template <class T, size_t N>
std::vector<std::array<T, N>> readAccessor(const tinygltf::Model& model, int index, const std::string& path,
                                           const char* what) {
  const auto& acc = model.accessors.at(size_t(index));
  const size_t comps = tinygltf::GetNumComponentsInType(uint32_t(acc.type));
  if (comps != N) throw MeshError(path + ": accessor for " + what + " has " + std::to_string(comps) + " components, expected " + std::to_string(N));
  std::vector<std::array<T, N>> out(acc.count);
  if (acc.bufferView < 0) return out;  // all zero (sparse accessors are not supported)
  const auto& view = model.bufferViews.at(size_t(acc.bufferView));
  const auto& buf = model.buffers.at(size_t(view.buffer));
  const size_t csize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType)));
  const size_t stride = view.byteStride ? view.byteStride : csize * N;
  const size_t base = view.byteOffset + acc.byteOffset;
  if (acc.count && base + stride * (acc.count - 1) + csize * N > buf.data.size())
    throw MeshError(path + ": accessor for " + what + " runs past its buffer");
  for (size_t i = 0; i < acc.count; ++i)
    for (size_t c = 0; c < N; ++c) {
      const unsigned char* p = buf.data.data() + base + stride * i + csize * c;
      double v = 0;
      switch (acc.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); v = f; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); v = u; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t u; std::memcpy(&u, p, 2); v = acc.normalized ? u / 65535.0 : u; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: v = acc.normalized ? *p / 255.0 : *p; break;
        default: throw MeshError(path + ": unsupported component type for " + what);
      }
      out[i][c] = T(v);
    }
  return out;
}

}  // namespace

Mesh loadGltf(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = path.size() > 4 && path.substr(path.size() - 4) == ".glb";
  bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path) : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) throw MeshError(path + ": cannot load glTF: " + (err.empty() ? "unknown error" : err));
  Mesh out;
  out.name = path;
  bool anyUv = true, anyTangent = true;
  std::function<void(int, const Mat&)> visit = [&](int ni, const Mat& parent) {
    const auto& node = model.nodes.at(size_t(ni));
    Mat m = mul(parent, nodeMatrix(node));
    if (node.mesh >= 0) {
      for (const auto& prim : model.meshes.at(size_t(node.mesh)).primitives) {
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;
        auto it = prim.attributes.find("POSITION");
        if (it == prim.attributes.end()) throw MeshError(path + ": primitive without POSITION");
        auto pos = readAccessor<float, 3>(model, it->second, path, "POSITION");
        const uint32_t base = uint32_t(out.positions.size());
        for (auto& p : pos) {
          std::array<float, 3> q;
          for (int r = 0; r < 3; ++r) q[r] = float(m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
          out.positions.push_back(q);
        }
        auto nit = prim.attributes.find("NORMAL");
        if (nit != prim.attributes.end()) {
          for (auto& nrm : readAccessor<float, 3>(model, nit->second, path, "NORMAL")) {  // upper 3x3 (uniform scale assumed)
            std::array<float, 3> q;
            for (int r = 0; r < 3; ++r) q[r] = float(m[r] * nrm[0] + m[4 + r] * nrm[1] + m[8 + r] * nrm[2]);
            out.normals.push_back(normalized(q, {0, 1, 0}));
          }
        }
        auto uit = prim.attributes.find("TEXCOORD_0");
        if (uit != prim.attributes.end()) {
          auto uv = readAccessor<float, 2>(model, uit->second, path, "TEXCOORD_0");
          out.uvs.insert(out.uvs.end(), uv.begin(), uv.end());
        } else {
          anyUv = false;
        }
        auto tit = prim.attributes.find("TANGENT");
        if (tit != prim.attributes.end()) {
          for (auto& t : readAccessor<float, 4>(model, tit->second, path, "TANGENT")) {
            std::array<float, 3> q;
            for (int r = 0; r < 3; ++r) q[r] = float(m[r] * t[0] + m[4 + r] * t[1] + m[8 + r] * t[2]);
            q = normalized(q, {1, 0, 0});
            out.tangents.push_back({q[0], q[1], q[2], t[3] < 0 ? -1.0f : 1.0f});
          }
        } else {
          anyTangent = false;
        }
        if (prim.indices >= 0) {
          for (auto& i : readAccessor<uint32_t, 1>(model, prim.indices, path, "indices")) out.indices.push_back(base + i[0]);
        } else {
          for (uint32_t i = 0; i < pos.size(); ++i) out.indices.push_back(base + i);
        }
      }
    }
    for (int c : node.children) visit(c, m);
  };
  const Mat id{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (!model.scenes.empty()) {
    int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    for (int n : model.scenes.at(size_t(s)).nodes) visit(n, id);
  } else {
    for (size_t n = 0; n < model.nodes.size(); ++n) visit(int(n), id);
  }
  if (out.normals.size() != out.positions.size()) out.normals.clear();
  if (!anyUv || out.uvs.size() != out.positions.size()) out.uvs.clear();
  if (!anyTangent || out.tangents.size() != out.positions.size()) out.tangents.clear();
  validateMesh(out, path);
  completeMesh(out);
  return out;
}

}  // namespace shadetwin
