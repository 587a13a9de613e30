// The keys, mouse buttons and gamepad buttons a program's input can be bound to (InputMap,
// fixstep/render/input_map.hpp), named the same by the SDL2 window, the browser page and the
// input scripts. Keyboard keys are physical positions (SDL scancodes, KeyboardEvent.code): "z"
// is the key left of "x" on any layout, as in raylib and Godot's physical keycodes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace fixstep {

// X(enumerator, name): every key, in the order of the Key enum.
// clang-format off
#define FIXSTEP_KEYS(X)                                                                       \
  X(none, "none")                                                                             \
  X(a, "a") X(b, "b") X(c, "c") X(d, "d") X(e, "e") X(f, "f") X(g, "g") X(h, "h") X(i, "i")   \
  X(j, "j") X(k, "k") X(l, "l") X(m, "m") X(n, "n") X(o, "o") X(p, "p") X(q, "q") X(r, "r")   \
  X(s, "s") X(t, "t") X(u, "u") X(v, "v") X(w, "w") X(x, "x") X(y, "y") X(z, "z")             \
  X(d0, "0") X(d1, "1") X(d2, "2") X(d3, "3") X(d4, "4") X(d5, "5") X(d6, "6") X(d7, "7")     \
  X(d8, "8") X(d9, "9")                                                                       \
  X(f1, "f1") X(f2, "f2") X(f3, "f3") X(f4, "f4") X(f5, "f5") X(f6, "f6") X(f7, "f7")         \
  X(f8, "f8") X(f9, "f9") X(f10, "f10") X(f11, "f11") X(f12, "f12")                           \
  X(left, "left") X(right, "right") X(up, "up") X(down, "down")                               \
  X(space, "space") X(enter, "enter") X(escape, "escape") X(backspace, "backspace")           \
  X(tab, "tab") X(left_shift, "left_shift") X(right_shift, "right_shift")                     \
  X(left_ctrl, "left_ctrl") X(right_ctrl, "right_ctrl") X(left_alt, "left_alt")               \
  X(right_alt, "right_alt") X(period, "period") X(comma, "comma") X(minus, "minus")           \
  X(equals, "equals") X(slash, "slash") X(semicolon, "semicolon") X(apostrophe, "apostrophe") \
  X(left_bracket, "left_bracket") X(right_bracket, "right_bracket")                           \
  X(backslash, "backslash") X(grave, "grave") X(home, "home") X(end, "end")                   \
  X(page_up, "page_up") X(page_down, "page_down") X(insert, "insert") X(delete_key, "delete") \
  X(keypad_plus, "keypad_plus") X(keypad_minus, "keypad_minus")                               \
  X(keypad_enter, "keypad_enter")                                                             \
  X(mouse_left, "mouse_left") X(mouse_right, "mouse_right") X(mouse_middle, "mouse_middle")   \
  X(pad_a, "pad_a") X(pad_b, "pad_b") X(pad_x, "pad_x") X(pad_y, "pad_y")                     \
  X(pad_back, "pad_back") X(pad_guide, "pad_guide") X(pad_start, "pad_start")                 \
  X(pad_left_stick, "pad_left_stick") X(pad_right_stick, "pad_right_stick")                   \
  X(pad_left_shoulder, "pad_left_shoulder") X(pad_right_shoulder, "pad_right_shoulder")       \
  X(pad_up, "pad_up") X(pad_down, "pad_down") X(pad_left, "pad_left") X(pad_right, "pad_right")
// clang-format on

/// A key, a mouse button or a gamepad button (the first gamepad's: SDL2's game controller
/// layout, the browser's "standard" gamepad mapping).
enum class Key : std::uint8_t {
#define FIXSTEP_KEY_ENUM(id, name) id,
  FIXSTEP_KEYS(FIXSTEP_KEY_ENUM)
#undef FIXSTEP_KEY_ENUM
};

/// How many Key values there are (Key::none included).
inline constexpr std::size_t key_count = static_cast<std::size_t>(Key::pad_right) + 1;

/// The key's name in bindings and input scripts ("z", "space", "left_shift", "mouse_left",
/// "pad_a").
[[nodiscard]] std::string_view key_name(Key key);
/// The key named `name` (key_name's spelling), or nothing.
[[nodiscard]] std::optional<Key> key_named(std::string_view name);

/// A gamepad's analogue axes (SDL2's SDL_GameControllerAxis order). A stick reads in [-1, 1]
/// (right and down positive, as SDL2 and the browser report them); a trigger in [0, 1].
enum class PadAxis : std::uint8_t { left_x, left_y, right_x, right_y, trigger_left, trigger_right };
inline constexpr std::size_t pad_axis_count = 6;
/// "left_x", "left_y", "right_x", "right_y", "trigger_left" or "trigger_right".
[[nodiscard]] std::string_view pad_axis_name(PadAxis axis);
[[nodiscard]] std::optional<PadAxis> pad_axis_named(std::string_view name);

/// An SDL2 game controller axis reading (-32768 .. 32767) as a value in [-1, 1]: v / 32767,
/// -32768 read as -1 (exact and the same on every platform: one correctly rounded division).
[[nodiscard]] double pad_axis_value(std::int16_t raw);

}  // namespace fixstep
