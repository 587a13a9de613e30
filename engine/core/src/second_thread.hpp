// The second thread of a world's disc contacts: from the integration to the contact events,
// the tick's passes over discs, pairs and contacts (the broadphase, the impact predictions,
// the gathering, the resting solver, the events) share their work by halves with it. Internal
// to the engine: not installed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>

#include "pass_team.hpp"
#include "workers.hpp"

namespace fixstep::detail {

/// A worker thread started on first use, serving one PassTeam for its whole life: both() posts
/// half of a pass to it, and runs that half itself when the worker has not claimed it by the
/// time the caller's own half is done.
///
/// A run (open() ... close(), one tick's disc phases) marks the passes that share their work
/// (callers ask is_open() before they split a pass); within it the worker spins between
/// passes, outside it sleeps after a short spin (PassTeam), so an idle world costs no CPU. A copy
/// (a snapshot) starts without a thread and outside a run; copying into one (a snapshot
/// restored) keeps its worker and ends its run: a thread holds no state a tick's result
/// depends on, and a rollback restores every frame.
class SecondThread {
 public:
  SecondThread() = default;
  SecondThread(const SecondThread& /*other*/) noexcept {}
  SecondThread& operator=(const SecondThread& other) noexcept {
    if (this != &other) close();
    return *this;
  }
  ~SecondThread() { stop(); }

  /// Starts a run (the worker started if it is not yet).
  void open() {
    start();
    if (!open_) state_->team.set_run(true);
    open_ = true;
  }
  /// Ends the run; nothing if none is open.
  void close() noexcept {
    if (open_) state_->team.set_run(false);
    open_ = false;
  }
  [[nodiscard]] bool is_open() const { return open_; }

  /// Runs job(1) on the worker (or here, if the worker has not started it when job(0) is done)
  /// while this thread runs job(0), and returns when both have finished (job(1) also when
  /// job(0) throws, before the exception leaves). An exception of job(1) (std::bad_alloc as a
  /// vector grows) is thrown here, after job(0) has finished.
  template <class Job>
  void both(Job& job) {
    start();
    ++handed_;
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
    state_->team.post(run, &half);
    try {
      job(0);
    } catch (...) {
      state_->team.wait();
      throw;
    }
    state_->team.wait();
    if (half.error) std::rethrow_exception(half.error);
  }
  /// Passes handed to the worker so far (both() calls; a copy counts from 0): a tick that
  /// handed one ran on two threads (World::threads_used()).
  [[nodiscard]] std::uint64_t handed() const { return handed_; }
  /// For the tests: the team the worker serves (nullptr before the first use).
  [[nodiscard]] const PassTeam* team() const { return state_ ? &state_->team : nullptr; }

 private:
  struct State {
    PassTeam team;
    Workers workers;  // last: its thread stops before the team it serves goes
  };
  void start() {
    if (state_) return;
    state_ = std::make_unique<State>();
    state_->workers.submit(&PassTeam::serve, &state_->team);
  }
  void stop() noexcept {
    if (state_) state_->team.finish();
    state_.reset();  // joins the worker, which leaves serve() at finish()
  }
  std::unique_ptr<State> state_;
  std::uint64_t handed_ = 0;
  bool open_ = false;
};

/// Runs pass(begin, end, half) over [0, n): as two halves (0 and 1) on `thread` when given and
/// n >= 2, else as one (half 0) here. For passes whose items are independent: the same result
/// either way.
template <class Pass>
void run_halves(SecondThread* thread, std::size_t n, Pass&& pass) {
  if (thread == nullptr || n < 2) {
    pass(std::size_t{0}, n, 0);
    return;
  }
  auto job = [&](int half) { half == 0 ? pass(std::size_t{0}, n / 2, 0) : pass(n / 2, n, 1); };
  thread->both(job);
}

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
