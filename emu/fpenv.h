// Per-stage denormal mode of the host CPU (the emulator runs a stage under its device's mode).
#pragma once
#include <xmmintrin.h>

namespace emu {

/// RAII: sets MXCSR flush-to-zero and denormals-are-zero while alive (when `flush` is true), so
/// float add/mul flush denormal inputs and results exactly as a flushing shader stage does.
class DenormalScope {
 public:
  explicit DenormalScope(bool flush) : saved_(_mm_getcsr()) {
    if (flush) _mm_setcsr(saved_ | 0x8040u);  // FTZ (bit 15) | DAZ (bit 6)
    else _mm_setcsr(saved_ & ~0x8040u);
  }
  ~DenormalScope() { _mm_setcsr(saved_); }
  DenormalScope(const DenormalScope&) = delete;
  DenormalScope& operator=(const DenormalScope&) = delete;

 private:
  unsigned saved_;
};

}  // namespace emu
