// An SDL2 window that presents frames rendered by fixstep::Renderer, pixel for pixel.
// Separate library target (fixstep::window) so headless users do not link SDL2.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/input.hpp"
#include "fixstep/loop.hpp"
#include "fixstep/render.hpp"
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
  bool rewind = false;    ///< Backspace held: step time backwards (programs that keep snapshots)
  Vec2 push_direction{};  ///< arrow keys held: components in {-1, 0, 1}
  /// A press or release of tick-input buttons (InputButton bits: arrows, Enter, mouse
  /// buttons), in the order they happened.
  struct ButtonEdge {
    bool press = false;
    std::uint32_t buttons = 0;
  };
  std::vector<ButtonEdge> edges{};
  bool pointer_seen = false;                ///< the pointer is over the window (pointer is valid)
  double pointer_x = 0.0, pointer_y = 0.0;  ///< pixels from the top-left corner
};

/// Hands the tick-input part of `ev` to `sampler`: every button edge in order, and the pointer
/// converted to world metres through `camera` for a width x height frame (screen_to_world).
void feed(const WindowEvents& ev, InputSampler& sampler, const Camera& camera, int width,
          int height);

/// Applies the loop keys of `ev` to `loop`, the same in every fixstep window: space toggles
/// pause; '.' pauses and runs exactly one tick on the next advance(); each '+' doubles and each
/// '-' halves the time scale, kept within [1/16, max_time_scale]. Quit, restart and the arrow
/// keys are left to the caller (what they reset or push differs per program).
inline void apply_loop_keys(const WindowEvents& ev, FixedStepLoop& loop,
                            double max_time_scale = 16.0) {
  if (ev.toggle_pause) loop.set_paused(!loop.paused());
  if (ev.single_step) {
    loop.set_paused(true);
    loop.request_single_step();
  }
  if (ev.time_scale_steps != 0) {
    loop.set_time_scale(std::clamp(loop.time_scale() * std::pow(2.0, ev.time_scale_steps),
                                   1.0 / 16.0, max_time_scale));
  }
}

class Window {
 public:
  /// Opens a width x height window (pixels) with SDL's software renderer. Throws WindowError,
  /// its message stating the fault only (no advice: that is the program's to give), when there
  /// is no display (neither DISPLAY nor WAYLAND_DISPLAY set and no SDL_VIDEODRIVER chosen, or
  /// SDL fell back to a driver that shows nothing), SDL cannot initialise video, or creating the
  /// window, its renderer or its streaming texture fails; whatever was acquired before the
  /// failure is released first.
  Window(const std::string& title, int width, int height);
  /// Destroys the texture, renderer and window, then quits SDL. Never throws.
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  /// Drains SDL's event queue.
  WindowEvents poll();
  /// Drains SDL's event queue into `ev`, reusing its storage (no allocation once its edge list
  /// has grown).
  void poll(WindowEvents& ev);
  /// Shows an RGBA8 frame (height rows of width*4 bytes, top row first), unscaled when the
  /// window has the frame's size. Throws WindowError if the frame has the wrong size.
  void present(std::span<const std::uint8_t> rgba);
  /// SDL's name for the video driver in use (e.g. "x11").
  [[nodiscard]] std::string driver() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fixstep
