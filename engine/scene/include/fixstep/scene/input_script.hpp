// Scripted input: a TOML file saying what the player does at which tick, turned into one
// TickInput per tick (for `fixstep run --input`, so CI can record and replay a session without
// a window). Format: docs/CLI.md, "Input scripts".
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"

namespace fixstep {

/// One [[at]] table: what changes at the start of tick `tick`.
struct ScriptEvent {
  std::uint64_t tick = 0;     ///< tick index (0 = the first tick)
  std::uint32_t press = 0;    ///< action bits pressed at this tick (InputButton by default)
  std::uint32_t release = 0;  ///< action bits released at this tick
  /// `axes = { NAME = VALUE }`: (axis index, value in [-1, 1]), levels kept until changed.
  std::vector<std::pair<std::size_t, double>> axes;
  std::optional<Vec2> pointer;  ///< m, world coordinates; a level kept until changed
  std::optional<Vec2> push;     ///< m/s²; a level kept until changed
  std::optional<Entity>
      drag;  ///< the body's handle (World::defined_bodies()), or null_entity (`drag = false`)
  /// `force` (N, this tick only), `impulse` (N·s, Δv = J/m at this tick), `velocity` (m/s,
  /// a kinematic body keeps it until changed), and for bodies with shapes `torque` (N·m, this
  /// tick only), `angular_impulse` (N·m·s, Δω = L/I at this tick), `angular_velocity` (rad/s,
  /// kept) and `target_angle` (rad, reached at this tick's end), their one number in value.x
  /// (value.y 0); bodies by their handles (World::defined_bodies()); in BodyInputKind order
  /// (forces first, then impulses, velocities, torques, ...), each kind in file order.
  std::vector<BodyInput> bodies;
  std::size_t line = 0;  ///< of the [[at]] table
};

/// A parsed input script.
struct InputScript {
  std::string file;                   ///< for messages
  std::vector<ScriptEvent> events;    ///< ticks strictly increasing
  std::vector<std::string> warnings;  ///< unknown keys, with suggestions
};

/// Largest script file accepted, bytes.
inline constexpr std::size_t max_script_bytes = 4u << 20;
/// Button names of `press` / `release`, in InputButton bit order: left, right, up, down,
/// action, pointer_primary, pointer_secondary.
[[nodiscard]] std::span<const std::pair<std::string_view, std::uint32_t>> button_names();

/// The action and axis names a script may use (`press`, `release`, `axes`): a game's
/// (app::Settings::actions and axes), or default_script_names().
struct ScriptNames {
  std::vector<std::pair<std::string, std::uint32_t>> actions;  ///< name, bit
  std::vector<std::pair<std::string, std::size_t>> axes;       ///< name, TickInput::axes index
};
/// fixstep's default actions (button_names()) and no axes.
[[nodiscard]] ScriptNames default_script_names();

/// Parses a script for a world of `bodies` (drag and the per-body inputs name a body; its
/// World::defined_bodies() handle is stored) and a program of the actions and axes `known`. Throws
/// SceneError "FILE:LINE:COLUMN: KEY: MESSAGE" for TOML syntax errors, an [[at]] without `tick`,
/// ticks not strictly increasing or beyond max_recording_ticks, an unknown action or axis (with a
/// suggestion), an axis value outside [-1, 1], a body name no body has (with a suggestion), a
/// force, impulse, torque or angular impulse on a body that is not dynamic, a velocity, angular
/// velocity or target angle for one that is not kinematic, an angular input for a body without
/// shapes, a per-body table without `body` or `value` or more than max_body_inputs of them in one
/// tick, vectors that are not [x, y] of finite numbers, an angular value that is not one finite
/// number, wrong types, binary or oversized text. Unknown keys (also inside a per-body table) are
/// warnings.
[[nodiscard]] InputScript parse_input_script(std::string_view text, const std::string& source_name,
                                             std::span<const BodyDef> bodies,
                                             const ScriptNames& known = default_script_names());
/// As parse_input_script, from a file (SceneError when it cannot be read).
[[nodiscard]] InputScript load_input_script(const std::filesystem::path& file,
                                            std::span<const BodyDef> bodies,
                                            const ScriptNames& known = default_script_names());

/// Plays a script tick by tick through an InputSampler, as the window would: levels (push,
/// pointer, drag) persist until changed; a press or release, a force and an impulse reach
/// exactly their tick (InputSampler::apply_force, apply_impulse), as do a torque and an angular
/// impulse (apply_torque, apply_angular_impulse); a velocity, angular velocity or target angle is
/// given at its tick (set_velocity, set_angular_velocity, set_target_angle) and the kinematic
/// body keeps what it sets.
class ScriptPlayer {
 public:
  /// The script must outlive the player.
  explicit ScriptPlayer(const InputScript& script) : script_(script) {}
  /// The input of the next tick (0, 1, 2, ... on successive calls). Allocates nothing.
  TickInput next();
  /// Gives `sampler` what the script does at tick `tick` (its presses, releases, axes, levels
  /// and per-body inputs), for a program that samples its own input (a game run with --input:
  /// its input() and prepare() still apply). Ticks must not decrease from call to call;
  /// events of ticks skipped over are dropped.
  void feed(std::uint64_t tick, InputSampler& sampler);
  /// Back to the script's start (tick 0, nothing pressed).
  void restart() {
    sampler_ = {};
    event_ = 0;
    tick_ = 0;
  }

 private:
  const InputScript& script_;
  InputSampler sampler_;
  std::size_t event_ = 0;
  std::uint64_t tick_ = 0;
};

/// The first `ticks` inputs of the script (ScriptPlayer::next() `ticks` times).
[[nodiscard]] std::vector<TickInput> script_inputs(const InputScript& script, std::uint64_t ticks);

}  // namespace fixstep
