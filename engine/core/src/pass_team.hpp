// Two threads through the many short passes of a world's tick (second_thread.hpp).
// Internal to the engine: not installed.
#pragma once

#include <atomic>
#include <chrono>

#include "spin_wait.hpp"

namespace fixstep::detail {

/// Two threads through a series of passes: the caller starts serve() on a worker once, then
/// posts one job per pass (post(), then wait() for it), and ends the series with finish().
///
/// A posted job is run once, by whichever thread claims it first: the worker as soon as it sees
/// it, or the caller in wait() when the worker has not started it yet (the worker still waking,
/// or not running at all because both threads share one core while the other core is busy).
/// Jobs are halves of a pass that may run in either order, so the result is the same; a worker
/// that is late costs the caller the time of the job, not the wait for a core.
///
/// Between passes each side waits by wait_for_change (spin_wait.hpp). Within a run (set_run:
/// one tick's passes, tens to hundreds of microseconds apart, less than a futex wake-up costs
/// on a virtual machine) the worker spins, so that it stays on its own core; outside a run it
/// sleeps after spin_budget. Spinning on the core the other thread needs only keeps it from
/// running (a sched_yield() does not reliably hand the core over: on Linux 6.18 two such
/// threads took turns of about a millisecond), so: the caller sleeps at once when it finds
/// itself on the worker's core; the worker, on the caller's core within a run, moves to
/// another core it is allowed (AllowedCores::leave: woken by the caller, the kernel may place
/// it on the caller's core and leave the other idle) and sleeps where there is none, and it
/// sleeps when it finds it was preempted while it spun.
///
/// Each wake-up of the worker is steered off the caller's core (WakeSteering: on a virtual
/// machine a woken thread lands on its waker's core), and the caller within a run waits for the
/// worker's half by spinning up to run_spin_budget rather than sleeping (woken by the worker, it
/// would land on the worker's core), unless it finds itself on the worker's core or preempted.
class PassTeam {
 public:
  /// The worker's loop, until finish(): Workers::submit(&PassTeam::serve, team), once.
  static void serve(void* team) { static_cast<PassTeam*>(team)->loop(); }
  /// Offers job(ctx) to the worker; the caller runs its own share, then wait().
  void post(void (*job)(void*), void* ctx) {
    job_ = job, ctx_ = ctx;
    const int here = current_cpu();
    caller_cpu_.store(here, std::memory_order_relaxed);
    steer_.before_wake(here);  // a worker that gave up spinning wakes off this core
    posted_.fetch_add(1, std::memory_order_release);
    posted_.notify_one();
  }
  /// Returns when the last posted job has run: here, if the worker has not claimed it yet; at
  /// once when nothing was posted since the last wait().
  void wait() {
    const unsigned want = posted_.load(std::memory_order_relaxed);
    if (want == waited_) return;  // else a job the caller ran would be waited for forever
    waited_ = want;
    if (claim(want)) {
      job_(ctx_);
      ++run_here_;
      return;
    }
    unsigned d = done_.load(std::memory_order_acquire);
    if (d == want) return;  // the worker's half was done first: no clock to read
    caller_wait_.start(run_.load(std::memory_order_relaxed) ? run_spin_budget : spin_budget);
    while (d != want) {
      if (wait_for_change(done_, d, d, {&caller_gives_up, this}) == WaitEnd::slept) {
        ++caller_slept_;
      }
    }
  }
  /// Starts or ends a run: within one the worker spins between jobs (unless it shares the
  /// caller's core); outside one it sleeps after spin_budget. Starting one wakes a sleeping
  /// worker (an empty job posted, which either thread runs): a tick opens its run before its
  /// first split pass, and the worker then spins by it instead of waking at it.
  void set_run(bool on) {
    if (on) caller_cpu_.store(current_cpu(), std::memory_order_relaxed);
    run_.store(on, std::memory_order_relaxed);
    if (on) {
      post([](void*) {}, nullptr);
      wait();
    }
  }
  /// Ends serve() (after the last job was waited for).
  void finish() {
    stop_.store(true, std::memory_order_relaxed);
    posted_.fetch_add(1, std::memory_order_release);
    posted_.notify_one();
  }
  /// For the tests, since the team was made: the worker's waits for a job that ended asleep,
  /// the jobs the caller ran itself (the worker had not claimed them), and the caller's waits
  /// for the worker's job that ended asleep.
  [[nodiscard]] unsigned worker_slept() const {
    return worker_slept_.load(std::memory_order_relaxed);
  }
  [[nodiscard]] unsigned run_here() const { return run_here_; }
  [[nodiscard]] unsigned caller_slept() const { return caller_slept_; }

 private:
  /// Takes job `gen` (the gen-th posted) for this thread; false when the other has it. Every
  /// job before it was claimed before it was posted, so claimed_ is before gen or gen itself
  /// (counts compared modulo 2^32).
  bool claim(unsigned gen) {
    unsigned last = claimed_.load(std::memory_order_relaxed);
    while (static_cast<int>(gen - last) > 0) {
      if (claimed_.compare_exchange_weak(last, gen, std::memory_order_acq_rel,
                                         std::memory_order_relaxed)) {
        return true;
      }
    }
    return false;
  }
  static bool caller_gives_up(void* p) {
    auto* t = static_cast<PassTeam*>(p);
    return t->caller_wait_.gives_up(t->worker_cpu_.load(std::memory_order_relaxed));
  }
  static bool worker_gives_up(void* p) {
    auto* t = static_cast<PassTeam*>(p);
    const auto now = std::chrono::steady_clock::now();
    const bool preempted = was_preempted(t->worker_checked_, now);
    t->worker_checked_ = now;
    const int caller = t->caller_cpu_.load(std::memory_order_relaxed);
    if (caller >= 0 && caller == current_cpu()) {
      // On the caller's core: move to another (the caller's wake-ups would bring it back
      // here, and the kernel may leave both on one core while the other idles), else sleep.
      return (!t->run_.load(std::memory_order_relaxed) || !t->cores_->leave(caller)) &&
             t->steer_.doze();
    }
    if (preempted) return t->steer_.doze();
    return !t->run_.load(std::memory_order_relaxed) && now >= t->worker_until_ && t->steer_.doze();
  }
  void loop() {
    // The jobs come after the last claimed: the caller may have claimed some before this
    // thread started, and finish() may have come already (posted_ then differs).
    unsigned seen = claimed_.load(std::memory_order_acquire);
    const AllowedCores cores;
    cores_ = &cores;
    steer_.serve(cores);
    for (;;) {
      worker_checked_ = std::chrono::steady_clock::now();
      worker_until_ = worker_checked_ + spin_budget;
      unsigned now = seen;
      if (wait_for_change(posted_, seen, now, {&worker_gives_up, this}) == WaitEnd::slept) {
        worker_slept_.fetch_add(1, std::memory_order_relaxed);
      }
      steer_.awake();
      seen = now;
      if (stop_.load(std::memory_order_relaxed)) return;
      if (!claim(seen)) continue;  // the caller ran it
      worker_cpu_.store(current_cpu(), std::memory_order_relaxed);
      job_(ctx_);
      done_.store(seen, std::memory_order_release);
      done_.notify_one();
    }
  }

  void (*job_)(void*) = nullptr;
  void* ctx_ = nullptr;
  /// Jobs posted, the last claimed and the last the worker finished (generation counts).
  std::atomic<unsigned> posted_{0}, claimed_{0}, done_{0}, worker_slept_{0};
  /// The core each side last ran on (-1: unknown), as it posted or claimed a job.
  std::atomic<int> caller_cpu_{-1}, worker_cpu_{-1};
  std::atomic<bool> run_{false}, stop_{false};
  WakeSteering steer_;  // the worker's wake-ups, off the caller's core
  /// When each side's spin ends by time (each written and read by its own thread only).
  std::chrono::steady_clock::time_point worker_until_{}, worker_checked_{};
  CallerWait caller_wait_;                    // the caller's only
  unsigned run_here_ = 0, caller_slept_ = 0;  // the caller's only
  unsigned waited_ = 0;                  ///< the last job wait() returned for (the caller's only)
  const AllowedCores* cores_ = nullptr;  // the worker's, while it serves
};

}  // namespace fixstep::detail
