// SDL2's input codes as fixstep Keys (sdl_keys.hpp).
#include "sdl_keys.hpp"

#include <array>
#include <utility>

namespace fixstep::detail {

namespace {

Key offset_key(Key first, int offset) {
  return static_cast<Key>(static_cast<int>(first) + offset);
}

constexpr std::array<std::pair<SDL_Scancode, Key>, 38> named_scancodes = {{
    {SDL_SCANCODE_LEFT, Key::left},
    {SDL_SCANCODE_RIGHT, Key::right},
    {SDL_SCANCODE_UP, Key::up},
    {SDL_SCANCODE_DOWN, Key::down},
    {SDL_SCANCODE_SPACE, Key::space},
    {SDL_SCANCODE_RETURN, Key::enter},
    {SDL_SCANCODE_ESCAPE, Key::escape},
    {SDL_SCANCODE_BACKSPACE, Key::backspace},
    {SDL_SCANCODE_TAB, Key::tab},
    {SDL_SCANCODE_LSHIFT, Key::left_shift},
    {SDL_SCANCODE_RSHIFT, Key::right_shift},
    {SDL_SCANCODE_LCTRL, Key::left_ctrl},
    {SDL_SCANCODE_RCTRL, Key::right_ctrl},
    {SDL_SCANCODE_LALT, Key::left_alt},
    {SDL_SCANCODE_RALT, Key::right_alt},
    {SDL_SCANCODE_PERIOD, Key::period},
    {SDL_SCANCODE_COMMA, Key::comma},
    {SDL_SCANCODE_MINUS, Key::minus},
    {SDL_SCANCODE_EQUALS, Key::equals},
    {SDL_SCANCODE_SLASH, Key::slash},
    {SDL_SCANCODE_SEMICOLON, Key::semicolon},
    {SDL_SCANCODE_APOSTROPHE, Key::apostrophe},
    {SDL_SCANCODE_LEFTBRACKET, Key::left_bracket},
    {SDL_SCANCODE_RIGHTBRACKET, Key::right_bracket},
    {SDL_SCANCODE_BACKSLASH, Key::backslash},
    {SDL_SCANCODE_GRAVE, Key::grave},
    {SDL_SCANCODE_HOME, Key::home},
    {SDL_SCANCODE_END, Key::end},
    {SDL_SCANCODE_PAGEUP, Key::page_up},
    {SDL_SCANCODE_PAGEDOWN, Key::page_down},
    {SDL_SCANCODE_INSERT, Key::insert},
    {SDL_SCANCODE_DELETE, Key::delete_key},
    {SDL_SCANCODE_KP_PLUS, Key::keypad_plus},
    {SDL_SCANCODE_KP_MINUS, Key::keypad_minus},
    {SDL_SCANCODE_KP_ENTER, Key::keypad_enter},
    {SDL_SCANCODE_KP_PERIOD, Key::period},
    {SDL_SCANCODE_0, Key::d0},
    {SDL_SCANCODE_NONUSBACKSLASH, Key::backslash},
}};

}  // namespace

Key sdl_scancode_key(SDL_Scancode code) {
  if (code >= SDL_SCANCODE_A && code <= SDL_SCANCODE_Z) {
    return offset_key(Key::a, code - SDL_SCANCODE_A);
  }
  if (code >= SDL_SCANCODE_1 && code <= SDL_SCANCODE_9) {  // SDL: 1 .. 9, then 0
    return offset_key(Key::d1, code - SDL_SCANCODE_1);
  }
  if (code >= SDL_SCANCODE_F1 && code <= SDL_SCANCODE_F12) {
    return offset_key(Key::f1, code - SDL_SCANCODE_F1);
  }
  for (const auto& [sdl, key] : named_scancodes) {
    if (sdl == code) return key;
  }
  return Key::none;
}

Key sdl_mouse_key(Uint8 button) {
  switch (button) {
    case SDL_BUTTON_LEFT:
      return Key::mouse_left;
    case SDL_BUTTON_RIGHT:
      return Key::mouse_right;
    case SDL_BUTTON_MIDDLE:
      return Key::mouse_middle;
    default:
      return Key::none;
  }
}

Key sdl_pad_key(Uint8 button) {
  if (button >= SDL_CONTROLLER_BUTTON_A && button <= SDL_CONTROLLER_BUTTON_DPAD_RIGHT) {
    // SDL's order: a b x y back guide start leftstick rightstick leftshoulder rightshoulder
    // dpad up down left right, which is Key's from pad_a on.
    return offset_key(Key::pad_a, button - SDL_CONTROLLER_BUTTON_A);
  }
  return Key::none;
}

}  // namespace fixstep::detail
