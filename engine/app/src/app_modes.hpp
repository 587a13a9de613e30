// Internal to fixstep::app: the modes app::run dispatches to (the level each starts from:
// fixstep/app/game_level.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/app/app.hpp"
#include "fixstep/app/game_level.hpp"
#include "fixstep/render/input_map.hpp"
#include "fixstep/scene/input_script.hpp"

namespace fixstep::app::detail {

/// Exit statuses of app::run (see its docstring).
inline constexpr int exit_error = 1;
inline constexpr int exit_usage = 2;
inline constexpr int exit_diverged = 4;
inline constexpr int exit_sync_mismatch = 8;

/// A command line run() refuses (exit_usage).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What the command line asked for.
struct Options {
  std::optional<std::string> scene;  ///< --scene FILE
  std::string out, record, replay, last_frame;
  std::string input;              ///< --input SCRIPT (empty: the autopilot or the window plays)
  std::vector<std::string> diff;  ///< --diff A B: the two recordings (else empty)
  std::int64_t frames = 0;        ///< 0: play in a window until quit
  int every = 1;                  ///< --every K
  int sync_test = 0;              ///< --sync-test K (0: none)
  bool window = false;            ///< --window
  bool overwrite = false;         ///< --overwrite: the old capture in --out DIR is removed first
};

/// Frames per second of a headless run's, a drawn replay's and a sync test's virtual clock.
inline constexpr double virtual_fps = 60.0;

/// Throws LimitError (command_limits.hpp) when `frames` frames of 1/virtual_fps s of `level`
/// (each `per_tick` times the ticks of one: 1, or 1 + K for a sync test of K) exceed the work
/// a command may do; `flag` names the claim ("--frames 1000000000000").
void check_frames_work(const Level& level, std::int64_t frames, std::uint64_t per_tick,
                       std::string_view flag);

/// Throws LimitError when `frames` frames of `level` recorded into `file` (a state hash a tick,
/// at most 33 bytes each) would pass max_recording_bytes, the most a recording may hold.
void check_recorded_frames(const Level& level, std::int64_t frames, const std::string& file);

/// After a stop request (StopOnSignal): "NAME: stopped by SIGINT after tick N (...); WRITTEN"
/// on standard error; returns 128 + the signal, as a shell reports a signal's death.
int stopped(const Settings& settings, std::uint64_t tick, bool torn, std::string_view written);

/// Plays in the window (until quit, or o.frames frames) or headless (o.frames frames), recording
/// into o.record when given; prints the summary. Returns the exit status.
int play(const AnyGame& game, const Settings& settings, const Options& o);
/// Replays o.replay, verifies it, draws it when asked. Returns the exit status.
int replay_file(const AnyGame& game, const Settings& settings, const Options& o);
/// Compares the recordings o.diff names, both replayed side by side with the game's rules
/// (diff_recordings), printing where they first differ. Returns 0 when identical, exit_diverged
/// when they differ, exit_error for recordings of other levels or rules.
int diff_files(const AnyGame& game, const Settings& settings, const Options& o);
/// Runs o.frames frames headless under a sync test of o.sync_test ticks. Returns the exit status.
int sync_test(const AnyGame& game, const Settings& settings, const Options& o);

}  // namespace fixstep::app::detail
