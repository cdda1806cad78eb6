// Device descriptions of the performance model (issue 19): what a device can do per second, as data, one
// JSON file per device in devices/. Software devices (lavapipe, swiftshader) are written by `shadetwin
// calibrate` from microkernels only (src/shaders/calibrate.comp); GPUs from public figures, unverified until
// measured on one.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace shadetwin::model {

/// Operation classes the counting lane types report (bench/op_count.h) and the microkernels measure.
// shift: integer shifts, a class of their own: SwiftShader's Subzero runs a vector shift as four scalar ones (calibrate:
// ~6x an fadd, where an integer add, and or xor costs less than an fadd); lavapipe and GPUs shift at the ialu rate.
// icmp, iselect: integer compares and selects of integers or masks (float compares and selects of floats are fcmp and
// select): SwiftShader runs an integer compare and the select it feeds at ~14x an integer add, a float pair at ~4x
// (straight-line probes, docs/RESULTS.md session 22); the GPUs at their compare/select rate.
// private_read, private_write: an element of a local array read or written at an index that is not a literal (the
// dialect's arrayGet / arraySet; only the glints kernels have such arrays). lavapipe's gallivm lowers a read to a scalar
// load per lane (lp_bld_nir_soa.c build_gather) and a write to a load, select and store per lane (emit_mask_scatter);
// calibrate's private-array kernels measure both (read-only; read, add, write). A GPU keeps such an array in local
// memory: its load/store units (the public-figure files).
// ex_div, ex_sqrt: one correctly rounded division or square root of the exact-math layer (shade/exact_math.h
// exDivPortable, exSqrtPortable: 164 and 101 operations of the classes above, straight-line), a class of its own because
// what a device makes of that mix is not the sum of its parts: lavapipe ran a division at 2.5-3x the price of its
// counted operations (probes, docs/RESULTS.md session 36). Software devices: calibrate's kernels run the shared routine
// itself (src/shaders/calibrate_exmath.comp, optimised like the shading modules). GPUs: the routine's operation mix
// (model/pass_counts.h exactMathMix) at the per-class rates of the public figures.
enum OpClass {
  kFAdd, kFMul, kIAlu, kIMul, kCvt, kSelect, kFCmp, kShift, kICmp, kISelect, kPrivateRead, kPrivateWrite, kExDiv, kExSqrt,
  kOpClasses
};
inline constexpr const char* kOpClassNames[kOpClasses] = {"fadd",  "fmul",  "ialu", "imul",    "cvt",          "select",
                                                          "fcmp",  "shift", "icmp", "iselect", "private_read", "private_write",
                                                          "ex_div", "ex_sqrt"};
/// RGBA32F lookups the model distinguishes: textureLod through a nearest, bilinear or trilinear sampler; a texelFetch
/// at coordinates every lane of the invocation group shares (uniform: shade/prelude.h texelFetchUniform, per lane); a
/// texelFetch at per-lane integer coordinates (fetch: no scaling, wrapping or level selection).
enum TexFilter { kNearest, kBilinear, kTrilinear, kUniformFetch, kFetch, kTexFilters };
inline constexpr const char* kTexFilterNames[kTexFilters] = {"nearest", "bilinear", "trilinear", "uniform", "fetch"};
/// Raster pipelines the model distinguishes: a triangle's set-up and a covered pixel cost what the pipeline makes of
/// them (lavapipe: 145 ns a tiny triangle through the G-buffer's, 210 ns through the depth-only shadow pipeline; a
/// covered pixel 10 ns with four RGBA32F targets and a fragment shader, 0.9 ns depth-only), so each has its rates.
enum RasterPipeline { kDepthOnly, kGbufferRaster, kRasterPipelines };
inline constexpr const char* kRasterPipelineNames[kRasterPipelines] = {"depth_only", "gbuffer"};

/// Fixed-function rasterization through one pipeline: triangles (set-up, clipping, binning) and covered pixels
/// (coverage, depth test and write, the targets' writes) per second; the shaders' own operations are counted with the
/// ALU classes. Target bytes: the render targets cleared and copied out, per second.
// vertexRunSeconds: one run of the vertex routine the device's post-transform vertex cache starts on a miss
// (VertexCacheDesc; 0 where the cache is not simulated and vertex work is in the triangle rate).
// outsideTriangleSeconds: a triangle whose vertices all lie outside one clip plane (emu RasterStats trianglesOutside),
// which a driver rejects before set-up and binning: its vertices' shading and the clip test (calibrate: the
// triangle-bound mesh moved out of the view; lavapipe 2026-12: ~0 against ~130 ns a triangle set up).
// drawSeconds: a draw beyond the pass's first in the same submission (calibrate: 16 empty draws against 1), where the
// submission itself is one dispatchSeconds.
// spanningTriangleSeconds: what a set-up triangle whose extent holds a pixel-centre row (emu RasterStats
// trianglesSpanning) costs beyond one that holds none, which a rasterizer drops after set-up without binning or
// walking it (calibrate: the triangle-bound sphere into targets where its triangles span rows, against the same sphere
// into 32^2 ones, where most do not; lavapipe 2026-12: the bunny's shadow maps cost ~0.22 us a triangle against
// calibrate's ~0.07 us from the 32^2 run alone).
// partialBlockSeconds: a 4x4 pixel block a triangle covers only partly (emu RasterStats partialBlocks), beyond its
// pixels: llvmpipe tests the triangle's edges per pixel of such a stamp before shading it, and shades a full one as is
// (calibrate: a fourth run, the sphere into 2048^2 targets, ~16 pixels and ~6 partial stamps a triangle; session 37:
// the bunny's shadow maps, 6-93 pixels a triangle, had cost ~2x what calibrate's one-pixel triangles and fully covered
// planes predicted). GPUs: 0 (in the pixel rate).
struct RasterRates {
  double trianglesPerSecond = 0.0, fragmentsPerSecond = 0.0, targetBytesPerSecond = 0.0;
  double vertexRunSeconds = 0.0;
  double outsideTriangleSeconds = 0.0, drawSeconds = 0.0;
  double spanningTriangleSeconds = 0.0;
  double partialBlockSeconds = 0.0;
};

/// A driver's post-transform vertex cache, as the model simulates it over each draw's index stream
/// (model/vertex_cache.h): `entries` direct-mapped slots (index mod entries), cleared every `batchTriangles` triangles
/// (the batch a worker takes), and a miss running the vertex routine on `runLanes` consecutive index-stream entries
/// at once (all written to the cache). entries 0: not simulated (every vertex once; its work in the triangle rate).
/// SwiftShader 147 (its source: Device/VertexProcessor.hpp, a direct-mapped VertexCache of 64; Device/Renderer.cpp,
/// batches of 128 primitives; Pipeline/VertexRoutine.cpp, a miss shades a SIMD width of 4 consecutive batch entries).
struct VertexCacheDesc {
  uint32_t entries = 0, batchTriangles = 0, runLanes = 1;
};

struct DeviceDesc {
  std::string device;      // the --device name: lavapipe, swiftshader, h100, h200
  std::string name;        // the Vulkan device name it was measured on, or the product
  bool verified = false;   // measured (calibrate) rather than taken from public figures
  std::string provenance;  // how the numbers were obtained (machine, command, sources)
  int lanes = 0;           // SIMD lanes per core (GPU: FP32 lanes per SM)
  int cores = 0;           // host cores the driver uses (GPU: SMs)
  double clockGHz = 0.0;   // 0 when not known (software devices run at the host's clock)
  std::array<double, kOpClasses> opsPerSecond{};         // scalar operations per second, whole device
  std::array<double, kTexFilters> lookupsPerSecond{};    // RGBA32F lookups per second, by kind (TexFilter)
  int cacheLineBytes = 0;
  double cacheBytes = 0.0;      // the last level shared by all cores (CPU L2/L3 per machine, GPU L2)
  double bandwidthBytesPerSecond = 0.0;  // read + write of a large buffer
  // A storage-buffer element re-read from a table the caches hold (a material record, the SH lighting, env's lights,
  // read by every invocation: PassCounts::bytesReread). Software devices: calibrate's kind 25 (lavapipe loads each
  // lane's component on its own: ~1.4x the copy rate's price of a byte, session 39). GPUs: the SMs' L1 load
  // bandwidth (128 bytes a clock an SM), overlapped with the other units like the rest of memory.
  double rereadBytesPerSecond = 0.0;
  // A texture line the cache simulation misses (model/op_count.h TexCache), beyond a lookup that hits: calibrate's
  // nearest lookups on a texture 8x the host's last-level cache against a cache-resident one (GPUs: a line at the
  // memory bandwidth).
  double textureMissSeconds = 0.0;
  // A texture line of a stream (misses next to a recent miss, TexCache's tex_stream_miss), which a prefetcher fetches
  // ahead: calibrate's row-order texelFetch on the large texture against the cache-resident one (GPUs: a line at the
  // memory bandwidth, like a scattered one).
  double textureStreamSeconds = 0.0;
  double dispatchSeconds = 0.0;          // an empty compute dispatch, submit to completion
  // A pipeline's first dispatch beyond a warm one (lavapipe compiles its machine code then, and the code runs cold), as
  // a line in the module's SPIR-V size: firstDispatchSeconds at zero words plus compileSecondsPerWord per word.
  // calibrate: the fastest first dispatch of 9 new pipelines of calibrate_group.comp (0.4K words) and of the
  // straight-line calibrate_compile.comp, each less the warm dispatch. Charged per pipeline a pass creates (the
  // technique inputs: PassCounts::pipelines and pipelineWords). GPUs compile when the pipeline is created: 0.
  double firstDispatchSeconds = 0.0;
  double compileSecondsPerWord = 0.0;
  // Per compute workgroup (64 invocations) beyond the work itself: calibrate's same fadd work in 4096 workgroups against
  // 64 (SwiftShader sets up each workgroup's invocations as coroutines: ~15 us; lavapipe ~0.1-0.5 us).
  double workgroupSeconds = 0.0;
  // What a larger module costs per operation: a compute pass whose module has W SPIR-V words (PassCounts::moduleWords)
  // runs its ALU time x the slowdown at W, read off measured points (codeWords[i], codeSlowdown[i]): 1 at or below the
  // first (the size calibrate's rates were read at), linear in log2(W) between two points, the last point's beyond it.
  // The device's machine code for a large module no longer fits the host's caches: probes (docs/RESULTS.md sessions 42,
  // 43) ran the same exact division 1.2-2.1x slower on SwiftShader in a module of the MIS pass's size (219K words)
  // than in calibrate's 16K-word one, and 10-15% faster on lavapipe. calibrate measures such points (its division
  // kernel written out 1x, 4x and 16x, calibrate_exmath.comp FIXED_UNROLL) and reports them without writing them: with
  // them the validation over-predicted the largest shading modules (docs/RESULTS.md session 44), so every shipped file
  // has none and the term is off. GPUs: no points (their instruction caches are unmeasured here).
  std::vector<double> codeWords, codeSlowdown;
  // What a value a loop carries from one iteration to the next costs beyond the first loopStateValues (model/
  // spirv_loops.h): loopStateSeconds per extra value per invocation and iteration, device-wide like the rates (a pass
  // runs its invocations on every core). A software device's compiler keeps so many values in the host's registers;
  // the rest are spilled and reloaded each iteration. Software devices: calibrate's carried-state kernels, 128
  // multiply-adds an iteration into 8 and into 64 accumulators (calibrate_carried.comp): the baseline is the 8-value
  // kernel's carried values, the price per value the difference of the two per iteration over the difference of their
  // carried values. GPUs: 0 (hundreds of registers a thread; the public figures hold no spill cost).
  double loopStateValues = 0.0, loopStateSeconds = 0.0;
  // Per raster pipeline (calibrate: generated geometry through the shadow pass's and the G-buffer pass's pipelines).
  std::array<RasterRates, kRasterPipelines> raster{};
  VertexCacheDesc vertexCache{};
  // How the units' times combine: false (software devices: the same cores run arithmetic, texture filtering and
  // memory traffic one after another, so the times add), true (GPUs: separate units overlap, the slowest bounds).
  bool unitsOverlap = false;
  // The core model of software devices (opcount::Scheduler): seconds from an operation's operands to its result on one
  // core (dependent-chain microkernels), and how many counted 8-lane operations one core keeps in flight (the window
  // microkernel). GPUs hide latency across warps: there the model stays throughput-bound and these are not used.
  std::array<double, kOpClasses> latencySeconds{};
  double windowOps = 0.0;
  // Whether the device runs every block of a structured `if` under the lane mask, leaving only loops at once when no
  // lane is active (lavapipe, SwiftShader: their shader compilers never branch around a block), or skips a block no
  // lane of a vector takes (GPUs). Software devices: calibrate's branch kernels measure it.
  bool executesEveryBlock = false;
  // Whether the shader compiler removes a block behind a specialization constant that is false (lavapipe, GPUs) or
  // runs it like any other block, under the constant as a mask (SwiftShader, inside loops): the scene's absent BRDF
  // kinds (kSceneBrdfKinds) then cost their straight-line code. Software devices: calibrate's spec-branch kernel.
  bool foldsSpecConstants = true;
  // Whether the shader compiler computes an expression once where sibling blocks (which a device that runs every block
  // turns into one straight line) repeat it within one loop iteration; the counted run then counts such an operation
  // once (opcount::valueNumbering; loop invariants still count every iteration). Software devices: calibrate's
  // shared-block kernels (lavapipe measured 94-101%: false). false: every operation the shared source writes counts.
  bool valueNumbering = false;
};

/// Parses a description; throws std::runtime_error naming `path` and the key for a missing or unknown key,
/// a wrong type or a non-positive rate.
DeviceDesc parseDeviceDesc(const std::string& json, const std::string& path);
DeviceDesc loadDeviceDesc(const std::string& path);
std::string deviceDescJson(const DeviceDesc& d);
/// Writes atomically (a temporary name, renamed when complete).
void saveDeviceDesc(const DeviceDesc& d, const std::string& path);

}  // namespace shadetwin::model
