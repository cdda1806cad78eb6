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
#include "passes/shade_emu_body.inl"
}  // namespace counted_pass

namespace model {

PassCounts countShadePass(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                          const VisibilityImage* vis, std::vector<float>* out, const CoreModel& core) {
  std::vector<float> image;
  PassCounts c;
  c.pass = "shade";
  opcount::sceneBrdfKinds = brdfKindsOf(materialRecords(scene, true));  // the pipeline's specialization constant
  addTicks(c, countedTicks([&] { counted_pass::shadeCounted(scene, g, in, dev, image, vis); }, core, &c.scheduledSeconds), 8);
  opcount::sceneBrdfKinds = 0xffffffffu;
  const uint64_t pixels = uint64_t(g.width) * g.height;
  c.invocations = (pixels + 7) / 8 * 8;
  c.dispatches = 1;
  c.bytesRead = pixels * uint64_t(kGbufFloats) * 4;
  c.bytesWritten = pixels * 16;
  if (out) *out = std::move(image);
  return c;
}

}  // namespace model
}  // namespace shadetwin
