// The browser's keyboard and pointer (emscripten's html5.h callbacks) as the events `fixstep
// view` reads from its SDL2 window (fixstep/window/window.hpp): the same keys, buttons and pointer,
// handed to the same per-tick input sampling (InputSampler). Web platform (wasm only).
#pragma once

#include <utility>

#include "fixstep/core/input.hpp"
#include "fixstep/render/input_map.hpp"
#include "fixstep/render/user_events.hpp"

namespace fixstep::web {

/// What happened since the last take(): the keys, buttons, gamepad and pointer of a window's
/// events (fixstep/render/user_events.hpp); a page has no close button.
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

  /// The bindings every take() applies from now on (InputMap::apply).
  void set_input_map(InputMap map) { map_ = std::move(map); }
  /// The events since the last call (the keys by KeyboardEvent.code, the physical key; the
  /// first gamepad by the browser's standard mapping), mapped by the InputMap; held keys stay
  /// held.
  [[nodiscard]] PageEvents take();

  // html5.h's callbacks (public so that the C callbacks can reach them).
  bool key(bool down, const char* code, const char* typed, bool repeat);
  void pointer(long x, long y);
  void button(bool down, unsigned short button);

 private:
  /// Registers the key and mouse callbacks with `input` as their data, or removes them (nullptr).
  void listen(PageInput* input) const;

  void add_key(bool down, Key key);
  void sample_pad();

  const char* canvas_;
  int width_, height_;
  PageEvents ev_;
  InputMap map_ = default_input_map();
};

}  // namespace fixstep::web
