// fixstep: run, capture and view fixed-timestep scenes.
//   fixstep run SCENE (--steps N | --duration S) [--csv FILE] [--every K] [--input SCRIPT]
//               [--record FILE] [--sync-test K] [overrides]
//   fixstep render [SCENE] (--out DIR | --video FILE.mp4|.gif) [--frames N] [--fps F]
//                  [--size WxH] [--png-level L] [--joints MODE] [overrides]
//   fixstep compare SCENE --with SPEC --with SPEC ... [--out DIR] [--video FILE] [--csv FILE]
//                   [--frames N] [--fps F] [--size WxH] [--joints MODE]
//   fixstep view SCENE [--size WxH] [--frames N] [--fps F] [--record FILE] [--no-watch]
//                [--joints MODE] [overrides]
//   fixstep replay FILE [--scene SCENE]
//   fixstep diff A.rec B.rec
//   fixstep new DIR
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/io/command_limits.hpp>
#include <fixstep/io/standard_output.hpp>
#include <fixstep/io/write_signals.hpp>
#include <fixstep/scene/suggest.hpp>
#include <new>
#include <string_view>

#include "capture_sink.hpp"
#include "command_phase.hpp"
#include "commands.hpp"
#include "compare.hpp"
#include "compare_tiles.hpp"
#include "fixstep/io/recording_file.hpp"
#include "new_project.hpp"
#include "output_paths.hpp"

namespace {

/// Options every subcommand shares: the scene and overrides of its [world] table.
/// SCENE is required unless `scene_optional` (render --replay takes the recording's).
void add_scene_options(CLI::App* cmd, fixstep::cli::SceneOptions& o, bool scene_optional = false) {
  cmd->add_option("scene", o.scene,
                  scene_optional ? "scene file (TOML); with --replay, default: the recording's"
                                 : "scene file (TOML), e.g. assets/scenes/default.toml")
      ->required(!scene_optional);
  std::vector<std::string> names;
  for (auto i : fixstep::all_integrators) names.emplace_back(fixstep::integrator_name(i));
  cmd->add_option("--integrator", o.integrator, "override [world] integrator")
      ->check(CLI::IsMember(names));
  cmd->add_option("--dt", o.dt, "override [world] dt, the fixed physics step (s), 0 < dt <= 1")
      ->check(fixstep::cli::dt_validator);
  cmd->add_option("--precision", o.precision, "override [world] precision")
      ->check(CLI::IsMember({"f32", "f64"}));
  cmd->add_option("--substeps", o.substeps,
                  "override [world] substeps (integration steps per tick)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--damping-split", o.damping_split,
                  "override [world] damping_split: where Forest-Ruth applies damped links' flows "
                  "(per_stage: order 4; per_step: cheaper, order 2 in the damping)")
      ->check(CLI::IsMember({"per_stage", "per_step"}));
  cmd->add_flag("--allow-unstable", o.allow_unstable,
                "run even when the stability guard finds an unstable body (warns instead)");
  cmd->add_flag("-q,--quiet", o.quiet,
                "print errors only: no summary, warnings or progress (standard output is empty)");
}

/// --joints MODE of the commands that draw (render, view, compare): [view] joints' override.
void add_joints_option(CLI::App* cmd, std::optional<std::string>& joints) {
  cmd->add_option("--joints", joints,
                  "override [view] joints, how joints are drawn: off, anchors (a mark at each "
                  "anchor: a ring, an axis, a line; the default) or limits (the marks and each "
                  "joint's limits: a revolute joint's arc, ticks along an axis)")
      ->check(CLI::IsMember(std::vector<std::string>(fixstep::cli::joint_view_names.begin(),
                                                     fixstep::cli::joint_view_names.end())));
}

/// --record FILE and --hash-every K (which needs --record).
void add_record_options(CLI::App* cmd, std::optional<std::string>& record,
                        std::uint64_t& hash_every) {
  auto* rec =
      cmd->add_option("--record", record,
                      "write a recording (inputs and state hashes) here: a file atomically; "
                      "-, a FIFO or a device streamed");
  cmd->add_option("--hash-every", hash_every,
                  "store the state hash every K ticks in the recording (default 1: replay names "
                  "the exact first tick that differs)")
      ->check(CLI::Range(std::uint64_t{1}, fixstep::max_hash_every))
      ->needs(rec);
}

/// --overwrite of render and compare (fixstep/capture/capture_dir.hpp).
constexpr const char* overwrite_help =
    "--out DIR may hold an older capture: remove its frames and CSVs first (without it, such "
    "a DIR is refused)";

/// `fixstep compare`'s options.
void add_compare_options(CLI::App* cmd, fixstep::cli::CompareOptions& o) {
  using namespace fixstep::cli;
  cmd->add_option("scene", o.scene, "scene file (TOML), e.g. assets/scenes/spring_damper.toml")
      ->required();
  cmd->add_option(
         "--with", o.with,
         "a tile: INTEGRATOR[@DT][:substeps=N][:precision=f32|f64][:split=per_stage|per_step], DT "
         "in s as a "
         "decimal or A/B (e.g. rk4@1/30); give it 2 to 6 times")
      ->required()
      ->check(tile_spec_validator);
  auto* out =
      cmd->add_option("--out", o.out, "write DIR/frame_NNNNNN.png, frames.csv, compare.csv");
  auto* video = cmd->add_option("--video", o.video, "write FILE.mp4 (H.264) or FILE.gif");
  cmd->add_option("--csv", o.csv,
                  "the summary, a row per tile (default: DIR/compare.csv or FILE.compare.csv)");
  cmd->add_flag("--window", o.window,
                "show the tiles in a window (the default without --out/--video)")
      ->excludes(out)
      ->excludes(video);
  cmd->add_option(
         "--frames", o.frames,
         "frames to capture (default 240), or to show before quitting (default: until Esc)")
      ->check(CLI::Range(std::int64_t{1}, max_ticks));
  cmd->add_option("--fps", o.fps, "virtual frames per second (default 60; the window: real time)")
      ->check(positive_finite);
  cmd->add_option("--size", o.size, "the whole frame in pixels, WxH (tiles share it)")
      ->check(frame_size_validator);
  cmd->add_option("--png-level", o.png_level, "PNG deflate level, as render --png-level")
      ->check(png_level_validator);
  cmd->add_flag("--allow-unstable", o.allow_unstable,
                "show a tile even when the stability guard finds it unstable (warns instead)");
  cmd->add_flag("-q,--quiet", o.quiet, "print errors only");
  cmd->add_flag("--overwrite", o.overwrite, overwrite_help);
  add_joints_option(cmd, o.joints);
}

/// CLI11 validator text: "" when value is a whole number (digits, an optional sign).
std::string whole_number_validator(const std::string& value) {
  const std::size_t start = !value.empty() && (value[0] == '-' || value[0] == '+') ? 1 : 0;
  const bool digits =
      value.size() > start && value.find_first_not_of("0123456789", start) == std::string::npos;
  return digits ? std::string() : fmt::format("must be a whole number of ticks, got '{}'", value);
}

/// "fixstep: unknown command 'rn': did you mean run?" for a mistyped subcommand, or "".
std::string unknown_subcommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return {};
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
  if (std::find(names.begin(), names.end(), argv[1]) != names.end()) return {};
  const auto best = fixstep::closest(argv[1], names);
  return fmt::format(
      "fixstep: unknown command '{}'{}; the commands are run, render, compare, "
      "view, replay, diff and new (fixstep --help)",
      argv[1], best ? fmt::format(" (did you mean {}?)", *best) : "");
}

}  // namespace

// The whole of main is one try block: an exception from any step (CLI11's setup included)
// becomes "fixstep: error: ..." and exit status 1, never std::terminate.
namespace {

/// Whether the command line asks for --quiet (-q): its results go nowhere, so a closed standard
/// output loses nothing.
bool quiet_asked(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg(argv[i]);
    if (arg == "--") return false;
    if (arg == "-q" || arg == "--quiet") return true;
  }
  return false;
}

int run_fixstep(int argc, char** argv) try {
  using namespace fixstep::cli;
  // A write past `ulimit -f` or into a closed pipe fails with an error fixstep reports (naming
  // the option and the file, temporaries removed) instead of killing it without a word.
  fixstep::ignore_write_signals();
  CLI::App app{
      "fixstep: fixed-timestep integration of spring-damper and projectile scenes, "
      "rendered headless with OSMesa or shown in an SDL2 window."};
  app.require_subcommand(1);

  RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "simulate without rendering; print a summary");
  add_scene_options(run_cmd, run.scene);
  auto* steps = run_cmd->add_option("--steps", run.steps, "number of ticks to simulate")
                    ->check(whole_number_validator)
                    ->check(CLI::Range(std::int64_t{0}, max_ticks));
  auto* duration =
      run_cmd->add_option("--duration", run.duration, "simulated time (s)")->check(positive_finite);
  steps->excludes(duration);
  run_cmd->add_option("--csv", run.csv,
                      "write tick,t,body,x,y,vx,vy,energy,... rows here: a file atomically; - "
                      "(standard output), a FIFO or a device streamed (see README)");
  run_cmd->add_option("--every", run.every, "record every K-th tick in the CSV (tick 0 always)")
      ->check(CLI::Range(std::int64_t{1}, max_ticks));
  run_cmd->add_option(
      "--input", run.input,
      "scripted input: a TOML file of [[at]] tables (see docs/CLI.md, Input scripts)");
  add_record_options(run_cmd, run.record, run.hash_every);
  run_cmd
      ->add_option("--sync-test", run.sync_test,
                   "every tick, roll back K ticks, re-simulate them and compare the states "
                   "(GGRS's sync test); exit 8 at the first difference")
      ->check(CLI::Range(1, 10000));

  RenderOptions render;
  CLI::App* render_cmd =
      app.add_subcommand("render", "capture frames headless (OSMesa) as DIR/frame_NNNNNN.png");
  add_scene_options(render_cmd, render.scene, /*scene_optional=*/true);
  render_cmd->add_option("--out", render.out,
                         "write DIR/frame_NNNNNN.png and DIR/frames.csv (DIR created if missing)");
  render_cmd->add_option("--video", render.video,
                         "write a video: FILE.mp4 (H.264) or FILE.gif, and FILE.frames.csv");
  render_cmd->add_option("--frames", render.frames, "number of frames (frame 0 is t = 0)")
      ->check(CLI::Range(1, 1000000));
  render_cmd->add_option("--fps", render.fps, "virtual frames per second")->check(positive_finite);
  render_cmd->add_option("--size", render.size, "frame size in pixels, WxH")
      ->check(frame_size_validator);
  render_cmd
      ->add_option("--png-level", render.png_level,
                   fmt::format("PNG deflate level {}..{} (libdeflate): 0 = uncompressed, "
                               "1 = fastest (default), 12 = smallest and slowest",
                               fixstep::min_png_level, fixstep::max_png_level))
      ->check(png_level_validator);
  render_cmd->add_option(
      "--replay", render.replay,
      "drive the ticks with this recording's inputs, on the world it carries (or names), at its "
      "settings; verified whole before the first frame (exit 4 if it diverges); --dt, "
      "--integrator, --precision, --substeps and --damping-split are refused with it");
  render_cmd->add_flag("--overwrite", render.overwrite, overwrite_help);
  add_joints_option(render_cmd, render.scene.joints);

  CompareOptions compare;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare",
      "one scene under 2-6 integrator/dt configurations side by side, each tile with its error, "
      "energy balance and cost; headless with --out/--video, else in a window");
  add_compare_options(compare_cmd, compare);

  ViewOptions view;
  CLI::App* view_cmd = app.add_subcommand("view", "open an SDL2 window showing the scene live");
  add_scene_options(view_cmd, view.scene);
  view_cmd->add_option("--size", view.size, "window size in pixels, WxH")
      ->check(frame_size_validator);
  view_cmd->add_option("--frames", view.frames, "quit after N frames (0 = run until Esc)")
      ->check(CLI::Range(std::int64_t{0}, max_ticks));
  view_cmd
      ->add_option("--fps", view.fps,
                   "use a virtual clock of F frames per second instead of the real clock")
      ->check(positive_finite);
  add_record_options(view_cmd, view.record, view.hash_every);
  add_joints_option(view_cmd, view.scene.joints);
  view_cmd->add_flag("--no-watch", view.no_watch,
                     "do not reload the scene when its file is saved (reloading is the default)");

  ReplayOptions replay;
  CLI::App* replay_cmd = app.add_subcommand(
      "replay", "re-simulate a recording headless and verify every stored state hash");
  replay_cmd->add_option("recording", replay.recording, "recording file (fixstep run --record)")
      ->required();
  replay_cmd->add_option("--scene", replay.scene,
                         "scene file (default: the scene the recording carries; for a recording "
                         "made before format 3, the file it names, relative to the current "
                         "directory, then to the recording's)");
  replay_cmd->add_flag("-q,--quiet", replay.quiet, "print errors only");

  DiffOptions diff;
  CLI::App* diff_cmd = app.add_subcommand(
      "diff",
      "where two recordings first differ: inputs, stored hashes and, replayed side by side, the "
      "first tick, body and field (exit 0 identical, 4 different, 6 different worlds)");
  diff_cmd->add_option("A.rec", diff.a, "recording A (fixstep run --record, a match's recording)");
  diff_cmd->add_option("B.rec", diff.b, "recording B");
  diff_cmd->add_flag("-q,--quiet", diff.quiet, "print errors only (the exit status says)");

  std::string new_dir;
  CLI::App* new_cmd = app.add_subcommand(
      "new",
      "write a prototype project into DIR (CMakeLists.txt, main.cpp, scene.toml, README.md), "
      "built against the installed fixstep package");
  new_cmd
      ->add_option("dir", new_dir,
                   "the project's directory, new or empty; its last component names the project")
      ->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError& e) {
    // Unknown options: name each, with the closest option of its subcommand.
    const int code = app.exit(e);
    for (const CLI::App* sub : app.get_subcommands()) {
      std::vector<std::string> known;
      for (const CLI::Option* opt : sub->get_options()) {
        for (const std::string& name : opt->get_lnames()) known.push_back("--" + name);
      }
      for (const std::string& arg : sub->remaining()) {
        if (arg.rfind("--", 0) != 0) continue;
        const std::string flag = arg.substr(0, arg.find('='));
        if (const auto best = fixstep::closest(flag, known)) {
          std::fprintf(stderr, "fixstep %s: unknown option %s: did you mean %s?\n",
                       sub->get_name().c_str(), flag.c_str(), best->c_str());
        }
      }
    }
    return code == 0 ? 0 : 2;
  } catch (const CLI::RequiredError& e) {
    if (const std::string typo = unknown_subcommand(app, argc, argv); !typo.empty()) {
      std::fprintf(stderr, "%s\n", typo.c_str());
      return 2;
    }
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the message (or the help, status 0); every command-line error exits 2.
    return app.exit(e) == 0 ? 0 : 2;
  }

  const CommandPaths paths = run_cmd->parsed()       ? run_paths(run)
                             : render_cmd->parsed()  ? render_paths(render, render.scene.scene)
                             : compare_cmd->parsed() ? compare_paths(compare)
                             : view_cmd->parsed()    ? view_paths(view)
                                                     : CommandPaths{};
  // `--csv -`: standard output carries the data alone; the summary goes to standard error.
  if (fixstep::data_on_standard_output(paths)) fixstep::keep_standard_output_for_data();
  // --quiet: the summaries and paths go to standard output, which is emptied wholesale;
  // errors go to standard error (warnings and progress are skipped where they are made).
  if ((run.scene.quiet || render.scene.quiet || view.scene.quiet || replay.quiet || compare.quiet ||
       diff.quiet) &&
      std::freopen("/dev/null", "w", stdout) == nullptr) {
    std::fputs("fixstep: error: --quiet: cannot open /dev/null for standard output\n", stderr);
    return 1;
  }
  const auto command = [&]() -> int {
    if (run_cmd->parsed()) {
      set_command("run");
      if (!steps->count() && !duration->count()) {
        std::fputs("fixstep run: give --steps N (ticks) or --duration S (simulated seconds)\n",
                   stderr);
        return 2;
      }
      return run_command(run);
    }
    if (render_cmd->parsed()) {
      set_command("render");
      if (render.scene.scene.empty() && !render.replay) {
        std::fputs("fixstep render: give SCENE (or --replay FILE, which names its scene)\n",
                   stderr);
        return 2;
      }
      const auto [width, height] = parse_frame_size(render.size);
      std::string e = render.replay ? replay_flag_conflict(render.scene) : "";
      if (e.empty())
        e = capture_targets_error(
            {.out = render.out, .video = render.video, .png_level = render.png_level});
      if (e.empty()) e = video_options_error(render.video, width, height, render.fps);
      if (!e.empty()) {
        std::fprintf(stderr, "fixstep render: %s\n", e.c_str());
        return 2;
      }
      return render_command(render);
    }
    if (compare_cmd->parsed()) {
      set_command("compare");
      if (compare.with.size() < min_tiles || compare.with.size() > max_tiles) {
        std::fprintf(stderr, "fixstep compare: give 2 to 6 --with configurations, got %zu\n",
                     compare.with.size());
        return 2;
      }
      const auto [width, height] = parse_frame_size(compare.size);
      std::string e = capture_targets_error({.out = compare.out, .video = compare.video});
      if (!compare.out && !compare.video) e.clear();  // the window
      if (e.empty())
        e = video_options_error(compare.video, width, height, compare.fps.value_or(60));
      if (!e.empty()) {
        std::fprintf(stderr, "fixstep compare: %s\n", e.c_str());
        return 2;
      }
      return compare_command(compare);
    }
    if (replay_cmd->parsed()) return set_command("replay"), replay_command(replay);
    if (diff_cmd->parsed()) {
      set_command("diff");
      if (diff.a.empty() || diff.b.empty()) {
        std::fprintf(stderr,
                     "fixstep diff: give two recordings: fixstep diff A.rec B.rec (got %s)\n",
                     diff.a.empty() ? "none" : "one");
        return 2;
      }
      return diff_command(diff);
    }
    if (new_cmd->parsed()) return set_command("new"), new_command(new_dir);
    return set_command("view"), view_command(view);
  };
  try {
    return command();
  } catch (const fixstep::RecordingError&) {
    throw;
  } catch (const std::runtime_error& e) {  // a write error: named by the option that gave it
    if (const auto named = naming_the_option(paths, e.what())) throw std::runtime_error(*named);
    throw;
  }
} catch (const fixstep::StopRequested& e) {  // a command that does not catch it (none should)
  std::fprintf(stderr, "fixstep: %s\n", e.what());
  return 128 + e.signal();
} catch (const fixstep::PathRefused& e) {  // an output that is an input, a used --out DIR
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
} catch (const fixstep::RecordingError& e) {
  std::fprintf(stderr, "fixstep: error: %s\n", e.what());
  return fixstep::cli::exit_code(e);
} catch (const std::bad_alloc&) {  // past the estimate's check: less memory free than it assumed
  std::fprintf(stderr,
               "fixstep: error: %s: out of memory (std::bad_alloc) while %s: less memory was free "
               "than this command's estimate needs (it may plan up to %.0f GiB: docs/CLI.md, "
               "\"Memory\"); free some, or ask for less: fewer bodies, tiles or frames, a smaller "
               "--size\n",
               fixstep::cli::command_name(), fixstep::cli::phase_name(),
               double(fixstep::max_command_bytes) / double(std::uint64_t{1} << 30));
  return 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "fixstep: error: %s\n", e.what());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  // Every command prints its results (a summary, a verdict, the paths written) on standard
  // output: a closed or full one is an error, not a silent loss (fixstep/io/standard_output.hpp).
  if (quiet_asked(argc, argv) && !fixstep::standard_output_is_open()) {
    return run_fixstep(argc, argv);  // --quiet reopens it on /dev/null
  }
  return fixstep::with_results_on_standard_output("fixstep",
                                                  [&] { return run_fixstep(argc, argv); });
}
