// Running a campaign's jobs: locally as child processes of this binary, or as a Slurm job array (cli/campaign.h).
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>
#include <cerrno>
#include <cstring>

#include "cli/campaign.h"
#include "util/output_file.h"
#include "util/progress.h"

extern char** environ;

namespace shadetwin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string selfExe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("campaign: cannot find this program (/proc/self/exe): " + ec.message());
  return p.string();
}

struct ChildResult {
  int exitCode = -1;   // the exit status, or -1 when it did not exit
  int signal = 0;      // the signal that ended it
  bool timedOut = false;
  double seconds = 0;
};

// Runs argv (argv[0] a path) with stdout and stderr appended to `logPath`; kills it past `timeout` seconds (0: none).
ChildResult runChild(const std::vector<std::string>& argv, const std::string& logPath, double timeout) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, logPath.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  std::vector<char*> cargv;
  for (const auto& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int err = posix_spawn(&pid, cargv[0], &fa, nullptr, cargv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (err != 0) throw std::runtime_error("campaign: cannot start " + argv[0] + ": " + std::strerror(err));
  ChildResult r;
  int status = 0;
  bool killed = false;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  for (;;) {
    const pid_t w = waitpid(pid, &status, timeout > 0 ? WNOHANG : 0);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) throw std::runtime_error(std::string("campaign: waitpid: ") + std::strerror(errno));
    if (timeout > 0 && elapsed() > timeout) {
      if (!killed) kill(pid, SIGTERM), killed = true, r.timedOut = true;
      else if (elapsed() > timeout + 10) kill(pid, SIGKILL);
    }
    if (timeout > 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  r.seconds = elapsed();
  if (WIFEXITED(status)) r.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  return r;
}

std::string readText(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void writeJson(const fs::path& p, const json& j) {
  OutputFile f(p.string());
  f.stream() << j.dump(2) << "\n";
  f.commit();
}

json jobParams(const CampaignJob& job) {
  json j = {{"id", job.id},         {"kind", job.kind},       {"suite", job.suite},   {"scene", job.sceneName},
            {"technique", job.technique}, {"samples", job.samples}, {"width", job.width}, {"height", job.height},
            {"device", job.device}, {"seed", job.seed}};
  return j;
}

}  // namespace

std::string campaignOutDir(const CampaignOptions& opts, const Campaign& c) {
  return opts.out.empty() ? (fs::path("results") / c.name).string() : opts.out;
}

int runCampaign(const CampaignOptions& opts, const Campaign& c, size_t first, size_t last, std::ostream& log) {
  const fs::path out = fs::absolute(campaignOutDir(opts, c));
  std::error_code ec;
  fs::create_directories(out / "jobs", ec);
  if (ec) throw std::runtime_error(out.string() + ": cannot create the results folder: " + ec.message());
  const std::string exe = selfExe();
  // In a Slurm task the CPUs are the task's (--cpus-per-task), not the node's.
  unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (const char* slurmCpus = std::getenv("SLURM_CPUS_PER_TASK"); slurmCpus && std::atoi(slurmCpus) > 0) cores = unsigned(std::atoi(slurmCpus));
  const unsigned parallel = std::max(1u, std::min<unsigned>(opts.jobs ? opts.jobs : cores, unsigned(std::max<size_t>(1, last - first))));
  const unsigned threads = std::max(1u, cores / parallel);
  // What to do: the plan's refusals are written as skipped; finished jobs with the same command are kept.
  std::vector<size_t> todo;
  size_t cached = 0, cachedDiffers = 0, skipped = 0;
  for (size_t i = first; i < last; ++i) {
    const CampaignJob& job = c.jobs[i];
    const fs::path dir = out / "jobs" / job.id;
    fs::create_directories(dir, ec);
    if (ec) throw std::runtime_error(dir.string() + ": cannot create the job's folder: " + ec.message());
    if (!job.skipReason.empty()) {
      json r = jobParams(job);
      r["status"] = "skipped", r["skip_reason"] = job.skipReason, r["command"] = json::array(), r["attempts"] = 0, r["seconds"] = 0.0;
      r["exit_code"] = nullptr;
      writeJson(dir / "result.json", r);
      ++skipped;
      continue;
    }
    if (!opts.force && fs::exists(dir / "result.json")) {
      try {
        const json old = json::parse(readText(dir / "result.json"));
        const std::string st = old.value("status", "");
        if ((st == "passed" || st == "differs") && old.value("command", json()) == json(job.command(dir.string()))) {
          ++cached;
          cachedDiffers += st == "differs";
          continue;
        }
      } catch (const json::exception&) {  // a damaged result: run the job again
      }
    }
    todo.push_back(i);
  }
  log << "campaign " << c.name << ": " << (last - first) << " jobs: " << todo.size() << " to run, " << cached
      << " already finished, " << skipped << " skipped by the plan; " << parallel << " at once, --threads " << threads
      << " each; results in " << out.string() << "\n";
  std::atomic<size_t> next{0};
  std::mutex mu;
  size_t done = 0, passed = 0, differs = 0, failed = 0;
  std::vector<std::string> failures;
  ProgressBar bar(log, "campaign " + c.name);
  auto worker = [&] {
    for (;;) {
      const size_t k = next++;
      if (k >= todo.size()) return;
      const CampaignJob& job = c.jobs[todo[k]];
      const fs::path dir = out / "jobs" / job.id;
      const std::vector<std::string> cmd = job.command(dir.string());
      std::vector<std::string> argv = {exe, "--threads", std::to_string(threads)};
      argv.insert(argv.end(), cmd.begin(), cmd.end());
      for (const char* stale : {"report.json", "junit.xml", "heatmap.png", "result.json"}) fs::remove(dir / stale, ec);
      const fs::path logPath = dir / "stdout.txt";
      { std::ofstream truncate(logPath, std::ios::trunc); }
      ChildResult r;
      unsigned attempt = 0;
      std::string status;
      for (;;) {
        ++attempt;
        {
          std::ofstream l(logPath, std::ios::app);
          l << "$";
          for (const auto& a : argv) l << " " << a;
          l << "\n";
        }
        r = runChild(argv, logPath.string(), opts.timeout);
        // verify's exit status 1 is "a difference" (a result, not a failure); anything else non-zero failed.
        status = r.exitCode == 0 ? "passed" : (r.exitCode == 1 && job.kind == "verify") ? "differs" : "failed";
        if (status != "failed" || attempt > opts.retries) break;
      }
      json res = jobParams(job);
      res["status"] = status, res["command"] = cmd, res["attempts"] = attempt, res["seconds"] = r.seconds;
      res["exit_code"] = r.exitCode >= 0 ? json(r.exitCode) : json(nullptr);
      if (r.signal) res["signal"] = r.signal;
      if (r.timedOut) res["timed_out"] = true;
      if (fs::exists(dir / "report.json")) {
        try {
          const json rep = json::parse(readText(dir / "report.json"));
          res["identical"] = rep.at("identical"), res["total"] = rep.at("total");
          for (const json& cs : rep.at("cases"))
            if (!cs.at("first_difference").is_null()) {
              const json& d = cs.at("first_difference");
              std::string where = cs.at("name").get<std::string>();
              where += d.contains("x") ? " (" + std::to_string(d["x"].get<int64_t>()) + ", " + std::to_string(d["y"].get<int64_t>()) + ")"
                                       : " [" + std::to_string(d["index"].get<int64_t>()) + "]";
              res["first_difference"] = where;
              break;
            }
        } catch (const json::exception& e) {
          res["report_error"] = std::string("report.json: ") + e.what();
        }
      }
      writeJson(dir / "result.json", res);
      std::lock_guard<std::mutex> lock(mu);
      ++done;
      if (status == "passed") ++passed;
      if (status == "differs") ++differs;
      if (status == "failed") {
        ++failed;
        failures.push_back(job.id + ": " + (r.timedOut ? "timed out" : r.signal ? "signal " + std::to_string(r.signal)
                                                                      : "exit status " + std::to_string(r.exitCode)) +
                           " after " + std::to_string(attempt) + " attempt(s); see " + logPath.string());
      }
      if (status != "passed") log << "  " << job.id << ": " << status << "\n";
      bar.update(double(done) / double(todo.size()));
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < parallel && t < todo.size(); ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (!todo.empty()) bar.finish();
  for (const auto& f : failures) log << "failed: " << f << "\n";
  log << "campaign " << c.name << ": " << passed << " passed, " << differs << " differ, " << failed << " failed, " << cached
      << " already finished (" << cachedDiffers << " of them differ), " << skipped << " skipped by the plan\n";
  return (failed || differs || cachedDiffers) ? 1 : 0;
}

namespace {

std::string shellQuote(const std::string& s) {
  std::string r = "'";
  for (char ch : s) r += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return r + "'";
}

// Runs argv (found on PATH) and returns its exit status and stdout.
std::pair<int, std::string> capture(const std::vector<std::string>& argv) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
  posix_spawn_file_actions_addclose(&fa, fds[0]);
  std::vector<char*> cargv;
  for (const auto& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);
  pid_t pid = 0;
  const int err = posix_spawnp(&pid, cargv[0], &fa, nullptr, cargv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  close(fds[1]);
  if (err != 0) {
    close(fds[0]);
    throw std::runtime_error("campaign submit: cannot run " + argv[0] + ": " + std::strerror(err) +
                             (argv[0] == "sbatch" ? " (install Slurm: Debian's slurm-wlm)" : ""));
  }
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) != 0;)
    if (n > 0) text.append(buf, size_t(n));
    else if (errno != EINTR) break;
  close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), text};
}

}  // namespace

int submitCampaign(const CampaignOptions& opts, const Campaign& c, std::ostream& log) {
  const fs::path out = fs::absolute(campaignOutDir(opts, c));
  std::error_code ec;
  fs::create_directories(out / "slurm", ec);
  if (ec) throw std::runtime_error(out.string() + ": cannot create the results folder: " + ec.message());
  const size_t chunk = std::max(1u, opts.chunk);
  const size_t tasks = (c.jobs.size() + chunk - 1) / chunk;
  const fs::path script = out / "slurm" / "array.sbatch";
  {
    OutputFile f(script.string());
    std::ostream& s = f.stream();
    s << "#!/bin/bash\n"
      << "# shadetwin campaign " << c.name << ": " << c.jobs.size() << " jobs in " << tasks << " array tasks of " << chunk
      << " (written by shadetwin campaign submit; each task is `shadetwin campaign run --task`)\n"
      << "#SBATCH --job-name=shadetwin-" << c.name << "\n"
      << "#SBATCH --array=0-" << (tasks - 1) << "\n"
      << "#SBATCH --cpus-per-task=" << std::max(1u, opts.cpusPerTask) << "\n"
      << "#SBATCH --output=" << (out / "slurm" / "task_%a.out").string() << "\n"
      << "exec " << shellQuote(selfExe()) << " campaign run " << shellQuote(fs::absolute(c.file).string()) << " --out "
      << shellQuote(out.string()) << " --task \"$SLURM_ARRAY_TASK_ID\" --chunk " << chunk << " --jobs "
      << std::max(1u, opts.cpusPerTask) << " --retries " << opts.retries;
    if (opts.timeout > 0) s << " --timeout " << opts.timeout;
    s << "\n";
    f.commit();
  }
  std::vector<std::string> argv = {"sbatch", "--parsable"};
  if (opts.wait) argv.push_back("--wait");
  argv.insert(argv.end(), opts.sbatchArgs.begin(), opts.sbatchArgs.end());
  argv.push_back(script.string());
  log << "campaign " << c.name << ": " << c.jobs.size() << " jobs as " << tasks << " Slurm array tasks (" << script.string() << ")\n";
  const auto [rc, text] = capture(argv);
  std::string id = text.substr(0, text.find_first_of(";\n"));
  log << "sbatch: job " << (id.empty() ? "(none)" : id) << (opts.wait ? (rc == 0 ? ": every array task finished" : ": an array task failed") : " submitted")
      << (rc ? " (sbatch exit status " + std::to_string(rc) + ")" : "") << "\n";
  log << "then: shadetwin campaign gather " << c.file << " --out " << out.string() << "\n";
  return rc == 0 ? 0 : 1;
}

int campaignCommand(const CampaignOptions& opts, std::ostream& log) {
  const Campaign c = loadCampaign(opts.file);
  if (opts.action == "plan") {
    size_t skipped = 0;
    for (const CampaignJob& job : c.jobs) {
      if (!job.skipReason.empty()) {
        ++skipped;
        log << job.id << "  skipped: " << job.skipReason << "\n";
        continue;
      }
      log << job.id << "  shadetwin";
      for (const auto& a : job.command("<out>/jobs/" + job.id)) log << " " << a;
      log << "\n";
    }
    log << "plan: " << c.jobs.size() << " jobs (" << (c.jobs.size() - skipped) << " to run, " << skipped << " skipped by the scene)\n";
    return 0;
  }
  if (opts.action == "run") {
    if (opts.task < 0) return runCampaign(opts, c, 0, c.jobs.size(), log);
    const size_t chunk = std::max(1u, opts.chunk), first = size_t(opts.task) * chunk;
    if (first >= c.jobs.size())
      throw std::runtime_error(c.file + ": --task " + std::to_string(opts.task) + " is past the plan's " + std::to_string(c.jobs.size()) +
                               " jobs in chunks of " + std::to_string(chunk));
    return runCampaign(opts, c, first, std::min(c.jobs.size(), first + chunk), log);
  }
  if (opts.action == "submit") return submitCampaign(opts, c, log);
  return gatherCampaign(opts, c, log);
}

}  // namespace shadetwin
