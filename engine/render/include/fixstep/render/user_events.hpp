// The events an interactive program's loop reads each frame, whichever platform delivers them
// (an SDL2 window: fixstep/window/window.hpp; a browser page: web/page_input.hpp). What a loop does
// with them is fixstep::app's (fixstep/app/key_bindings.hpp).
#pragma once

#include <cstdint>
#include <vector>

namespace fixstep {

/// Key presses since the last poll, the held keys, and the pointer.
struct UserEvents {
  bool quit = false;          ///< Esc or the close button (a window only)
  bool toggle_pause = false;  ///< space
  bool single_step = false;   ///< '.'
  int time_scale_steps = 0;   ///< '+' (or '=') = +1, '-' = -1 (each press)
  bool restart = false;       ///< 'r'
  bool rewind = false;  ///< Backspace held: step time backwards (programs that keep snapshots)
  /// A press or release of tick-input buttons (InputButton bits: arrows, Enter, mouse
  /// buttons), in the order they happened.
  struct ButtonEdge {
    bool press = false;
    std::uint32_t buttons = 0;
  };
  std::vector<ButtonEdge> edges{};
  bool pointer_seen = false;                ///< the pointer has been over the frame
  double pointer_x = 0.0, pointer_y = 0.0;  ///< frame pixels from the top-left corner
};

}  // namespace fixstep
