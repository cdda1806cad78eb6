#include "util/memory.h"

#include <sys/resource.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace shadetwin {

namespace {
// A "Key:   123 kB" line of a /proc file, in bytes; -1 when absent.
double procKilobytes(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, key.size() + 1, key + ":") == 0) {
      std::istringstream s(line.substr(key.size() + 1));
      double kb = -1;
      s >> kb;
      return kb < 0 ? -1 : kb * 1024.0;
    }
  return -1;
}

// A cgroup v2 file holding one number ("max": none), -1 when absent or unlimited.
double cgroupNumber(const char* file) {
  std::ifstream in(file);
  std::string word;
  if (!(in >> word) || word == "max") return -1;
  char* end = nullptr;
  const double v = std::strtod(word.c_str(), &end);
  return end && *end == 0 ? v : -1;
}
}  // namespace

double parseByteCount(const std::string& text) {
  std::string t = text;
  while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.pop_back();
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  std::string unit = end ? std::string(end) : std::string();
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  if (unit.size() > 1 && unit.back() == 'B') unit.pop_back();
  if (unit.size() > 1 && unit.back() == 'I') unit.pop_back();
  double scale = 0;
  if (unit.empty()) scale = 1;
  else if (unit == "K") scale = 1024.0;
  else if (unit == "M") scale = 1024.0 * 1024;
  else if (unit == "G") scale = 1024.0 * 1024 * 1024;
  else if (unit == "T") scale = 1024.0 * 1024 * 1024 * 1024;
  if (end == t.c_str() || scale == 0 || !std::isfinite(v) || v <= 0)
    throw std::invalid_argument("'" + text + "': expected a positive byte count such as 2147483648, 512M or 24G");
  return v * scale;
}

MemoryBudget memoryBudget() {
  if (const char* env = std::getenv("SHADETWIN_MEMORY_LIMIT"); env && *env) {
    try {
      return {parseByteCount(env), "SHADETWIN_MEMORY_LIMIT"};
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("SHADETWIN_MEMORY_LIMIT: ") + e.what());
    }
  }
  // What the process holds plus what the system could still give it.
  const double held = residentBytes();
  MemoryBudget b{-1, ""};
  if (const double avail = procKilobytes("/proc/meminfo", "MemAvailable"); avail >= 0)
    b = {avail + held, "MemAvailable in /proc/meminfo plus this process's resident set"};
  const double max = cgroupNumber("/sys/fs/cgroup/memory.max"), cur = cgroupNumber("/sys/fs/cgroup/memory.current");
  if (max > 0 && cur >= 0 && (b.bytes < 0 || max - cur + held < b.bytes))
    b = {max - cur + held, "the cgroup's memory.max less its memory.current, plus this process's resident set"};
  if (b.bytes < 0) b = {INFINITY, "no limit found (no /proc/meminfo)"};
  return b;
}

double peakResidentBytes() {
  if (const double hwm = procKilobytes("/proc/self/status", "VmHWM"); hwm >= 0) return hwm;
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) * 1024.0;  // Linux: kilobytes
}

double residentBytes() { return std::max(0.0, procKilobytes("/proc/self/status", "VmRSS")); }

std::string formatBytes(double bytes) {
  static const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 5) bytes /= 1024.0, ++u;
  char buf[64];
  std::snprintf(buf, sizeof buf, u ? "%.2f %s" : "%.0f %s", bytes, units[u]);
  return buf;
}

double totalBytes(const std::vector<MemoryNeed>& needs) {
  double total = 0;
  for (const MemoryNeed& n : needs) total += n.bytes;
  return total;
}

void checkMemoryBudget(const std::string& file, const std::vector<MemoryNeed>& needs, const MemoryBudget& budget) {
  const double total = totalBytes(needs);
  const double held = residentBytes();
  if (total + held <= budget.bytes) return;
  std::vector<MemoryNeed> parts = needs;
  std::stable_sort(parts.begin(), parts.end(), [](const MemoryNeed& a, const MemoryNeed& b) { return a.bytes > b.bytes; });
  std::string list;
  for (const MemoryNeed& n : parts)
    if (n.bytes >= 1024.0 * 1024) list += (list.empty() ? "" : ", ") + n.what + " " + formatBytes(n.bytes);
  throw std::runtime_error(file + ": this run would need about " + formatBytes(total) + " (" + list + ") beyond the " +
                           formatBytes(held) + " the process holds, more than the " + formatBytes(budget.bytes) +
                           " it may use (" + budget.source + ")");
}

void checkMemoryBudget(const std::string& file, const std::vector<MemoryNeed>& needs) {
  checkMemoryBudget(file, needs, memoryBudget());
}

bool keepHeapAcrossFrames() {
#if defined(__GLIBC__)
  // mallopt returns 1 when it took the setting. An explicit M_MMAP_THRESHOLD also turns off glibc's dynamic threshold,
  // which would otherwise set the trim threshold back to twice the largest mmapped block freed.
  const bool trim = mallopt(M_TRIM_THRESHOLD, 0x7fffffff) == 1;  // mallopt takes an int: 2 GiB - 1
  const bool mmap = mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1;
  return trim && mmap;
#else
  return false;
#endif
}

}  // namespace shadetwin
