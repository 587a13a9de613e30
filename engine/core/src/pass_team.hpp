// Two threads through the many short passes of a tick's disc contacts (second_thread.hpp).
// Internal to the engine: not installed.
#pragma once

#include <atomic>
#include <thread>

namespace fixstep::detail {

/// The second thread of a run of passes: the caller starts serve() on a worker, then posts one
/// job per pass (post(), then wait() for it) and ends the run with finish(). Between passes the
/// worker spins on an atomic counter instead of sleeping: the passes are tens to hundreds of
/// microseconds apart, less than a futex wake-up costs on a virtual machine (a wake-up per
/// pass made two threads slower than one). It yields the core after a few thousand spins.
class PassTeam {
 public:
  /// The worker's loop, until finish(): Workers::submit(&PassTeam::serve, team).
  static void serve(void* team) { static_cast<PassTeam*>(team)->loop(); }
  /// Starts job(ctx) on the worker; the caller runs its own share, then wait().
  void post(void (*job)(void*), void* ctx) {
    job_ = job, ctx_ = ctx;
    posted_.fetch_add(1, std::memory_order_release);
  }
  /// Returns when the last posted job has finished.
  void wait() const {
    const unsigned want = posted_.load(std::memory_order_relaxed);
    spin_until([&] { return done_.load(std::memory_order_acquire) == want; });
  }
  /// Ends serve() (after the last job was waited for).
  void finish() {
    stop_.store(true, std::memory_order_relaxed);
    posted_.fetch_add(1, std::memory_order_release);
  }

 private:
  template <class Ready>
  static void spin_until(Ready ready) {
    for (int i = 0; !ready(); ++i) {
      if (i < 4096) {
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
      } else {
        std::this_thread::yield();
      }
    }
  }
  void loop() {
    unsigned seen = done_.load(std::memory_order_relaxed);
    for (;;) {
      spin_until([&] { return posted_.load(std::memory_order_acquire) != seen; });
      seen = posted_.load(std::memory_order_acquire);
      if (stop_.load(std::memory_order_relaxed)) {
        stop_.store(false, std::memory_order_relaxed);
        done_.store(seen, std::memory_order_release);
        return;
      }
      job_(ctx_);
      done_.store(seen, std::memory_order_release);
    }
  }

  void (*job_)(void*) = nullptr;
  void* ctx_ = nullptr;
  std::atomic<unsigned> posted_{0}, done_{0};
  std::atomic<bool> stop_{false};
};

}  // namespace fixstep::detail
