// A worker thread: the second thread of a world's links (World::parallel in world_coupled.cpp)
// and of its disc contacts (second_thread.hpp). Internal to the engine: not installed.
#pragma once

#include <atomic>
#include <chrono>
#include <thread>

#include "spin_wait.hpp"
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

/// One worker thread that runs a job while the calling thread runs its own share. Each side
/// waits for the other by wait_for_change (spin_wait.hpp): a spin on an atomic generation
/// counter for the short waits between passes, a futex wait (std::atomic::wait) for the long
/// ones between ticks, so an idle world costs no CPU. The worker's wake-ups are steered off the
/// caller's core (WakeSteering), and the caller spins for the worker's job up to
/// run_spin_budget while the worker runs on another core (woken from a sleep by the worker, it
/// would land on the worker's core on a virtual machine); it sleeps at once on the worker's
/// core, and when it finds it was preempted.
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
    steer_.before_wake(current_cpu());
    const unsigned gen = start_.fetch_add(1, std::memory_order_release) + 1;
    pending_ = gen;
    start_.notify_one();
  }
  void wait() {
    unsigned d = done_.load(std::memory_order_acquire);
    if (d == pending_) return;
    caller_wait_.start(run_spin_budget);
    while (d != pending_) wait_for_change(done_, d, d, {&caller_gives_up, this});
  }

 private:
  static bool caller_gives_up(void* p) {
    auto* w = static_cast<Workers*>(p);
    return w->caller_wait_.gives_up(w->worker_cpu_.load(std::memory_order_relaxed));
  }
  static bool worker_gives_up(void* p) {
    auto* w = static_cast<Workers*>(p);
    return std::chrono::steady_clock::now() >= w->worker_until_ && w->steer_.doze();
  }
  void loop() {
    const AllowedCores cores;
    steer_.serve(cores);
    for (unsigned seen = 0;;) {
      worker_until_ = std::chrono::steady_clock::now() + spin_budget;
      unsigned now = seen;
      wait_for_change(start_, seen, now, {&worker_gives_up, this});
      steer_.awake();
      seen = now;
      if (stop_.load(std::memory_order_relaxed)) return;
      worker_cpu_.store(current_cpu(), std::memory_order_relaxed);
      job_(ctx_);
      done_.store(seen, std::memory_order_release);
      done_.notify_one();
    }
  }

  void (*job_)(void*) = nullptr;
  void* ctx_ = nullptr;
  unsigned pending_ = 0;
  std::atomic<unsigned> start_{0}, done_{0};
  std::atomic<int> worker_cpu_{-1};  ///< the core the worker last started a job on
  std::atomic<bool> stop_{false};
  std::chrono::steady_clock::time_point worker_until_{};  ///< the worker's spin ends (its own)
  CallerWait caller_wait_;                                // the caller's only
  WakeSteering steer_;  // the worker's wake-ups, off the caller's core
  std::thread thread_;  // last: starts after every other member is initialised
};

}  // namespace fixstep::detail
