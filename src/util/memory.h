// What a run may use and what it used: the memory budget (this machine's available memory, a cgroup's limit, or
// SHADETWIN_MEMORY_LIMIT), the process's peak resident size, and the early check that refuses a run that would need
// more than the budget before it allocates (issue 20 item 6; docs/RESULTS.md "Stress").
#pragma once
#include <string>
#include <vector>

namespace shadetwin {

/// One part of a run's memory, as estimated before the run allocates it.
struct MemoryNeed {
  std::string what;
  double bytes = 0;
};

struct MemoryBudget {
  double bytes = 0;
  std::string source;  // where the number comes from, for the error message
};

/// The memory a run may use: SHADETWIN_MEMORY_LIMIT (bytes, or with a K/M/G suffix, powers of 1024) when set, else
/// the smaller of /proc/meminfo's MemAvailable and the cgroup's memory.max less its memory.current. Throws
/// std::invalid_argument for a malformed SHADETWIN_MEMORY_LIMIT.
MemoryBudget memoryBudget();

/// The process's peak resident set (VmHWM of /proc/self/status; getrusage's ru_maxrss where that is missing), bytes.
double peakResidentBytes();
/// The process's resident set now (VmRSS), bytes; 0 when unknown.
double residentBytes();

/// The heap policy of a process that renders frame after frame (the CLI calls it first; docs/RESULTS.md session 35).
/// By default glibc hands the free memory at the top of a heap back to the kernel once it passes 128 KiB
/// (M_TRIM_THRESHOLD, also per thread arena) and serves blocks from 128 KiB up by mmap, so a Vulkan driver that
/// allocates a frame's bins and vertex buffers and frees them at the end (lavapipe) touches fresh pages in every frame,
/// and on a VM where a page fault costs microseconds those faults were most of a small G-buffer pass (64x48 bunny
/// 1.20 ms, 0.71 ms with this policy). Here the heap keeps what it has (trim threshold 2 GiB) and blocks below 32 MiB
/// (glibc's largest dynamic threshold) come from the heap. Returns false where the allocator refused a setting (a
/// sanitizer's allocator, another libc): the process then runs with its allocator's defaults.
bool keepHeapAcrossFrames();

/// The needs' sum, bytes.
double totalBytes(const std::vector<MemoryNeed>& needs);

/// "1.23 GiB", "456.7 MiB", "12.0 KiB".
std::string formatBytes(double bytes);
/// Parses "123", "64K", "512M", "24G" (powers of 1024; an optional trailing B or iB); throws std::invalid_argument.
double parseByteCount(const std::string& text);

/// Throws std::runtime_error "FILE: this run needs about X (a X, b Y, ...) beyond the Z the process holds, more than the
/// W available (source)" when the needs' sum exceeds the budget less what the process already holds. The parts are
/// listed largest first.
void checkMemoryBudget(const std::string& file, const std::vector<MemoryNeed>& needs, const MemoryBudget& budget);
void checkMemoryBudget(const std::string& file, const std::vector<MemoryNeed>& needs);

}  // namespace shadetwin
