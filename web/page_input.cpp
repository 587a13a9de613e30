// The browser's keyboard and pointer as `fixstep view`'s window events (page_input.hpp); the
// keys are those of engine/window/src/window.cpp (KeyboardEvent.key names, as the browser
// reports them).
#include "page_input.hpp"

#include <emscripten/html5.h>

#include <cstring>
#include <string_view>

namespace fixstep::web {

namespace {

/// The InputButton bit of a key, or 0.
std::uint32_t key_button(std::string_view key) {
  if (key == "ArrowLeft") return button_left;
  if (key == "ArrowRight") return button_right;
  if (key == "ArrowUp") return button_up;
  if (key == "ArrowDown") return button_down;
  if (key == "Enter") return button_action;
  return 0;
}

/// The loop's own keys: whether `key` is one.
bool loop_key(std::string_view key, PageEvents& ev) {
  if (key == " ") {
    ev.toggle_pause = true;
  } else if (key == ".") {
    ev.single_step = true;
  } else if (key == "+" || key == "=") {
    ++ev.time_scale_steps;
  } else if (key == "-") {
    --ev.time_scale_steps;
  } else if (key == "r") {
    ev.restart = true;
  } else {
    return false;
  }
  return true;
}

EM_BOOL on_key(int type, const EmscriptenKeyboardEvent* e, void* input) {
  return static_cast<PageInput*>(input)->key(type == EMSCRIPTEN_EVENT_KEYDOWN, e->key,
                                             e->repeat != 0);
}

EM_BOOL on_mouse(int type, const EmscriptenMouseEvent* e, void* input) {
  auto* in = static_cast<PageInput*>(input);
  // A release is heard on the window (a drag may end outside the canvas), where targetX/Y are
  // not the canvas's: the pointer stays where the canvas last saw it.
  if (type != EMSCRIPTEN_EVENT_MOUSEUP) in->pointer(e->targetX, e->targetY);
  if (type == EMSCRIPTEN_EVENT_MOUSEDOWN || type == EMSCRIPTEN_EVENT_MOUSEUP) {
    in->button(type == EMSCRIPTEN_EVENT_MOUSEDOWN, e->button);
  }
  return type != EMSCRIPTEN_EVENT_MOUSEMOVE;  // no text selection on a drag
}

}  // namespace

PageInput::PageInput(const char* canvas, int width, int height)
    : canvas_(canvas), width_(width), height_(height) {
  listen(this);
}

PageInput::~PageInput() {
  listen(nullptr);
}

void PageInput::listen(PageInput* input) const {
  const char* window = EMSCRIPTEN_EVENT_TARGET_WINDOW;
  const em_key_callback_func key = input ? on_key : nullptr;
  const em_mouse_callback_func mouse = input ? on_mouse : nullptr;
  emscripten_set_keydown_callback(window, input, true, key);
  emscripten_set_keyup_callback(window, input, true, key);
  emscripten_set_mousedown_callback(canvas_, input, true, mouse);
  emscripten_set_mousemove_callback(canvas_, input, true, mouse);
  // Released anywhere: a drag may end outside the canvas.
  emscripten_set_mouseup_callback(window, input, true, mouse);
}

bool PageInput::key(bool down, const char* key, bool repeat) {
  const std::string_view k = key;
  if (k == "Backspace") {
    backspace_held_ = down;
    return true;  // not the browser's "back"
  }
  if (const std::uint32_t b = key_button(k)) {
    if (!repeat) ev_.edges.push_back({down, b});
    return true;  // arrows do not scroll the page
  }
  return down && loop_key(k, ev_);
}

void PageInput::pointer(long x, long y) {
  // targetX/Y are CSS pixels of the canvas; the frame may be shown scaled.
  double css_w = 0.0, css_h = 0.0;
  emscripten_get_element_css_size(canvas_, &css_w, &css_h);
  const double sx = css_w > 0.0 ? width_ / css_w : 1.0, sy = css_h > 0.0 ? height_ / css_h : 1.0;
  ev_.pointer_seen = true;
  ev_.pointer_x = (double(x) + 0.5) * sx;
  ev_.pointer_y = (double(y) + 0.5) * sy;
}

void PageInput::button(bool down, unsigned short button) {
  // MouseEvent.button: 0 the main (left) button, 2 the secondary (right) one.
  const std::uint32_t b = button == 0   ? button_pointer_primary
                          : button == 2 ? button_pointer_secondary
                                        : 0u;
  if (b != 0) ev_.edges.push_back({down, b});
}

PageEvents PageInput::take() {
  PageEvents out = ev_;
  out.rewind = backspace_held_;
  ev_.toggle_pause = ev_.single_step = ev_.restart = false;
  ev_.time_scale_steps = 0;
  ev_.edges.clear();
  return out;
}

}  // namespace fixstep::web
