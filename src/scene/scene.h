// Scene files (JSON, see README "Scene files"): meshes, per-object materials, camera, image size,
// environment map. loadScene() validates everything and throws SceneError naming the file, the key
// and what was expected; missing assets name the path and how to fetch them.
#pragma once
#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "scene/mesh.h"

namespace shadetwin {

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Mat4 = std::array<float, 16>;  // column-major, as GLSL mat4
using Vec3 = std::array<float, 3>;

/// One generalized cosine lobe of the Lafortune et al. (1997) model: rho max(s . wi, 0)^n with
/// s = (Cx wo.x, Cy wo.y, Cz wo.z) in the shading frame (Cx = Cy = -1, Cz = 1: a Phong lobe about the
/// mirror direction; rho carries the normalization, e.g. (n + 2) / (2 pi) for a normalized Phong lobe).
struct LafortuneLobe {
  Vec3 c{-1.0f, -1.0f, 1.0f};
  float n = 10.0f;
  float rho = 1.0f;
};

struct Material {
  std::string name;
  Vec3 diffuse{0.5f, 0.5f, 0.5f};  // albedo of the Lambertian term
  Vec3 specular{0.04f, 0.04f, 0.04f};
  std::string brdf = "phong";  // phong | blinn | ward | lafortune | ggx (FIS issue); "mirror" for a perfect mirror
  float exponent = 100.0f;     // Phong / Blinn-Phong exponent
  float roughness = 0.2f;      // GGX alpha / Ward alpha (x and y)
  float roughnessY = 0.2f;
  std::vector<LafortuneLobe> lobes;  // lafortune: one or two lobes
  // Spatially varying parameters (resolved paths of images readable by OpenImageIO; empty: none).
  // diffuse and specular maps multiply the constant colours (RGB); a roughness map multiplies the
  // roughness (ward: both alphas; ggx) by its red channel. Maps are sampled with trilinear filtering
  // and repeat addressing at the LOD of the pixel's uv footprint (shade/material.h).
  std::string diffuseMap, specularMap, roughnessMap;
  bool hasMaps() const { return !diffuseMap.empty() || !specularMap.empty() || !roughnessMap.empty(); }
  // Glints (issue 17, the "glints" block; technique glints): a conductor whose micro-normals come from
  // a tiled normal map (a generator kind or an image file), `scale` tiles per uv unit, each texel a
  // Gaussian lobe of width sigma (radians), Fresnel from the complex index eta + i k per channel.
  bool glints = false;
  std::string glintMap = "flakes";  // flat, flakes, scratches, brushed, bumps, or a resolved file path
  uint32_t glintMapSize = 512, glintMapSeed = 1;
  float glintSpread = 0.15f, glintScale = 4.0f, glintSigma = 0.05f;
  Vec3 glintEta{0.143f, 0.374f, 1.442f}, glintK{3.983f, 2.385f, 1.603f};  // gold
};

struct Object {
  std::string name;
  uint32_t mesh = 0;
  uint32_t material = 0;
  Mat4 model{};  // object -> world
};

/// `model` turned by `degrees` about the vertical axis through its own origin (the object's position):
/// world = T(o) R_y(degrees) T(-o) model, in double, rounded once. Right-handed about +y.
Mat4 rotateAboutOwnAxis(const Mat4& model, double degrees);

struct Camera {
  Vec3 eye{0, 0, 3}, target{0, 0, 0}, up{0, 1, 0};
  float fovY = 40.0f;  // degrees
  float near = 0.1f, far = 100.0f;
};

/// Orthonormal camera frame: right, up (world up made orthogonal), forward (eye -> target).
struct CameraBasis {
  Vec3 right, up, forward;
};

/// Shading techniques: "fis" (filtered importance sampling, issue 4), its baselines "unfiltered"
/// (the same samples at level 0) and "stochastic" (per-pixel rotated samples at level 0), and
/// "env" (environment importance sampling as directional lights), and "mirror" (the simple lookup
/// pass of issue 3). The first three run the FIS pass (shade/shade_fis.h). "kdtree-mis",
/// "alias-mis" and "inversion-mis" (issue 5) run the MIS pass (shade/shade_env_mis.h) with the
/// environment sampled by the kd-tree's fitted block distribution, an alias table over the same
/// blocks, or the inversion method.
/// "glints" (issue 17) runs shade/shade_glints.h; "glints-gxd" is its ground truth, G x D over each
/// pixel's footprint by Monte Carlo (reference/glints_gxd.h), shaded on the host in double whichever
/// build draws the G-buffer.
inline constexpr const char* kTechniques[] = {"fis",           "unfiltered", "stochastic", "env",       "mirror", "kdtree-mis",
                                             "alias-mis",     "inversion-mis", "glints",  "glints-gxd"};
inline bool isTechnique(const std::string& t) {
  for (const char* k : kTechniques)
    if (t == k) return true;
  return false;
}
inline bool usesFisPass(const std::string& t) { return t == "fis" || t == "unfiltered" || t == "stochastic"; }
inline bool usesMisPass(const std::string& t) { return t == "kdtree-mis" || t == "alias-mis" || t == "inversion-mis"; }
inline bool isGlintsTechnique(const std::string& t) { return t == "glints" || t == "glints-gxd"; }
inline constexpr const char* kMisHeuristics[] = {"balance", "power", "env-only", "brdf-only"};  // shade_env_mis.h kMis*

struct Scene {
  std::string path;  // the scene file
  uint32_t width = 512, height = 512;
  Camera camera;
  std::string environment;        // resolved path of the EXR/HDR
  float environmentIntensity = 1.0f;
  bool envClampNegative = false;  // "environment": {"negative": "clamp"}: negative texels set to 0 (default: kept)
  std::string technique = "fis";  // shading technique, see kTechniques
  // Filtered importance sampling ("fis" block): samples per pixel, the level constant K of
  // l = max(log4(K w h / (N p r)), 0), and the face size S of the 2S x S paraboloid atlas.
  uint32_t fisSamples = 40;
  float fisK = 4.0f;
  float fisLevelBias = 0.0f;  // added after the max: 1 = the book chapter's form (with k = 1)
  uint32_t fisFaceSize = 256;
  // What background pixels show ("fis": {"background": ...}): "environment" (default: the equirectangular map, as
  // every other technique) or "atlas" (the dual-paraboloid atlas at level 0: what the pass read before issue 22).
  bool fisBackgroundAtlas = false;
  // MIS techniques ("mis" block): sample pairs (one environment + one BRDF sample) per pixel and
  // frame, the heuristic (index into kMisHeuristics), kd-tree blocks, the Philox seed; misFrame is the
  // frame the pass draws random numbers for (set per frame by render --frames, 0 otherwise).
  uint32_t misSamples = 16;
  uint32_t misHeuristic = 1;  // power
  uint32_t envBlocks = 6144;
  uint32_t misSeed = 0;
  // SH visibility from shadow maps ("visibility" block, issue 16; fis and its baselines): K maps of
  // S x S (0: off, no shadow pass runs), the fit (V max(0, n.w) or V alone) and the depth bias in map
  // texels (inputs/visibility.h VisibilitySettings).
  uint32_t visMaps = 0;
  uint32_t visSize = 1024;
  bool visFitCosine = true;
  float visBias = 1.0f, visSlopeBias = 1.5f;
  uint32_t visFilterRadius = 2;  // spatial filter of the coefficients: radius (0: none), edge-aware or box
  bool visFilterEdge = true;
  uint32_t misFrame = 0;
  // Glints ("glints" block, issue 17): SH degree of the lighting table and the shading, the NDF
  // histogram's bins (rings over [0, thetaMax], sectors) and the lighting table's view grid.
  uint32_t glintOrder = 16;
  uint32_t glintRings = 9, glintSectors = 32;
  float glintThetaMax = 1.57079633f;
  uint32_t glintViewRings = 65, glintViewSectors = 128;
  uint32_t glintGxdSamples = 64;  // technique glints-gxd: MIS sample pairs per pixel
  uint32_t glintLobeRings = 0, glintLobeSectors = 0;  // the rotated-lobe table's grid (0: recurrences per bin)
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Object> objects;

  CameraBasis basis() const;
  Mat4 view() const;
  Mat4 projection() const;  // Vulkan clip space: y down, depth [0, 1]
  Mat4 viewProjection() const;
  std::array<Vec3, 2> bounds() const;  // world-space AABB of every object
  size_t triangles() const;
};

/// The largest scene file loadScene reads (bytes).
inline constexpr uint64_t kMaxSceneFileBytes = uint64_t(16) << 20;
Scene loadScene(const std::string& path);
/// A command line's --technique: sets scene.technique, or throws std::invalid_argument for an unknown
/// technique (listing the known ones) or a glints technique on a scene with a material lacking a glints
/// block (naming the scene file and the material).
void setTechnique(Scene& scene, const std::string& technique);
/// Why `scene` cannot be shaded with `technique` ("" when it can): a glints technique on a material without a glints
/// block, mirror on material maps. The reason names the scene file and the material.
std::string techniqueRefusal(const Scene& scene, const std::string& technique);

/// What a command line may change of a scene: the same options on every command that renders a frame
/// (src/cli/main.cpp addSceneOptions defines them once). 0 or empty keeps the scene's value.
struct SceneOverrides {
  std::string technique;            // --technique (setTechnique's checks)
  uint32_t width = 0, height = 0;   // --width, --height
  uint32_t samples = 0;             // --samples: the technique's samples (fis: per pixel; env: lights; *-mis: sample
                                    // pairs per frame; glints-gxd: G x D pairs)
  uint32_t blocks = 0;              // --blocks: kd-tree / alias blocks of the *-mis samplers
  uint32_t visMaps = 0;             // --vis-maps: shadow maps K of the scene's "visibility" block
  std::string glintViews;           // --glint-views RINGSxSECTORS: the glints lighting table's view grid
};
/// A grid RINGSxSECTORS (rings 2-513, sectors 1-1024: the scene file's glints.view_rings / view_sectors and lobe_rings /
/// lobe_sectors ranges); throws std::invalid_argument naming `flag` and the text otherwise.
std::pair<uint32_t, uint32_t> parseGlintGrid(const std::string& grid, const char* flag);
/// Applies `o` to `scene`; throws std::invalid_argument naming the scene file and the option for an unknown technique,
/// a glints technique on a scene without glints materials, --vis-maps on a scene without a visibility block, or
/// --glint-views on a scene without glints materials or with a grid out of range.
void applyOverrides(Scene& scene, const SceneOverrides& o);
/// loadScene(path) with `o` applied.
Scene loadScene(const std::string& path, const SceneOverrides& o);
/// The repository root guess used to resolve `assets/...`: the scene file's directory's parent.
std::string defaultScenePath();

Mat4 mul(const Mat4& a, const Mat4& b);
Mat4 identity();
/// Upper 3x3 inverse-transpose of `m` (normal matrix), returned as a Mat4 with zero translation.
Mat4 normalMatrix(const Mat4& m);

}  // namespace shadetwin
