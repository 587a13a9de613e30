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
#include "fixstep/io/recording_writer.hpp"
#include "fixstep/scene/input_script.hpp"

namespace fixstep::app::detail {

/// One frame of `game` on `session`: the frame prepared (Session::prepare_frame), the game's
/// drawing into `overlay` (emptied first; bound to the session while the game draws), its HUD
/// lines and `hint` (one line per '\n' in it) as the status lines, then the frame drawn with
/// the overlay.
void draw_game(Session& session, const AnyGame& game, Overlay& overlay, std::string_view hint);

/// The game, its Session and the input sampler; a recording streamed to its file when
/// recording (RecordingWriter: O(1) memory however long the session; finished early, with a
/// warning, when it nears max_recording_bytes, so that it stays readable). Every live tick: the
/// sampler's input, prepare(), step, rules(), record. No tick starts once a stop is requested
/// (fixstep::request_stop, e.g. by StopOnSignal's SIGINT / SIGTERM handler).
class GamePlay {
 public:
  /// Starts a copy of level.game (the game as setup() left it) on `level`; records into
  /// `record_file` unless it is empty: its temporary file (".NAME.tmp.PID" beside it) is
  /// created here (std::runtime_error naming the file when it cannot be), and renamed onto
  /// `record_file` by finish() or finish_stopped().
  GamePlay(Level level, const Settings& settings, std::string record_file);
  GamePlay(const GamePlay&) = delete;
  GamePlay& operator=(const GamePlay&) = delete;

  /// One frame of `seconds` (s) of real or virtual time. Ticks due after a stop request are not
  /// run; a tick in progress when one arrives throws StopRequested (stop_request.hpp), and the
  /// world is then torn (finish_stopped(true)).
  void advance(double seconds);
  /// Draws the frame: the world, the engine's HUD, the game's lines and `hint`.
  void draw(std::string_view hint);
  /// Back to tick 0: a fresh copy of the game, an empty sampler, a new recording (the old
  /// one's temporary file removed).
  void restart();
  /// Prints the summary line and the game's, and writes the recording, if any, up to the
  /// current tick.
  void finish();
  /// After a stop: writes the recording, if any, up to the last complete tick; `torn` (a tick
  /// abandoned half-way by StopRequested): up to the last tick before it, and no summary is
  /// printed (the state is no tick's). Otherwise as finish().
  void finish_stopped(bool torn);

  /// Plays `script` (kept; it must outlive the play) as the input of every tick from now on,
  /// before the game's prepare() (--input SCRIPT); a restart plays it from its start again.
  void play_script(const InputScript& script) { script_.emplace(script); }

  [[nodiscard]] Session& session() { return session_; }
  [[nodiscard]] InputSampler& sampler() { return sampler_; }
  [[nodiscard]] AnyGame& game() { return *game_; }

 private:
  void start_recording();
  /// Records a tick; finishes the recording when it nears max_recording_bytes.
  void record(const TickInput& input, const World& world);

  Level level_;
  std::string name_, record_file_;
  std::uint32_t rules_version_;         ///< Settings::rules_version
  bool rules_before_step_;              ///< Settings::rules_before_step
  std::optional<ScriptPlayer> script_;  ///< --input
  Session session_;
  std::unique_ptr<AnyGame> game_;
  InputSampler sampler_;
  std::optional<RecordingWriter> recorder_;
  std::uint64_t initial_hash_ = 0;    ///< the state hash at tick 0 (finish_stopped)
  std::uint64_t recorded_ticks_ = 0;  ///< the ticks of a recording finished at its limit
  TickInput last_;                    ///< the last tick's input (drawn: the pointer's drag)
  Overlay overlay_;
};

}  // namespace fixstep::app::detail
