// What a game run by fixstep::app::run draws over its world each frame (Game::draw): shapes in
// world or screen coordinates (a DrawList), drawn after the bodies and under the HUD, and lines
// of text added to the HUD.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/world.hpp"
#include "fixstep/render/draw_list.hpp"
#include "fixstep/render/render.hpp"

namespace fixstep {
class Session;
}

namespace fixstep::app {

/// A game's drawing for one frame. The shapes (DrawList: line, polyline, circle, disc, rect,
/// polygon, arrow, label; world or screen coordinates) are drawn after the bodies, their trails,
/// springs and links, and before the HUD, which stays on top; text() adds lines to the HUD
/// below the engine's. run() empties the overlay before each Game::draw and keeps its storage:
/// drawing the same shapes every frame allocates nothing once warm.
///
/// A shape that follows a body must be placed where the body is drawn: position(body) is its
/// position interpolated between the last two ticks (the loop's alpha), as the body's disc is
/// drawn, not World::body(e).position (the last tick's), which runs up to a tick ahead.
class Overlay : public DrawList {
 public:
  /// Adds one line to the HUD (the bitmap font: ASCII only).
  void text(std::string_view line);
  /// The HUD lines added since the last clear(), in order.
  [[nodiscard]] std::span<const std::string> lines() const {
    return std::span(lines_).first(line_count_);
  }
  /// Forgets every shape and line, keeping the storage (run() does before each Game::draw).
  void clear();

  /// Where `body` is drawn in this frame, m (interpolated by the loop's alpha); nullopt for a
  /// body that is not live, or outside a draw.
  [[nodiscard]] std::optional<Vec2> position(Entity body) const;
  /// The world being drawn (read only), or nullptr outside a draw.
  [[nodiscard]] const World* world() const;
  /// The view this frame is drawn through (m): Space::world shapes go through it.
  [[nodiscard]] Camera camera() const;
  /// The frame's size, px (0 outside a draw).
  [[nodiscard]] int width() const;
  [[nodiscard]] int height() const;
  /// Pixel coordinates (Space::screen) of world point p (m) in this frame.
  [[nodiscard]] Vec2 to_screen(Vec2 p) const;

  /// The session being drawn: run() binds it before each Game::draw (Session::prepare_frame
  /// done) and unbinds it (nullptr) after. Not for games.
  void bind(const Session* session) { session_ = session; }

 private:
  std::vector<std::string> lines_;  ///< lines_[0, line_count_) are this frame's
  std::size_t line_count_ = 0;
  const Session* session_ = nullptr;
};

}  // namespace fixstep::app
