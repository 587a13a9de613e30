// A worker thread: the second thread of a world's links (World::parallel in world_coupled.cpp)
// and of its disc contacts (second_thread.hpp). Internal to the engine: not installed.
#pragma once

#include <atomic>
#include <thread>

#include "world_kernel.hpp"

namespace fixstep::detail {

/// Whether this build can start a thread: not wasm32 built without pthreads (emscripten's
/// default), where std::thread's constructor throws; worlds there step on one thread, with the
/// same states (WorldSettings::threads).
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
inline constexpr bool threads_supported = false;
#else
inline constexpr bool threads_supported = true;
#endif

/// Whether the machine has a second core (asked once: a system call).
inline bool has_second_core() {
  static const bool second = std::thread::hardware_concurrency() >= 2;
  return second;
}

/// The threads a world uses for WorldSettings::threads = want: 1 when asked for or when the
/// build cannot start a thread, 2 when asked for, and for 0 (automatic) 2 where the machine has
/// a second core (the links add a least size: parallel_min_bodies). The states are the same
/// either way.
inline int threads_for(int want) {
  if (want == 1 || !threads_supported) return 1;
  return want >= 2 || has_second_core() ? 2 : 1;
}

/// One worker thread that runs a job while the calling thread runs its own share: a spin on
/// an atomic generation counter for the short waits between passes, a futex wait
/// (std::atomic::wait) for the long ones between ticks, so an idle world costs no CPU.
class Workers {
 public:
  Workers() : thread_([this] { loop(); }) {}
  ~Workers() {
    stop_.store(true, std::memory_order_relaxed);
    start_.fetch_add(1, std::memory_order_release);
    start_.notify_one();
    thread_.join();
  }
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;

  /// Starts job(ctx) on the worker; wait() returns when it has finished.
  void submit(void (*job)(void*), void* ctx) {
    job_ = job, ctx_ = ctx;
    const unsigned gen = start_.fetch_add(1, std::memory_order_release) + 1;
    pending_ = gen;
    start_.notify_one();
  }
  void wait() {
    for (int i = 0; i < spin_limit && done_.load(std::memory_order_acquire) != pending_; ++i) {
      pause();
    }
    for (unsigned d; (d = done_.load(std::memory_order_acquire)) != pending_;) {
      done_.wait(d, std::memory_order_acquire);
    }
  }

 private:
  static constexpr int spin_limit = 1 << 11;  // about 10-50 µs of pause instructions
  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  void loop() {
    unsigned seen = 0;
    for (;;) {
      unsigned s = start_.load(std::memory_order_acquire);
      for (int i = 0; i < spin_limit && s == seen; ++i) {
        pause();
        s = start_.load(std::memory_order_acquire);
      }
      while (s == seen) {
        start_.wait(seen, std::memory_order_acquire);
        s = start_.load(std::memory_order_acquire);
      }
      seen = s;
      if (stop_.load(std::memory_order_relaxed)) return;
      job_(ctx_);
      done_.store(s, std::memory_order_release);
      done_.notify_one();
    }
  }

  void (*job_)(void*) = nullptr;
  void* ctx_ = nullptr;
  unsigned pending_ = 0;
  std::atomic<unsigned> start_{0}, done_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;  // last: starts after every other member is initialised
};

}  // namespace fixstep::detail
