// Progress of a long `run` or `render` on a terminal: one line on standard error, rewritten in
// place, e.g. "render: frame 37/120 (31 %)  52.1 frames/s  1.6 s left". Nothing at all when
// standard error is not a terminal (CI logs, pipes) or with --quiet.
#pragma once

#include <chrono>
#include <cstdint>
#include <fixstep/core/work_progress.hpp>
#include <optional>
#include <string>

namespace fixstep::cli {

/// A line of free text on standard error, rewritten in place at most every 0.1 s, while some
/// work without a count goes on (e.g. "loading s.toml: building the world, 2.1 s"). Nothing when
/// standard error is not a terminal or when not enabled (--quiet).
class StatusLine {
 public:
  explicit StatusLine(bool enabled);
  ~StatusLine();
  StatusLine(const StatusLine&) = delete;
  StatusLine& operator=(const StatusLine&) = delete;
  /// Shows `text` in place of the line shown before (unless that was less than 0.1 s ago).
  void show(const std::string& text) {
    if (due()) draw(text);
  }
  /// Shows `text` now, however recently the line was drawn.
  void draw(const std::string& text);
  /// Whether the line is shown (enabled and a terminal).
  [[nodiscard]] bool shown() const { return shown_; }
  /// Whether show() would draw now: shown, and not drawn within the last 0.1 s.
  [[nodiscard]] bool due() const;
  /// Erases the line (also done by the destructor).
  void finish();

 private:
  bool shown_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

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
  [[nodiscard]] bool shown() const { return line_.shown(); }

 private:
  std::string what_, unit_;
  std::uint64_t total_;
  std::chrono::steady_clock::time_point start_;
  StatusLine line_;
};

/// The engine's long work that a program does not loop over itself (a scene's generators, the
/// stability guard's power iteration on a large network, replay(): work_progress.hpp) shown as
/// a Progress line while this lives, e.g. "generating the scene: body 65536/1000000 ...",
/// "stability guard: iteration 310/10000 ..." (10000 is the iteration's limit; it usually stops
/// far sooner) or "replay: tick 4096/300000 ...". Each new kind of work (what, unit, total)
/// starts a line of its own.
class WorkProgressLine {
 public:
  explicit WorkProgressLine(bool enabled);
  /// Erases the line shown, if any (so that what follows starts on a clean line).
  void finish() { line_.reset(); }

 private:
  bool enabled_;
  std::string what_, unit_;
  std::uint64_t total_ = 0;
  std::optional<Progress> line_;
  WorkProgressScope scope_;
};

}  // namespace fixstep::cli
