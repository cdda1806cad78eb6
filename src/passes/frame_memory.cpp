#include "passes/frame_memory.h"

#include <set>

#include "inputs/glints.h"
#include "passes/gbuffer.h"

namespace shadetwin {

std::vector<MemoryNeed> frameMemory(const Scene& s, uint32_t envWidth, uint32_t envHeight, uint32_t envChannels, FrameBuild build) {
  const bool vk = build == FrameBuild::Vulkan;
  const double px = double(s.width) * s.height, texels = double(envWidth) * envHeight;
  const double mip = 4.0 / 3.0;  // a full MIP chain over level 0
  std::vector<MemoryNeed> n;
  // G-buffer: four RGBA32F targets and the depth, drawn into the emulator's targets and copied out (on a device: its
  // images, the read-back buffer, the copy and the shading pass's upload of it).
  n.push_back({"G-buffer", px * (kGbufFloats + 1) * 4.0 * (vk ? 4 : 2)});
  // Geometry beyond the loaded meshes: transformed vertices and set-up triangles of the G-buffer and shadow passes.
  // Measured, not derived: the stress run's 2,000,000-triangle mesh peaked 1.06 GiB above the other parts (docs/RESULTS.md
  // "Stress"), ~570 bytes per triangle.
  n.push_back({"geometry", double(s.triangles()) * 576.0});
  // The shaded image, the EXR writer's copy and the PNG's 8-bit pixels; a device's storage image and read-back.
  n.push_back({"image", px * (16.0 + 16.0 + 4.0 + (vk ? 32.0 : 0.0))});
  if (usesMisPass(s.technique)) n.push_back({"progressive mean", px * 32.0});
  // The environment: the file's channels and the RGBA32F level 0 while loading, then the MIP chain as levels and as the
  // emulator's texture; a device's image and its staging copy (fis on a device: one more pair, the atlas's resampling
  // reads one and the shading pass's background another).
  const double deviceCopies = vk ? (usesFisPass(s.technique) ? 4.0 : 2.0) : 0.0;
  n.push_back({"environment", texels * (4.0 * envChannels + 16.0 + 2 * 16.0 * mip + deviceCopies * 16.0 * mip)});
  if (usesMisPass(s.technique)) n.push_back({"sampler tables", texels * 16.0});
  if (usesFisPass(s.technique)) n.push_back({"paraboloid atlas", 2.0 * s.fisFaceSize * s.fisFaceSize * 16.0 * mip * (vk ? 3 : 1)});
  if (s.visMaps && (usesFisPass(s.technique) || usesMisPass(s.technique))) {
    // K maps of size^2 D32F, their copy as the fit's array (a device: the images and their read-back), then 16
    // coefficients per pixel and as many filtered.
    const double maps = double(s.visMaps) * s.visSize * s.visSize * 4.0;
    n.push_back({"shadow maps", maps * (vk ? 3 : 2)});
    n.push_back({"visibility coefficients", px * 16 * 4.0 * (s.visFilterRadius ? 2 : 1) * (vk ? 2 : 1)});
  }
  if (s.technique == "glints") {
    // Per distinct normal map (glintInputs: one per map, size, seed and spread): the map (3 floats a texel), its NDF
    // histogram SAT (rings x sectors 16-bit counts a texel), the SAT as a texture and the one array holding every map.
    std::set<GlintMapKey> maps;
    double mapBytes = 0;
    for (const Material& m : s.materials)
      if (m.glints && maps.insert(glintMapKey(m)).second) {
        const double t = double(m.glintMapSize) * m.glintMapSize;
        mapBytes += t * (12.0 + 3.0 * s.glintRings * s.glintSectors * 2.0);
      }
    n.push_back({"glint tables", mapBytes * (vk ? 4.0 / 3.0 : 1.0)});
    const double coeffs = double(s.glintOrder + 1) * (s.glintOrder + 1);
    n.push_back({"glint lighting table", double(s.glintViewRings) * s.glintViewSectors * coeffs * 16.0 * 2});
    if (s.glintLobeRings) n.push_back({"glint lobe table", double(s.glintLobeRings) * s.glintLobeSectors * coeffs / 4.0 * 16.0});
  }
  return n;
}

}  // namespace shadetwin
