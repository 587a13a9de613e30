// Bindings: which keys, mouse buttons and gamepad buttons and axes mean which of a program's
// actions (TickInput bits), axes (TickInput::axes) and loop commands (pause, step, speed,
// restart, rewind, quit). The window and the browser page apply one to the raw events of every
// poll (UserEvents), so a game sees actions, never keys: raylib's IsKeyDown, Godot's InputMap
// actions, Bevy's ButtonInput, as fixed-tick input that is recorded and replayed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/render/keys.hpp"
#include "fixstep/render/user_events.hpp"

namespace fixstep {

/// One action: a bit of TickInput::held / pressed / released and the keys that hold it down
/// (any of them; the action is held while at least one is).
struct ActionBinding {
  std::string name;         ///< its name in input scripts and help lines ("jump")
  std::uint32_t bit = 0;    ///< exactly one bit
  std::vector<Key> keys{};  ///< keys, mouse buttons, gamepad buttons
};

/// One analogue axis (TickInput::axes[index]): a gamepad axis, and keys reading -1 and +1 when
/// held (both or neither: 0). A gamepad axis beyond its dead zone wins over the keys.
struct AxisBinding {
  std::string name;             ///< its name in input scripts and help lines ("steer")
  std::size_t index = 0;        ///< < max_axes
  std::vector<Key> negative{};  ///< keys reading -1
  std::vector<Key> positive{};  ///< keys reading +1
  std::optional<PadAxis> pad{};
  /// |reading| at or below this reads 0 (stick drift); the reading is kept as is above it.
  double dead_zone = 0.15;
};

/// What the program's loop does on its own, not in the ticks.
enum class LoopAction : std::uint8_t { quit, pause, step, faster, slower, restart, rewind };
/// "quit", "pause", "step", "faster", "slower", "restart" or "rewind".
[[nodiscard]] std::string_view loop_action_name(LoopAction action);

struct LoopBinding {
  LoopAction action = LoopAction::pause;
  std::vector<Key> keys{};
};

/// A program's bindings. A key bound to an action is not also a loop key: the action takes it
/// (a game that jumps with space has no pause on space; give pause another key).
struct InputMap {
  std::vector<ActionBinding> actions{};
  std::vector<AxisBinding> axes{};
  std::vector<LoopBinding> loop{};

  /// Fills `ev`'s mapped part from its raw part: the loop flags (quit also on
  /// ev.close_requested), an edge per action key press or release, in order (an action with
  /// another of its keys still down is not released; one already down is not pressed again),
  /// rewind while a rewind key is held, and the axes (with the bits of those that changed since
  /// the last apply to `ev`).
  void apply(UserEvents& ev) const;
  /// The bit of the action named `name`, or nothing.
  [[nodiscard]] std::optional<std::uint32_t> action_bit(std::string_view name) const;
  /// The index of the axis named `name`, or nothing.
  [[nodiscard]] std::optional<std::size_t> axis_index(std::string_view name) const;
  /// Whether `key` means anything here: an action's, an axis's or a loop binding's key (a page
  /// keeps such a key from the browser: no scrolling on the arrows, no "back" on Backspace).
  [[nodiscard]] bool binds(Key key) const;
  /// Every action's bit.
  [[nodiscard]] std::uint32_t action_bits() const;
  /// The loop keys as a help line ("space pause  . step  ..."), quit left out when `can_quit`
  /// is false (a web page).
  [[nodiscard]] std::string loop_help(bool can_quit = true) const;
  /// What is wrong: an action without a name or with a name used twice, a bit that is not
  /// exactly one or is used twice, an axis index >= max_axes or used twice, a dead zone
  /// outside [0, 1), Key::none bound; nothing when the map is sound.
  [[nodiscard]] std::optional<std::string> problem() const;
};

/// fixstep's default actions (the InputButton bits): "left", "right", "up", "down" on the
/// arrow keys and the gamepad's d-pad, "action" on Enter and the gamepad's A,
/// "pointer_primary" and "pointer_secondary" on the mouse buttons.
[[nodiscard]] std::vector<ActionBinding> default_actions();
/// fixstep's loop keys: space pause, '.' step, '+' / '=' faster, '-' slower, 'r' restart,
/// Backspace rewind, Esc quit.
[[nodiscard]] std::vector<LoopBinding> default_loop_bindings();
/// default_actions(), no axes, default_loop_bindings().
[[nodiscard]] InputMap default_input_map();

}  // namespace fixstep
