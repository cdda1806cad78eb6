#include "util/output_file.h"

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <unistd.h>

#include "util/image_io.h"

namespace shadetwin {

namespace {
namespace fs = std::filesystem;

// The live temporaries, readable from a signal handler: fixed slots of C strings, claimed and released atomically
// (a slot's name is written before its state becomes kLive and the handler reads only kLive slots).
constexpr int kSlots = 256;
constexpr size_t kPathMax = 4096;
enum : int { kFree = 0, kClaimed = 1, kLive = 2 };
std::array<std::atomic<int>, kSlots> gState{};
std::array<std::array<char, kPathMax>, kSlots> gPath{};
std::atomic<unsigned> gCounter{0};

int claim(const std::string& temp) {
  if (temp.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (gState[size_t(i)].compare_exchange_strong(expected, kClaimed)) {
      std::memcpy(gPath[size_t(i)].data(), temp.c_str(), temp.size() + 1);
      gState[size_t(i)].store(kLive);
      return i;
    }
  }
  return -1;  // more than kSlots files open at once: still written safely, only not removed on a signal
}

void release(int slot) {
  if (slot >= 0) gState[size_t(slot)].store(kFree);
}

extern "C" void onInterrupt(int sig) {
  for (int i = 0; i < kSlots; ++i)
    if (gState[size_t(i)].load() == kLive) ::unlink(gPath[size_t(i)].data());  // async-signal-safe
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}
}  // namespace

void checkWritable(const std::string& path) {
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw FileError(path + ": cannot write: folder " + dir.string() + " does not exist");
  if (target.filename().empty() || fs::is_directory(target, ec)) throw FileError(path + ": cannot write: it is a folder");
  if (::access(dir.c_str(), W_OK) != 0) throw FileError(path + ": cannot write: folder " + dir.string() + " is not writable");
}

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  checkWritable(path_);
  const fs::path target(path_);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  temp_ = (dir / (".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(gCounter++) + "-" + target.filename().string())).string();
  slot_ = claim(temp_);
}

OutputFile::~OutputFile() {
  if (!committed_) {
    if (out_.is_open()) out_.close();
    std::error_code ec;
    fs::remove(temp_, ec);
  }
  release(slot_);
}

std::ostream& OutputFile::stream() {
  if (!out_.is_open()) {
    out_.open(temp_, std::ios::out | std::ios::trunc);
    if (!out_) throw FileError(path_ + ": cannot write: cannot create " + temp_);
  }
  return out_;
}

void OutputFile::commit() {
  if (committed_) return;
  if (out_.is_open()) {
    out_.flush();
    const bool ok = bool(out_);
    out_.close();
    if (!ok || out_.fail()) throw FileError(path_ + ": cannot write: the write failed (disk full?)");
  }
  std::error_code ec;
  if (!fs::exists(temp_, ec)) throw FileError(path_ + ": cannot write: nothing was written");
  fs::rename(temp_, path_, ec);
  if (ec) throw FileError(path_ + ": cannot write: " + ec.message());
  committed_ = true;
  release(slot_);
  slot_ = -1;
}

void installInterruptCleanup() {
  static std::atomic<bool> installed{false};
  if (installed.exchange(true)) return;
  struct sigaction sa {};
  sa.sa_handler = onInterrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction old {};
    sigaction(sig, nullptr, &old);
    if (old.sa_handler == SIG_IGN) continue;  // ignored by whoever started us (nohup, a background job): stay so
    sigaction(sig, &sa, nullptr);
  }
}

int liveOutputTemporaries() {
  int n = 0;
  for (int i = 0; i < kSlots; ++i) n += gState[size_t(i)].load() == kLive;
  return n;
}

}  // namespace shadetwin
