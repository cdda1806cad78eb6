#include "util/progress.h"

#include <unistd.h>

#include <cstdio>
#include <iomanip>
#include <iostream>

namespace shadetwin {

ProgressBar::ProgressBar(std::ostream& out, std::string label)
    : out_(out), label_(std::move(label)), start_(std::chrono::steady_clock::now()) {
  tty_ = (&out == &std::cerr && isatty(STDERR_FILENO)) || (&out == &std::cout && isatty(STDOUT_FILENO));
}

void ProgressBar::update(double fraction) {
  if (finished_) return;
  const int pct = int(fraction * 100.0 + 1e-9);
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (tty_) {
    if (pct == lastShown_) return;
    constexpr int kWidth = 40;
    const int fill = pct * kWidth / 100;
    out_ << "\r" << label_ << " [" << std::string(size_t(fill), '#') << std::string(size_t(kWidth - fill), ' ') << "] "
         << std::setw(3) << pct << "%  " << std::fixed << std::setprecision(1) << sec << " s";
    if (fraction > 0.0 && fraction < 1.0) out_ << ", " << sec * (1.0 - fraction) / fraction << " s left   ";
    out_ << std::flush;
  } else {
    if (pct / 10 == lastShown_ / 10 && lastShown_ >= 0) return;
    out_ << label_ << ": " << pct << "% (" << std::fixed << std::setprecision(1) << sec << " s)\n";
  }
  lastShown_ = pct;
}

void ProgressBar::finish() {
  if (finished_) return;
  update(1.0);
  if (tty_) out_ << "\n";
  finished_ = true;
}

}  // namespace shadetwin
