// Progress of a long `run` or `render` on a terminal: one line on standard error, rewritten in
// place, e.g. "render: frame 37/120 (31 %)  52.1 frames/s  1.6 s left". Nothing at all when
// standard error is not a terminal (CI logs, pipes) or with --quiet.
#pragma once

#include <chrono>
#include <cstdint>
#include <fixstep/work_progress.hpp>
#include <optional>
#include <string>

namespace fixstep::cli {

class Progress {
 public:
  /// `what` names the command ("render"), `unit` the item counted ("frame", "tick"), `total`
  /// the items to do (> 0). Shown only when `enabled` and standard error is a terminal.
  Progress(std::string what, std::string unit, std::uint64_t total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// `done` items finished: redraws the line at most every 0.1 s (and at the last item).
  void update(std::uint64_t done);
  /// Erases the line (also done by the destructor), so what follows starts on a clean line.
  void finish();

  /// Whether the line is shown (enabled and a terminal).
  [[nodiscard]] bool shown() const { return shown_; }

 private:
  std::string what_, unit_;
  std::uint64_t total_;
  bool shown_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

/// The engine's long work that a program does not loop over itself (the stability guard's power
/// iteration on a large network, replay(): work_progress.hpp) shown as a Progress line while
/// this lives, e.g. "stability guard: iteration 310/10000 ..." (10000 is the iteration's limit;
/// it usually stops far sooner) or "replay: tick 4096/300000 ...".
class WorkProgressLine {
 public:
  explicit WorkProgressLine(bool enabled);

 private:
  bool enabled_;
  std::optional<Progress> line_;
  WorkProgressScope scope_;
};

}  // namespace fixstep::cli
