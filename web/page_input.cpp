// The browser's keyboard and pointer as `fixstep view`'s window events (page_input.hpp); the
// keys are those of engine/window/src/window.cpp (KeyboardEvent.key names, as the browser
// reports them).
#include "page_input.hpp"

#include <emscripten/html5.h>

#include <algorithm>
#include <cstring>
#include <string_view>
#include <utility>

namespace fixstep::web {

namespace {

/// The Key of a KeyboardEvent.code (the physical key, as an SDL scancode), or Key::none.
Key code_key(std::string_view code) {
  if (code.size() == 4 && code.starts_with("Key") && code[3] >= 'A' && code[3] <= 'Z') {
    return static_cast<Key>(static_cast<int>(Key::a) + (code[3] - 'A'));
  }
  if (code.size() == 6 && code.starts_with("Digit") && code[5] >= '0' && code[5] <= '9') {
    return static_cast<Key>(static_cast<int>(Key::d0) + (code[5] - '0'));
  }
  static constexpr std::pair<std::string_view, Key> named[] = {
      {"ArrowLeft", Key::left},
      {"ArrowRight", Key::right},
      {"ArrowUp", Key::up},
      {"ArrowDown", Key::down},
      {"Space", Key::space},
      {"Enter", Key::enter},
      {"Escape", Key::escape},
      {"Backspace", Key::backspace},
      {"Tab", Key::tab},
      {"ShiftLeft", Key::left_shift},
      {"ShiftRight", Key::right_shift},
      {"ControlLeft", Key::left_ctrl},
      {"ControlRight", Key::right_ctrl},
      {"AltLeft", Key::left_alt},
      {"AltRight", Key::right_alt},
      {"Period", Key::period},
      {"Comma", Key::comma},
      {"Minus", Key::minus},
      {"Equal", Key::equals},
      {"Slash", Key::slash},
      {"Semicolon", Key::semicolon},
      {"Quote", Key::apostrophe},
      {"BracketLeft", Key::left_bracket},
      {"BracketRight", Key::right_bracket},
      {"Backslash", Key::backslash},
      {"IntlBackslash", Key::backslash},
      {"Backquote", Key::grave},
      {"Home", Key::home},
      {"End", Key::end},
      {"PageUp", Key::page_up},
      {"PageDown", Key::page_down},
      {"Insert", Key::insert},
      {"Delete", Key::delete_key},
      {"NumpadAdd", Key::keypad_plus},
      {"NumpadSubtract", Key::keypad_minus},
      {"NumpadEnter", Key::keypad_enter},
      {"NumpadDecimal", Key::period}};
  for (const auto& [name, key] : named) {
    if (name == code) return key;
  }
  if (code.size() >= 2 && code.size() <= 3 && code[0] == 'F') {  // F1 .. F12
    int n = 0;
    for (char c : code.substr(1)) n = c >= '0' && c <= '9' ? n * 10 + (c - '0') : 99;
    if (n >= 1 && n <= 12) return static_cast<Key>(static_cast<int>(Key::f1) + n - 1);
  }
  return Key::none;
}

/// The Key of a KeyboardEvent.key (what the key types), for an event without a code (one a
/// script dispatched), or Key::none.
Key typed_key(std::string_view key) {
  if (key.size() == 1) {
    const char c = key[0];
    if (c >= 'a' && c <= 'z') return static_cast<Key>(static_cast<int>(Key::a) + (c - 'a'));
    if (c >= 'A' && c <= 'Z') return static_cast<Key>(static_cast<int>(Key::a) + (c - 'A'));
    if (c >= '0' && c <= '9') return static_cast<Key>(static_cast<int>(Key::d0) + (c - '0'));
    switch (c) {
      case ' ':
        return Key::space;
      case '.':
        return Key::period;
      case ',':
        return Key::comma;
      case '+':
      case '=':
        return Key::equals;
      case '-':
        return Key::minus;
      case '/':
        return Key::slash;
      default:
        return Key::none;
    }
  }
  if (key == "Shift") return Key::left_shift;
  if (key == "Control") return Key::left_ctrl;
  if (key == "Alt") return Key::left_alt;
  return code_key(key);  // "ArrowLeft", "Enter", "Escape", "Backspace", "Tab", "Home", ...
}

EM_BOOL on_key(int type, const EmscriptenKeyboardEvent* e, void* input) {
  return static_cast<PageInput*>(input)->key(type == EMSCRIPTEN_EVENT_KEYDOWN, e->code, e->key,
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

bool PageInput::key(bool down, const char* code, const char* typed, bool repeat) {
  // The physical key (code); an event without one (dispatched by a script) by what it types.
  const Key k = code[0] != '\0' ? code_key(code) : typed_key(typed);
  if (k == Key::none) return false;
  if (!repeat) add_key(down, k);
  return map_.binds(k);
}

void PageInput::add_key(bool down, Key key) {
  if (ev_.keys_down[static_cast<std::size_t>(key)] == down) return;
  ev_.keys.push_back({down, key});
  ev_.keys_down[static_cast<std::size_t>(key)] = down;
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
  // MouseEvent.button: 0 the main (left) button, 1 the middle, 2 the secondary (right) one.
  const Key k = button == 0   ? Key::mouse_left
                : button == 1 ? Key::mouse_middle
                : button == 2 ? Key::mouse_right
                              : Key::none;
  if (k != Key::none) add_key(down, k);
}

void PageInput::sample_pad() {
  if (emscripten_sample_gamepad_data() != EMSCRIPTEN_RESULT_SUCCESS) return;
  if (emscripten_get_num_gamepads() < 1) return;
  EmscriptenGamepadEvent pad{};
  if (emscripten_get_gamepad_status(0, &pad) != EMSCRIPTEN_RESULT_SUCCESS || !pad.connected) {
    return;
  }
  // The "standard" mapping's buttons in Key order (pad_a .. pad_right); triggers are axes.
  static constexpr int standard[] = {0, 1, 2, 3, 8, 16, 9, 10, 11, 4, 5, 12, 13, 14, 15};
  for (int i = 0; i < 15; ++i) {
    if (standard[i] < pad.numButtons) {
      add_key(pad.digitalButton[standard[i]] != 0,
              static_cast<Key>(static_cast<int>(Key::pad_a) + i));
    }
  }
  for (int i = 0; i < 4 && i < pad.numAxes; ++i) ev_.pad_axes[i] = pad.axis[i];
  if (pad.numButtons > 7) {
    ev_.pad_axes[4] = pad.analogButton[6];
    ev_.pad_axes[5] = pad.analogButton[7];
  }
}

PageEvents PageInput::take() {
  sample_pad();
  map_.apply(ev_);  // the axes compared with the last take's
  PageEvents out = ev_;
  ev_.keys.clear();
  ev_.toggle_pause = ev_.single_step = ev_.restart = false;
  ev_.time_scale_steps = 0;
  ev_.edges.clear();
  return out;
}

}  // namespace fixstep::web
