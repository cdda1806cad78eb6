// Which device passes an emulated frame ran, by name (the performance model's coverage test, tests/pass_counts_test.cpp:
// every pass the frame runs must have a counted run in model/pass_counts.h). Off unless a PassLog is alive on the
// calling thread; each emulated pass's entry point notes itself once per dispatch or draw sequence.
#pragma once
#include <string>
#include <vector>

#include "util/thread_log.h"

namespace shadetwin {

struct PassLog : ThreadLog<PassLog> {
  std::vector<std::string> names;  // in the order the passes ran, repeats included
};

inline void notePass(const char* name) {
  if (PassLog* l = PassLog::active()) l->names.emplace_back(name);
}

}  // namespace shadetwin
