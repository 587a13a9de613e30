// Waiting for another thread to move an atomic counter: spin for a bounded time, then sleep in
// the kernel. Used by the worker thread (workers.hpp) and by the runs of passes it serves
// (pass_team.hpp). Internal to the engine: not installed.
#pragma once

#include <atomic>
#include <chrono>

#if defined(__linux__)
#include <pthread.h>
#include <sched.h>
#endif

namespace fixstep::detail {

/// How long a waiting thread spins before it sleeps. Spinning pays while the other thread runs
/// on another core and is about to move the counter: waking a sleeping thread (a futex) costs
/// tens of microseconds on a virtual machine, more than many passes of a tick take. Spinning
/// loses when both threads share one core (the other core busy, or the scheduler placed them
/// there): the waiter then holds the core its partner needs, and a sched_yield() does not
/// reliably hand it over (on Linux 6.18 the two threads took turns of about a millisecond).
/// After this budget the waiter sleeps, so the partner runs within a context switch.
inline constexpr std::chrono::microseconds spin_budget{50};
/// How long the stepping thread spins for the worker's half of a pass within a tick's run
/// (PassTeam) while the worker runs on another core: a half can take milliseconds at 10^5
/// bodies, and a sleeping caller woken by the worker lands on the worker's core on a virtual
/// machine (pass_team.hpp). Past it, the sleep's wake-up costs little against the wait.
inline constexpr std::chrono::microseconds run_spin_budget{2000};

/// One pause of a spin loop (the x86 PAUSE instruction; nothing elsewhere).
inline void cpu_pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

/// The CPU this thread runs on, or -1 where the system does not say (glibc's sched_getcpu: a
/// read of the kernel's restartable-sequences area, no system call).
inline int current_cpu() {
#if defined(__linux__)
  return sched_getcpu();
#else
  return -1;
#endif
}

/// A thread as hold_off() names it (pthread_t on Linux; elsewhere nothing can be held).
#if defined(__linux__)
using ThreadHandle = pthread_t;
inline ThreadHandle current_thread() {
  return pthread_self();
}
#else
using ThreadHandle = int;
inline ThreadHandle current_thread() {
  return 0;
}
#endif

/// The cores a thread may run on, as the system allowed them when it was read (Linux; elsewhere
/// nothing is known and nothing can be asked).
class AllowedCores {
 public:
  /// Reads the calling thread's allowed cores.
  AllowedCores() {
#if defined(__linux__)
    CPU_ZERO(&set_);
    known_ = sched_getaffinity(0, sizeof(set_), &set_) == 0;
#endif
  }
  /// Moves the calling thread off core `cpu`: allows it every core it was allowed but that one
  /// (the kernel migrates it within the call), then every core again (the kernel keeps a thread
  /// on a core it is allowed, so it stays where it moved). A move, not a pin: a thread kept off
  /// one core of two is held to the other, and a caller that wakes there later would share it
  /// while the first core idled. False, and nothing changed, where `cpu` is not known or is the
  /// only core allowed.
  bool leave(int cpu) const {
    if (!hold_off(current_thread(), cpu)) return false;
    restore();  // failing, it stays held off `cpu`: moved all the same
    return true;
  }
  /// Holds `thread` off core `cpu` until it calls restore(): a sleeping thread woken after this
  /// call wakes on another core. False, and nothing changed, where `cpu` is not known or is the
  /// only core allowed.
  bool hold_off(ThreadHandle thread, int cpu) const {
#if defined(__linux__)
    if (!known_ || cpu < 0 || cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &set_) ||
        CPU_COUNT(&set_) < 2) {
      return false;
    }
    cpu_set_t others = set_;
    CPU_CLR(cpu, &others);
    return pthread_setaffinity_np(thread, sizeof(others), &others) == 0;
#else
    (void)thread, (void)cpu;
    return false;
#endif
  }
  /// Allows the calling thread every core it was allowed when this was made.
  void restore() const {
#if defined(__linux__)
    if (known_) sched_setaffinity(0, sizeof(set_), &set_);
#endif
  }

 private:
#if defined(__linux__)
  cpu_set_t set_{};
#endif
  bool known_ = false;
};

/// A worker's wake-ups steered off the core of the thread that wakes it. A thread woken on a
/// virtual machine tends to land on its waker's core even with the other core idle (a halted
/// virtual CPU is not offered to it), and there it waits until the waker stops: a game's tick
/// at 60 Hz, whose worker sleeps between ticks, lost its second thread that way in most ticks.
/// The worker names itself (serve()), says when it gives up spinning (doze()) and when its wait
/// ended (awake()); the waker, before each wake-up, holds a dozing worker off its own core
/// (before_wake()) until the worker is awake and allows itself every core again.
class WakeSteering {
 public:
  /// Worker: the calling thread is the one steered, allowed `cores` (which outlive its use).
  void serve(const AllowedCores& cores) {
    cores_ = &cores;
    worker_ = current_thread();  // both published to the waker by doze()
  }
  /// Worker: it gives up spinning and sleeps unless woken first. True.
  bool doze() {
    dozing_.store(true, std::memory_order_release);
    return true;
  }
  /// Worker: its wait ended; it allows itself every core again if it was held off one.
  void awake() {
    dozing_.store(false, std::memory_order_relaxed);
    if (held_.load(std::memory_order_acquire)) {
      cores_->restore();
      held_.store(false, std::memory_order_relaxed);
    }
  }
  /// Waker, on core `cpu`, before it wakes the worker: a worker that dozed is held off `cpu`.
  /// (Its release store that wakes the worker publishes this to awake().)
  void before_wake(int cpu) {
    if (dozing_.load(std::memory_order_acquire) && !held_.load(std::memory_order_relaxed) &&
        cores_->hold_off(worker_, cpu)) {
      held_.store(true, std::memory_order_relaxed);
    }
  }

 private:
  /// The worker gave up spinning (set by it, cleared as its wait ends); the waker held it off
  /// its core (set by the waker, cleared by the worker once it allows itself every core).
  std::atomic<bool> dozing_{false}, held_{false};
  const AllowedCores* cores_ = nullptr;
  ThreadHandle worker_{};
};

/// What a wait did, for the tests: whether it ended by sleeping (std::atomic::wait).
enum class WaitEnd : unsigned char { spun, slept };

/// When a spinning wait gives up and sleeps: after spin_budget (the default), or on the first
/// check (every 64 pauses) where `give_up()` says so.
struct SpinBudget {
  bool (*give_up)(void*) = nullptr;  ///< nullptr: spin_budget
  void* ctx = nullptr;
};

/// Whether a spinning thread was off its core between two of its checks `last` and `now`
/// (64 pauses apart: microseconds): then another thread needed the core, which the spin holds
/// whenever it runs.
inline bool was_preempted(std::chrono::steady_clock::time_point last,
                          std::chrono::steady_clock::time_point now) {
  return now - last > spin_budget;
}

/// A caller's wait for its worker's job (PassTeam, Workers): it spins until its budget ends,
/// but gives up (and sleeps) at once on the worker's core, and when it finds it was preempted
/// (a busy machine). For SpinBudget::give_up, through the owner's own function.
class CallerWait {
 public:
  /// Starts a wait that may spin for `budget`.
  void start(std::chrono::microseconds budget) {
    checked_ = std::chrono::steady_clock::now();
    until_ = checked_ + budget;
  }
  /// Whether the waiting caller sleeps now, the worker last seen on core `worker_cpu` (-1:
  /// unknown).
  bool gives_up(int worker_cpu) {
    const auto now = std::chrono::steady_clock::now();
    const bool preempted = was_preempted(checked_, now);
    checked_ = now;
    const int here = current_cpu();
    return (here >= 0 && here == worker_cpu) || preempted || now >= until_;
  }

 private:
  std::chrono::steady_clock::time_point until_{}, checked_{};
};

/// Returns once `word` no longer holds `old` (acquire), the value it then holds in `now`: spins
/// on it, checking `budget` once every 64 pauses, then sleeps on it (std::atomic::wait: a futex
/// on Linux) until another thread stores a new value and calls notify_one() or notify_all() on
/// it. The storer must notify after every store a waiter may wait for (cheap when none sleeps).
inline WaitEnd wait_for_change(const std::atomic<unsigned>& word, unsigned old, unsigned& now,
                               SpinBudget budget = {}) {
  now = word.load(std::memory_order_acquire);
  if (now != old) return WaitEnd::spun;
  using Clock = std::chrono::steady_clock;  // read only without give_up: it keeps its own time
  const auto until = budget.give_up ? Clock::time_point{} : Clock::now() + spin_budget;
  for (unsigned i = 1;; ++i) {
    cpu_pause();
    now = word.load(std::memory_order_acquire);
    if (now != old) return WaitEnd::spun;
    if (i % 64 != 0) continue;
    if (budget.give_up ? budget.give_up(budget.ctx) : Clock::now() >= until) {
      break;
    }
  }
  do {
    word.wait(old, std::memory_order_acquire);
    now = word.load(std::memory_order_acquire);
  } while (now == old);
  return WaitEnd::slept;
}

}  // namespace fixstep::detail
