#include "model/pass_counts.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "inputs/env_sampling.h"
#include "inputs/material.h"
#include "lanes/instantiate.h"
#include "passes/passes_vk.h"
#include "passes/visibility.h"

#include "model/counted.h"

namespace shadetwin {
namespace counted_pass {
#define SHADE_EMU_NS counted
#define SHADE_EMU_F opcount::F<8>
#define SHADE_EMU_U opcount::U<8>
#define SHADE_EMU_I opcount::I<8>
#define SHADE_EMU_M opcount::M<8>
#define SHADE_EMU_ENTRY shadeCounted
// Each vector of 8 pixels is one invocation of the entry point: the compiler's redundancy elimination does not reach
// across invocations (opcount::valueNumbering numbers within one).
#define SHADE_EMU_INVOCATION() opcount::startInvocation()
#include "passes/shade_emu_body.inl"
#undef SHADE_EMU_INVOCATION
}  // namespace counted_pass

namespace model {

PassCounts countShadePass(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                          const VisibilityImage* vis, std::vector<float>* out, const CoreModel& core) {
  std::vector<float> image;
  PassCounts c;
  c.pass = "shade";
  runsModule(c, shadeModule(scene.technique));
  opcount::sceneBrdfKinds = brdfKindsOf(materialRecords(scene, true));  // the pipeline's specialization constant
  // Value numbering (a device whose compiler computes a repeated expression once: DeviceDesc value_numbering) is
  // applied where the counted driver marks its invocations: the shading pass, whose shared source repeats the most (a
  // BRDF kind's blocks in pdf and eval of one direction). The other passes' counted drivers do not mark them, so they
  // count every operation as written.
  CoreModel shadeCore = core;
  shadeCore.invocationsMarked = true;
  addTicks(c, countedTicks([&] { counted_pass::shadeCounted(scene, g, in, dev, image, vis); }, shadeCore, &c.scheduledSeconds), 8);
  opcount::sceneBrdfKinds = 0xffffffffu;
  const uint64_t pixels = uint64_t(g.width) * g.height;
  c.invocations = (pixels + 7) / 8 * 8;
  c.dispatches = 1;
  c.bytesRead = pixels * uint64_t(kGbufFloats) * 4;
  c.bytesWritten = pixels * 16;
  // The storage-buffer reads of the technique's entry point (src/shaders/shade_*.comp) beside its G-buffer texel, per
  // invocation (the tail's too: it shades the last pixel again). Distinct bytes are the tables; every invocation's
  // read of a table row (its material record, the SH lighting, the environment's lights) is a re-read, which a GPU's
  // caches serve and a software device pays per lane (lavapipe loads a storage-buffer element one lane and one
  // component at a time, at a uniform index as at any: session 36 probes). Components as the entry points read them:
  // a material record 26 (diffuse.xyz, specular.xyz, kind.x, brdf, lobe0, lobe1, rho, maps.xyz; mirror: diffuse.xyz
  // and specular.xyz); fis the SH lighting (9 x .xyz) and with visibility the pixel's 16 coefficients and the
  // 48-float light transport; the MIS techniques their 64-byte settings block (and the pixel's 16 coefficients);
  // env each light's dir.xyz and weight.xyz, for every lane of a vector that runs the light loop;
  // glints its 44-byte settings.
  const bool visOn = vis && in.visibility;
  const uint64_t inv = c.invocations, materialRows = materialRecords(scene, true).size();
  uint64_t rowBytes = 0, tableBytes = 0;  // per invocation; the tables' distinct bytes
  if (isGlintsTechnique(scene.technique)) {
    rowBytes = 44, tableBytes = 44;
  } else {
    rowBytes = scene.technique == "mirror" ? 24 : 104, tableBytes = materialRows * 128;
    if (usesFisPass(scene.technique)) {
      rowBytes += 108, tableBytes += 21 * 16;
      if (visOn) rowBytes += 64 + 192;
    } else if (usesMisPass(scene.technique)) {
      rowBytes += 64, tableBytes += 64;
      if (visOn) rowBytes += 64;
    }
    if (visOn) c.bytesRead += pixels * 64;  // the pixel's coefficients, once each
  }
  uint64_t reread = inv * rowBytes;
  if (scene.technique == "env") {
    // The light loop runs for an 8-lane vector of consecutive invocations (lavapipe's) where any lane holds geometry
    // (g0.w: the material slot + 1; a vector with none leaves the loop at once, calibrate's untaken loop), and every
    // lane of it is counted: gallivm's per-lane load tests the lane's mask, a branch per lane and component whichever
    // way it goes. (Probe, session 39, clipped 64x48, 256 lights: the loop without its two loads ran 8.7 ms against
    // 28.6 with them.)
    uint64_t looping = 0;  // inv is a whole number of vectors
    for (uint64_t v = 0; v < inv; v += 8) {
      bool any = false;
      for (uint64_t i = v; i < v + 8; ++i) any = any || g.texels[std::min(i, pixels - 1) * kGbufFloats + 3] != 0.0f;
      looping += any ? 8 : 0;
    }
    reread += looping * in.lights.count * 24;
    tableBytes += uint64_t(in.lights.count) * 32;
  }
  c.bytesRead += tableBytes;
  c.bytesReread = reread > tableBytes ? reread - tableBytes : 0;
  if (out) *out = std::move(image);
  return c;
}

namespace {
std::array<uint64_t, opcount::kKinds> countExactMath(opcount::Kind k) {
  opcount::countPortableExactMath = true;
  const auto t = countedTicks([&] {
    // Operands of every kind (normal, subnormal, zero, inf, NaN): the routine is straight-line, the count the same.
    opcount::F<8> a(0.0f), b(0.0f);
    const float va[8] = {1.5f, 3.0e-39f, 0.0f, 1e30f, -2.0f, INFINITY, NAN, 7.0f};
    const float vb[8] = {3.0f, 2.0f, 5.0f, 1e-30f, 0.0f, 1.0f, 1.0f, -INFINITY};
    for (int i = 0; i < 8; ++i) a.set(i, va[i]), b.set(i, vb[i]);
    if (k == opcount::kExDiv)
      shade::counted::exDiv(a, b);
    else
      shade::counted::exSqrt(a);
  });
  opcount::countPortableExactMath = false;
  return t;
}
}  // namespace

std::array<uint64_t, opcount::kKinds> exactMathMix(opcount::Kind k) {
  if (k != opcount::kExDiv && k != opcount::kExSqrt) throw std::invalid_argument("exactMathMix: kExDiv or kExSqrt");
  // Straight-line routines: counted once (coreModel asks for them on every counted frame).
  static const std::array<uint64_t, opcount::kKinds> div = countExactMath(opcount::kExDiv), sqrt = countExactMath(opcount::kExSqrt);
  return k == opcount::kExDiv ? div : sqrt;
}

}  // namespace model
}  // namespace shadetwin
