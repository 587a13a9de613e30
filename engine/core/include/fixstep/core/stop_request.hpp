// A request to stop a long operation early, process-wide as signals are: a SIGINT handler (or
// another thread) calls request_stop(); the long loops of the engine — a tick's substeps, the
// Newton iterations and sparse factorizations of implicit Euler, the stability guard's power
// iteration — poll it and throw StopRequested, so a command can stop within a second even when
// one tick takes hours. Polling costs one relaxed atomic load per substep or iteration.
//
// A tick that throws StopRequested is abandoned half-way: the world's state is then neither the
// state before the tick nor after it. Discard the world or restore a snapshot taken before the
// tick; the outputs of the ticks completed before it (CSV rows, recorded ticks, frames) are whole.
//
// A thread's own work can also be stopped alone: a StopScope makes the calling thread's polls see
// a flag of its owner's too (a background load that the program cancels while its main thread
// goes on stepping a world: a process-wide request would stop that as well).
#pragma once

#include <atomic>
#include <stdexcept>

namespace fixstep {

/// Thrown by a long engine operation that saw a stop request. `signal()` is the value given to
/// request_stop() (a signal number for the CLI, any non-zero value for a program).
class StopRequested : public std::runtime_error {
 public:
  explicit StopRequested(int signal);
  [[nodiscard]] int signal() const noexcept { return signal_; }

 private:
  int signal_;
};

/// Requests a stop; `signal` must be non-zero. Async-signal-safe (a lock-free atomic store).
void request_stop(int signal) noexcept;

/// The value of the pending request, or 0 when none is pending. Async-signal-safe.
[[nodiscard]] int stop_requested() noexcept;

/// Withdraws a pending request (a command does this when it starts).
void clear_stop_request() noexcept;

/// Throws StopRequested when a stop is pending; otherwise does nothing.
void throw_if_stop_requested();

/// While this lives, stop_requested() on the thread that made it returns `flag`'s value when no
/// process-wide request is pending (so throw_if_stop_requested() throws once it is non-zero):
/// another thread stops this thread's work by storing a non-zero value in `flag`, which must
/// outlive the scope. Scopes nest (the innermost flag is seen).
class StopScope {
 public:
  explicit StopScope(const std::atomic<int>& flag) noexcept;
  ~StopScope();
  StopScope(const StopScope&) = delete;
  StopScope& operator=(const StopScope&) = delete;

 private:
  const std::atomic<int>* previous_;
};

}  // namespace fixstep
