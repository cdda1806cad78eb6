// A progress bar for long work: on a terminal one line redrawn in place ("\r"), elsewhere (CI logs,
// pipes) a line at every 10 %, so logs stay short. Not thread-safe: callers serialise update().
#pragma once
#include <chrono>
#include <ostream>
#include <string>

namespace shadetwin {

class ProgressBar {
 public:
  ProgressBar(std::ostream& out, std::string label);
  void update(double fraction);  // 0..1
  void finish();

 private:
  std::ostream& out_;
  std::string label_;
  bool tty_;
  int lastShown_ = -1;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace shadetwin
