// The page's game mode (game=NAME, page_options.hpp): a game of demos/ played as its program's
// fixstep::app::run plays it, through the same pieces (fixstep/app/game_level.hpp,
// game_play.hpp): the level its setup() builds, its rules after every tick, its input from the
// browser's pointer and keys (the same feed() into the same InputSampler as a window's), its
// drawing and HUD lines over the world in its view; headless frames= with its autopilot, and
// replay= of its recordings verified with its rules. Web platform (wasm only).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "fixstep/app/app.hpp"
#include "fixstep/app/game_level.hpp"
#include "fixstep/app/game_play.hpp"
#include "fixstep/app/session.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/rules.hpp"
#include "fixstep/scene/input_script.hpp"
#include "page_input.hpp"
#include "page_options.hpp"

namespace fixstep::web {

class PageGame {
 public:
  /// Builds o.game's level and starts it (interactive or frames=); for replay= it waits for
  /// the recording (recording_fetched). Throws what the level's checks throw.
  explicit PageGame(PageOptions o);
  ~PageGame();
  PageGame(const PageGame&) = delete;
  PageGame& operator=(const PageGame&) = delete;

  /// One browser frame at `now_ms` (performance.now(), ms); false once the page has finished.
  bool frame(double now_ms);
  /// replay=: the recording's text. Throws std::invalid_argument naming the file for a
  /// recording of a scene (no rules) or of another game's rules (naming both), and what
  /// parse_recording and app::detail::replay_game throw; a recording that diverges is reported
  /// (id result) and not played back.
  void recording_fetched(const std::string& text);
  /// input=: the script's text, parsed against the level's bodies and the game's actions and
  /// axes (SceneError naming the script, line and key); the frames then play it.
  void script_fetched(const std::string& text);

 private:
  void interactive_frame(double now_ms);
  bool frames_frame(double now_ms);
  bool replay_frame(double now_ms);
  /// Writes "tick=N state_hash=H" (id result) and the summary lines the program prints (id
  /// summary: the engine's line, then the game's); title "done".
  void report();
  void show_summary(const World& world, double initial_energy, const app::detail::AnyGame& game);

  PageOptions o_;
  std::unique_ptr<const app::detail::AnyGame> prototype_;  ///< the game before its setup()
  app::Settings settings_;
  std::unique_ptr<app::detail::GamePlay> play_;  ///< live: interactive and frames=
  std::int64_t frames_done_ = 0;
  std::unique_ptr<PageInput> input_;
  std::string hint_;
  double last_ms_ = -1.0;
  // replay: the recording played back on its level after the verdict
  std::optional<Recording> recording_;
  std::unique_ptr<Session> session_;
  std::unique_ptr<app::detail::AnyGame> game_;
  std::optional<InputScript> script_;  ///< input=, once fetched
  TickRules replay_rules_;  ///< game_'s rules, in the game's order (Settings::rules_before_step)
  TickInput last_;
  app::Overlay overlay_;
  bool replay_stopped_ = false;  ///< the recording diverged: nothing to play
};

}  // namespace fixstep::web
