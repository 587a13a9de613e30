// The browser's keyboard and pointer (emscripten's html5.h callbacks) as the events `fixstep
// view` reads from its SDL2 window (fixstep/window.hpp): the same keys, buttons and pointer,
// handed to the same per-tick input sampling (InputSampler). Web platform (wasm only).
#pragma once

#include <cstdint>
#include <vector>

#include "fixstep/input.hpp"
#include "fixstep/render.hpp"
#include "fixstep/types.hpp"

namespace fixstep::web {

/// What happened since the last take(), as WindowEvents (fixstep/window.hpp) has it.
struct PageEvents {
  bool toggle_pause = false;  ///< space
  bool single_step = false;   ///< '.'
  int time_scale_steps = 0;   ///< '+' (or '=') = +1, '-' = -1, each press
  bool restart = false;       ///< 'r'
  bool rewind = false;        ///< Backspace held
  /// Presses and releases of InputButton bits (arrows, Enter, mouse buttons), in order.
  struct ButtonEdge {
    bool press = false;
    std::uint32_t buttons = 0;
  };
  std::vector<ButtonEdge> edges{};
  bool pointer_seen = false;                ///< the pointer has been over the canvas
  double pointer_x = 0.0, pointer_y = 0.0;  ///< frame pixels from the top-left corner
};

/// Listens to the window's keys and to the mouse on the canvas (selector, e.g. "#canvas",
/// whose drawing buffer is width x height px: pointer positions are scaled from the canvas's
/// CSS size to it). One per page: the callbacks refer to it until it is destroyed.
class PageInput {
 public:
  PageInput(const char* canvas, int width, int height);
  ~PageInput();
  PageInput(const PageInput&) = delete;
  PageInput& operator=(const PageInput&) = delete;

  /// The events since the last call; the held keys (Backspace) stay held.
  [[nodiscard]] PageEvents take();

  // html5.h's callbacks (public so that the C callbacks can reach them).
  bool key(bool down, const char* key, bool repeat);
  void pointer(long x, long y);
  void button(bool down, unsigned short button);

 private:
  const char* canvas_;
  int width_, height_;
  PageEvents ev_;
  bool backspace_held_ = false;
};

/// Hands the tick-input part of `ev` to `sampler`, as fixstep::feed does for a window: the
/// button edges in order, and the pointer in world metres through `camera` for a width x height
/// frame (screen_to_world).
void feed(const PageEvents& ev, InputSampler& sampler, const Camera& camera, int width, int height);

}  // namespace fixstep::web
