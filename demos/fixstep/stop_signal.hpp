// SIGINT / SIGTERM during a long command (run, render, compare): the handler only records the
// signal; the command finishes the tick or frame in progress, writes out everything produced so
// far (the CSV, every queued frame) and exits 128 + the signal number, as a shell reports a
// signal death.
#pragma once

namespace fixstep::cli {

/// Installs a recording handler for SIGINT and SIGTERM for the lifetime of the object (one at a
/// time); requested() is the signal received since, or 0.
class StopOnSignal {
 public:
  StopOnSignal();
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

}  // namespace fixstep::cli
