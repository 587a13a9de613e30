// The second thread of a world's passes (engine/core/src/second_thread.hpp, pass_team.hpp,
// spin_wait.hpp): an exception on the worker reaches the caller, in a run and outside one; a
// nested run leaves the outer one open; copying into one keeps its worker; a job the worker has
// not claimed is run by the caller;
// a wait with nothing posted returns; opening a run wakes a sleeping worker;
// on one core the two threads take turns by sleeping, not by spinning; a thread asked to leave a
// core does, and is not pinned by it; a thread held off a core wakes elsewhere; and a worker woken
// after a frame's sleep (the disc contacts' and the links') runs off the stepping thread's core.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <sched.h>
#endif

#include "pass_team.hpp"
#include "second_thread.hpp"
#include "workers.hpp"

namespace fixstep::detail {
namespace {

// A pass whose second half throws (std::bad_alloc as a vector grows, say): both() returns the
// exception to the caller once the first half is done, inside a run and outside one, and the
// thread serves the next pass. Without the hand-back, the worker would end the program.
TEST(SecondThread, AnExceptionOfTheWorkersHalfIsThrownOnTheCaller) {
  SecondThread thread;
  for (const bool run : {false, true}) {
    if (run) thread.open();
    int first = 0, second = 0;
    auto failing = [&](int half) {
      if (half == 1) throw std::runtime_error("half 1");
      first = 1;
    };
    EXPECT_THROW(thread.both(failing), std::runtime_error) << "run " << run;
    EXPECT_EQ(first, 1);  // the caller's half ran to its end
    auto working = [&](int half) { (half == 0 ? first : second) = 2; };
    thread.both(working);
    EXPECT_EQ(first, 2);
    EXPECT_EQ(second, 2);
    EXPECT_EQ(thread.is_open(), run);
  }
  thread.close();
  EXPECT_FALSE(thread.is_open());
}

// A world opens a run for its tick and the disc phase asks for one again: the inner scope
// neither opens nor closes it; close() ends a run before its scope does.
TEST(SecondThread, ANestedRunLeavesTheOuterOneOpen) {
  SecondThread thread;
  {
    const SecondThreadRun outer(&thread);
    EXPECT_TRUE(thread.is_open());
    {
      const SecondThreadRun inner(&thread);
      EXPECT_TRUE(thread.is_open());
    }
    EXPECT_TRUE(thread.is_open());
  }
  EXPECT_FALSE(thread.is_open());
  {  // closed before the scope ends (a tick after its contact events): once, and for good
    SecondThreadRun run(&thread);
    SecondThreadRun inner(&thread);
    inner.close();
    EXPECT_TRUE(thread.is_open());
    run.close();
    EXPECT_FALSE(thread.is_open());
    run.close();
  }
  EXPECT_FALSE(thread.is_open());
  const SecondThreadRun none(nullptr);
  EXPECT_FALSE(thread.is_open());
}

// A snapshot copies a world's SecondThread without its worker; a restore copies into the
// world's own, which keeps its worker (a rollback restores every frame: stopping the worker
// there started a thread a frame) and ends its run; the worker serves the next pass.
TEST(SecondThread, CopyingIntoOneKeepsItsWorkerAndEndsItsRun) {
  SecondThread thread;
  thread.open();
  int halves = 0;
  auto count = [&](int half) {
    if (half == 0) halves += 1;
  };
  thread.both(count);
  const PassTeam* team = thread.team();
  ASSERT_NE(team, nullptr);
  const SecondThread copy(thread);
  EXPECT_EQ(copy.team(), nullptr);
  EXPECT_FALSE(copy.is_open());
  thread = copy;
  EXPECT_EQ(thread.team(), team);
  EXPECT_FALSE(thread.is_open());
  int second = 0;
  auto mark = [&](int half) {
    if (half == 1) second = 1;
  };
  thread.both(mark);
  EXPECT_EQ(second, 1);
  EXPECT_EQ(halves, 1);
}

// A job posted to a team that no worker serves (the worker not started yet, or not running):
// wait() runs it on the caller instead of waiting for a thread that would take it late.
TEST(PassTeam, AJobTheWorkerHasNotClaimedRunsOnTheCaller) {
  PassTeam team;
  int runs = 0;
  auto job = [](void* p) { ++*static_cast<int*>(p); };
  for (int k = 0; k < 3; ++k) {
    team.post(job, &runs);
    team.wait();
  }
  EXPECT_EQ(runs, 3);
  EXPECT_EQ(team.run_here(), 3u);
  // A worker started late sees that the jobs were taken, and serves the next ones or ends.
  std::thread worker(&PassTeam::serve, &team);
  team.post(job, &runs);
  team.wait();
  EXPECT_EQ(runs, 4);
  team.finish();
  worker.join();
}

// wait() with nothing posted since the last one returns at once. It waited for the worker to
// finish the last job, which the caller had run itself: forever.
TEST(PassTeam, AWaitWithNothingPostedSinceTheLastReturns) {
  static PassTeam team;                      // outlives a waiter that hangs
  static std::atomic<bool> returned{false};  // set by that waiter
  int runs = 0;
  team.post([](void* p) { ++*static_cast<int*>(p); }, &runs);
  team.wait();  // no worker: run here
  EXPECT_EQ(runs, 1);
  std::thread([] {
    team.wait();
    returned = true;
  }).detach();
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!returned && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(returned) << "a second wait() did not return";
  EXPECT_EQ(runs, 1);
}

// A tick opens its run before its first split pass (the integration, the planes run first):
// opening wakes a worker that slept since the last tick, so that it spins by that pass instead
// of waking at it. At 60 ticks a second the worker sleeps between ticks, and a wake-up at the
// first pass (a futex on a virtual machine) cost the 10^4-disc gas's tick more than the second
// thread saved.
TEST(SecondThread, OpeningARunWakesASleepingWorker) {
  SecondThread thread;
  auto nothing = [](int) {};
  thread.both(nothing);  // starts the worker
  // Outside a run the worker sleeps spin_budget after the last pass.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_NE(thread.team(), nullptr);
  const unsigned slept = thread.team()->worker_slept();  // its waits that ended asleep
  const SecondThreadRun run(&thread);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (thread.team()->worker_slept() == slept && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  EXPECT_GT(thread.team()->worker_slept(), slept) << "the worker slept on after the run opened";
}

#if defined(__linux__)
/// Pins this thread (and the threads it starts after) to one core for a scope.
class OneCore {
 public:
  OneCore() {
    pinned_ = sched_getaffinity(0, sizeof(old_), &old_) == 0;
    cpu_set_t one;
    CPU_ZERO(&one);
    for (int c = 0; c < CPU_SETSIZE && pinned_; ++c) {
      if (CPU_ISSET(c, &old_)) {
        CPU_SET(c, &one);
        break;
      }
    }
    pinned_ = pinned_ && sched_setaffinity(0, sizeof(one), &one) == 0;
  }
  ~OneCore() {
    if (pinned_) sched_setaffinity(0, sizeof(old_), &old_);
  }
  OneCore(const OneCore&) = delete;
  OneCore& operator=(const OneCore&) = delete;
  [[nodiscard]] bool pinned() const { return pinned_; }

 private:
  cpu_set_t old_{};
  bool pinned_ = false;
};

// Both threads on one core (the other core busy, or the scheduler's choice), inside a run:
// every pass's halves run once, and the worker, given the core while the caller sleeps, gives
// it up by sleeping while it waits for a pass. A worker that spun there (a yield does not reliably
// hand the core over) kept the caller from running for a scheduler's time slice, about a
// millisecond, at every pass: two threads then took twelve times as long as one on the 1000-disc
// gas.
TEST(SecondThread, OnOneCoreTheWorkerSleepsWhileItWaits) {
  const OneCore one;
  if (!one.pinned()) GTEST_SKIP() << "this system did not let the test pin itself to one core";
  SecondThread thread;
  const SecondThreadRun run(&thread);
  constexpr int passes = 200;
  std::vector<int> ran(2 * passes, 0);
  for (int k = 0; k < passes; ++k) {
    auto job = [&](int half) { ++ran[2 * k + half]; };
    thread.both(job);
    // The caller off the core for a moment, as between a tick's passes: the worker gets it.
    if (k % 10 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  for (int i = 0; i < 2 * passes; ++i)
    ASSERT_EQ(ran[i], 1) << "half " << i % 2 << " of pass " << i / 2;
  ASSERT_NE(thread.team(), nullptr);
  EXPECT_GT(thread.team()->worker_slept(), 0u)
      << "the worker never slept while it waited on the caller's core ("
      << thread.team()->run_here() << " of " << passes << " halves ran on the caller)";
}

/// The number of cores the calling thread is allowed, or -1 where the system does not say.
int allowed_count() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  return sched_getaffinity(0, sizeof(allowed), &allowed) == 0 ? CPU_COUNT(&allowed) : -1;
}

// A thread allowed two cores or more leaves the one it is asked to leave at once (the kernel
// migrates it within the call), and is allowed every core again after: a move, not a pin. A
// worker held to the one other core of two stayed there, and the stepping thread, woken there
// after a frame's sleep, shared it with the worker through the tick while its own core idled.
// One allowed a single core stays.
TEST(AllowedCores, LeaveMovesTheThreadOffTheCoreWithoutPinningIt) {
  std::thread mover([] {
    const AllowedCores cores;
    const int here = current_cpu();
    const int count = allowed_count();
    if (count < 2) {
      EXPECT_FALSE(cores.leave(here));
      return;
    }
    ASSERT_TRUE(cores.leave(here));
    EXPECT_NE(current_cpu(), here);
    EXPECT_EQ(allowed_count(), count) << "the thread was left held off core " << here;
    EXPECT_FALSE(cores.leave(-1));
  });
  mover.join();
  const OneCore one;
  if (!one.pinned()) return;
  std::thread pinned([] { EXPECT_FALSE(AllowedCores().leave(current_cpu())); });
  pinned.join();
}

// hold_off keeps another thread off a core (a sleeping thread wakes elsewhere) until that
// thread calls restore().
TEST(AllowedCores, HoldOffKeepsAnotherThreadOffTheCoreUntilItRestores) {
  if (allowed_count() < 2) GTEST_SKIP() << "one core allowed: nowhere else to hold a thread";
  std::atomic<int> ready{0}, go{0};
  ThreadHandle handle{};
  int woke_on = -1, held_count = -1, restored_count = -1;
  std::thread sleeper([&] {
    const AllowedCores cores;
    handle = current_thread();
    ready = 1;
    ready.notify_one();
    go.wait(0);
    woke_on = current_cpu(), held_count = allowed_count();
    cores.restore();
    restored_count = allowed_count();
  });
  ready.wait(0);
  const int here = current_cpu();
  const AllowedCores cores;  // this thread's cores: the sleeper's, inherited
  ASSERT_TRUE(cores.hold_off(handle, here));
  go = 1;
  go.notify_one();
  sleeper.join();
  const int count = allowed_count();
  EXPECT_NE(woke_on, here);
  EXPECT_EQ(held_count, count - 1);
  EXPECT_EQ(restored_count, count);
}

// A game steps its world once a frame: the worker sleeps between ticks, and the tick's first
// pass wakes it. Woken from a frame's sleep on a virtual machine, it landed on the stepping
// thread's core in most ticks (the other core idle) and waited there for the tick to end, the
// stepping thread running every half itself. Each of 12 frames here: this thread and the worker
// asleep for a frame, then a pass whose first half waits for the second: the worker must run
// the second half on another core, allowed every core again.
TEST(SecondThread, AWorkerWokenAfterAFrameRunsOffTheCallersCoreUnpinned) {
  if (allowed_count() < 2) GTEST_SKIP() << "one core allowed: the two threads share it";
  SecondThread thread;
  auto nothing = [](int) {};
  thread.both(nothing);  // starts the worker
  ASSERT_NE(thread.team(), nullptr);
  const int count = allowed_count();
  constexpr int frames = 12;
  int shared = 0;
  for (int f = 0; f < frames; ++f) {
    const unsigned slept = thread.team()->worker_slept();
    // A frame's sleep: the worker sleeps spin_budget after the last pass.
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
    const SecondThreadRun run(&thread);
    std::atomic<bool> second_done{false};
    int caller_cpu = -1, worker_cpu = -1, worker_count = -1;
    auto pass = [&](int half) {
      if (half == 1) {
        worker_cpu = current_cpu(), worker_count = allowed_count();
        second_done = true;
        return;
      }
      caller_cpu = current_cpu();
      const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
      while (!second_done && std::chrono::steady_clock::now() < end) cpu_pause();
    };
    thread.both(pass);
    ASSERT_TRUE(second_done) << "frame " << f << ": the worker never ran its half";
    ASSERT_GT(thread.team()->worker_slept(), slept) << "frame " << f << ": the worker never slept";
    if (caller_cpu < 0 || worker_cpu < 0) GTEST_SKIP() << "this system does not say which core";
    shared += worker_cpu == caller_cpu ? 1 : 0;
    EXPECT_EQ(worker_count, count) << "frame " << f << ": the worker ran held off a core";
  }
  EXPECT_EQ(shared, 0) << "of " << frames << " frames, the worker ran its half on the caller's "
                       << "core in " << shared;
}

// The links' worker (Workers) is woken for each pass: after a frame's sleep it must also wake
// off the caller's core, and allowed every core again. Without the hold it ran on the caller's
// core, where the caller, spinning on its own share, kept it waiting.
TEST(Workers, AWorkerWokenAfterAFrameRunsOffTheCallersCoreUnpinned) {
  if (allowed_count() < 2) GTEST_SKIP() << "one core allowed: the two threads share it";
  Workers workers;
  struct Job {
    std::atomic<bool> done{false};
    int cpu = -1, count = -1;
  } job;
  auto run = [](void* p) {
    auto* j = static_cast<Job*>(p);
    j->cpu = current_cpu(), j->count = allowed_count();
    j->done = true;
  };
  const int count = allowed_count();
  constexpr int frames = 12;
  int shared = 0;
  for (int f = 0; f < frames; ++f) {
    std::this_thread::sleep_for(std::chrono::milliseconds(16));  // the worker sleeps
    job.done = false;
    const int here = current_cpu();
    workers.submit(run, &job);
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (!job.done && std::chrono::steady_clock::now() < end) cpu_pause();  // the caller's share
    workers.wait();
    ASSERT_TRUE(job.done) << "frame " << f;
    if (here < 0 || job.cpu < 0) GTEST_SKIP() << "this system does not say which core";
    shared += job.cpu == here ? 1 : 0;
    EXPECT_EQ(job.count, count) << "frame " << f << ": the worker ran held off a core";
  }
  EXPECT_EQ(shared, 0) << "of " << frames << " frames, the worker ran on the caller's core in "
                       << shared;
}
#endif

// Within a run the caller waits for a worker's half on another core by spinning, up to
// run_spin_budget: woken from a sleep by the worker on a virtual machine, it landed on the
// worker's core and waited there for it, the second thread's work lost. Passes whose second
// half takes a millisecond: with spin_budget the caller slept through every one, always. A busy
// machine (CI runs the tests two at a time beside clang-tidy) preempts the caller, which then
// rightly sleeps (6 to 10 of 12 seen there): of five tries of twelve passes, one must have the
// caller awake through at least one pass.
TEST(SecondThread, WithinARunTheCallerSpinsForTheWorkersLongHalf) {
  if (threads_for(0) < 2) GTEST_SKIP() << "one core: the caller rightly sleeps";
  SecondThread thread;
  const SecondThreadRun run(&thread);
  constexpr unsigned passes = 12;
  std::atomic<bool> started{false};
  // The first half returns once the worker has started the second, which takes a millisecond.
  auto pass = [&](int half) {
    const auto now = std::chrono::steady_clock::now();
    if (half == 0) {
      while (!started && std::chrono::steady_clock::now() < now + std::chrono::seconds(5)) {
        cpu_pause();
      }
      return;
    }
    started = true;
    while (std::chrono::steady_clock::now() < now + std::chrono::milliseconds(1)) cpu_pause();
  };
  ASSERT_NE(thread.team(), nullptr);
  std::vector<unsigned> slept_in;
  for (int attempt = 0; attempt < 5; ++attempt) {
    const unsigned slept = thread.team()->caller_slept(), here = thread.team()->run_here();
    for (unsigned k = 0; k < passes; ++k) {
      started = false;
      thread.both(pass);
    }
    ASSERT_EQ(thread.team()->run_here(), here) << "the caller ran a second half";
    slept_in.push_back(thread.team()->caller_slept() - slept);
    if (slept_in.back() < passes) return;
  }
  ADD_FAILURE() << "the caller slept through " << slept_in[0] << ", " << slept_in[1] << ", "
                << slept_in[2] << ", " << slept_in[3] << " and " << slept_in[4] << " of " << passes
                << " of the worker's halves";
}

}  // namespace
}  // namespace fixstep::detail
