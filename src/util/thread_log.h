// A log that is active on the calling thread while it is alive (nested logs stack: the innermost records), for
// recorders deep in a call chain that must cost nothing when no one listens: util/pass_log.h (the passes a frame ran)
// and vk::DispatchLog (the times of the Kernel::run calls). Derived : ThreadLog<Derived>.
#pragma once

namespace shadetwin {

template <class Derived>
class ThreadLog {
 public:
  ThreadLog() : prev_(active()) { active() = static_cast<Derived*>(this); }
  ~ThreadLog() { active() = prev_; }
  ThreadLog(const ThreadLog&) = delete;
  ThreadLog& operator=(const ThreadLog&) = delete;
  static Derived*& active() {
    thread_local Derived* p = nullptr;
    return p;
  }

 private:
  Derived* prev_;
};

}  // namespace shadetwin
