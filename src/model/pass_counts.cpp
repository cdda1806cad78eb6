#include "model/pass_counts.h"

#include <algorithm>
#include <cstring>
#include <memory>

#include <tbb/task_arena.h>

#include "inputs/glints.h"
#include "inputs/material.h"
#include "inputs/paraboloid.h"
#include "inputs/sh_irradiance.h"
#include "inputs/shade_inputs.h"
#include "inputs/visibility.h"
#include "model/spirv_loops.h"
#include "model/vertex_cache.h"
#include "passes/gbuffer.h"
#include "passes/mips.h"
#include "passes/shadow.h"
#include "passes/visibility.h"
// The technique inputs' modules, for their sizes only (a first dispatch compiles the module: PassCounts::pipelineWords).
#include "glint_lighting_comp.inc"
#include "mip_downsample.inc"
#include "paraboloid_resample_comp.inc"
#include "sh_project_comp.inc"
#include "sh_reduce_comp.inc"
#include "visibility_filter_comp.inc"
#include "visibility_fit_comp.inc"

namespace shadetwin::model {
namespace {

struct Checker {
  FrameCounts& f;
  void operator()(const std::string& pass, const float* a, const float* b, size_t n) {
    size_t same = 0;
    for (size_t i = 0; i < n; ++i) same += std::memcmp(a + i, b + i, 4) == 0;
    f.compared += n, f.identical += same;
    if (same != n) f.differing.push_back(pass);
  }
  void operator()(const std::string& pass, const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) {
      f.differing.push_back(pass + " (size)");
      return;
    }
    (*this)(pass, a.data(), b.data(), a.size());
  }
};

static_assert(opcount::kLoop3 - opcount::kLoop1 + 1 == kLoopDepths,
              "the loop-state term's depths: the counting kinds and carriedByDepth agree");

// A pipeline the pass creates and first dispatches (the Vulkan build makes the technique inputs' pipelines when it builds
// them): its first dispatch compiles `module`, so the pass counts the module's size with it.
template <size_t N>
void addPipeline(PassCounts& c, const uint32_t (&module)[N]) {
  ++c.pipelines;
  c.pipelineWords += N;
  runsModule(c, module);
}

void addRaster(PassCounts& c, const emu::RasterStats& r) {
  c.triangles += r.trianglesIn;
  c.fragments += r.fragments;
  c.blocks += r.blocks;
  c.spanningTriangles += r.trianglesSpanning;
  c.partialBlocks += r.partialBlocks;
  c.outsideTriangles += r.trianglesOutside;
  c.culledTriangles += r.trianglesCulled;
  c.helperLanes += 4 * r.quads - r.fragments;
}

// A MIP chain's downsampling dispatches (one per level below 0), counted into `c`; returns the chain.
std::vector<std::vector<float>> countMips(PassCounts& c, const std::vector<float>& level0, uint32_t w, uint32_t h, uint32_t layers,
                                          const CoreModel& core) {
  std::vector<std::vector<float>> chain;
  addTicks(c, countedTicks([&] { chain = mipChainCpu(level0, w, h, layers, 0); }, core, &c.scheduledSeconds), 8);
  addPipeline(c, kSpv_mip_downsample);  // the Vulkan build makes the chain's pipeline per chain (passes/mips.cpp)
  for (size_t l = 1; l < chain.size(); ++l) {
    const uint32_t dw = std::max(1u, w >> l), dh = std::max(1u, h >> l);
    c.invocations += uint64_t((dw + 7) / 8 * 8) * dh * layers;
    c.workgroups += (uint64_t(dw) * dh * layers + 63) / 64;  // passes/mips.cpp: one invocation per texel of the level
    c.bytesWritten += chain[l].size() * 4;
    c.bytesRead += chain[l - 1].size() * 4;
    // mip_downsample.glsl reads a 3x3 footprint (clamped at the edges) per texel of the level: 9 vec4 loads each.
    const uint64_t loads = uint64_t(dw) * dh * layers * 9 * 16;
    c.bytesReread += loads > chain[l - 1].size() * 4 ? loads - chain[l - 1].size() * 4 : 0;
    ++c.dispatches;
  }
  return chain;
}

// Adds another run of the same pass (the material maps' MIP chain after the atlas's).
void accumulate(PassCounts& into, const PassCounts& c) {
  for (int k = 0; k < opcount::kKinds; ++k) into.ops[size_t(k)] += c.ops[size_t(k)];
  into.invocations += c.invocations, into.dispatches += c.dispatches, into.pipelines += c.pipelines, into.pipelineWords += c.pipelineWords;
  into.moduleWords = std::max(into.moduleWords, c.moduleWords);
  for (int d = 0; d < kLoopDepths; ++d) into.loopCarried[size_t(d)] = std::max(into.loopCarried[size_t(d)], c.loopCarried[size_t(d)]);
  into.workgroups += c.workgroups;
  into.bytesRead += c.bytesRead, into.bytesWritten += c.bytesWritten, into.bytesReread += c.bytesReread, into.rasterBytes += c.rasterBytes, into.scheduledSeconds += c.scheduledSeconds;
  into.blocks += c.blocks, into.partialBlocks += c.partialBlocks;
}

}  // namespace

std::array<uint64_t, opcount::kKinds> countedTicks(const std::function<void()>& f, const CoreModel& core, double* scheduledSeconds) {
  std::array<uint64_t, opcount::kKinds> t{};
  tbb::task_arena one(1);  // the counters are per thread: one thread does all the work
  one.execute([&] {
    opcount::counts = {};
    opcount::executeEveryBlock = core.executeEveryBlock;
    opcount::foldsSpecConstants = core.foldsSpecConstants;
    opcount::valueNumbering = core.valueNumbering && core.invocationsMarked;
    if (opcount::valueNumbering) opcount::vnTable.reset();
    opcount::texCache.configure(core.cacheLineBytes, core.cacheBytes);  // cold at the start of every counted pass
    opcount::Scheduler& s = opcount::sched;
    s.on = core.on;
    if (core.on) {
      s.latency = core.latency, s.interval = core.interval, s.slots = core.slots, s.window = std::max(1u, core.window);
      s.start();
    }
    f();
    s.on = false;
    opcount::executeEveryBlock = false;
    opcount::foldsSpecConstants = true;
    opcount::valueNumbering = false;
    if (scheduledSeconds) *scheduledSeconds = core.on ? s.lastRetire : 0.0;
    for (int k = 0; k < opcount::kKinds; ++k) t[size_t(k)] = opcount::counts[size_t(k)];
  });
  return t;
}

void runsModule(PassCounts& c, std::span<const uint32_t> module) {
  c.moduleWords = std::max<uint64_t>(c.moduleWords, module.size());
  const std::vector<uint32_t> carried = carriedByDepth(module);
  for (int d = 0; d < kLoopDepths; ++d) c.loopCarried[size_t(d)] = std::max(c.loopCarried[size_t(d)], carried[size_t(d)]);
}

void addTicks(PassCounts& c, const std::array<uint64_t, opcount::kKinds>& ticks, double lanes) {
  for (int k = 0; k < opcount::kKinds; ++k)
    c.ops[size_t(k)] += double(ticks[size_t(k)]) * (k < opcount::kTexLookup || k >= opcount::kLoop1 ? lanes : 1.0);
}

FrameCounts countFrame(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev, const CoreModel& core) {
  FrameCounts f;
  Checker check{f};
  // G-buffer: every object one draw; vertex invocations and fragment lanes (helpers included) at one lane per tick.
  GbufferStats gs;
  PassCounts gb;
  gb.pass = "gbuffer";
  gb.rasterPipeline = kGbufferRaster;
  GBuffer counted;
  addTicks(gb, countedTicks([&] { counted = gbufferCounted(scene, dev, &gs); }), 1);
  const GBuffer g = gbufferEmu(scene, dev);
  check("gbuffer", counted.texels, g.texels);
  check("gbuffer depth", counted.depth, g.depth);
  addRaster(gb, gs.raster);
  for (const Object& o : scene.objects) {
    const Mesh& m = scene.meshes[o.mesh];
    gb.invocations += m.positions.size();
    gb.vertexRuns += vertexCacheRuns(m.indices, core.vertexCache);
    gb.rasterBytes += m.positions.size() * sizeof(VertexGpu) + m.indices.size() * 4;
  }
  gb.invocations += 4 * gs.raster.quads;
  gb.dispatches = scene.objects.size();
  // Covered pixels write the attachments; the targets are cleared and copied out.
  gb.rasterBytes += gs.raster.fragments * (uint64_t(kGbufFloats) * 4 + 4);
  gb.attachmentBytes = uint64_t(scene.width) * scene.height * (uint64_t(kGbufFloats) * 4 + 4);
  f.passes.push_back(gb);

  // The technique's inputs, as shadeInputsEmu builds them (inputs/shade_inputs.cpp).
  const ShadeInputs in = shadeInputsEmu(scene, env, dev);
  if (in.atlas) {
    PassCounts pa;
    pa.pass = "paraboloid";
    addPipeline(pa, kSpv_paraboloid_resample_comp);
    std::vector<float> atlas;
    addTicks(pa, countedTicks([&] { atlas = paraboloidAtlasCounted(env, dev, scene.fisFaceSize); }, core, &pa.scheduledSeconds), 8);
    const size_t n = 2 * size_t(scene.fisFaceSize) * scene.fisFaceSize;
    check("paraboloid", atlas.data(), reinterpret_cast<const float*>(in.atlas->levels()[0].data()), 4 * n);
    pa.invocations = (n + 7) / 8 * 8, pa.dispatches = 1, pa.bytesWritten = 16 * n;
    f.passes.push_back(pa);
    PassCounts mp;
    mp.pass = "mips";
    const auto chain = countMips(mp, atlas, 2 * scene.fisFaceSize, scene.fisFaceSize, 1, core);
    for (size_t l = 1; l < chain.size(); ++l)
      check("mips", chain[l].data(), reinterpret_cast<const float*>(in.atlas->levels()[l].data()), chain[l].size());
    f.passes.push_back(mp);

    PassCounts pr, rd;
    pr.pass = "sh-project", rd.pass = "sh-reduce";
    addPipeline(pr, kSpv_sh_project_comp), addPipeline(rd, kSpv_sh_reduce_comp);
    std::array<uint64_t, opcount::kKinds> project{};
    ShIrradiance sh;
    double projectSeconds = 0;
    const auto all = countedTicks([&] {
      sh = shIrradianceCounted(env, dev, [&] {
        project = opcount::counts;
        projectSeconds = opcount::sched.on ? opcount::sched.lastRetire : 0.0;
        opcount::sched.on = false;  // the reduction is counted one lane at a time: not scheduled
      });
    }, core);
    pr.scheduledSeconds = projectSeconds;
    std::array<uint64_t, opcount::kKinds> reduce{};
    for (int k = 0; k < opcount::kKinds; ++k) reduce[size_t(k)] = all[size_t(k)] - project[size_t(k)];
    addTicks(pr, project, 8);
    addTicks(rd, reduce, 1);
    check("sh", sh.c.data(), in.sh.c.data(), sh.c.size());
    check("sh", sh.band3.data(), in.sh.band3.data(), sh.band3.size());
    pr.invocations = (env.height() + 7) / 8 * 8, pr.dispatches = 1, pr.bytesWritten = uint64_t(env.height()) * 256;
    // sh_reduce.comp's pairwise tree: rows - 1 merges per coefficient, each reading two vec4 and writing one in place,
    // then one read of the root and one vec4 of the result per coefficient. Distinct bytes read are the rows (16 vec4
    // each); the rest are re-reads of what the tree wrote.
    const uint64_t rows = env.height(), merges = rows ? rows - 1 : 0;
    rd.invocations = 16, rd.dispatches = 1, rd.workgroups = 1;  // local_size_x = 16: one workgroup, one core
    const uint64_t reads = (merges * 2 + 1) * 256;
    rd.bytesRead = rows * 256;
    rd.bytesReread = reads - std::min(reads, rd.bytesRead);
    rd.bytesWritten = (merges + 1) * 256;
    f.passes.push_back(pr);
    f.passes.push_back(rd);
  }
  if (in.glints) {
    PassCounts gl;
    gl.pass = "glint-lighting";
    addPipeline(gl, kSpv_glint_lighting_comp);
    GlintLightingTable t;
    addTicks(gl, countedTicks([&] { t = glintLightingCounted(env, dev, in.glints->lightingSpec); }, core, &gl.scheduledSeconds), 8);
    const GlintLightingTable e = glintLightingEmu(env, dev, in.glints->lightingSpec);
    check("glint-lighting", t.rgba, e.rgba);
    const uint32_t views = t.spec.rings * t.spec.sectors;
    const uint32_t eh = env.levelHeight(t.spec.level), rows = t.spec.bandRows ? t.spec.bandRows : eh;
    const uint32_t bands = (eh + rows - 1) / rows;
    gl.invocations = uint64_t((views + 7) / 8 * 8) * (t.spec.order + 1) * bands;
    gl.dispatches = bands, gl.bytesWritten = uint64_t(t.bytes()) * bands, gl.bytesRead = uint64_t(t.bytes()) * (bands - 1);
    f.passes.push_back(gl);
  }
  if (in.maps) {
    const MaterialMapImages m = loadMaterialMaps(scene);
    if (m.width > 1 || m.height > 1) {
      PassCounts mp;
      mp.pass = "mips";
      const auto chain = countMips(mp, m.texels, m.width, m.height, m.layers, core);
      for (size_t l = 1; l < chain.size(); ++l)
        check("mips", chain[l].data(), reinterpret_cast<const float*>(in.maps->levels()[l].data()), chain[l].size());
      auto atlasMips = std::find_if(f.passes.begin(), f.passes.end(), [](const PassCounts& p) { return p.pass == "mips"; });
      if (atlasMips != f.passes.end()) accumulate(*atlasMips, mp);
      else f.passes.push_back(mp);
    }
  }

  // Visibility: the K shadow maps, the fit, the filter (passes/visibility_emu.cpp's order).
  std::unique_ptr<VisibilityImage> vis;
  if (in.visibility) {
    const VisibilitySetup& v = *in.visibility;
    PassCounts sp;
    sp.pass = "shadow";
    ShadowStats ss;
    ShadowMaps sm;
    addTicks(sp, countedTicks([&] { sm = shadowCounted(scene, v.directions, v.settings.size, dev, &ss); }), 1);
    const ShadowMaps se = shadowEmu(scene, v.directions, v.settings.size, dev);
    for (size_t k = 0; k < sm.maps.size(); ++k) check("shadow", sm.maps[k], se.maps[k]);
    addRaster(sp, ss.raster);
    for (const Object& o : scene.objects) {
      const Mesh& m = scene.meshes[o.mesh];
      sp.invocations += m.positions.size() * v.directions.size();
      sp.vertexRuns += vertexCacheRuns(m.indices, core.vertexCache) * v.directions.size();
      sp.rasterBytes += (m.positions.size() * sizeof(VertexGpu) + m.indices.size() * 4) * v.directions.size();
    }
    sp.helperLanes = 0;  // depth only: no fragment shader, no quads run
    sp.dispatches = scene.objects.size() * v.directions.size();
    sp.rasterBytes += ss.raster.fragments * 4;  // depth writes; the maps are cleared and copied out
    sp.attachmentBytes = uint64_t(v.settings.size) * v.settings.size * 4 * v.directions.size();
    f.passes.push_back(sp);

    const emu::Texture maps = shadowMapArray(se);
    const uint64_t pixels = uint64_t(g.width) * g.height;
    PassCounts fp;
    fp.pass = "visibility-fit";
    runsModule(fp, kSpv_visibility_fit_comp);
    VisibilityImage fit;
    addTicks(fp, countedTicks([&] { fit = visibilityFitCounted(g, maps, v, dev); }, core, &fp.scheduledSeconds), 8);
    const VisibilityImage fitE = visibilityFitEmu(g, maps, v, dev);
    check("visibility-fit", fit.coeffs, fitE.coeffs);
    fp.invocations = (pixels + 7) / 8 * 8, fp.dispatches = 1, fp.bytesRead = pixels * 32, fp.bytesWritten = pixels * 64;
    f.passes.push_back(fp);
    vis = std::make_unique<VisibilityImage>(fitE);
    if (v.settings.filterRadius) {
      PassCounts fl;
      fl.pass = "visibility-filter";
      runsModule(fl, kSpv_visibility_filter_comp);
      VisibilityImage filt;
      addTicks(fl, countedTicks([&] { filt = visibilityFilterCounted(g, fitE, v, dev); }, core, &fl.scheduledSeconds), 8);
      const VisibilityImage filtE = visibilityFilterEmu(g, fitE, v, dev);
      check("visibility-filter", filt.coeffs, filtE.coeffs);
      fl.invocations = (pixels + 7) / 8 * 8, fl.dispatches = 1, fl.bytesWritten = pixels * 64;
      f.passes.push_back(fl);
      *vis = filtE;
    }
  }

  if (scene.technique == "glints-gxd") return f;  // its shading is the host's double-precision ground truth
  std::vector<float> image;
  PassCounts sc = countShadePass(scene, g, in, dev, vis.get(), &image, core);
  check("shade", image, shadeEmu(scene, g, in, dev, vis.get()));
  f.passes.push_back(sc);
  return f;
}

}  // namespace shadetwin::model
