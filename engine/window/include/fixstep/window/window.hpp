// An SDL2 window that presents frames rendered by fixstep::Renderer, pixel for pixel.
// Separate library target (fixstep::window) so headless users do not link SDL2.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

#include "fixstep/core/types.hpp"
#include "fixstep/render/input_map.hpp"
#include "fixstep/render/render.hpp"
#include "fixstep/render/user_events.hpp"

namespace fixstep {

/// The window could not open: no display, SDL initialisation or window creation failed.
class WindowError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A window's events: the keys, mouse buttons, first gamepad and pointer of
/// fixstep/render/user_events.hpp, mapped by the window's InputMap (default_input_map() unless
/// set_input_map), the close button as `quit`.
using WindowEvents = UserEvents;

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

  /// The bindings every poll applies from now on (InputMap::apply).
  void set_input_map(InputMap map);
  /// Drains SDL's event queue: keys as physical keys (scancodes), mouse buttons, the first game
  /// controller's buttons and axes; then the InputMap's actions, axes and loop commands.
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
  void open_pad(int device);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fixstep
