// SIGINT / SIGTERM during a long command (fixstep run, render, compare; a game, a match): the
// handler records the signal and calls fixstep::request_stop, so the engine's long loops throw
// StopRequested inside the tick in progress (stop_request.hpp); the command discards that tick,
// writes out everything produced before it (the CSV, every queued frame) and exits 128 + the signal
// number, as a shell reports a signal death.
#pragma once

namespace fixstep {

/// Installs a recording handler for SIGINT and SIGTERM for the lifetime of the object (one at a
/// time); requested() is the signal received since, or 0.
class StopOnSignal {
 public:
  /// `interrupt_ticks` false: the handler only records the signal (no request_stop), so no tick
  /// is abandoned half-way; for a program whose loop polls requested() between ticks and whose
  /// ticks must stay whole (a networked match: a peer's bookkeeping follows every tick).
  explicit StopOnSignal(bool interrupt_ticks = true);
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  [[nodiscard]] static int requested();
  /// "SIGINT" or "SIGTERM".
  [[nodiscard]] static const char* name();

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

}  // namespace fixstep
