// Internal to fixstep::app, and shared with the web page (web/): a game being played live, in
// a window, headless or in a browser.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "fixstep/app/game_level.hpp"
#include "fixstep/app/overlay.hpp"
#include "fixstep/app/session.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"

namespace fixstep::app::detail {

/// One frame of `game` on `session`: the frame prepared (Session::prepare_frame), the game's
/// drawing into `overlay` (emptied first; bound to the session while the game draws), its HUD
/// lines and `hint` (one line per '\n' in it) as the status lines, then the frame drawn with
/// the overlay.
void draw_game(Session& session, const AnyGame& game, Overlay& overlay, std::string_view hint);

/// The game, its Session and the input sampler; a recorder when recording. Every live tick:
/// the sampler's input, prepare(), step, rules(), record.
class GamePlay {
 public:
  /// Starts a copy of level.game (the game as setup() left it) on `level`; records into
  /// `record_file` unless it is empty.
  GamePlay(Level level, const Settings& settings, std::string record_file);
  GamePlay(const GamePlay&) = delete;
  GamePlay& operator=(const GamePlay&) = delete;

  /// One frame of `seconds` (s) of real or virtual time.
  void advance(double seconds);
  /// Draws the frame: the world, the engine's HUD, the game's lines and `hint`.
  void draw(std::string_view hint);
  /// Back to tick 0: a fresh copy of the game, an empty sampler, a new recording.
  void restart();
  /// Prints the summary line and the game's, and writes the recording, if any.
  void finish();

  [[nodiscard]] Session& session() { return session_; }
  [[nodiscard]] InputSampler& sampler() { return sampler_; }
  [[nodiscard]] AnyGame& game() { return *game_; }

 private:
  void start_recording();

  Level level_;
  std::string name_, record_file_;
  std::uint32_t rules_version_;  ///< Settings::rules_version
  Session session_;
  std::unique_ptr<AnyGame> game_;
  InputSampler sampler_;
  std::optional<Recorder> recorder_;
  TickInput last_;  ///< the last tick's input (drawn: the pointer's drag)
  Overlay overlay_;
};

}  // namespace fixstep::app::detail
