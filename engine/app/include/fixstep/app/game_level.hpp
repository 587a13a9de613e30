// Internal to fixstep::app, and shared with the web page (web/): the level a game's run starts
// from, the rules name its recordings carry, and a recording replayed with its rules and
// verified. app::run's modes (engine/app/src) and the page's game mode are built on these, so
// that both run a game the same way.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/app/app.hpp"
#include "fixstep/app/session.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/render/input_map.hpp"
#include "fixstep/scene/input_script.hpp"

namespace fixstep::app::detail {

/// The rules name a game's recordings carry: `program` with every character a rules name
/// may not hold (is_rules_name_char) made '_', cut to max_rules_name_bytes;
/// "game" for an empty name.
inline std::string rules_name_of(const std::string& program) {
  std::string name = program.empty() ? std::string("game") : program;
  if (name.size() > max_rules_name_bytes) name.resize(max_rules_name_bytes);
  for (char& c : name) {
    if (!is_rules_name_char(c)) c = '_';
  }
  return name;
}

/// The level a run starts from: the game's setup() applied to the scene's world (or to an
/// empty one), with what a recording of it stores and the view it is shown with.
struct Level {
  WorldDef def;
  std::string scene_name;  ///< Recording::scene: the scene file, or "NAME (built in code)"
  std::string scene_text;  ///< Recording::scene_text: the scene file's bytes, or empty
  SessionSettings view;
  /// The game after its setup(): what a run plays, and what a restart, a replay and a rollback
  /// copy (so what setup() keeps in the game's members, handles and tags, is kept).
  std::unique_ptr<const AnyGame> game;
};

/// Loads the scene file `file` (none when empty), prints its warnings, applies the setup() of
/// a copy of `game` (kept as Level::game; `game` is not changed). Throws SceneError for a bad
/// scene. The level is checked where its world is made (World(def): the stability guard, with
/// the scene's allow_unstable, the limits and the overlaps).
[[nodiscard]] Level load_level(const AnyGame& game, const Settings& settings,
                               const std::string& file);
/// The level `rec` was recorded on: the scene it carries, else `scene` (--scene) or the game's
/// scene file; the game's setup(), then the recorded settings (dt, integrator, precision). The
/// recorded run ran, so an unstable level is replayed all the same (def.allow_unstable; its
/// limits are checked).
[[nodiscard]] Level replay_level(const AnyGame& game, const Settings& settings,
                                 const Recording& rec, const std::optional<std::string>& scene);
/// The game's bindings: Settings::actions (fixstep's default actions when empty), axes and loop
/// keys. Throws std::invalid_argument naming the fault (InputMap::problem).
[[nodiscard]] InputMap game_input_map(const Settings& settings);
/// Loads --input SCRIPT for `level`, its press / release / axes naming the game's actions and
/// axes (SceneError naming the file, line and key); prints its warnings (unknown keys).
[[nodiscard]] InputScript game_script(const Settings& settings, const Level& level,
                                      const std::string& file);
/// The names an input script may press and set: the map's actions and axes.
[[nodiscard]] ScriptNames script_names(const InputMap& map);
/// TickRules that run `game`'s rules (held by reference) after each step, or before it when
/// `before_step` (Settings::rules_before_step), and save and restore the game by copy.
[[nodiscard]] TickRules game_rules(AnyGame& game, bool before_step);

/// A recording replayed with a game's rules (replay_game).
struct GameReplay {
  Level level{};                    ///< the level it was replayed on (replay_level)
  std::unique_ptr<World> world{};   ///< where the replay stopped
  std::unique_ptr<AnyGame> game{};  ///< the game's state there
  double initial_energy = 0.0;      ///< J, the level's at tick 0 (summary_line)
  ReplayReport report{};            ///< verified hashes, or the first mismatch
};

/// Replays `rec` (read from `file`, named in messages) on its level (replay_level with `scene`)
/// with a copy of `game`'s rules, verifying every stored hash. Does not compare the rules name
/// (the caller decides what a recording of other rules means). Throws std::runtime_error
/// "FILE was recorded on another level (hash H, this one H')" when the level's definition hash
/// is not the recording's, LimitError ("FILE: end N: ...") when its ticks exceed the command
/// limits (check_command_work, before a tick is stepped), and what replay_level throws.
[[nodiscard]] GameReplay replay_game(const AnyGame& game, const Settings& settings,
                                     const Recording& rec, const std::string& file,
                                     const std::optional<std::string>& scene);

}  // namespace fixstep::app::detail
