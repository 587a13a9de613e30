// An SDL2 window that presents frames rendered by fixstep::Renderer, pixel for pixel.
// Separate library target (fixstep::window) so headless users do not link SDL2.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include "fixstep/types.hpp"

namespace fixstep {

/// The window could not open: no display, SDL initialisation or window creation failed.
class WindowError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Key presses since the last poll(), and the held arrow keys.
struct WindowEvents {
  bool quit = false;          ///< Esc or the close button
  bool toggle_pause = false;  ///< space
  bool single_step = false;   ///< '.'
  int time_scale_steps = 0;   ///< '+' = +1, '-' = -1 (each press)
  bool restart = false;       ///< 'r'
  Vec2 push_direction{};      ///< arrow keys held: components in {-1, 0, 1}
};

class Window {
 public:
  /// Opens a width x height window (pixels). Throws WindowError when there is no display
  /// (neither DISPLAY nor WAYLAND_DISPLAY set and no SDL_VIDEODRIVER chosen) or SDL fails.
  Window(const std::string& title, int width, int height);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  /// Drains SDL's event queue.
  WindowEvents poll();
  /// Shows an RGBA8 frame (height rows of width*4 bytes, top row first), unscaled when the
  /// window has the frame's size. Throws WindowError if the frame has the wrong size.
  void present(std::span<const std::uint8_t> rgba);
  /// SDL's name for the video driver in use (e.g. "x11").
  [[nodiscard]] std::string driver() const;

  struct Impl;

 private:
  Impl* impl_;
};

}  // namespace fixstep
