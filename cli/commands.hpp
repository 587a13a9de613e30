// The fixstep subcommands, separated from argument parsing.
#pragma once

#include <array>
#include <cstdint>
#include <fixstep/app/session.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/scene/scene.hpp>
#include <fixstep/window/window.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/io/recording_file.hpp"

namespace fixstep::cli {

/// Exit status when the runtime guard stopped the simulation (a body's state left the finite
/// range; World::fault). 1 is any other error, 2 a command-line error.
inline constexpr int exit_diverged = 3;
/// `replay`: a stored state hash differs from the replayed state's.
inline constexpr int exit_replay_diverged = 4;
/// `diff`: the two recordings differ (in inputs, stored hashes or length), as a diverged replay.
inline constexpr int exit_recordings_differ = exit_replay_diverged;
/// A recording that cannot be read: unreadable, truncated, corrupt or not a recording.
inline constexpr int exit_bad_recording = 5;
/// The scene no longer matches the recording (its definition hash differs).
inline constexpr int exit_scene_mismatch = 6;
/// A recording of a format version this build cannot read.
inline constexpr int exit_unsupported_version = 7;
/// Exit status when `run --sync-test K` found a re-simulated tick whose state differs.
inline constexpr int exit_sync_test_failed = 8;

struct SceneOptions {
  std::string scene;
  std::optional<std::string> integrator;
  std::optional<double> dt;  ///< s
  std::optional<std::string> precision;
  std::optional<int> substeps;
  std::optional<std::string> damping_split;  ///< per_stage | per_step (WorldSettings)
  bool allow_unstable = false;
  bool quiet = false;  ///< --quiet: errors only (no summary, warnings or progress)
  /// --joints off|anchors|limits (render, view): overrides [view] joints.
  std::optional<std::string> joints;
};

struct RunOptions {
  SceneOptions scene;
  std::optional<std::int64_t> steps;
  std::optional<double> duration;  ///< s
  std::optional<std::string> csv;
  std::int64_t every = 1;
  std::optional<std::string> input;   ///< --input SCRIPT: scripted input (input_script.hpp)
  std::optional<std::string> record;  ///< --record FILE: write a recording of the run
  std::uint64_t hash_every = 1;       ///< --hash-every K: ticks between stored state hashes
  std::optional<int> sync_test;       ///< --sync-test K: roll back K ticks every tick (SyncTest)
};

struct RenderOptions {
  SceneOptions scene;
  std::optional<std::string> out;    ///< --out DIR: PNG frames (the default capture)
  std::optional<std::string> video;  ///< --video FILE: .mp4 (H.264) or .gif
  std::int64_t frames = 120;
  double fps = 60.0;
  std::string size = "1280x720";
  int png_level = default_png_level;  ///< see PngSettings::level
  /// --replay FILE: every tick takes the recording's input (none past its end), on the world
  /// scene_for_recording gives; the recording is verified whole before the first frame.
  std::optional<std::string> replay;
  bool overwrite = false;  ///< --overwrite: remove the old capture's files in --out DIR first
};

struct ViewOptions {
  SceneOptions scene;
  std::string size = "1280x720";
  std::int64_t frames = 0;
  std::optional<double> fps;
  std::optional<std::string> record;  ///< --record FILE: write a recording of the session
  std::uint64_t hash_every = 1;       ///< --hash-every K: ticks between stored state hashes
  bool no_watch = false;              ///< --no-watch: no hot reload when the scene file is saved
};

struct ReplayOptions {
  std::string recording;
  /// --scene SCENE; default: the scene the recording carries, or for a recording without one
  /// the file it names (scene_for_recording).
  std::optional<std::string> scene;
  bool quiet = false;
};

struct DiffOptions {
  std::string a, b;    ///< the two recording files
  bool quiet = false;  ///< --quiet: the exit status alone (errors still printed)
};

/// Largest --steps, --every and view --frames: 10^12 ticks (over 500 years at 60 Hz).
inline constexpr std::int64_t max_ticks = 1'000'000'000'000;

/// CLI11 validator text: "" when value is a step length dt in (0, 1] s, the scene rule.
std::string dt_validator(const std::string& value);
/// CLI11 validator text: "" when value is a finite number > 0.
std::string positive_finite(const std::string& value);
/// CLI11 validator text: "" when value is WxH within the renderer's limits.
std::string frame_size_validator(const std::string& value);
/// CLI11 validator text: "" when value is an integer PNG level in [min_png_level, max_png_level].
std::string png_level_validator(const std::string& value);
/// Parses "WxH" (validated by frame_size_validator).
std::pair<int, int> parse_frame_size(const std::string& value);

/// "scene=FILE integrator=NAME precision=f32|f64 dt=S [substeps=N]": the first line every
/// subcommand prints.
std::string describe(const Scene& scene);

/// --joints' values, as [view] joints spells them.
inline constexpr std::array<const char*, 3> joint_view_names{"off", "anchors", "limits"};
/// Sets scene.view.joints as --joints `joints` (one of joint_view_names) says, if given.
void apply_joint_view(const std::optional<std::string>& joints, Scene& scene);

/// Loads the scene, applies the overrides (--joints' among them), checks the work and memory limits
/// (LimitError) and prints the scene's warnings to stderr. The generators' progress is shown on a
/// terminal unless
/// --quiet (seconds for 10^6 bodies: WorkProgressLine); they poll stop requests (StopRequested).
/// Given `warnings`, the warnings are appended there (whatever --quiet says) instead of printed
/// and no progress line is made: the reports go to the caller's WorkProgressScope (a load on
/// another thread, whose caller prints).
Scene load_with_overrides(const SceneOptions& options,
                          std::vector<std::string>* warnings = nullptr);

/// The scene's world: World(scene.def), which checks it (the stability guard among the checks),
/// with a refusal located in the file (SceneError naming the line, key and what to change:
/// located, scene_stability.hpp) and the guard's warnings located too, printed to stderr
/// unless `quiet`. The guard's progress is shown as load_with_overrides shows the generators';
/// given `warnings`, they are appended there instead and no progress line is made.
[[nodiscard]] World build_world(const Scene& scene, bool quiet,
                                std::vector<std::string>* warnings = nullptr);

/// Opens the window; without a display, the WindowError's message (the library's: the fault
/// only) ends with the advice to capture headless with the command `headless`.
[[nodiscard]] Window open_window(const std::string& title, int width, int height,
                                 std::string_view headless);

/// What set a scene's dt, for messages: "--dt S" when the command line did, else "[world] dt =
/// S s in FILE".
[[nodiscard]] std::string dt_source(const SceneOptions& options, const Scene& scene);
/// How to give a longer dt, for check_frame_ticks: "give --dt" when the command line set it,
/// else "set [world] dt (or --dt) to".
[[nodiscard]] std::string dt_fix(const SceneOptions& options);
/// Throws LimitError when a frame of up to `frame_seconds` (s: the loop's frame-time clamp, or
/// 1/fps when longer) is more ticks of `dt` (s) than a frame may step (max_frame_ticks, the
/// Session's refusal): the message starts with `source`, what set dt ("--dt 1e-10", "--with
/// 'rk4@1e-10'"), says where the frame's length comes from (`fps`: the --fps given, if any),
/// and ends with `fix`, how to give a longer dt, after the smallest dt that would do.
void check_frame_ticks(double frame_seconds, double dt, std::optional<double> fps,
                       std::string_view source, std::string_view fix);

/// How a Session shows a scene: its [view] and its file name in the HUD, width x height pixels.
[[nodiscard]] SessionSettings session_settings(const Scene& scene, int width, int height);
/// Throws LimitError when `ticks` ticks with a hash every `hash_every` would make the recording
/// `file` larger than max_recording_bytes (the reader's limit), naming the --hash-every to use.
void check_recording_size(std::uint64_t ticks, std::uint64_t hash_every, const std::string& file);

int run_command(const RunOptions& options);
int render_command(const RenderOptions& options);
int view_command(const ViewOptions& options);
int replay_command(const ReplayOptions& options);
/// `fixstep diff A B`: the report of describe(RecordingDiff) on standard output; 0 when the
/// recordings are identical, exit_recordings_differ when they differ, exit_scene_mismatch when
/// their worlds (scene, settings or rules) differ; a recording that cannot be read throws
/// RecordingError (naming its file).
int diff_command(const DiffOptions& options);

/// The exit status for a recording error: exit_bad_recording, exit_scene_mismatch or
/// exit_unsupported_version.
[[nodiscard]] int exit_code(const RecordingError& error);

/// The scene file a recording names: its path as recorded if that exists (relative to the
/// current directory), else relative to the recording file's directory.
[[nodiscard]] std::string recorded_scene(const Recording& rec, const std::string& recording_file);
/// The scene to replay `rec` (read from `recording_file`) on, warnings printed unless quiet:
/// `scene_file` when given (a note says so when the recording carries its own scene), else
/// the scene the recording carries (Recording::scene_text; the file on disk is not read), else,
/// for a recording without one (format versions 1 and 2), the file it names (recorded_scene;
/// std::runtime_error when it is not there). The recording's precision, dt, integrator,
/// substeps and damping split replace the scene's and the stability guard is off (the
/// recorded run ran). The scene's definition hash must be the recording's: else RecordingError
/// scene_mismatch for a scene file, corrupt for the scene the recording carries (as for one
/// that does not load); every body the recording names must be in it (else RecordingError
/// corrupt: check_recorded_bodies).
[[nodiscard]] Scene scene_for_recording(const Recording& rec, const std::string& recording_file,
                                        const std::optional<std::string>& scene_file, bool quiet);
/// Replays `rec` headless on `scene`'s world (scene_for_recording's), checking every stored
/// hash and the final one (fixstep::replay), with a progress line unless quiet.
[[nodiscard]] ReplayReport verify_recording(const Scene& scene, const Recording& rec, bool quiet);
/// Prints the located error of a diverged replay to stderr: "fixstep: error: FILE: replay
/// diverged at tick N: state_hash H recorded, H' replayed (...); LIKELY CAUSE" and `written`
/// (what the command wrote, or "" for nothing to say).
void report_divergence(const ReplayReport::Mismatch& mismatch, const std::string& recording_file,
                       std::string_view written);
/// "" when `options` may go with --replay; else the message naming the first flag that would
/// change the recorded world or its stepping (--dt, --integrator, --precision, --substeps,
/// --damping-split), for exit 2.
[[nodiscard]] std::string replay_flag_conflict(const SceneOptions& options);

}  // namespace fixstep::cli
