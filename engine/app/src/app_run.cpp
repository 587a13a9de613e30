// fixstep::app::run: the command line, and the mode it names.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/output_target.hpp>
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
  auto* record_opt =
      cli.add_option("--record", o.record, "record the session into FILE")->type_name("FILE");
  auto* replay_opt =
      cli.add_option("--replay", o.replay, "replay FILE headless, verifying every state hash")
          ->type_name("FILE");
  cli.add_option("--every", o.every, "with --replay --out: every K-th frame (and the last)")
      ->type_name("K")
      ->check(at_least_one);
  auto* last_opt = cli.add_option("--last-frame", o.last_frame,
                                  "with --frames or --replay: write the last frame as PNG")
                       ->type_name("PNG");
  auto* sync_opt = cli.add_option("--sync-test", o.sync_test,
                                  "with --frames: roll every tick back K ticks and re-simulate")
                       ->type_name("K")
                       ->check(at_least_one)
                       ->needs(frames_opt);
  replay_opt->excludes(record_opt)->excludes(frames_opt);
  sync_opt->excludes(record_opt)->excludes(out_opt)->excludes(last_opt);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(cli.help().c_str(), stdout);
    throw;
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
  if (scene_opt->count() > 0) o.scene = scene;
  if (last_opt->count() > 0 && o.frames == 0 && o.replay.empty()) {
    throw UsageError("--last-frame PNG needs --frames N or --replay FILE");
  }
  if (!o.out.empty() && o.replay.empty() && (o.frames == 0 || o.window)) {
    throw UsageError("--out DIR needs --frames N (headless) or --replay FILE");
  }
  return o;
}

/// Refuses, before anything runs, an output that may not be written (a directory, a socket, a
/// missing directory) or that is one of the inputs: a session is not played only to be lost.
void check_outputs(const Settings& settings, const Options& o) {
  const std::string scene = o.scene.value_or(settings.scene_file);
  check_output_before_run("--record", o.record, {scene, o.replay});
  check_output_before_run("--last-frame", o.last_frame, {scene, o.replay});
}

int run_mode(const AnyGame& game, const Settings& settings, const Options& o) {
  if (!o.replay.empty()) return replay_file(game, settings, o);
  if (o.sync_test > 0) return sync_test(game, settings, o);
  return play(game, settings, o);
}

}  // namespace

int run_game(const AnyGame& game, const Settings& settings, int argc, char** argv) {
  const char* name = settings.name.c_str();
  try {
    const Options o = parse(settings, argc, argv);
    check_outputs(settings, o);
    return run_mode(game, settings, o);
  } catch (const CLI::CallForHelp&) {
    return 0;
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

}  // namespace fixstep::app::detail
