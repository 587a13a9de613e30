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
  std::uint64_t tick = 0;       ///< tick index (0 = the first tick)
  std::uint32_t press = 0;      ///< InputButton bits pressed at this tick
  std::uint32_t release = 0;    ///< InputButton bits released at this tick
  std::optional<Vec2> pointer;  ///< m, world coordinates; a level kept until changed
  std::optional<Vec2> push;     ///< m/s²; a level kept until changed
  std::optional<Entity>
      drag;  ///< the body's handle (World::defined_bodies()), or null_entity (`drag = false`)
  /// `force` (N, this tick only), `impulse` (N·s, Δv = J/m at this tick) and `velocity` (m/s,
  /// a kinematic body keeps it until changed), bodies by their handles (World::defined_bodies());
  /// forces first, then impulses, then velocities, each in file order.
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

/// Parses a script for a world of `bodies` (drag, force, impulse and velocity name a body; its
/// its World::defined_bodies() handle is stored). Throws SceneError "FILE:LINE:COLUMN: KEY:
/// MESSAGE" for TOML syntax errors, an [[at]] without `tick`, ticks not strictly increasing or
/// beyond max_recording_ticks, an unknown button (with a suggestion), a body name no body has (with
/// a suggestion), a force or impulse on a body that is not dynamic, a velocity for one that is not
/// kinematic, a per-body table without `body` or `value` or more than max_body_inputs of them in
/// one tick, vectors that are not [x, y] of finite numbers, wrong types, binary or oversized text.
/// Unknown keys (also inside a per-body table) are warnings.
[[nodiscard]] InputScript parse_input_script(std::string_view text, const std::string& source_name,
                                             std::span<const BodyDef> bodies);
/// As parse_input_script, from a file (SceneError when it cannot be read).
[[nodiscard]] InputScript load_input_script(const std::filesystem::path& file,
                                            std::span<const BodyDef> bodies);

/// Plays a script tick by tick through an InputSampler, as the window would: levels (push,
/// pointer, drag) persist until changed; a press or release, a force and an impulse reach
/// exactly their tick (InputSampler::apply_force, apply_impulse); a velocity is given at its
/// tick (set_velocity) and the kinematic body keeps it.
class ScriptPlayer {
 public:
  /// The script must outlive the player.
  explicit ScriptPlayer(const InputScript& script) : script_(script) {}
  /// The input of the next tick (0, 1, 2, ... on successive calls). Allocates nothing.
  TickInput next();

 private:
  const InputScript& script_;
  InputSampler sampler_;
  std::size_t event_ = 0;
  std::uint64_t tick_ = 0;
};

/// The first `ticks` inputs of the script (ScriptPlayer::next() `ticks` times).
[[nodiscard]] std::vector<TickInput> script_inputs(const InputScript& script, std::uint64_t ticks);

}  // namespace fixstep
