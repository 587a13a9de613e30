// SDL2's scancodes, mouse buttons and game controller buttons as fixstep Keys
// (fixstep/render/keys.hpp).
#pragma once

#include <SDL.h>

#include "fixstep/render/keys.hpp"

namespace fixstep::detail {

/// The Key of a physical key, or Key::none.
[[nodiscard]] Key sdl_scancode_key(SDL_Scancode code);
/// The Key of a mouse button (SDL_BUTTON_LEFT, ...), or Key::none.
[[nodiscard]] Key sdl_mouse_key(Uint8 button);
/// The Key of a game controller button (SDL_CONTROLLER_BUTTON_A, ...), or Key::none.
[[nodiscard]] Key sdl_pad_key(Uint8 button);

}  // namespace fixstep::detail
