// The second thread of a world's disc contacts: from the integration to the contact events,
// the tick's passes over discs, pairs and contacts (the broadphase, the impact predictions,
// the gathering, the resting solver, the events) share their work by halves with it. Internal
// to the engine: not installed.
#pragma once

#include <exception>
#include <memory>

#include "pass_team.hpp"
#include "workers.hpp"

namespace fixstep::detail {

/// A worker thread started on first use, and two ways to hand it half of a pass:
/// - outside a run (open() not called), each both() wakes the worker (Workers: a futex wait
///   between calls, so an idle world costs no CPU);
/// - inside a run (open() ... close(), one tick's disc phases), the worker spins between passes
///   (PassTeam), since a futex wake-up costs tens of microseconds on a virtual machine, more
///   than many of a tick's passes take.
/// A copy (a snapshot) starts without a thread and outside a run.
class SecondThread {
 public:
  SecondThread() = default;
  SecondThread(const SecondThread& /*other*/) noexcept {}
  SecondThread& operator=(const SecondThread& other) noexcept {
    if (this != &other) close(), state_.reset();
    return *this;
  }
  ~SecondThread() { close(); }

  /// Starts a run: until close(), the worker waits for the next pass by spinning.
  void open() {
    if (open_) return;
    start();
    state_->workers.submit(&PassTeam::serve, &state_->team);
    open_ = true;
  }
  /// Ends the run (the worker then sleeps between calls); nothing if none is open.
  void close() noexcept {
    if (!open_) return;
    state_->team.finish();
    state_->workers.wait();
    open_ = false;
  }
  [[nodiscard]] bool is_open() const { return open_; }

  /// Runs job(1) on the worker while this thread runs job(0), and returns when both have
  /// finished (job(1) also when job(0) throws, before the exception leaves). An exception of
  /// job(1) (std::bad_alloc as a vector grows) is thrown here, after job(0) has finished.
  template <class Job>
  void both(Job& job) {
    start();
    struct Half {
      Job* job;
      std::exception_ptr error;
    } half{&job, nullptr};
    auto run = [](void* p) {
      auto* h = static_cast<Half*>(p);
      try {
        (*h->job)(1);
      } catch (...) {
        h->error = std::current_exception();
      }
    };
    if (open_) {
      state_->team.post(run, &half);
    } else {
      state_->workers.submit(run, &half);
    }
    try {
      job(0);
    } catch (...) {
      wait();
      throw;
    }
    wait();
    if (half.error) std::rethrow_exception(half.error);
  }

 private:
  struct State {
    PassTeam team;
    Workers workers;  // last: its thread stops before the team it may serve goes
  };
  void start() {
    if (!state_) state_ = std::make_unique<State>();
  }
  void wait() {
    if (open_) {
      state_->team.wait();
    } else {
      state_->workers.wait();
    }
  }
  std::unique_ptr<State> state_;
  bool open_ = false;
};

/// Keeps a SecondThread's run open for a scope (a tick's disc phases), and closes it on the way
/// out (or at close()), by return or by exception; nothing when given no thread, or one whose run
/// an outer scope keeps open.
class SecondThreadRun {
 public:
  explicit SecondThreadRun(SecondThread* thread)
      : thread_(thread != nullptr && !thread->is_open() ? thread : nullptr) {
    if (thread_) thread_->open();
  }
  ~SecondThreadRun() { close(); }
  /// Ends the run before the scope does (the worker then sleeps); nothing if it holds none.
  void close() noexcept {
    if (thread_) thread_->close();
    thread_ = nullptr;
  }
  SecondThreadRun(const SecondThreadRun&) = delete;
  SecondThreadRun& operator=(const SecondThreadRun&) = delete;

 private:
  SecondThread* thread_;
};

}  // namespace fixstep::detail
