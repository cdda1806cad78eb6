// shadetwin command line.
#include <CLI/CLI.hpp>

#include <tbb/global_control.h>

#include <exception>
#include <map>
#include <memory>
#include <string>
#include <iostream>

#include "util/compare.h"
#include "reference/reference.h"
#include "cli/bench.h"
#include "cli/calibrate.h"
#include "cli/campaign.h"
#include "cli/model_cmd.h"
#include "cli/sweep.h"
#include "cli/render.h"
#include "scene/scene.h"
#include "cli/verify/verify.h"
#include "util/memory.h"
#include "util/output_file.h"
#include "vk/context.h"

namespace {

// The scene options, defined once for every command that renders (issue 22): which of them a command takes.
enum SceneOptions : unsigned { kSize = 1, kTechnique = 2, kSamples = 4, kBlocks = 8, kVisMaps = 16, kGlintViews = 32, kAllScene = 63 };

// The scene file, as the first positional argument or --scene (both spellings on every command), and the overrides
// of shadetwin::SceneOverrides that `which` names.
void addSceneOptions(CLI::App* cmd, std::string& scene, shadetwin::SceneOverrides& o, unsigned which, bool required = false) {
  auto* file = cmd->add_option("scene,--scene", scene,
                               "scene file (JSON, see README" + (scene.empty() ? std::string(")") : "; default " + scene + ")"));
  if (required) file->required();
  if (which & kTechnique)
    cmd->add_option("--technique", o.technique,
                    "shading technique (default: the scene's): fis, unfiltered, stochastic, env, mirror, kdtree-mis, alias-mis, "
                    "inversion-mis, glints, glints-gxd");
  if (which & kSamples)
    cmd->add_option("--samples", o.samples,
                    "samples of the technique (default: the scene's): fis samples per pixel, env lights, MIS sample pairs, "
                    "G x D sample pairs")
        ->check(CLI::Range(1, 1 << 20));
  if (which & kSize) {
    cmd->add_option("--width", o.width, "override the scene's image width")->check(CLI::Range(1, 16384));
    cmd->add_option("--height", o.height, "override the scene's image height")->check(CLI::Range(1, 16384));
  }
  if (which & kBlocks)
    cmd->add_option("--blocks", o.blocks, "kd-tree / alias blocks of the *-mis samplers (default: the scene's mis.blocks)")
        ->check(CLI::Range(1, 1 << 20));
  if (which & kVisMaps)
    cmd->add_option("--vis-maps", o.visMaps, "shadow maps K of the scene's visibility block (default: the scene's)")
        ->check(CLI::Range(1, 1024));
  if (which & kGlintViews)
    cmd->add_option("--glint-views", o.glintViews,
                    "RINGSxSECTORS: view grid of a glints scene's lighting table (default: the scene's glints.view_rings x "
                    "view_sectors, 65x128)");
}

}  // namespace

int main(int argc, char** argv) {
  shadetwin::installInterruptCleanup();  // SIGINT / SIGTERM remove every output's temporary (util/output_file.h)
  shadetwin::keepHeapAcrossFrames();     // before any driver allocates: freed frame memory stays in the heap
  CLI::App app{"shadetwin: a bit-exact CPU twin of a Vulkan image-based-lighting renderer"};
  app.require_subcommand(1);
  unsigned threads = 0;
  app.add_option("--threads", threads, "worker threads of the emulator and the host passes, before the command (shadetwin --threads 1 "
                 "render ...; default: every core); outputs do not depend on it")->check(CLI::Range(1, 4096));
  shadetwin::VerifyOptions vo;
  auto* verify = app.add_subcommand("verify", "differential tests: emulator and C++ builds against a Vulkan device");
  verify->require_subcommand(1);
  for (const char* what : {"math", "texture", "mips", "raster", "shadow", "shade", "frame", "paraboloid", "sh", "visibility", "ndf", "glint-lighting"}) {
    auto* sub = verify->add_subcommand(what, std::string("verify ") + what);
    sub->add_option("--count", vo.count, "inputs per function / lookups per configuration")->check(CLI::Range(1, 100000000));
    sub->add_option("--seed", vo.seed, "random seed");
    sub->add_option("--device", vo.device, "Vulkan device (substring of its name; default lavapipe)");
    sub->add_flag("--validate", vo.validate, "enable Vulkan validation layers; any error fails the run");
    sub->add_option("--junit", vo.junit, "write the result as JUnit XML: a test case per stage and channel group, failures with "
                                         "the identical count and the first difference");
    sub->add_option("--json", vo.json, "write the same result as JSON (tests/verify_report.schema.json)");
    sub->add_option("--heatmap", vo.heatmap, "when an image stage differs, write a PNG of where: a panel per differing "
                                             "channel, the ULP distance on a log scale, with a legend");
    const std::string w = what;
    if (w == "raster" || w == "shadow" || w == "shade" || w == "frame" || w == "paraboloid" || w == "sh" ||
        w == "visibility" || w == "glint-lighting") {
      // The suites that render a frame's passes take every scene option; the technique-input suites the file.
      const bool frame = w == "raster" || w == "shade" || w == "frame" || w == "visibility";
      addSceneOptions(sub, vo.scene, vo, !frame ? 0u : w == "visibility" ? kAllScene & ~kVisMaps : kAllScene, true);  // visibility: --maps K
    }
    if (w == "shadow") {
      sub->add_option("--directions", vo.directions, "number of shadow-map directions")->check(CLI::Range(1, 4096));
      sub->add_option("--size", vo.shadowSize, "shadow-map resolution")->check(CLI::Range(1, 8192));
    }
    if (w == "visibility") {
      sub->add_option("--maps", vo.directions, "K visibility directions (shadow maps), from the environment's luminance")
          ->check(CLI::Range(1, 4096));
      sub->add_option("--size", vo.shadowSize, "shadow-map resolution")->check(CLI::Range(1, 8192));
      sub->add_flag("--fit-v", vo.visibilityV, "fit V alone instead of V max(0, n.w)");
    }
    if (w == "glint-lighting") {
      sub->add_option("--order", vo.glintOrder, "SH degree")->check(CLI::Range(0, 64));
      sub->add_option("--rings", vo.glintRings, "view directions in theta")->check(CLI::Range(2, 1024));
      sub->add_option("--sectors", vo.glintSectors, "view directions in phi")->check(CLI::Range(1, 2048));
      sub->add_option("--level", vo.glintLevel, "environment MIP level summed (default: the first at most 64 texels wide)");
    }
    if (w == "ndf") {
      sub->add_option("--map", vo.mapKind, "normal map kind: flat, flakes, scratches, brushed, bumps");
      sub->add_option("--size", vo.mapSize, "normal map size")->check(CLI::Range(1, 4096));
    }
    if (w == "paraboloid")
      sub->add_option("--face-size", vo.faceSize, "face size S of the 2S x S atlas")->check(CLI::Range(4, 8192));
    if (std::string(what) == "texture") {
      sub->add_flag("--finite", vo.finiteTexels, "only finite normal texel values (no inf, NaN or denormals)");
      sub->add_option("--filters", vo.filters,
                      "comma-separated cases: texelFetch,nearest,nearest-miplin,bilinear,trilinear,magN-minL");
      sub->add_option("--stages", vo.stages, "comma-separated shader stages: compute,fragment (default both)");
      sub->add_flag("--implicit-lod", vo.implicitLod,
                    "fragment-stage texture() with implicit LOD on smooth coordinate fields (instead of textureLod)");
      sub->add_option("--image", vo.image, "sample this image (EXR/HDR/PNG) with its MIP chain instead of random textures");
      sub->add_option("--seeds", vo.seeds, "run N consecutive seeds from --seed (rows only for configurations that differ)")
          ->check(CLI::Range(1, 100000));
    }
    sub->add_option("--profile-set", vo.profileSet,
                    "KEY=VALUE: run the emulator with an alternative value of a device-profile field (e.g. "
                    "maskedFragmentLanes=skip; math: denormCompute / denormFragment), to measure what the profile's "
                    "choice is worth; repeatable");
  }
  app.add_subcommand("devices", "list Vulkan devices");
  shadetwin::RenderOptions ro;
  auto* render = app.add_subcommand("render", "render a scene (default scenes/bunny.json) to an EXR and a tone-mapped PNG");
  addSceneOptions(render, ro.scene, ro, kAllScene);
  render->add_option("--device", ro.device, "emu (the emulated GPU) or vulkan")->check(CLI::IsMember({"emu", "vulkan"}));
  render->add_option("--out", ro.out, "output EXR (the PNG is written next to it); default <scene>.exr");
  render->add_option("--profile", ro.profile, "device profile the emulator follows (lavapipe, nvidia)");
  render->add_option("--frames", ro.frames, "frames to render (OUT_0000.exr, ...); technique inputs are rebuilt only when the environment changes")
      ->check(CLI::Range(1, 100000));
  render->add_option("--env-rotate", ro.envRotate, "degrees the environment turns about +y per frame (whole texel columns)");
  render->add_option("--object-rotate", ro.objectRotate,
                     "degrees the first object turns about its vertical axis per frame: the G-buffer, shadow maps and "
                     "visibility fit are redone every frame");
  shadetwin::ReferenceCommandOptions refo;
  auto* ref = app.add_subcommand("reference", "ground truth: Embree + TBB Monte Carlo with MIS, written as EXR + PNG");
  addSceneOptions(ref, refo.scene, refo, kSize);  // the ground truth has no technique
  ref->add_option("--spp", refo.render.spp, "samples per pixel (each: one environment and one BRDF direction)")->check(CLI::Range(1, 1 << 24));
  ref->add_option("--seed", refo.render.seed, "random seed");
  ref->add_flag("--visibility", refo.render.visibility, "trace an occlusion ray for every direction");
  ref->add_option("--out", refo.out, "output EXR; default <scene>_ref.exr");
  std::string cmpA, cmpB;
  auto* cmp = app.add_subcommand("compare", "error metrics of image A against reference B: RMSE, relMSE, PSNR");
  cmp->add_option("A", cmpA, "image")->required();
  cmp->add_option("B", cmpB, "reference image")->required();
  shadetwin::BenchOptions bo;
  shadetwin::CalibrateOptions co;
  auto* calibrate = app.add_subcommand("calibrate", "measure a software Vulkan device with microkernels and write its "
                                                    "description for the performance model (devices/D.json)");
  calibrate->add_option("--device", co.device, "Vulkan device (substring of its name: lavapipe, swiftshader)");
  calibrate->add_option("--out", co.out, "output file (default devices/<device>.json)");
  calibrate->add_flag("--quick", co.quick, "short runs (rough rates; for tests)");
  calibrate->add_option("--rounds", co.rounds, "rounds of every microkernel; each value is the best of its rounds "
                                               "(default 3, --quick 1)")
      ->check(CLI::Range(1, 20));
  shadetwin::ModelOptions mo;
  auto* modelCmd = app.add_subcommand("model", "predict a pass's time on a device from its counted work and the device's "
                                               "description, every pass of a frame; --validate against the software devices");
  addSceneOptions(modelCmd, mo.scene, mo, kAllScene);
  modelCmd->add_option("--device", mo.device, "device description devices/<D>.json: lavapipe, swiftshader, h100, h200");
  modelCmd->add_option("--devices", mo.devicesDir, "folder of the device descriptions (default devices)");
  modelCmd->add_option("--repeat", mo.repeat, "timed runs of each measured pass (the fastest is compared)")->check(CLI::Range(1, 100));
  modelCmd->add_flag("--validate", mo.validate, "every shipped scene x technique on every present software device, ending with "
                                                "the mean and worst absolute error");
  modelCmd->add_option("--scenes", mo.scenes, "--validate: scene files (default: every scenes/*.json)");
  modelCmd->add_option("--devices-list", mo.devices, "--validate: software devices (default: lavapipe swiftshader)");
  modelCmd->add_option("--csv", mo.csv, "--validate: write one row per pass to this CSV");
  modelCmd->add_option("--rounds", mo.rounds, "--validate: measure every pass this many times, each round after all the others "
                                              "(the fastest over the rounds is compared; default 1)")
      ->check(CLI::Range(1, 20));
  modelCmd->add_flag("--calibrate", mo.calibrate, "--validate: calibrate each device (devices/<D>.json) just before measuring it");
  modelCmd->add_option("--calibrate-rounds", mo.calibrateRounds, "--calibrate: calibrate's --rounds (default 3)")
      ->check(CLI::Range(1, 20));
  modelCmd->add_flag("--calibrate-quick", mo.calibrateQuick, "--calibrate: calibrate's --quick (short runs; tests the path, not for shipped files)");
  auto* bench = app.add_subcommand("bench", "time passes on the emulator and on a Vulkan device in one run; last line: ratio emu/vulkan");
  addSceneOptions(bench, bo.scene, bo, kAllScene);
  bench->add_option("--passes", bo.passes, "comma-separated passes: gbuffer, shadow, shade");
  bench->add_option("--repeat", bo.repeat, "timed runs per pass (median reported)")->check(CLI::Range(1, 1000));
  bench->add_option("--directions", bo.directions, "shadow-map directions")->check(CLI::Range(1, 4096));
  bench->add_option("--shadow-size", bo.shadowSize, "shadow-map resolution")->check(CLI::Range(1, 8192));
  bench->add_option("--device", bo.device, "Vulkan device (substring of its name; default lavapipe)");
  shadetwin::SweepOptions so;
  auto* sweep = app.add_subcommand("sweep", "speed against error: techniques x sample counts vs the reference; CSV + plots");
  addSceneOptions(sweep, so.scene, so, kSize | kBlocks);  // --technique, --samples, --vis-maps: the sweep's lists below
  sweep->add_option("--technique", so.techniques, "comma-separated: fis, unfiltered, stochastic, env, kdtree-mis, alias-mis, inversion-mis");
  sweep->add_option("--maps", so.maps, "with a *-mis technique: environment maps (assets/hdri/NAME.exr) of the sampler study");
  sweep->add_option("--samples", so.samples, "comma-separated sample counts (glints: the G x D baseline's sample pairs)");
  sweep->add_option("--glint-orders", so.glintOrders, "with --technique glints: comma-separated SH degrees (<= 64)");
  sweep->add_option("--glint-bins", so.glintBins,
                    "with --technique glints: comma-separated histogram binnings RINGSxSECTORS@THETAMAX (degrees), e.g. 9x32@40,18x32@40");
  sweep->add_option("--glint-views", so.glintViews,
                    "with --technique glints: comma-separated lighting-table view grids RINGSxSECTORS, e.g. 9x16,33x64,65x128");
  sweep->add_option("--glint-lobes", so.glintLobes,
                    "with --technique glints: comma-separated rotated-lobe table grids RINGSxSECTORS (instead of the recurrences), e.g. 17x32,65x128");
  sweep->add_option("--glint-frames", so.glintFrames,
                    "with --technique glints: temporal stability over N frames of an orbiting camera (0: none)")
      ->check(CLI::Range(0, 1000));
  sweep->add_option("--glint-orbit", so.glintOrbit, "with --glint-frames: degrees the camera orbits the target per frame");
  sweep->add_option("--reference", so.reference, "reference EXR (default: render it)");
  sweep->add_option("--reference-spp", so.referenceSpp, "samples per pixel of the rendered reference")->check(CLI::Range(1, 1 << 20));
  sweep->add_option("--out", so.out, "output folder");
  sweep->add_option("--device", so.device, "Vulkan device (substring of its name; default lavapipe)");
  sweep->add_flag("!--no-vulkan", so.vulkan, "emulator only");
  sweep->add_option("--vis-maps", so.visMapCounts,
                    "comma-separated SH visibility map counts K for fis (0: none), against a reference with visibility");
  sweep->add_option("--vis-rays", so.visRays,
                    "rays per pixel of the Embree order-4 SH visibility fit (the SH-order error; 0: skip)")->check(CLI::Range(0, 1 << 20));
  shadetwin::CampaignOptions cpo;
  auto* campaign = app.add_subcommand("campaign", "many scenes x techniques x devices x seeds as independent jobs (campaign files: "
                                                  "README); locally or as a Slurm job array");
  campaign->require_subcommand(1);
  for (const char* what : {"plan", "run", "submit", "gather"}) {
    static const std::map<std::string, std::string> help = {
        {"plan", "expand the campaign into jobs with stable ids; print each job's command, or why the scene refuses it"},
        {"run", "run the jobs here (in parallel; finished jobs with the same command are kept), one result file each"},
        {"submit", "write a Slurm job array (sbatch --array) whose tasks are `campaign run --task`, and submit it"},
        {"gather", "merge the jobs' results into <out>/campaign.csv and the self-contained <out>/report.html"}};
    auto* sub = campaign->add_subcommand(what, help.at(what));
    sub->add_option("file", cpo.file, "campaign file (JSON)")->required();
    const std::string w = what;
    if (w != "plan") sub->add_option("--out", cpo.out, "results folder (default results/<campaign name>; shared by the nodes for submit)");
    if (w == "run" || w == "submit") {
      sub->add_option("--retries", cpo.retries, "extra attempts of a job that fails (a difference is a result: not retried)")
          ->check(CLI::Range(0, 100));
      sub->add_option("--timeout", cpo.timeout, "seconds a job may take; past it the job is killed and counted failed (0: none)")
          ->check(CLI::Range(0.0, 1e7));
      sub->add_option("--chunk", cpo.chunk, "jobs per Slurm array task (run: with --task)")->check(CLI::Range(1, 1000000));
    }
    if (w == "run") {
      sub->add_option("--jobs", cpo.jobs, "jobs at once (default: every core; each job gets --threads cores/jobs)")->check(CLI::Range(1, 4096));
      sub->add_flag("--force", cpo.force, "run finished jobs again too");
      sub->add_option("--task", cpo.task, "run only Slurm array task I: the jobs I*chunk ... I*chunk+chunk-1 (what submit's tasks run)")
          ->check(CLI::Range(0, 100000000));
    }
    if (w == "submit") {
      sub->add_option("--cpus-per-task", cpo.cpusPerTask, "CPUs of each array task (its jobs at once)")->check(CLI::Range(1, 4096));
      sub->add_flag("--wait", cpo.wait, "sbatch --wait: return when every array task has finished (non-zero if one failed)");
      sub->add_option("--sbatch-arg", cpo.sbatchArgs, "an extra sbatch argument, e.g. --sbatch-arg=--partition=render; repeatable")
          ->allow_extra_args(false);
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  std::unique_ptr<tbb::global_control> threadLimit;
  if (threads) threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  try {
    if (app.got_subcommand("devices")) {
      for (auto& n : shadetwin::vk::Context::listDevices()) std::cout << n << "\n";
      return 0;
    }
    if (app.got_subcommand("render")) return shadetwin::renderCommand(ro, std::cout);
    if (app.got_subcommand("campaign")) {
      for (const char* what : {"plan", "run", "submit", "gather"})
        if (campaign->got_subcommand(what)) cpo.action = what;
      return shadetwin::campaignCommand(cpo, std::cout);
    }
    if (app.got_subcommand("sweep")) return shadetwin::sweepCommand(so, std::cout);
    if (app.got_subcommand("calibrate")) return shadetwin::calibrateCommand(co, std::cout);
    if (app.got_subcommand("model")) return shadetwin::modelCommand(mo, std::cout);
    if (app.got_subcommand("bench")) {
      if (!bo.technique.empty() && bench->get_option("--passes")->count() == 0) bo.passes = "gbuffer,shade";
      return shadetwin::benchCommand(bo, std::cout);
    }
    if (app.got_subcommand("reference")) return shadetwin::referenceCommand(refo, std::cout);
    if (app.got_subcommand("compare")) return shadetwin::compareCommand(cmpA, cmpB, std::cout);
    for (const std::string* report : {&vo.junit, &vo.json, &vo.heatmap})  // before the work: a missing folder costs nothing
      if (!report->empty()) shadetwin::checkWritable(*report);
    if (verify->got_subcommand("math")) return shadetwin::verifyMath(vo, std::cout);
    if (verify->got_subcommand("texture")) return shadetwin::verifyTexture(vo, std::cout);
    if (verify->got_subcommand("raster")) return shadetwin::verifyRaster(vo, std::cout);
    if (verify->got_subcommand("shadow")) return shadetwin::verifyShadow(vo, std::cout);
    if (verify->got_subcommand("shade")) return shadetwin::verifyShade(vo, std::cout);
    if (verify->got_subcommand("frame")) return shadetwin::verifyFrame(vo, std::cout);
    if (verify->got_subcommand("mips")) return shadetwin::verifyMips(vo, std::cout);
    if (verify->got_subcommand("paraboloid")) return shadetwin::verifyParaboloid(vo, std::cout);
    if (verify->got_subcommand("sh")) return shadetwin::verifyShIrradiance(vo, std::cout);
    if (verify->got_subcommand("visibility")) return shadetwin::verifyVisibility(vo, std::cout);
    if (verify->got_subcommand("ndf")) return shadetwin::verifyNdf(vo, std::cout);
    if (verify->got_subcommand("glint-lighting")) return shadetwin::verifyGlintLighting(vo, std::cout);
  } catch (const std::exception& e) {
    std::cerr << "shadetwin: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
