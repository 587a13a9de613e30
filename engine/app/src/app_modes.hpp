// Internal to fixstep::app: the modes app::run dispatches to, and the level each starts from.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "fixstep/app.hpp"
#include "fixstep/recording.hpp"
#include "fixstep/session.hpp"

namespace fixstep::app::detail {

/// Exit statuses of app::run (see its docstring).
inline constexpr int exit_error = 1;
inline constexpr int exit_usage = 2;
inline constexpr int exit_diverged = 4;
inline constexpr int exit_sync_mismatch = 8;

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

/// A command line run() refuses (exit_usage).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What the command line asked for.
struct Options {
  std::optional<std::string> scene;  ///< --scene FILE
  std::string out, record, replay, last_frame;
  std::int64_t frames = 0;  ///< 0: play in a window until quit
  int every = 1;            ///< --every K
  int sync_test = 0;        ///< --sync-test K (0: none)
  bool window = false;      ///< --window
};

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
  /// The checks' findings on def (check_definition): the stability guard's warnings.
  std::vector<std::string> warnings;
};

/// Loads the scene file `file` (none when empty), prints its warnings, applies the setup() of
/// a copy of `game` (kept as Level::game; `game` is not changed), then checks the level
/// (check_definition, with the scene's allow_unstable). Throws SceneError for a bad scene, what
/// check_definition throws for a level it refuses.
[[nodiscard]] Level load_level(const AnyGame& game, const Settings& settings,
                               const std::string& file);
/// The level `rec` was recorded on: the scene it carries, else `scene` (--scene) or the game's
/// scene file; the game's setup(), then the recorded settings (dt, integrator, precision). The
/// recorded run ran, so an unstable level is replayed all the same (its limits are checked).
[[nodiscard]] Level replay_level(const AnyGame& game, const Settings& settings,
                                 const Recording& rec, const std::optional<std::string>& scene);
/// TickRules that run `game`'s rules (held by reference) and save and restore it by copy.
[[nodiscard]] TickRules game_rules(AnyGame& game);

/// Plays in the window (until quit, or o.frames frames) or headless (o.frames frames), recording
/// into o.record when given; prints the summary. Returns the exit status.
int play(const AnyGame& game, const Settings& settings, const Options& o);
/// Replays o.replay, verifies it, draws it when asked. Returns the exit status.
int replay_file(const AnyGame& game, const Settings& settings, const Options& o);
/// Runs o.frames frames headless under a sync test of o.sync_test ticks. Returns the exit status.
int sync_test(const AnyGame& game, const Settings& settings, const Options& o);

}  // namespace fixstep::app::detail
