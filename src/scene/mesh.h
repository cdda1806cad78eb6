// Triangle meshes: procedural (sphere, plane, torus), the npm `bunny` / `teapot` packages, glTF 2.0
// (tinygltf). Every mesh comes out with per-vertex normals, tangents (xyz + handedness) and UVs.
#pragma once
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadetwin {

struct MeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Mesh {
  std::string name;
  std::vector<std::array<float, 3>> positions, normals;
  std::vector<std::array<float, 4>> tangents;  // xyz, w = handedness (+1 / -1)
  std::vector<std::array<float, 2>> uvs;
  std::vector<uint32_t> indices;  // triangles
  size_t triangles() const { return indices.size() / 3; }
};

Mesh makeSphere(uint32_t segments = 96, uint32_t rings = 48);      // radius 1, centred at 0
/// makeSphere's triangles strip by strip of `w` columns, each strip's vertices numbered as their own (rings + 1) x
/// (w + 1) block (shared columns duplicated): the same triangles and pixels, a triangle's vertices w + 1 apart instead
/// of segments + 1 (what a small direct-mapped vertex cache holds: calibrate's vertex-run measurement).
Mesh makeSphereStrips(uint32_t segments, uint32_t rings, uint32_t w);
Mesh makePlane();                                                   // [-1,1]^2 in y = 0, normal +y
Mesh makeTorus(float major = 1.0f, float minor = 0.35f, uint32_t segments = 96, uint32_t sides = 48);

/// npm packages `bunny` / `teapot`: a CommonJS module with `exports.positions=[[x,y,z],...]` and
/// `exports.cells=[[a,b,c],...]`. Normals are area-weighted, UVs spherical about the bounding-box centre.
Mesh loadNpmMesh(const std::string& path);
/// glTF 2.0 (.gltf or .glb): every triangle primitive of every node of the default scene, node
/// transforms applied. Missing normals / UVs / tangents are generated.
Mesh loadGltf(const std::string& path);

/// Small 3-vector helpers of the host-side geometry code (scene set-up, mesh completion). Lengths
/// and dot products accumulate in double.
namespace v3 {
using F3 = std::array<float, 3>;
inline F3 sub(F3 a, F3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline F3 cross(F3 a, F3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
inline double dot(F3 a, F3 b) {
  return double(a[0]) * double(b[0]) + double(a[1]) * double(b[1]) + double(a[2]) * double(b[2]);
}
/// a / |a|, or `fallback` when |a| is 0 or not finite.
F3 normalized(F3 a, F3 fallback);
}  // namespace v3

/// Axis-aligned bounds {min, max} of the positions.
std::array<std::array<float, 3>, 2> meshBounds(const Mesh& m);

/// What weldNormals did: distinct positions, smoothing groups (one normal each), edges between duplicated vertices
/// kept sharp (counted from each end).
struct WeldStats {
  size_t positionClasses = 0, groups = 0, creaseEdges = 0;
};
/// The default crease angle between the faces of duplicated vertices: above it an edge stays sharp. Measured
/// (tests/mesh_test.cpp): the npm teapot's patch borders meet at up to 69.3 degrees (a coarse tessellation), a cube's
/// faces at 90.
inline constexpr float kCreaseDegrees = 80.0f;
/// Generates normals with duplicated vertices welded: the corners of one vertex index are one smoothing group (a
/// shared vertex stays smooth, so a mesh without duplicates gets exactly the per-index area-weighted normals); the
/// corners of different vertices at one position (bitwise, -0 = +0) join across each edge their faces share unless the
/// faces meet at more than `creaseDegrees`. Each group's normal is the area-weighted sum of its faces. The npm teapot's
/// duplicated patch borders therefore get equal normals, a cube of 24 vertices keeps its edges. Zero-area faces join
/// nothing. Replaces m.normals; vertices and indices are unchanged.
WeldStats weldNormals(Mesh& m, float creaseDegrees = kCreaseDegrees);
/// Fills normals (weldNormals) when absent, UVs (spherical) when absent, and tangents (from UV gradients,
/// Gram-Schmidt against the normal, accumulated over vertices equal in position, normal and UV) when absent.
void completeMesh(Mesh& m, float creaseDegrees = kCreaseDegrees);
/// Checks indices and finiteness; throws MeshError naming `what` and the problem.
void validateMesh(const Mesh& m, const std::string& what);

}  // namespace shadetwin
