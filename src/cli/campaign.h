// `shadetwin campaign`: many scenes x techniques x devices x seeds as independent jobs (issue 21, items 1, 2 and 5).
//
// A campaign file (JSON, strict keys like scene files) names the axes and the jobs:
//
//   {"name": "example", "description": "...",
//    "axes": {"scenes": ["../scenes/*.json"], "techniques": ["fis", "env"], "samples": [4], "sizes": ["48x32"],
//             "devices": ["lavapipe", "swiftshader"], "seeds": [1, 2]},
//    "jobs": [{"kind": "verify", "suite": "frame"}, {"kind": "verify", "suite": "math", "args": ["--count", "10000"]},
//             {"kind": "render", "techniques": ["fis"]}, {"kind": "sweep", "args": ["--no-vulkan"]},
//             {"kind": "model", "devices": ["lavapipe"]}],
//    "devices_folder": "../devices"}
//
// Paths (scenes, devices_folder: the model's device descriptions, default ../devices) are relative to the campaign file;
// a scene entry may be a pattern in its file name (*.json).
//
// Every job takes the axes that apply to its kind (kindAxes below); a job may replace an axis with a key of its own.
// plan expands the product into jobs with stable ids (kind[-suite].scene.technique.sN.WxH.device.seedK, the parts that
// apply), checks each against its scene (setTechnique's refusals: glints on a scene without glint materials, mirror on
// material maps) and marks the refused ones skipped with the scene's reason. run executes each job as a child process of
// this binary (the ordinary command line, so nothing is re-implemented), writes <out>/jobs/<id>/result.json and the
// job's own outputs beside it, and skips jobs already finished with the same command (resumable). submit hands the
// same run to Slurm as a job array (sbatch --array; each task runs `campaign run --task I --chunk N`). gather merges
// every result into <out>/campaign.csv and a self-contained <out>/report.html.
#pragma once
#include <cstdint>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadetwin {

/// A campaign file's problem: the message names the file, the key path and what was expected.
struct CampaignError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CampaignJob {
  std::string id;
  std::string groupId;      // the id without the device: a row of the report's matrix
  std::string kind, suite;  // kind: verify (suite: math, frame, ...), render, sweep, model
  std::string scene;        // absolute scene file ("" for suites without a scene)
  std::string sceneName;    // its stem, as in the id and the CSV
  std::string technique;    // "" : the scene's own
  std::vector<std::string> techniques;  // sweep: its technique list ("" : sweep's default)
  std::vector<uint32_t> sampleList;     // sweep: its sample counts
  uint32_t samples = 0, width = 0, height = 0;  // 0: the scene's
  std::string device;       // verify/sweep: Vulkan device; model: device description; "" : none
  int64_t seed = -1;        // -1: none
  std::string devicesDir;         // model: the device descriptions' folder (absolute)
  std::vector<std::string> args;  // the job's extra arguments, after the generated ones
  std::string skipReason;         // non-empty: refused at plan time, never run
  /// The command line after the binary and its --threads: the generated arguments with the outputs in `dir`.
  std::vector<std::string> command(const std::string& dir) const;
};

struct Campaign {
  std::string file;  // the campaign file as given
  std::string name, description;
  std::vector<CampaignJob> jobs;  // in plan order (the Slurm array index is the position)
};

/// Reads, expands and checks a campaign file; throws CampaignError naming the file and the key.
Campaign loadCampaign(const std::string& path);

struct CampaignOptions {
  std::string action;  // plan, run, submit, gather
  std::string file;
  std::string out;     // results folder (default results/<name>)
  unsigned jobs = 0;   // run: jobs at once (default: every core)
  unsigned retries = 0;     // run: extra attempts of a failed job
  double timeout = 0;       // run: seconds a job may take (0: no limit); past it the job is killed and failed
  bool force = false;       // run: re-run finished jobs too
  int task = -1;            // run: only the Slurm array task `task` (jobs task*chunk ... task*chunk + chunk - 1)
  unsigned chunk = 1;       // run --task / submit: jobs per array task
  unsigned cpusPerTask = 1; // submit: --cpus-per-task of each array task (its --jobs)
  bool wait = false;        // submit: sbatch --wait (returns when the array has finished; non-zero if a task failed)
  std::vector<std::string> sbatchArgs;  // submit: extra sbatch arguments (--partition=..., --time=...)
};

int campaignCommand(const CampaignOptions& opts, std::ostream& log);

// The pieces, for tests.
/// Where `opts` puts the results of `c`.
std::string campaignOutDir(const CampaignOptions& opts, const Campaign& c);
/// Runs the jobs [first, last) of `c` (see CampaignOptions); returns 0 when none failed or differs.
int runCampaign(const CampaignOptions& opts, const Campaign& c, size_t first, size_t last, std::ostream& log);
/// Writes <out>/campaign.csv and <out>/report.html from the jobs' result files; returns 0 when every job passed or
/// was skipped by the plan.
int gatherCampaign(const CampaignOptions& opts, const Campaign& c, std::ostream& log);
/// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string csvField(const std::string& s);

}  // namespace shadetwin
