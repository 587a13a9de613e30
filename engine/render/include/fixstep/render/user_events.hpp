// The events an interactive program's loop reads each frame, whichever platform delivers them
// (an SDL2 window: fixstep/window/window.hpp; a browser page: web/page_input.hpp): the raw keys,
// mouse and gamepad, and what the platform's InputMap (fixstep/render/input_map.hpp) made of
// them: loop commands, action edges and axes. What a loop does with them is fixstep::app's
// (fixstep/app/key_bindings.hpp).
#pragma once

#include <array>
#include <bitset>
#include <cstdint>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/render/keys.hpp"

namespace fixstep {

/// Key presses since the last poll, the held keys, the gamepad and the pointer; then what the
/// InputMap made of them.
struct UserEvents {
  // What the platform delivered.
  /// A key, mouse button or gamepad button went down or up (no key repeats), in order.
  struct KeyEdge {
    bool press = false;
    Key key = Key::none;
  };
  std::vector<KeyEdge> keys{};
  std::bitset<key_count> keys_down{};  ///< held now (bit = Key value)
  /// The first gamepad's axes (PadAxis order, pad_axis_value), 0 without one.
  std::array<double, pad_axis_count> pad_axes{};
  bool close_requested = false;  ///< the window's close button (a window only)

  // What the InputMap made of it (InputMap::apply).
  bool quit = false;          ///< the close button, or a quit key (Esc by default)
  bool toggle_pause = false;  ///< a pause key (space by default)
  bool single_step = false;   ///< a step key ('.' by default)
  int time_scale_steps = 0;   ///< faster keys +1, slower keys -1 (each press)
  bool restart = false;       ///< a restart key ('r' by default)
  /// A rewind key held (Backspace by default): step time backwards (programs that keep
  /// snapshots).
  bool rewind = false;
  /// A press or release of actions (TickInput bits: by default the InputButton bits of the
  /// arrows, Enter and the mouse buttons), in the order they happened.
  struct ButtonEdge {
    bool press = false;
    std::uint32_t buttons = 0;
  };
  std::vector<ButtonEdge> edges{};
  /// The map's axes (TickInput::axes), each in [-1, 1].
  std::array<double, max_axes> axes{};
  bool pointer_seen = false;                ///< the pointer has been over the frame
  double pointer_x = 0.0, pointer_y = 0.0;  ///< frame pixels from the top-left corner
};

}  // namespace fixstep
