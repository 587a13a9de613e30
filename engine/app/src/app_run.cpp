// fixstep::app::run: the command line, and the mode it names.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/command_limits.hpp>
#include <fixstep/io/output_paths.hpp>
#include <fixstep/io/output_target.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/io/standard_output.hpp>
#include <fixstep/io/stop_signal.hpp>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "app_modes.hpp"
#ifdef FIXSTEP_APP_WINDOW
#include <fixstep/window/window.hpp>
#endif

namespace fixstep::app::detail {

namespace {

/// A whole number >= 1: CLI11's PositiveNumber accepts 0.5 and prints its range as 1.8e308.
const CLI::Validator at_least_one(
    [](std::string& text) -> std::string {
      std::int64_t n = 0;
      const char* end = text.data() + text.size();
      const auto [stop, error] = std::from_chars(text.data(), end, n);
      if (error == std::errc{} && stop == end && n >= 1) return {};
      return "wants a whole number >= 1, got '" + text + "'";
    },
    "N >= 1");

/// --help's statement of what a run may cost, every bound checked before the first tick.
constexpr const char* bounds_help =
    "Work: --frames N steps at most 10^9 ticks (N / 60 s of the level's dt) and 10^13 "
    "body-substeps in all (with --sync-test K, each tick counts 1 + K times); a --replay the "
    "recording's ticks, the same bounds (--diff: both recordings' ticks up to where they differ). "
    "Memory: the level's world and one frame; --record "
    "streams the recording to its file (a few kB held, at most 256 MiB written); --replay holds "
    "the recording read (at most 256 MiB); --sync-test K holds K + 1 snapshots of the world, at "
    "most 2 GiB. Refused before the first tick, naming the flag. SIGINT or SIGTERM stops any mode "
    "within a second: the recording is written up to its last complete tick, the frames drawn "
    "are whole; exit 130 or 143.\n";

/// The command line's options, refused (UsageError) when they do not fit together.
Options parse(const Settings& settings, int argc, char** argv) {
  Options o;
  CLI::App cli(
      settings.description.empty() ? settings.name : settings.name + ": " + settings.description,
      settings.name);
  std::string scene;
  auto* scene_opt =
      cli.add_option("--scene", scene, "play the level in FILE (a scene file)")->type_name("FILE");
  auto* frames_opt = cli.add_option("--frames", o.frames,
                                    "run N frames headless (60 frames/s), the autopilot playing")
                         ->type_name("N")
                         ->check(at_least_one);
  cli.add_flag("--window", o.window, "with --frames: in the window, then quit")->needs(frames_opt);
  auto* out_opt =
      cli.add_option("--out", o.out, "write every frame as a PNG into DIR")->type_name("DIR");
  cli.add_flag("--overwrite", o.overwrite,
               "with --out: remove the capture DIR already holds first (else refused)")
      ->needs(out_opt);
  auto* record_opt =
      cli.add_option("--record", o.record, "record the session into FILE")->type_name("FILE");
  auto* replay_opt =
      cli.add_option("--replay", o.replay, "replay FILE headless, verifying every state hash")
          ->type_name("FILE");
  auto* diff_opt =
      cli.add_option("--diff", o.diff,
                     "where recordings A and B first differ: inputs, stored hashes and, replayed "
                     "side by side with the rules, the first tick, body and field (exit 4: they "
                     "differ)")
          ->type_name("A B")
          ->expected(2);
  cli.add_option("--every", o.every, "with --replay --out: every K-th frame (and the last)")
      ->type_name("K")
      ->check(at_least_one);
  auto* last_opt = cli.add_option("--last-frame", o.last_frame,
                                  "with --frames or --replay: write the last frame as PNG")
                       ->type_name("PNG");
  auto* input_opt =
      cli.add_option("--input", o.input,
                     "with --frames: the input script FILE plays (press / release the game's "
                     "actions by name), not the autopilot")
          ->type_name("SCRIPT")
          ->needs(frames_opt);
  auto* sync_opt = cli.add_option("--sync-test", o.sync_test,
                                  "with --frames: roll every tick back K ticks and re-simulate")
                       ->type_name("K")
                       ->check(at_least_one)
                       ->needs(frames_opt);
  replay_opt->excludes(record_opt)->excludes(frames_opt)->excludes(input_opt);
  diff_opt->excludes(replay_opt)->excludes(record_opt)->excludes(frames_opt)->excludes(out_opt);
  diff_opt->excludes(last_opt);
  cli.footer(bounds_help);
  sync_opt->excludes(record_opt)->excludes(out_opt)->excludes(last_opt);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(cli.help().c_str(), stdout);
    throw;
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
  if (scene_opt->count() > 0) {
    if (settings.scene_file.empty()) {  // setup() builds the level: a scene would be replaced
      throw UsageError("--scene " + scene + ": " + settings.name +
                       " builds its level in code and plays no scene file, so the scene would "
                       "not be the level played; run without --scene");
    }
    o.scene = scene;
  }
  if (last_opt->count() > 0 && o.frames == 0 && o.replay.empty()) {
    throw UsageError("--last-frame PNG needs --frames N or --replay FILE");
  }
  if (!o.out.empty() && o.replay.empty() && (o.frames == 0 || o.window)) {
    throw UsageError("--out DIR needs --frames N (headless) or --replay FILE");
  }
  return o;
}

/// Refuses, before anything runs, an output that may not be written (a directory, a socket, a
/// descriptor not open for writing, a missing directory), that is one of the inputs or another
/// output, or a --out DIR that holds a capture (without --overwrite): the checks of the fixstep
/// command's outputs (fixstep/io/output_paths.hpp). A session is not played only to be lost.
/// Returns the paths checked.
OutputPaths check_outputs(const Settings& settings, const Options& o) {
  const std::string scene = o.scene.value_or(settings.scene_file);
  OutputPaths paths{.program = settings.name, .overwrite = o.overwrite};
  if (!scene.empty()) paths.inputs.push_back({"--scene", scene});
  if (!o.replay.empty()) paths.inputs.push_back({"--replay", o.replay});
  if (!o.input.empty()) paths.inputs.push_back({"--input", o.input});
  for (const std::string& file : o.diff) paths.inputs.push_back({"--diff", file});
  if (!o.record.empty()) paths.outputs.push_back({"--record", o.record});
  if (!o.last_frame.empty()) paths.outputs.push_back({"--last-frame", o.last_frame});
  if (!o.out.empty()) {
    paths.capture_dir = o.out;
    paths.outputs.push_back(
        {"--out DIR's manifest", (std::filesystem::path(o.out) / "frames.csv").string()});
  }
  check_output_paths(paths);
  check_output_before_run("--record", o.record, {scene, o.replay, o.input});
  check_output_before_run("--last-frame", o.last_frame, {scene, o.replay, o.input});
  return paths;
}

int run_mode(const AnyGame& game, const Settings& settings, const Options& o) {
  (void)game_input_map(settings);  // a game's bad bindings: before anything runs
  if (!o.diff.empty()) return diff_files(game, settings, o);
  if (!o.replay.empty()) return replay_file(game, settings, o);
  if (o.sync_test > 0) return sync_test(game, settings, o);
  return play(game, settings, o);
}

}  // namespace

int stopped(const Settings& settings, std::uint64_t tick, bool torn, std::string_view written) {
  std::fprintf(stderr, "%s: stopped by %s after tick %llu%s%s%s\n", settings.name.c_str(),
               StopOnSignal::name(), static_cast<unsigned long long>(tick),
               torn ? " (the tick in progress discarded)" : "", written.empty() ? "" : "; ",
               std::string(written).c_str());
  return 128 + StopOnSignal::requested();
}

void check_recorded_frames(const Level& level, std::int64_t frames, const std::string& file) {
  const double ticks =
      std::ceil(static_cast<double>(frames) / virtual_fps / level.def.settings.dt) + 1.0;
  constexpr double hash_line_bytes = 33.0;  // "hash " + 10 digits + " " + 16 hex + "\n"
  if (ticks * hash_line_bytes > static_cast<double>(max_recording_bytes)) {
    const double most_frames = static_cast<double>(max_recording_bytes) / hash_line_bytes *
                               level.def.settings.dt * virtual_fps;
    throw LimitError(fmt::format(
        "--record {}: --frames {} is about {:.3g} ticks, each with its state hash: about {:.0f} "
        "MB of hashes; a recording may hold at most {} MiB: record at most {:.0f} frames",
        file, frames, ticks, ticks * hash_line_bytes / 1e6, max_recording_bytes >> 20,
        std::floor(most_frames) - 2.0));
  }
}

void check_frames_work(const Level& level, std::int64_t frames, std::uint64_t per_tick,
                       std::string_view flag) {
  // Frame 0 runs no tick; each later one runs at most ceil(1 / (fps dt)) of them.
  const double ticks =
      std::ceil(static_cast<double>(frames) / virtual_fps / level.def.settings.dt) + 1.0;
  const std::uint64_t claimed =
      ticks >= 0x1p63 ? std::uint64_t{1} << 63 : static_cast<std::uint64_t>(ticks);
  check_command_work(claimed, tick_work(level.def) * per_tick,
                     fmt::format("{} (at {:g} frames/s and dt = {:g} s)", flag, virtual_fps,
                                 level.def.settings.dt));
}

InputScript game_script(const Settings& settings, const Level& level, const std::string& file) {
  InputScript script =
      load_input_script(file, level.def.bodies, script_names(game_input_map(settings)));
  for (const std::string& w : script.warnings) {
    std::fprintf(stderr, "%s: warning: %s\n", settings.name.c_str(), w.c_str());
  }
  return script;
}

int run_game_unchecked(const AnyGame& game, const Settings& settings, int argc, char** argv) {
  const char* name = settings.name.c_str();
  try {
    const Options o = parse(settings, argc, argv);
    // `--record -`: standard output carries the recording alone; the summary goes to stderr.
    if (data_on_standard_output(check_outputs(settings, o))) keep_standard_output_for_data();
    const StopOnSignal signals;  // SIGINT / SIGTERM: the mode stops and writes what it has
    return run_mode(game, settings, o);
  } catch (const CLI::CallForHelp&) {
    return 0;
  } catch (const PathRefused& e) {  // an output that is an input, a --out DIR holding a capture
    std::fprintf(stderr, "%s\n", e.what());
    return exit_usage;
  } catch (const StopRequested& e) {  // a stop while loading or verifying: nothing to keep
    std::fprintf(stderr, "%s: stopped by %s; nothing was written\n", name, StopOnSignal::name());
    return 128 + e.signal();
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\nRun with --help for more information.\n", name, e.what());
    return exit_usage;
#ifdef FIXSTEP_APP_WINDOW
  } catch (const WindowError& e) {
    std::fprintf(stderr, "%s: error: %s. Run headless instead: %s --frames 120 --out frames\n",
                 name, e.what(), name);
    return exit_error;
#endif
  } catch (const std::exception& e) {  // a bad scene, a bad recording, an unwritable file
    std::fprintf(stderr, "%s: error: %s\n", name, e.what());
    return exit_error;
  }
}

int run_game(const AnyGame& game, const Settings& settings, int argc, char** argv) {
  return with_results_on_standard_output(
      settings.name, [&] { return run_game_unchecked(game, settings, argc, argv); });
}

}  // namespace fixstep::app::detail
