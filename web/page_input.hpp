// The browser's keyboard and pointer (emscripten's html5.h callbacks) as the events `fixstep
// view` reads from its SDL2 window (fixstep/window/window.hpp): the same keys, buttons and pointer,
// handed to the same per-tick input sampling (InputSampler). Web platform (wasm only).
#pragma once

#include "fixstep/core/input.hpp"
#include "fixstep/render/user_events.hpp"

namespace fixstep::web {

/// What happened since the last take(): the keys, buttons and pointer of a window's events
/// (fixstep/render/user_events.hpp) but for `quit` (a page has no Esc to quit).
using PageEvents = UserEvents;

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
  /// Registers the key and mouse callbacks with `input` as their data, or removes them (nullptr).
  void listen(PageInput* input) const;

  const char* canvas_;
  int width_, height_;
  PageEvents ev_;
  bool backspace_held_ = false;
};

}  // namespace fixstep::web
