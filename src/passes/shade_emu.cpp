#include "passes/shade.h"
#include "passes/visibility.h"

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
#include "util/pass_log.h"
#include "util/timer.h"

namespace shadetwin {

// Host set-up in double (the promotions spelled out: this file forbids implicit ones).
CameraRays cameraRays(const Scene& scene) {
  const CameraBasis b = scene.basis();
  const double t = std::tan(double(scene.camera.fovY) * 3.14159265358979323846 / 360.0);
  const double aspect = double(scene.width) / scene.height;
  CameraRays r;
  for (int k = 0; k < 3; ++k) {
    r.eye[k] = scene.camera.eye[k];
    r.fwd[k] = b.forward[size_t(k)];
    r.right[k] = float(double(b.right[size_t(k)]) * t * aspect);
    r.down[k] = float(double(-b.up[size_t(k)]) * t);
  }
  return r;
}

std::vector<float> shadeEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                            const VisibilityImage* vis) {
  std::vector<float> out;
  shadeEmu(scene, g, in, dev, out, vis);
  return out;
}

shade::Sampler2D environmentSampler(const emu::Texture& tex, const emu::DeviceProfile& dev, bool repeatU) {
  shade::Sampler2D s;
  s.tex = &tex;
  s.dev = &dev;
  s.desc.addressU = repeatU ? emu::AddressMode::Repeat : emu::AddressMode::ClampToEdge;
  s.desc.addressV = emu::AddressMode::ClampToEdge;
  return s;
}

shade::Sampler2D materialMapSampler(const emu::Texture& tex, const emu::DeviceProfile& dev) {
  shade::Sampler2D s = environmentSampler(tex, dev, true);
  s.desc.addressV = emu::AddressMode::Repeat;
  return s;
}

uint32_t fisMode(const Scene& scene) {
  if (scene.technique == "unfiltered") return shade::scalar::kFisUnfiltered;
  if (scene.technique == "stochastic") return shade::scalar::kFisStochastic;
  return shade::scalar::kFisFiltered;
}

GlintUniforms glintUniforms(const GlintInputs& in) {
  return {in.order, in.bins.rings, in.bins.sectors, in.sat->width() / ndfSatGroups(in.bins), in.sat->height(),
          1.0f / float(in.sat->width() / ndfSatGroups(in.bins)), 1.0f / float(in.sat->height()), in.lightingSpec.rings,
          in.lightingSpec.sectors, in.lobeRings, in.lobeSectors};
}

float fisLevelConstant(const Scene& scene) {
  const double S = scene.fisFaceSize;
  return float(std::log2(double(scene.fisK) * S * S / double(scene.fisSamples)));
}

#define SHADE_EMU_NS x8
#define SHADE_EMU_F emu::F32<8>
#define SHADE_EMU_U emu::U32<8>
#define SHADE_EMU_I emu::I32<8>
#define SHADE_EMU_M emu::Mask<8>
#define SHADE_EMU_ENTRY shadeEmuX8
#include "passes/shade_emu_body.inl"

void shadeEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev, std::vector<float>& out,
              const VisibilityImage* vis) {
  notePass("shade");
  shadeEmuX8(scene, g, in, dev, out, vis);
}
}  // namespace shadetwin
