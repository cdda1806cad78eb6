// Safe outputs (issue 20, item 4): every file is written under a temporary name and renamed into place; a failed,
// abandoned or interrupted write (SIGINT, SIGTERM) leaves no partial or hidden file and the previous result intact.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "util/image_io.h"
#include "util/output_file.h"

namespace {
namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::path(testing::TempDir()) / ("output_file_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<std::string> entries(const fs::path& d) {  // every name in the folder, hidden ones too
  std::vector<std::string> v;
  for (const auto& e : fs::directory_iterator(d)) v.push_back(e.path().filename().string());
  std::sort(v.begin(), v.end());
  return v;
}

// Runs `body` in a child process and returns the signal that ended it (0 if it exited).
template <class F>
int signalOfChild(F body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    body();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFSIGNALED(status) ? WTERMSIG(status) : 0;
}
}  // namespace

TEST(OutputFile, CommitRenamesIntoPlaceAndLeavesNoTemporary) {
  const fs::path d = freshDir("commit");
  const std::string path = (d / "a.csv").string();
  {
    shadetwin::OutputFile f(path);
    f.stream() << "x,y\n1,2\n";
    EXPECT_FALSE(fs::exists(path));  // not there until complete
    EXPECT_TRUE(fs::exists(f.tempPath()));
    EXPECT_EQ(fs::path(f.tempPath()).parent_path(), d);  // the same folder: the rename is atomic
    EXPECT_EQ(fs::path(f.tempPath()).extension(), ".csv");  // writers that pick a format by extension see the target's
    EXPECT_EQ(shadetwin::liveOutputTemporaries(), 1);
    f.commit();
  }
  EXPECT_EQ(slurp(path), "x,y\n1,2\n");
  EXPECT_EQ(entries(d), std::vector<std::string>{"a.csv"});
  EXPECT_EQ(shadetwin::liveOutputTemporaries(), 0);
}

TEST(OutputFile, AnAbandonedWriteKeepsThePreviousFile) {
  const fs::path d = freshDir("abandon");
  const std::string path = (d / "sweep.csv").string();
  std::ofstream(path) << "previous";
  {
    shadetwin::OutputFile f(path);
    f.stream() << "half a new file";
    f.stream().flush();
    // an exception unwinds here: no commit
  }
  EXPECT_EQ(slurp(path), "previous");
  EXPECT_EQ(entries(d), std::vector<std::string>{"sweep.csv"});
}

TEST(OutputFile, AMissingOrUnwritableFolderIsNamedAndNothingIsWritten) {
  const fs::path d = freshDir("missing");
  const std::string path = (d / "no" / "such" / "out.exr").string();
  try {
    shadetwin::OutputFile f(path);
    FAIL() << "expected a FileError";
  } catch (const shadetwin::FileError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path), std::string::npos) << m;
    EXPECT_NE(m.find("does not exist"), std::string::npos) << m;
  }
  EXPECT_THROW(shadetwin::OutputFile{d.string()}, shadetwin::FileError);  // a folder, not a file name
  EXPECT_TRUE(entries(d).empty());
  if (::geteuid() != 0) {  // root writes anywhere
    fs::permissions(d, fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THROW(shadetwin::OutputFile{(d / "x.csv").string()}, shadetwin::FileError);
    fs::permissions(d, fs::perms::owner_all);
  }
}

TEST(OutputFile, AFailedImageWriteKeepsThePreviousImage) {
  const fs::path d = freshDir("image");
  const std::string path = (d / "frame.exr").string();
  shadetwin::writeExr(path, 2, 1, std::vector<float>(8, 0.5f));
  const std::string before = slurp(path);
  EXPECT_THROW(shadetwin::writeExr(path, 2, 2, std::vector<float>(8, 1.0f)), shadetwin::FileError);  // size mismatch
  EXPECT_THROW(shadetwin::writeExr((d / "frame.unknownext").string(), 2, 1, std::vector<float>(8, 1.0f)), shadetwin::FileError);
  EXPECT_EQ(slurp(path), before);
  EXPECT_EQ(entries(d), std::vector<std::string>{"frame.exr"});
  shadetwin::writeExr(path, 2, 1, std::vector<float>(8, 2.0f));  // a complete write replaces it
  EXPECT_NE(slurp(path), before);
  EXPECT_EQ(shadetwin::loadImageRGBA(path).texels[0], 2.0f);
}

TEST(OutputFile, AnInterruptRemovesTheTemporariesAndKeepsThePreviousFiles) {
  for (int sig : {SIGINT, SIGTERM}) {
    const fs::path d = freshDir("interrupt" + std::to_string(sig));
    const std::string a = (d / "a.csv").string(), b = (d / "b.png").string();
    std::ofstream(a) << "previous a";
    const int got = signalOfChild([&] {
      shadetwin::installInterruptCleanup();
      shadetwin::OutputFile fa(a), fb(b), fc((d / "c.txt").string());
      fa.stream() << "partial";
      fa.stream().flush();
      std::ofstream(fb.tempPath()) << "partial png";  // a writer that takes the temporary's path
      fc.stream() << "done";
      fc.commit();  // committed before the signal: kept
      ::raise(sig);
      ::_exit(3);  // not reached: the signal ends the process
    });
    EXPECT_EQ(got, sig);
    EXPECT_EQ(slurp(a), "previous a");
    EXPECT_EQ(slurp(d / "c.txt"), "done");
    EXPECT_EQ(entries(d), (std::vector<std::string>{"a.csv", "c.txt"})) << "signal " << sig;
  }
}
