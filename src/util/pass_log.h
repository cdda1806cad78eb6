// Which device passes an emulated frame ran, by name (the performance model's coverage test, tests/pass_counts_test.cpp:
// every pass the frame runs must have a counted run in model/pass_counts.h). Off unless a PassLog is alive on the
// calling thread; each emulated pass's entry point notes itself once per dispatch or draw sequence.
#pragma once
#include <string>
#include <vector>

namespace shadetwin {

class PassLog {
 public:
  PassLog() : prev_(active()) { active() = this; }
  ~PassLog() { active() = prev_; }
  PassLog(const PassLog&) = delete;
  PassLog& operator=(const PassLog&) = delete;
  std::vector<std::string> names;  // in the order the passes ran, repeats included
  static PassLog*& active() {
    thread_local PassLog* p = nullptr;
    return p;
  }

 private:
  PassLog* prev_;
};

inline void notePass(const char* name) {
  if (PassLog* l = PassLog::active()) l->names.emplace_back(name);
}

}  // namespace shadetwin
