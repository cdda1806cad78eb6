// The performance model's arithmetic (issue 19): counted vector ticks become scalar operations, each class and
// filter is divided by its rate, software devices add the terms and GPUs overlap them, the largest term is the bound.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <string>

#include "model/device_desc.h"
#include "model/model.h"

namespace {
using namespace shadetwin::model;

DeviceDesc device(bool overlap) {
  DeviceDesc d;
  d.opsPerSecond.fill(1e9);
  d.opsPerSecond[kIAlu] = 2e9;
  d.lookupsPerSecond = {4e8, 2e8, 1e8, 8e8, 1.6e9};
  d.bandwidthBytesPerSecond = 1e10;
  d.rereadBytesPerSecond = 5e9;
  d.dispatchSeconds = 1e-4;
  d.raster[kDepthOnly] = {1e7, 1e9, 1e10};
  d.raster[kGbufferRaster] = {5e6, 1e8, 2e9};
  d.unitsOverlap = overlap;
  return d;
}

TEST(Model, TicksBecomeLaneOperationsAndMaskLogicIsIntegerAlu) {
  PassCounts c;
  std::array<uint64_t, opcount::kKinds> t{};
  t[opcount::kFAdd] = 10, t[opcount::kMaskOp] = 3, t[opcount::kIAlu] = 2, t[opcount::kTexBilinear] = 16;
  addTicks(c, t, 8);  // 8-lane vectors; texture kinds are per lane already
  const auto ops = scalarOps(c);
  EXPECT_EQ(ops[kFAdd], 80.0);
  EXPECT_EQ(ops[kIAlu], 40.0);
  EXPECT_EQ(ops[kFMul], 0.0);
  EXPECT_EQ(c.ops[opcount::kTexBilinear], 16.0);
  addTicks(c, t, 1);  // one-lane runs (vertex and fragment stages) add their ticks as they are
  EXPECT_EQ(scalarOps(c)[kFAdd], 90.0);
}

TEST(Model, ShiftsAreCostedAtTheirOwnRate) {
  PassCounts c;
  std::array<uint64_t, opcount::kKinds> t{};
  t[opcount::kShift] = 5, t[opcount::kIAlu] = 1;
  addTicks(c, t, 8);
  EXPECT_EQ(scalarOps(c)[kShift], 40.0);
  EXPECT_EQ(scalarOps(c)[kIAlu], 8.0);
  DeviceDesc d = device(false);
  d.opsPerSecond[kShift] = 1e8;  // SwiftShader-like: a shift 20x an add
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 40.0 / 1e8 + 8.0 / 2e9);
  d.opsPerSecond[kShift] = d.opsPerSecond[kIAlu];  // lavapipe and the GPUs: the add rate
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 48.0 / 2e9);
}

TEST(Model, VertexRunsCostTheirPipelinesRunTime) {
  PassCounts c;
  c.triangles = 1000, c.fragments = 0, c.vertexRuns = 600, c.rasterPipeline = kGbufferRaster;
  DeviceDesc d = device(false);
  const double without = predict(c, d).rasterSeconds;
  EXPECT_DOUBLE_EQ(without, 1000.0 / 5e6);  // vertex_run_seconds 0: the runs cost nothing of their own
  d.raster[kGbufferRaster].vertexRunSeconds = 4e-8;
  EXPECT_DOUBLE_EQ(predict(c, d).rasterSeconds, without + 600 * 4e-8);
  d.raster[kDepthOnly].vertexRunSeconds = 1.0;  // another pipeline's cost does not apply
  EXPECT_DOUBLE_EQ(predict(c, d).rasterSeconds, without + 600 * 4e-8);
}

TEST(Model, OutsideTrianglesAndFurtherDrawsCostTheirPipelinesRates) {
  PassCounts c;
  c.triangles = 1000, c.outsideTriangles = 400, c.dispatches = 5, c.rasterPipeline = kGbufferRaster;
  DeviceDesc d = device(false);
  d.raster[kGbufferRaster].outsideTriangleSeconds = 1e-9;
  d.raster[kGbufferRaster].drawSeconds = 2e-5;
  const Prediction p = predict(c, d);
  EXPECT_DOUBLE_EQ(p.rasterSeconds, 600.0 / 5e6 + 400 * 1e-9);
  EXPECT_DOUBLE_EQ(p.launchSeconds, 1e-4 + 4 * 2e-5);  // one submission, four draws beyond the first
  // The old charges (an outside triangle at the set-up rate, a draw at a dispatch) give the old prediction.
  d.raster[kGbufferRaster].outsideTriangleSeconds = 1.0 / 5e6, d.raster[kGbufferRaster].drawSeconds = d.dispatchSeconds;
  EXPECT_DOUBLE_EQ(predict(c, d).rasterSeconds, 1000.0 / 5e6);
  EXPECT_DOUBLE_EQ(predict(c, d).launchSeconds, 5 * 1e-4);
  c.triangles = 0, c.outsideTriangles = 0, c.fragments = 0;  // compute: every dispatch a submission, no draw cost
  EXPECT_DOUBLE_EQ(predict(c, device(false)).launchSeconds, 5 * 1e-4 + 1 * 0.0);
}

// A set-up triangle whose extent holds a pixel-centre row costs its pipeline's spanning_triangle_seconds on top of the
// set-up rate (a rasterizer bins and walks it; one that spans no row it drops after set-up); an outside triangle is
// never a spanning one, and a count above the set-up triangles is capped at them.
TEST(Model, TrianglesSpanningARowCostTheirPipelinesExtra) {
  PassCounts c;
  c.triangles = 1000, c.outsideTriangles = 100, c.spanningTriangles = 700, c.rasterPipeline = kDepthOnly;
  DeviceDesc d = device(false);
  d.raster[kDepthOnly].outsideTriangleSeconds = 1e-9;
  const double without = predict(c, d).rasterSeconds;
  EXPECT_DOUBLE_EQ(without, 900.0 / d.raster[kDepthOnly].trianglesPerSecond + 100 * 1e-9);
  d.raster[kDepthOnly].spanningTriangleSeconds = 7e-8;
  EXPECT_DOUBLE_EQ(predict(c, d).rasterSeconds, without + 700 * 7e-8);
  c.spanningTriangles = 5000;  // more than the 900 set up: capped
  EXPECT_DOUBLE_EQ(predict(c, d).rasterSeconds, without + 900 * 7e-8);
  d.raster[kGbufferRaster].spanningTriangleSeconds = 1.0;  // another pipeline's cost does not apply
  EXPECT_DOUBLE_EQ(predict(c, d).rasterSeconds, without + 900 * 7e-8);
}

TEST(Model, SoftwareDevicesAddTheTermsGpusOverlapThem) {
  PassCounts c;
  c.dispatches = 1;
  c.ops[opcount::kFMul] = 1e6;               // 1 ms at 1e9/s
  c.ops[opcount::kIAlu] = 2e6;               // 1 ms at 2e9/s
  c.ops[opcount::kTexTrilinear] = 300000;    // 3 ms at 1e8/s
  c.ops[opcount::kTexNearest] = 400000;      // 1 ms at 4e8/s
  c.ops[opcount::kTexUniform] = 800000;      // 1 ms at 8e8/s (texelFetchUniform, per lane)
  c.ops[opcount::kTexFetch] = 1600000;       // 1 ms at 1.6e9/s (texelFetch, per-lane coordinates)
  c.bytesRead = 10000000, c.bytesWritten = 5000000;  // 1.5 ms at 1e10 B/s
  const Prediction s = predict(c, device(false));
  {  // re-read buffer bytes (table rows, a MIP level's 3x3 footprints) cost their bytes at the re-read rate, not the
     // copy rate: a software device adds them to the other terms, a GPU's L1 serves them beside its memory traffic
    PassCounts r = c;
    r.bytesReread = 20000000;  // 4 ms at 5e9 B/s (2 ms at the copy rate)
    EXPECT_DOUBLE_EQ(predict(r, device(false)).memorySeconds, 1.5e-3 + 4e-3);
    EXPECT_DOUBLE_EQ(predict(r, device(true)).memorySeconds, predict(c, device(true)).memorySeconds + 4e-3);
    DeviceDesc fast = device(false);
    fast.rereadBytesPerSecond = 2e10;
    EXPECT_DOUBLE_EQ(predict(r, fast).memorySeconds, 1.5e-3 + 1e-3);
  }
  {  // texture lines the cache simulation missed cost the device's miss time each, in the texture term
    PassCounts m = c;
    m.ops[opcount::kTexMiss] = 20000;
    DeviceDesc d = device(false);
    d.textureMissSeconds = 1e-7;  // 2 ms
    EXPECT_DOUBLE_EQ(predict(m, d).textureSeconds, 6e-3 + 2e-3);
    EXPECT_DOUBLE_EQ(predict(m, d).memorySeconds, 1.5e-3);
    m.ops[opcount::kTexStreamMiss] = 5000;  // a prefetched stream's lines cost the stream time instead
    d.textureStreamSeconds = 1e-8;
    EXPECT_DOUBLE_EQ(predict(m, d).textureSeconds, 6e-3 + 1.5e-3 + 5e-5);
    EXPECT_DOUBLE_EQ(predict(m, d).memorySeconds, 1.5e-3);
  }
  EXPECT_DOUBLE_EQ(s.aluSeconds, 2e-3);
  EXPECT_DOUBLE_EQ(s.textureSeconds, 6e-3);
  EXPECT_DOUBLE_EQ(s.memorySeconds, 1.5e-3);
  EXPECT_DOUBLE_EQ(s.seconds, 2e-3 + 6e-3 + 1.5e-3 + 1e-4);
  EXPECT_EQ(s.bound, "texture");
  const Prediction g = predict(c, device(true));
  EXPECT_DOUBLE_EQ(g.seconds, 6e-3 + 1e-4);
  EXPECT_EQ(g.bound, "texture");
  PassCounts idle;  // nothing to do: the launch bounds it
  EXPECT_EQ(predict(idle, device(true)).bound, "launch");
  idle.dispatches = 12;  // a launch per dispatch (a MIP chain's levels, a draw per object)
  EXPECT_DOUBLE_EQ(predict(idle, device(false)).launchSeconds, 12e-4);
  DeviceDesc jit = device(false);  // a pipeline's first dispatch, and a cost per workgroup of 64 invocations
  jit.firstDispatchSeconds = 5e-4, jit.workgroupSeconds = 1e-6;
  PassCounts input;
  input.dispatches = 1, input.pipelines = 1, input.invocations = 6400;
  EXPECT_DOUBLE_EQ(predict(input, jit).launchSeconds, 1e-4 + 5e-4 + 100 * 1e-6);
  input.workgroups = 7;  // counted explicitly (a MIP chain: one set per level)
  EXPECT_DOUBLE_EQ(predict(input, jit).launchSeconds, 1e-4 + 5e-4 + 7 * 1e-6);
  jit.compileSecondsPerWord = 5e-8;  // a first dispatch compiles the module: a cost that grows with its size
  input.pipelineWords = 6000;
  EXPECT_DOUBLE_EQ(predict(input, jit).launchSeconds, 1e-4 + 5e-4 + 6000 * 5e-8 + 7 * 1e-6);
  input.pipelines = 0, input.pipelineWords = 0;  // a warm pipeline (the persistent passes): neither
  EXPECT_DOUBLE_EQ(predict(input, jit).launchSeconds, 1e-4 + 7 * 1e-6);
  PassCounts raster;  // triangles, covered pixels and render-target bytes at the raster rates
  raster.dispatches = 1, raster.triangles = 20000, raster.fragments = 3000000, raster.attachmentBytes = 50000000;
  raster.invocations = 640000;  // vertex and fragment lanes: no compute workgroups
  DeviceDesc rd = device(false);
  rd.workgroupSeconds = 1.0;
  const Prediction r = predict(raster, rd);
  EXPECT_DOUBLE_EQ(r.rasterSeconds, 2e-3 + 3e-3 + 5e-3);
  EXPECT_EQ(r.bound, "raster");
  raster.rasterPipeline = kGbufferRaster;  // the G-buffer's pipeline at its own rates
  EXPECT_DOUBLE_EQ(predict(raster, rd).rasterSeconds, 4e-3 + 3e-2 + 2.5e-2);
  // Vertex fetch and fragment writes: inside a software device's raster rates (calibrate's draws do both), a GPU's
  // memory traffic.
  raster.rasterBytes = 20000000;  // 2 ms at 1e10 B/s
  EXPECT_DOUBLE_EQ(predict(raster, rd).memorySeconds, 0.0);
  EXPECT_DOUBLE_EQ(predict(raster, device(true)).memorySeconds, 2e-3);
}

// A workgroup runs on one core (GPU: one SM): a compute pass of fewer workgroups than cores has only that many busy,
// so its ALU, texture and (software device) buffer terms take cores / workgroups as long as the rates of all cores
// say; the launch and raster terms do not change (the SH reduction: one workgroup of 16 invocations).
TEST(Model, AComputePassOfFewerWorkgroupsThanCoresRunsOnThatMany) {
  PassCounts c;
  c.dispatches = 1, c.invocations = 16, c.workgroups = 1;
  c.ops[opcount::kFMul] = 1e6;             // 1 ms at 1e9/s on every core
  c.ops[opcount::kTexNearest] = 400000;    // 1 ms at 4e8/s
  c.bytesRead = 10000000;                  // 1 ms at 1e10 B/s
  DeviceDesc d = device(false);
  d.cores = 4;
  const Prediction one = predict(c, d);
  EXPECT_DOUBLE_EQ(one.aluSeconds, 4e-3);
  EXPECT_DOUBLE_EQ(one.textureSeconds, 4e-3);
  EXPECT_DOUBLE_EQ(one.memorySeconds, 4e-3);
  EXPECT_DOUBLE_EQ(one.launchSeconds, 1e-4);
  c.workgroups = 2;
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 2e-3);
  c.workgroups = 0, c.invocations = 64 * 4;  // one per 64 invocations when not counted: every core busy
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 1e-3);
  c.workgroups = 1000;
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 1e-3);
  c.workgroups = 1, c.scheduledSeconds = 8e-3;  // one core's scheduled time, on the one busy core
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 8e-3);
  c.scheduledSeconds = 0;
  DeviceDesc g = device(true);  // a GPU: one SM's ALU and texture units; the memory system is not the SM's
  g.cores = 4;
  EXPECT_DOUBLE_EQ(predict(c, g).aluSeconds, 4e-3);
  EXPECT_DOUBLE_EQ(predict(c, g).memorySeconds, 1e-3);
  PassCounts raster;  // raster passes bin over every core
  raster.dispatches = 1, raster.triangles = 20000, raster.ops[opcount::kFMul] = 1e6;
  EXPECT_DOUBLE_EQ(predict(raster, d).aluSeconds, 1e-3);
}

TEST(Model, IntegerComparesAndSelectsAreCostedAtTheirOwnRates) {
  PassCounts c;
  std::array<uint64_t, opcount::kKinds> t{};
  t[opcount::kICmp] = 3, t[opcount::kISel] = 2, t[opcount::kSel] = 1, t[opcount::kFCmp] = 1;
  addTicks(c, t, 8);
  EXPECT_EQ(scalarOps(c)[kICmp], 24.0);
  EXPECT_EQ(scalarOps(c)[kISelect], 16.0);
  EXPECT_EQ(scalarOps(c)[kSelect], 8.0);
  EXPECT_EQ(scalarOps(c)[kIAlu], 0.0);
  DeviceDesc d = device(false);
  d.opsPerSecond[kICmp] = 1e8, d.opsPerSecond[kISelect] = 5e7;  // SwiftShader-like: far below the float pair
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 24.0 / 1e8 + 16.0 / 5e7 + 8.0 / d.opsPerSecond[kSelect] + 8.0 / d.opsPerSecond[kFCmp]);
}

}  // namespace

namespace {
// Private array accesses (the dialect's arrayGet / arraySet) are their own classes, each at its own rate: lavapipe pays
// a gather or a masked scatter per access, where an fadd beside them is cheap.
TEST(Model, PrivateArrayAccessesAreCostedAtTheirOwnRates) {
  PassCounts c;
  std::array<uint64_t, opcount::kKinds> t{};
  t[opcount::kPrivRead] = 6, t[opcount::kPrivWrite] = 3, t[opcount::kFAdd] = 2;
  addTicks(c, t, 8);
  EXPECT_EQ(scalarOps(c)[kPrivateRead], 48.0);
  EXPECT_EQ(scalarOps(c)[kPrivateWrite], 24.0);
  EXPECT_EQ(scalarOps(c)[kIAlu], 0.0);
  DeviceDesc d = device(false);
  d.opsPerSecond[kPrivateRead] = 2e8, d.opsPerSecond[kPrivateWrite] = 1e8;
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 48.0 / 2e8 + 24.0 / 1e8 + 16.0 / 1e9);
  d.opsPerSecond[kPrivateRead] = d.opsPerSecond[kPrivateWrite] = 1e9;  // accesses at the fadd rate
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 88.0 / 1e9);
}
}  // namespace

namespace {
// The exact-math layer's division and square root are one operation each of their own class (model/device_desc.h
// ex_div, ex_sqrt), at the rate calibrate measured on the routine itself.
TEST(Model, ExactDivisionsAndSquareRootsAreCostedAtTheirOwnRates) {
  PassCounts c;
  std::array<uint64_t, opcount::kKinds> t{};
  t[opcount::kExDiv] = 4, t[opcount::kExSqrt] = 2, t[opcount::kFMul] = 1;
  addTicks(c, t, 8);
  EXPECT_EQ(scalarOps(c)[kExDiv], 32.0);
  EXPECT_EQ(scalarOps(c)[kExSqrt], 16.0);
  EXPECT_EQ(scalarOps(c)[kIAlu], 0.0);
  DeviceDesc d = device(false);
  d.opsPerSecond[kExDiv] = 1e7, d.opsPerSecond[kExSqrt] = 2e7;
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 32.0 / 1e7 + 16.0 / 2e7 + 8.0 / 1e9);
}

// A module larger than calibrate's first point runs its ALU time slower by the measured slowdown at its size (linear in
// log2 of the size between two points, the last point's beyond them); the other terms do not change, and a module at or
// below the first point (or a device without points) costs its rates.
TEST(Model, ALargerModuleRunsItsAluTimeAtTheMeasuredSlowdown) {
  PassCounts c;
  std::array<uint64_t, opcount::kKinds> t{};
  t[opcount::kExDiv] = 4, t[opcount::kFMul] = 1, t[opcount::kTexBilinear] = 3;
  addTicks(c, t, 8);
  DeviceDesc d = device(false);
  c.moduleWords = 1u << 20;
  const Prediction base = predict(c, d);  // no points: the term is off
  EXPECT_EQ(base.codeFactor, 1.0);
  d.codeWords = {16000, 64000, 256000}, d.codeSlowdown = {1.0, 1.25, 2.0};
  for (uint64_t words : {0ull, 1000ull, 16000ull}) {
    c.moduleWords = words;
    EXPECT_EQ(predict(c, d).aluSeconds, base.aluSeconds) << words;
    EXPECT_EQ(codeSizeFactor(d, words), 1.0);
  }
  for (const auto& [words, factor] : {std::pair{32000ull, 1.125}, {64000ull, 1.25}, {128000ull, 1.625}, {256000ull, 2.0},
                                      {1ull << 22, 2.0}, {24000ull, 1.0 + 0.25 * std::log2(1.5) / 2.0}}) {
    c.moduleWords = words;
    const Prediction p = predict(c, d);
    EXPECT_DOUBLE_EQ(p.codeFactor, factor) << words;
    EXPECT_DOUBLE_EQ(p.aluSeconds, base.aluSeconds * factor) << words;
    EXPECT_EQ(p.textureSeconds, base.textureSeconds) << words;
    EXPECT_DOUBLE_EQ(p.seconds - p.aluSeconds, base.seconds - base.aluSeconds) << words;
  }
}

// The loop-state term: per loop depth, the invocation-iterations (8-lane ticks x 8) times the values its module's loops
// of that depth carry beyond the device's baseline, at the device's price per value; added to the ALU term after the
// code-size factor, shared over the busy cores like the rest of it, nothing at or below the baseline or on a device
// whose price is 0 (the GPUs).
TEST(Model, ALoopCarryingMoreValuesThanTheBaselinePaysEachIterationForTheRest) {
  PassCounts c;
  std::array<uint64_t, opcount::kKinds> t{};
  t[opcount::kFMul] = 100, t[opcount::kLoop1] = 10, t[opcount::kLoop2] = 40, t[opcount::kLoop3] = 7;
  addTicks(c, t, 8);
  EXPECT_EQ(c.ops[opcount::kLoop1], 80.0);  // iterations are per lane, like operations
  EXPECT_EQ(scalarOps(c)[kFMul], 800.0);    // and are no operation of any class
  c.workgroups = 4;
  DeviceDesc d = device(false);
  d.cores = 2;
  const Prediction off = predict(c, d);
  EXPECT_EQ(off.loopStateSeconds, 0.0);
  c.loopCarried = {49, 12, 30};
  EXPECT_EQ(predict(c, d).aluSeconds, off.aluSeconds);  // price 0: nothing, whatever the loops carry
  d.loopStateValues = 10, d.loopStateSeconds = 2e-10;
  const double expected = (80.0 * 39 + 320.0 * 2 + 56.0 * 20) * 2e-10;
  EXPECT_DOUBLE_EQ(loopStateSeconds(c, d), expected);
  const Prediction p = predict(c, d);
  EXPECT_DOUBLE_EQ(p.loopStateSeconds, expected);
  EXPECT_DOUBLE_EQ(p.aluSeconds, off.aluSeconds + expected);
  EXPECT_DOUBLE_EQ(p.seconds, off.seconds + expected);
  c.workgroups = 1;  // one workgroup runs on one of the two cores: its iterations at one core's share
  EXPECT_DOUBLE_EQ(predict(c, d).loopStateSeconds, 2.0 * expected);
  c.workgroups = 4;
  d.codeWords = {1000, 2000}, d.codeSlowdown = {1.0, 2.0}, c.moduleWords = 2000;  // the factor is not applied to it
  EXPECT_DOUBLE_EQ(predict(c, d).aluSeconds, 2.0 * off.aluSeconds + expected);
  c.loopCarried = {10, 9, 0};  // at or below the baseline: nothing
  EXPECT_EQ(loopStateSeconds(c, d), 0.0);
}

// The portable routines are straight-line: one vector's operations by kind, the same for any operands, and every kind
// an ALU kind (no texture, no private array, no nested exact operation).
TEST(Model, ExactMathMixIsTheRoutinesStraightLineOperations) {
  for (opcount::Kind k : {opcount::kExDiv, opcount::kExSqrt}) {
    const auto mix = exactMathMix(k);
    uint64_t alu = 0;
    for (int j = 0; j < opcount::kTexLookup; ++j) alu += mix[size_t(j)];
    for (int j = opcount::kTexLookup; j < opcount::kKinds; ++j) EXPECT_EQ(mix[size_t(j)], 0u) << opcount::kKindNames[j];
    EXPECT_EQ(mix[opcount::kExDiv] + mix[opcount::kExSqrt] + mix[opcount::kPrivRead] + mix[opcount::kPrivWrite], 0u);
    // exact_math.h's derivation block: 164 counted operations per division, 101 per square root.
    EXPECT_EQ(alu, k == opcount::kExDiv ? 164u : 101u);
    EXPECT_GT(mix[opcount::kIMul], 0u);
    EXPECT_GT(mix[opcount::kFMul], 0u);
  }
  EXPECT_THROW(exactMathMix(opcount::kFAdd), std::invalid_argument);
}

// A GPU's ex_div and ex_sqrt (devices/h100.json, h200.json: public figures) are the routine's operation mix at the
// file's per-class rates, and their latencies the mix's operations one after another (not used: a GPU's ALU term is
// throughput-bound). Recomputed here so the files cannot drift from the routine or the rates.
TEST(Model, GpuExactMathRatesAreTheRoutinesMixAtThePublicRates) {
  for (const char* gpu : {"h100", "h200"}) {
    const DeviceDesc d = loadDeviceDesc(std::string(SHADETWIN_SOURCE_DIR) + "/devices/" + gpu + ".json");
    for (opcount::Kind k : {opcount::kExDiv, opcount::kExSqrt}) {
      PassCounts c;
      addTicks(c, exactMathMix(k), 1);  // lane operations per lane's division
      const auto ops = scalarOps(c);
      double seconds = 0, latency = 0;
      for (int j = 0; j < kOpClasses; ++j)
        if (ops[size_t(j)] > 0) seconds += ops[size_t(j)] / d.opsPerSecond[size_t(j)], latency += ops[size_t(j)] * d.latencySeconds[size_t(j)];
      const OpClass cls = k == opcount::kExDiv ? kExDiv : kExSqrt;
      EXPECT_NEAR(d.opsPerSecond[cls] * seconds, 1.0, 1e-9) << gpu << " " << kOpClassNames[cls] << ": " << std::setprecision(17) << 1.0 / seconds;
      EXPECT_NEAR(d.latencySeconds[cls] / latency, 1.0, 1e-9) << gpu << " " << kOpClassNames[cls] << ": " << std::setprecision(17) << latency;
    }
  }
}

// An operation that holds several window entries (an exact division) leaves room for fewer others in flight: two
// independent ones each of half the window overlap, of the whole window they run one after the other.
TEST(Model, AnOperationOfManyWindowEntriesLimitsTheOverlap) {
  auto twoIndependent = [](uint32_t slots) {
    opcount::Scheduler s;
    s.latency[opcount::kExDiv] = 10.0, s.interval[opcount::kExDiv] = 1.0, s.slots[opcount::kExDiv] = slots, s.window = 8;
    s.start();
    s.issue(opcount::kExDiv, 0.0);
    s.issue(opcount::kExDiv, 0.0);
    return s.lastRetire;
  };
  EXPECT_DOUBLE_EQ(twoIndependent(1), 11.0);  // the second dispatches one interval later
  EXPECT_DOUBLE_EQ(twoIndependent(4), 11.0);  // both fit the window
  EXPECT_DOUBLE_EQ(twoIndependent(8), 20.0);  // the second waits for the first to retire
  EXPECT_DOUBLE_EQ(twoIndependent(100), 20.0);  // clamped to the window
}
}  // namespace

namespace {
// Partly covered 4x4 blocks (emu RasterStats::partialBlocks) cost their pipeline's partial_block_seconds on top of the
// pixels: the same pixels in more partial blocks (smaller triangles) cost more; another pipeline's rate does not apply.
TEST(Model, PartlyCoveredBlocksCostTheirPipelinesRate) {
  PassCounts c;
  c.triangles = 100, c.fragments = 1600, c.blocks = 100, c.partialBlocks = 0, c.rasterPipeline = kGbufferRaster;
  DeviceDesc d = device(false);
  d.raster[kGbufferRaster].partialBlockSeconds = 5e-8;
  const double full = predict(c, d).rasterSeconds;
  EXPECT_DOUBLE_EQ(full, 100.0 / 5e6 + 1600.0 / 1e8);
  c.blocks = 400, c.partialBlocks = 400;  // the same pixels as 400 partial blocks
  EXPECT_DOUBLE_EQ(predict(c, d).rasterSeconds, full + 400 * 5e-8);
  d.raster[kDepthOnly].partialBlockSeconds = 1.0;
  EXPECT_DOUBLE_EQ(predict(c, d).rasterSeconds, full + 400 * 5e-8);
  d.unitsOverlap = true;  // a GPU's raster term has it too where its file gives one (h100/h200: 0)
  EXPECT_DOUBLE_EQ(predict(c, d).rasterSeconds, full + 400 * 5e-8);
}
}  // namespace
