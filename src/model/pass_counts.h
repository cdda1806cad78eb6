// What each pass of a frame does, counted (issue 19): every emulated pass's driver compiled over the counting lane
// types (model/op_count.h, model/counted.h) as well as over the emulator's, so the counts are those of the code the
// GPU runs: operations by class, texture lookups by filter, invocations, dispatches, buffer bytes and, for raster
// passes, triangles, fragments and helper lanes. Counting changes no bit: every counted pass returns the emulator's
// output (countFrame checks it; ctest model_* and PassCounts.*).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "emu/device_profile.h"
#include "emu/texture.h"
#include "model/device_desc.h"
#include "model/op_count.h"
#include "model/spirv_loops.h"
#include "passes/shade.h"
#include "scene/scene.h"

namespace shadetwin::model {

struct PassCounts {
  std::string pass;  // gbuffer, shadow, visibility-fit, visibility-filter, paraboloid, mips, sh-project, sh-reduce, glint-lighting, shade
  // Lane operations by kind: a vector operation over N lanes (live, tail or helper) counts N; the texture kinds are
  // per lane already (lookups by filter, texels read).
  std::array<double, opcount::kKinds> ops{};
  uint64_t invocations = 0;   // compute: invocations incl. the tail; raster: vertex invocations + fragment lanes
  uint64_t dispatches = 0;    // dispatches or draws
  uint64_t pipelines = 0;     // pipelines created for the pass and first dispatched in it (the technique inputs)
  uint64_t pipelineWords = 0; // the SPIR-V words of those pipelines' modules (a first dispatch compiles them)
  // compute passes: the SPIR-V words of the module its invocations run (the largest, where it runs several), for the
  // model's code-size term (DeviceDesc codeWords, codeSlowdown); raster passes: 0 (their rates hold their shaders)
  uint64_t moduleWords = 0;
  // compute passes: per loop depth 1, 2, 3+ the most values a loop of that depth in the module carries across its back
  // edge (model/spirv_loops.h carriedByDepth), for the loop-state term; the iterations are ops[kLoop1 + depth - 1].
  // The counted iterations are the dialect's FOR loops by their FOR depth; a loop of literal count (a plain `for`) is a
  // SPIR-V loop too and may deepen the loops inside it there: the term then reads the loops of the depth the FOR has.
  std::array<uint32_t, kLoopDepths> loopCarried{};
  uint64_t workgroups = 0;    // compute workgroups dispatched (0: one per 64 invocations; raster passes have none)
  uint64_t bytesRead = 0, bytesWritten = 0;  // buffer traffic (texture reads are in the lookups)
  // Buffer reads beyond bytesRead's distinct bytes: what invocations read again that a neighbour read (the MIP chain's
  // 3x3 footprints, 9 texels read per 4 of the level; a table row every invocation reads). A software device pays
  // every storage-buffer access alike, whatever the address (lavapipe loads per lane and component: DESIGN §13); a
  // GPU's caches hit.
  uint64_t bytesReread = 0;
  uint64_t attachmentBytes = 0;  // raster passes: render-target bytes cleared and copied out
  // raster passes: vertex and index bytes fetched and fragment outputs written. A GPU's memory term pays them; on a
  // software device they are inside the raster rates (calibrate's draws fetch their vertices and write their pixels),
  // and its "bandwidth" is the price of a shader's storage-buffer access (DESIGN §13), which neither is.
  uint64_t rasterBytes = 0;
  uint64_t triangles = 0, fragments = 0, helperLanes = 0;  // raster passes: triangles in, covered pixels, quad helpers
  // raster passes: per triangle, the 4x4 pixel blocks it covers a pixel of, and of those the ones it covers only partly
  // (emu RasterStats::blocks, partialBlocks)
  uint64_t blocks = 0, partialBlocks = 0;
  RasterPipeline rasterPipeline = kDepthOnly;              // raster passes: whose rates they run at
  uint64_t spanningTriangles = 0;  // raster passes: triangles whose extent holds a pixel-centre row (emu RasterStats)
  // raster passes: triangles entirely outside one clip plane (rejected before set-up) and triangles set-up rejected
  // (zero area, back-facing where culled, no pixel centre inside the target)
  uint64_t outsideTriangles = 0, culledTriangles = 0;
  uint64_t vertexRuns = 0;  // raster passes: vertex routine runs the device's vertex cache starts (model/vertex_cache.h)
  // One core's time for the pass's 8-lane operations on the device's core model (CoreModel on), 0 when not scheduled
  // (GPUs; passes counted one lane at a time: vertex and fragment stages, the SH reduction).
  double scheduledSeconds = 0;
};

/// The core a counted run is scheduled on (opcount::Scheduler): per kind the result latency and the issue interval of
/// one counted 8-lane operation on one core, and the window; off: counting only.
struct CoreModel {
  bool executeEveryBlock = false;  // opcount::executeEveryBlock (software devices), also without the schedule
  bool foldsSpecConstants = true;  // opcount::foldsSpecConstants
  bool valueNumbering = false;     // opcount::valueNumbering, where the run marks its invocations:
  bool invocationsMarked = false;  // the counted driver calls opcount::startInvocation before each
  bool on = false;
  std::array<double, opcount::kKinds> latency{}, interval{};
  std::array<uint32_t, opcount::kKinds> slots = opcount::Scheduler::ones();  // window entries per operation
  uint32_t window = 256;
  // The texture cache of the counted run (opcount::TexCache): the device's line size and capacity (0: no capacity
  // given, lines are counted and no miss is).
  uint32_t cacheLineBytes = 64;
  double cacheBytes = 0.0;
  VertexCacheDesc vertexCache{};  // the device's post-transform vertex cache (entries 0: not simulated)
};

/// Runs `f` on the calling thread alone (a TBB arena of one) with the counters cleared; returns its ticks.
/// With `core` on, the run is also scheduled and `scheduledSeconds` receives one core's time.
std::array<uint64_t, opcount::kKinds> countedTicks(const std::function<void()>& f, const CoreModel& core = {},
                                                   double* scheduledSeconds = nullptr);
/// The operations, by kind, of one vector of the exact-math layer's portable division (k = kExDiv) or square root
/// (kExSqrt) (shade/exact_math.h exDivPortable, exSqrtPortable: straight-line, the same for every operand): what one
/// counted ex_div or ex_sqrt operation stands for on a GPU, and the window entries it holds on a software core.
std::array<uint64_t, opcount::kKinds> exactMathMix(opcount::Kind k);
/// A compute pass runs `module`: its size (moduleWords, the largest of the pass's modules) and its loops' carried values
/// (loopCarried, the most per depth) are the code-size and loop-state terms' inputs.
void runsModule(PassCounts& c, std::span<const uint32_t> module);
/// Adds ticks of a run whose vectors have `lanes` lanes (ALU kinds are multiplied, texture kinds are per lane).
void addTicks(PassCounts& c, const std::array<uint64_t, opcount::kKinds>& ticks, double lanes);

/// The shading pass of scene.technique counted (model/shade_counts.cpp); `out` (optional) receives its image.
PassCounts countShadePass(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                          const VisibilityImage* vis = nullptr, std::vector<float>* out = nullptr, const CoreModel& core = {});

struct FrameCounts {
  std::vector<PassCounts> passes;  // in the order the frame runs them; a pass run several times (mips) is one entry
  size_t compared = 0, identical = 0;  // output values of the counted passes against the emulator's
  std::vector<std::string> differing;  // passes whose counted output differs (empty when counting changed no bit)
};
/// Every device pass of one emulated frame of `scene` (its technique, visibility block, maps) counted, each against the
/// emulator's own run of the same pass.
FrameCounts countFrame(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev, const CoreModel& core = {});

}  // namespace shadetwin::model
