// What a game run by fixstep::app::run draws over its world each frame (Game::draw).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace fixstep::app {

/// Lines of text a game adds to the HUD each frame (a score, a hint), drawn below the engine's
/// lines in the bitmap font (ASCII only). Emptied before each draw().
class Overlay {
 public:
  /// Adds one line.
  void text(std::string line) { lines_.push_back(std::move(line)); }
  /// The lines added since the last clear(), in order.
  [[nodiscard]] const std::vector<std::string>& lines() const { return lines_; }
  /// Forgets every line (run() does before each Game::draw).
  void clear() { lines_.clear(); }

 private:
  std::vector<std::string> lines_;
};

}  // namespace fixstep::app
