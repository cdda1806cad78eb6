// Memory budget, peak and the early refusal of a frame too large for the machine (issue 20 item 6; util/memory.h,
// passes/frame_memory.h; docs/RESULTS.md "Stress").
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "cli/render.h"
#include "passes/frame_memory.h"
#include "passes/gbuffer.h"
#include "scene/scene.h"
#include "util/memory.h"

namespace {
namespace fs = std::filesystem;
using namespace shadetwin;

constexpr double kGiB = 1024.0 * 1024 * 1024;

double need(const std::vector<MemoryNeed>& n, const std::string& what) {
  for (const MemoryNeed& m : n)
    if (m.what == what) return m.bytes;
  return -1;
}

double sum(const std::vector<MemoryNeed>& n) { return totalBytes(n); }

// A scene file in a folder of its own whose ../assets is the checkout's (the shipped scenes' relative paths work).
struct SceneDir {
  fs::path root = fs::path(testing::TempDir()) / ("shadetwin_memory_" + std::to_string(::getpid()));
  SceneDir() {
    fs::create_directories(root / "scenes");
    std::error_code ec;
    fs::create_directory_symlink(fs::path(SHADETWIN_SOURCE_DIR) / "assets", root / "assets", ec);
  }
  ~SceneDir() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
  std::string write(const std::string& name, const std::string& json) const {
    const fs::path p = root / "scenes" / name;
    std::ofstream(p) << json;
    return p.string();
  }
};

struct EnvVar {
  std::string name;
  EnvVar(const char* n, const char* v) : name(n) { ::setenv(n, v, 1); }
  ~EnvVar() { ::unsetenv(name.c_str()); }
};

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Memory, ByteCountsParseWithBinarySuffixesAndRefuseTheRest) {
  EXPECT_EQ(parseByteCount("4096"), 4096.0);
  EXPECT_EQ(parseByteCount("64K"), 65536.0);
  EXPECT_EQ(parseByteCount("512M"), 512.0 * 1024 * 1024);
  EXPECT_EQ(parseByteCount("24G"), 24 * kGiB);
  EXPECT_EQ(parseByteCount("1.5GiB"), 1.5 * kGiB);
  EXPECT_EQ(parseByteCount("2gb"), 2 * kGiB);
  for (const char* bad : {"", "G", "-1G", "0", "12X", "1e999", "nan"}) EXPECT_THROW(parseByteCount(bad), std::invalid_argument) << bad;
  EXPECT_EQ(formatBytes(1536.0 * 1024 * 1024), "1.50 GiB");
  EXPECT_EQ(formatBytes(100), "100 B");
}

TEST(Memory, TheBudgetIsTheLimitWhenSetElseWhatTheMachineCanGive) {
  {
    EnvVar v("SHADETWIN_MEMORY_LIMIT", "3G");
    const MemoryBudget b = memoryBudget();
    EXPECT_EQ(b.bytes, 3 * kGiB);
    EXPECT_EQ(b.source, "SHADETWIN_MEMORY_LIMIT");
  }
  {
    EnvVar v("SHADETWIN_MEMORY_LIMIT", "lots");
    const std::string e = errorOf([] { memoryBudget(); });
    EXPECT_NE(e.find("SHADETWIN_MEMORY_LIMIT"), std::string::npos) << e;
  }
  // Unset: /proc/meminfo's MemAvailable (plus what this process holds), at most the machine's memory.
  const MemoryBudget b = memoryBudget();
  const double phys = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
  EXPECT_GT(b.bytes, 64.0 * 1024 * 1024) << b.source;
  EXPECT_LE(b.bytes, phys * 1.01) << b.source;
}

TEST(Memory, ThePeakGrowsWithTouchedPagesAndNeverFalls) {
  const double before = peakResidentBytes();
  EXPECT_GT(before, 0);
  EXPECT_GE(before, residentBytes() * 0.99);
  const size_t n = size_t(256) << 20;
  {
    std::vector<char> big(n);
    std::memset(big.data(), 1, n);  // touched: resident
    volatile char sink = big[n / 2];
    (void)sink;
    EXPECT_GE(residentBytes(), 200.0 * (1 << 20));
  }
  const double after = peakResidentBytes();
  EXPECT_GE(after, 200.0 * (1 << 20));
  EXPECT_GE(after, before);
}

// The page faults of a frame's second round of allocations in a worker thread (its own malloc arena, as a driver's
// rasterizer threads have): 256 blocks of 64 KiB allocated, written and freed twice, the faults of the second round
// counted. Run in a child process so that each policy starts from a fresh heap; -1 where the child failed.
long secondRoundFaults(bool keep) {
  int fd[2];
  if (pipe(fd) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    long faults = -2;
    if (!keep || keepHeapAcrossFrames()) {
      std::thread t([&] {
        auto round = [] {
          std::vector<char*> blocks;
          for (int i = 0; i < 256; ++i) {
            blocks.push_back(static_cast<char*>(std::malloc(64 << 10)));
            std::memset(blocks.back(), i, 64 << 10);
          }
          for (char* b : blocks) std::free(b);
        };
        round();
        rusage u0, u1;
        getrusage(RUSAGE_THREAD, &u0);
        round();
        getrusage(RUSAGE_THREAD, &u1);
        faults = u1.ru_minflt - u0.ru_minflt;
      });
      t.join();
    }
    const ssize_t w = write(fd[1], &faults, sizeof faults);
    _exit(w == sizeof faults ? 0 : 1);
  }
  close(fd[1]);
  long faults = -1;
  if (pid < 0 || read(fd[0], &faults, sizeof faults) != sizeof faults) faults = -1;
  close(fd[0]);
  if (pid > 0) waitpid(pid, nullptr, 0);
  return faults;
}

TEST(Memory, TheFrameHeapPolicyKeepsFreedPagesForTheNextFrame) {
#if defined(__SANITIZE_ADDRESS__) || !defined(__GLIBC__)
  GTEST_SKIP() << "the sanitizer's allocator or a non-glibc libc: mallopt does not apply";
#else
  // glibc's defaults hand the freed 16 MiB back to the kernel (the arena trims past 128 KiB), so the second round
  // faults its pages in again (4096 small pages, fewer where the heap is on transparent huge pages); with the policy the
  // heap keeps them and the second round touches only pages it holds.
  const long byDefault = secondRoundFaults(false), kept = secondRoundFaults(true);
  std::printf("second round's page faults: %ld by default, %ld with the policy\n", byDefault, kept);
  ASSERT_GE(byDefault, 0);
  ASSERT_GE(kept, 0) << "the child could not set the policy (-2) or failed (-1)";
  EXPECT_GE(byDefault, 8) << "the default policy should return the freed pages";
  EXPECT_LE(kept, 2) << "the policy should keep the freed pages";
#endif
}

TEST(Memory, ABudgetTooSmallIsAnErrorListingTheParts) {
  const std::vector<MemoryNeed> needs = {{"image", 3 * kGiB}, {"glint tables", 40 * kGiB}, {"tiny", 10}};
  const std::string e = errorOf([&] { checkMemoryBudget("s.json", needs, {16 * kGiB, "test"}); });
  EXPECT_EQ(e.rfind("s.json: ", 0), 0u) << e;
  EXPECT_NE(e.find("43.00 GiB"), std::string::npos) << e;
  EXPECT_LT(e.find("glint tables 40.00 GiB"), e.find("image 3.00 GiB")) << e;  // largest first
  EXPECT_EQ(e.find("tiny"), std::string::npos) << e;                          // parts under 1 MiB not listed
  EXPECT_NE(e.find("16.00 GiB it may use (test)"), std::string::npos) << e;
  EXPECT_NO_THROW(checkMemoryBudget("s.json", needs, {1024 * kGiB, "test"}));
  // What the process holds counts against the budget.
  EXPECT_THROW(checkMemoryBudget("s.json", {{"x", 1}}, {residentBytes() * 0.5, "test"}), std::runtime_error);
}

TEST(FrameMemory, PartsFollowTheImageTheEnvironmentAndTheTechnique) {
  Scene s;
  s.width = 4096, s.height = 4096;
  setTechnique(s, "mirror");
  const double px = 4096.0 * 4096;
  auto emu = frameMemory(s, 1024, 512, 3, FrameBuild::Emu);
  EXPECT_EQ(need(emu, "G-buffer"), px * (kGbufFloats + 1) * 4 * 2);  // the targets and the copy out
  EXPECT_EQ(need(emu, "paraboloid atlas"), -1);  // mirror reads no atlas
  EXPECT_EQ(need(emu, "shadow maps"), -1);
  // The environment grows with its texels; Vulkan adds device copies of the frame's images.
  const double e1 = need(emu, "environment"), e4 = need(frameMemory(s, 2048, 1024, 3, FrameBuild::Emu), "environment");
  EXPECT_DOUBLE_EQ(e4, 4 * e1);
  EXPECT_GT(sum(frameMemory(s, 1024, 512, 3, FrameBuild::Vulkan)), 1.5 * sum(emu));
  // A 4096^2 frame fits the 24 GiB of this project's machines with room; a 16384^2 one with visibility does not.
  EXPECT_LT(sum(emu), 4 * kGiB);
  setTechnique(s, "fis");
  s.visMaps = 16, s.visSize = 1024;
  const auto fis = frameMemory(s, 1024, 512, 3, FrameBuild::Emu);
  EXPECT_GT(need(fis, "paraboloid atlas"), 0);
  EXPECT_EQ(need(fis, "shadow maps"), 16.0 * 1024 * 1024 * 4 * 2);
  EXPECT_EQ(need(fis, "visibility coefficients"), px * 16 * 4 * 2);  // the filtered copy (radius 2 by default)
  s.width = s.height = 16384;
  EXPECT_GT(sum(frameMemory(s, 1024, 512, 3, FrameBuild::Emu)), 24 * kGiB);
  setTechnique(s, "kdtree-mis");
  EXPECT_GT(need(frameMemory(s, 1024, 512, 3, FrameBuild::Emu), "progressive mean"), 0);
}

TEST(FrameMemory, GlintTablesCountEachDistinctMapOnce) {
  Scene s;
  setTechnique(s, "glints");
  s.glintRings = 16, s.glintSectors = 64;
  Material a;
  a.glints = true, a.glintMapSize = 4096, a.glintMapSeed = 1;
  Material b = a;  // the same map: one table
  Material c = a;
  c.glintMapSeed = 2;  // another map
  s.materials = {a, b};
  const double one = need(frameMemory(s, 64, 32, 3, FrameBuild::Emu), "glint tables");
  EXPECT_GT(one, 4096.0 * 4096 * 16 * 64 * 2);  // at least the SAT itself: 32 GiB
  s.materials = {a, b, c};
  EXPECT_DOUBLE_EQ(need(frameMemory(s, 64, 32, 3, FrameBuild::Emu), "glint tables"), 2 * one);
}

// The render command refuses before it loads the environment or writes anything, naming the scene and the parts.
TEST(FrameMemory, RenderRefusesAFrameLargerThanTheBudgetBeforeWritingAnything) {
  const SceneDir d;
  const std::string scene = d.write("big.json", R"({"image": {"width": 2048, "height": 2048},
    "camera": {"eye": [0, 0, 3], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/studio.exr"},
    "technique": "mirror", "objects": [{"mesh": "sphere"}]})");
  const std::string out = (d.root / "big.exr").string();
  {
    std::ofstream(out) << "previous result";
    EnvVar v("SHADETWIN_MEMORY_LIMIT", "256M");
    RenderOptions o;
    o.scene = scene, o.out = out;
    std::ostringstream log;
    const std::string e = errorOf([&] { renderCommand(o, log); });
    EXPECT_EQ(e.rfind(scene + ": this run would need about", 0), 0u) << e;
    EXPECT_NE(e.find("G-buffer 544.00 MiB"), std::string::npos) << e;  // 2048^2 x 17 floats, twice
    EXPECT_NE(e.find("SHADETWIN_MEMORY_LIMIT"), std::string::npos) << e;
    EXPECT_EQ(log.str().find("environment + MIP chain"), std::string::npos) << "the environment was loaded first";
  }
  std::ifstream f(out);
  std::string kept;
  std::getline(f, kept);
  EXPECT_EQ(kept, "previous result");
  EXPECT_FALSE(fs::exists(d.root / "big.png"));
  // The same scene at 64x64 fits and says what it used.
  RenderOptions o;
  o.scene = scene, o.out = out, o.width = 64, o.height = 64;
  std::ostringstream log;
  ASSERT_EQ(renderCommand(o, log), 0);
  EXPECT_NE(log.str().find("estimated for a frame"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("peak memory "), std::string::npos) << log.str();
}

// Without any limit set: a glint table no machine of this project holds (8 maps of 4096^2, 16 x 64 bins: 770 GiB) is
// refused naming the scene and the part, before a byte of it is allocated.
TEST(FrameMemory, AGlintTableLargerThanTheMachineIsRefusedUpFront) {
  const SceneDir d;
  std::string mats, objs;
  for (int i = 0; i < 8; ++i) {
    mats += std::string(i ? "," : "") + R"({"name": "m)" + std::to_string(i) +
            R"(", "glints": {"map": "flakes", "size": 4096, "seed": )" + std::to_string(i + 1) + "}}";
    objs += std::string(i ? "," : "") + R"({"mesh": "sphere", "material": "m)" + std::to_string(i) + R"("})";
  }
  const std::string scene = d.write("glints_huge.json", R"({"image": {"width": 64, "height": 64},
    "camera": {"eye": [0, 0, 3], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/studio.exr"},
    "technique": "glints", "glints": {"rings": 16, "sectors": 64}, "materials": [)" + mats + "], \"objects\": [" + objs + "]}");
  RenderOptions o;
  o.scene = scene, o.out = (d.root / "g.exr").string();
  std::ostringstream log;
  const std::string e = errorOf([&] { renderCommand(o, log); });
  EXPECT_EQ(e.rfind(scene + ":", 0), 0u) << e;
  EXPECT_NE(e.find("glint tables"), std::string::npos) << e;
  std::smatch m;  // 8 x 4096^2 texels x (12 + 3 x 16 x 64 x 2) bytes = 770 GiB
  ASSERT_TRUE(std::regex_search(e, m, std::regex("glint tables ([0-9.]+) GiB"))) << e;
  EXPECT_NEAR(std::stod(m[1]), 8.0 * 4096 * 4096 * (12 + 3 * 16 * 64 * 2) / kGiB, 0.01) << e;
  EXPECT_FALSE(fs::exists(o.out));
}
