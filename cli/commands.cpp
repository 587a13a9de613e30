#include "commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fixstep/app/session.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/stability.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/core/sync_test.hpp>
#include <fixstep/core/work_progress.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/recording_writer.hpp>
#include <fixstep/io/stop_signal.hpp>
#include <fixstep/scene/input_script.hpp>
#include <fixstep/scene/scene_stability.hpp>
#include <stdexcept>
#include <vector>

#include "command_memory.hpp"
#include "command_phase.hpp"
#include "csv_field.hpp"
#include "exact_reference.hpp"
#include "fixstep/io/command_limits.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"
#include "output_paths.hpp"
#include "progress.hpp"

namespace fixstep::cli {

std::string positive_finite(const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (end == value.c_str() || *end != '\0' || !std::isfinite(v) || v <= 0.0) {
    return fmt::format("must be a finite number > 0, got '{}'", value);
  }
  return {};
}

std::string dt_validator(const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (end == value.c_str() || *end != '\0' || !std::isfinite(v) || v <= 0.0 || v > 1.0) {
    return fmt::format("must be a step length > 0 and <= 1 s (as [world] dt), got '{}'", value);
  }
  return {};
}

std::string frame_size_validator(const std::string& value) {
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(value.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < min_frame_size ||
      h < min_frame_size || w > max_frame_size || h > max_frame_size) {
    return fmt::format("must be WxH with {} <= W, H <= {} pixels, got '{}'", min_frame_size,
                       max_frame_size, value);
  }
  return {};
}

std::string png_level_validator(const std::string& value) {
  char* end = nullptr;
  errno = 0;
  const long level = std::strtol(value.c_str(), &end, 10);
  if (end == value.c_str() || *end != '\0' || errno == ERANGE || level < INT_MIN ||
      level > INT_MAX) {
    return fmt::format("must be an integer {}..{}, got '{}'", min_png_level, max_png_level, value);
  }
  return png_level_error(static_cast<int>(level));
}

std::pair<int, int> parse_frame_size(const std::string& value) {
  int w = 0, h = 0;
  std::sscanf(value.c_str(), "%dx%d", &w, &h);
  return {w, h};
}

void apply_joint_view(const std::optional<std::string>& joints, Scene& scene) {
  if (!joints) return;
  constexpr SceneJoints values[] = {SceneJoints::off, SceneJoints::anchors, SceneJoints::limits};
  for (std::size_t i = 0; i < joint_view_names.size(); ++i)
    if (*joints == joint_view_names[i]) scene.view.joints = values[i];
}

Scene load_with_overrides(const SceneOptions& o, std::vector<std::string>* warnings) {
  // The generators: seconds for 10^6 bodies and their links. A caller that takes the warnings
  // shows the progress itself: no scope of our own, the reports go to its scope.
  std::optional<WorkProgressLine> shown;
  if (!warnings) shown.emplace(!o.quiet);
  set_phase("loading the scene");
  Scene scene = load_scene(o.scene);
  if (o.integrator) scene.def.settings.integrator = *parse_integrator(*o.integrator);
  if (o.dt) scene.def.settings.dt = *o.dt;
  if (o.precision) scene.def.precision = *parse_precision(*o.precision);
  if (o.substeps) scene.def.settings.substeps = *o.substeps;
  if (o.damping_split) scene.def.settings.damping_split = *parse_damping_split(*o.damping_split);
  if (o.allow_unstable) scene.def.allow_unstable = true;
  apply_joint_view(o.joints, scene);
  try {  // the overrides may ask for more work per tick than the file did (limits.hpp)
    check_world_limits(scene.def.bodies, scene.def.links, scene.def.planes, scene.def.settings);
  } catch (const LimitError& e) {
    throw LimitError(fmt::format("{} with the command line's settings: {}", o.scene, e.what()));
  }
  if (shown) shown->finish();  // the warnings start on a clean line
  if (warnings) {
    warnings->insert(warnings->end(), scene.warnings.begin(), scene.warnings.end());
  } else if (!o.quiet) {
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  return scene;
}

World build_world(const Scene& scene, bool quiet, std::vector<std::string>* warnings) {
  // The guard: seconds for a network of 10^6 bodies.
  std::optional<WorkProgressLine> shown;
  if (!warnings) shown.emplace(!quiet);
  report_work_progress("checking the scene", "", 0, 0);  // no count until the guard iterates
  set_phase("building the world");
  std::optional<World> world;
  try {
    world.emplace(scene.def);
  } catch (const UnstableDefinition& e) {
    throw located(scene, e);  // the line and key in the file, and what to change there
  }
  if (shown) shown->finish();  // the warnings start on a clean line
  const std::vector<std::string> guard = located_warnings(scene, world->warnings());
  if (warnings) {
    warnings->insert(warnings->end(), guard.begin(), guard.end());
  } else if (!quiet) {
    for (const std::string& w : guard) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  return std::move(*world);
}

std::string dt_source(const SceneOptions& o, const Scene& scene) {
  return o.dt ? fmt::format("--dt {:g}", *o.dt)
              : fmt::format("[world] dt = {:g} s in {}", scene.def.settings.dt, scene.file);
}

std::string dt_fix(const SceneOptions& o) {
  return o.dt ? "give --dt" : "set [world] dt (or --dt) to";
}

void check_frame_ticks(double frame_seconds, double dt, std::optional<double> fps,
                       std::string_view source, std::string_view fix) {
  const double ticks = std::ceil(frame_seconds / dt) + 1.0;
  if (ticks <= max_frame_ticks) return;
  // ceil(frame / dt) + 1 <= 2^30 for dt >= frame / (2^30 - 1): shown rounded up.
  const double smallest = frame_seconds / (max_frame_ticks - 1.0) * 1.001;
  const bool by_fps = fps && 1.0 / *fps >= frame_seconds;
  throw LimitError(fmt::format(
      "{}: a frame {} is {:.3g} ticks of dt = {:g} s, more than the {:.0f} one frame may step: "
      "{} {:.3g} s or more{}",
      source,
      by_fps ? fmt::format("of {:g} s (--fps {:g})", frame_seconds, *fps)
             : fmt::format("of up to {:g} s (the loop's frame-time clamp)", frame_seconds),
      ticks - 1.0, dt, max_frame_ticks, fix, smallest, by_fps ? ", or a larger --fps" : ""));
}

std::string describe(const Scene& scene) {
  return fmt::format("scene={} integrator={} precision={} dt={}{}", scene.file,
                     integrator_name(scene.def.settings.integrator),
                     precision_name(scene.def.precision), scene.def.settings.dt,
                     scene.def.settings.substeps > 1
                         ? fmt::format(" substeps={}", scene.def.settings.substeps)
                         : std::string());
}

void check_recording_size(std::uint64_t ticks, std::uint64_t hash_every, const std::string& file) {
  // A hash line is at most 33 bytes ("hash " + 10 digits + " " + 16 + "\n"): refused before
  // the run when the hashes alone would pass the reader's limit.
  const std::uint64_t hash_bytes = ticks / hash_every * 33;
  if (hash_bytes > max_recording_bytes) {
    throw LimitError(fmt::format(
        "--record {}: {} ticks with a state hash every {} ticks would write about {} MB of "
        "hashes; a recording may have at most {} bytes: use --hash-every {} or more",
        file, ticks, hash_every, hash_bytes / 1000000, max_recording_bytes,
        (ticks * 33 + max_recording_bytes - 1) / max_recording_bytes + 1));
  }
}

namespace {

/// Ticks for a simulated duration: the nearest whole number when duration/dt is one to within
/// round-off (10 s / 0.01 s = 1000, not 1001), otherwise rounded up.
std::uint64_t ticks_for(double duration, double dt) {
  const double n = duration / dt;
  if (!(n <= double(max_ticks))) {
    throw std::invalid_argument(
        fmt::format("--duration {:g} s at dt = {:g} s is {:.3g} ticks; a run may take at most {:g} "
                    "ticks: give a shorter --duration",
                    duration, dt, n, double(max_ticks)));
  }
  const double nearest = std::round(n);
  return static_cast<std::uint64_t>(
      std::abs(n - nearest) <= 1e-9 * std::max(1.0, n) ? nearest : std::ceil(n));
}

/// One row per body of `sim`'s state at its tick; with_angles: each body's angle (rad) and
/// angular velocity (rad/s) after vy (a world with shapes, csv_columns).
void append_rows(AtomicFile& csv, const ExactReference& reference, const TouchedBodies& touched,
                 const World& sim, bool with_exact, bool with_angles, double e0,
                 std::vector<double>& energies, std::string& buffer) {
  std::vector<std::optional<Body>> exact;
  if (with_exact) reference.at(sim.time(), exact, &touched);
  energies.resize(sim.body_count());
  sim.body_energies(energies);
  buffer.clear();
  auto out = std::back_inserter(buffer);
  const double world_energy = sim.energy().total(), dissipated = sim.dissipated_energy();
  const double balance = energy_balance(sim, e0);
  for (std::size_t j = 0; j < sim.body_count(); ++j) {
    const Body b = sim.body(sim.bodies()[j]);
    // {} prints the shortest text that reads back as the same double: exact, no lost bits.
    fmt::format_to(out, "{},{},{},{},{},{},{}", sim.tick(), sim.time(),
                   csv_field(sim.name(sim.bodies()[j])), b.position.x, b.position.y, b.velocity.x,
                   b.velocity.y);
    if (with_angles) fmt::format_to(out, ",{},{}", b.angle, b.angular_velocity);
    fmt::format_to(out, ",{},{},{},{}", energies[j], world_energy, dissipated, balance);
    if (with_exact) {
      if (const auto& e = exact[j]) {
        fmt::format_to(out, ",{},{},{}", e->position.x, e->position.y,
                       std::hypot(b.position.x - e->position.x, b.position.y - e->position.y));
      } else {
        // No closed form for this body (rest-length spring), or a contact has touched it.
        fmt::format_to(out, ",,,");
      }
    }
    buffer.push_back('\n');
  }
  csv.append(buffer);
}

}  // namespace

const std::string csv_header = "tick,t,body,x,y,vx,vy,energy,world_energy,world_dissipated,balance";

namespace {

/// The CSV's header line: csv_header, with angle,angular_velocity after vy for a world whose
/// bodies carry shapes (they turn), and the exact solution's columns when there is one.
std::string csv_columns(bool with_angles, bool with_exact) {
  std::string h = csv_header;
  if (with_angles) h.insert(h.find(",energy"), ",angle,angular_velocity");
  return h + (with_exact ? ",x_exact,y_exact,error\n" : "\n");
}

}  // namespace

namespace {

/// The message and exit status of a failed sync test.
int sync_test_failed(const SyncTest& sync, int rollback) {
  const SyncTest::Mismatch& m = *sync.mismatch();
  std::fprintf(stderr,
               "fixstep: error: sync test failed at tick %llu: after a rollback of %d ticks the "
               "re-simulation gave %s %s, the first run %s. Some state is missing from the "
               "snapshot, or a step depends on something besides the state and the input.\n",
               static_cast<unsigned long long>(m.tick), rollback,
               m.dissipated_differs ? "the same state_hash but a different dissipated energy, "
                                      "state_hash"
                                    : "state_hash",
               hex_hash(m.actual).c_str(), hex_hash(m.expected).c_str());
  return exit_sync_test_failed;
}
}  // namespace

int run_command(const RunOptions& o) {
  check_paths(run_paths(o));  // before any work: no output may be an input
  const Scene scene = load_with_overrides(o.scene);
  const std::uint64_t ticks = o.steps ? static_cast<std::uint64_t>(*o.steps)
                                      : ticks_for(*o.duration, scene.def.settings.dt);
  const std::uint64_t work = tick_work(scene.def);
  check_command_work(  // before the world is built (limits.hpp)
      ticks, work,
      o.steps
          ? fmt::format("--steps {}", *o.steps)
          : fmt::format("--duration {:g} (at dt = {:g} s)", *o.duration, scene.def.settings.dt));
  if (o.sync_test) {  // each tick re-simulates K more
    check_command_work(ticks * (1 + static_cast<std::uint64_t>(*o.sync_test)), work,
                       fmt::format("{} with --sync-test {} (every tick re-simulates {} more)",
                                   o.steps ? fmt::format("--steps {}", *o.steps)
                                           : fmt::format("--duration {:g}", *o.duration),
                                   *o.sync_test, *o.sync_test));
  }
  if (o.record) check_recording_size(ticks, o.hash_every, *o.record);
  check_memory("run", scene.file, run_memory(scene, o.sync_test));  // before the world is built
  World sim = build_world(scene, o.scene.quiet);
  if (o.sync_test) check_sync_test_memory(sim, *o.sync_test);
  const double e0 = sim.energy().total();

  std::optional<AtomicFile> csv;
  std::vector<double> energies;
  std::string buffer;
  const ExactReference reference(scene);
  // The exact solutions are of the scene alone: with scripted input (pushes, drags) they do not
  // apply; nor to a body from the tick a disc contact touches it.
  const bool has_exact = !o.input && exact_error(reference, sim).has_value();
  TouchedBodies touched(scene);
  const bool with_angles = std::any_of(scene.def.bodies.begin(), scene.def.bodies.end(),
                                       [](const BodyDef& b) { return !b.shapes.empty(); });
  if (o.csv) {
    csv.emplace(*o.csv);
    csv->append(csv_columns(with_angles, has_exact));
    append_rows(*csv, reference, touched, sim, has_exact, with_angles, e0, energies, buffer);
  }
  std::optional<InputScript> script;
  std::optional<ScriptPlayer> player;
  if (o.input) {
    script = load_input_script(*o.input, scene.def.bodies);
    for (const std::string& w : script->warnings) {
      if (!o.scene.quiet) std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
    player.emplace(*script);
  }
  std::optional<RecordingWriter> recorder;  // streamed to its file: O(1) memory
  if (o.record) {  // carrying the scene's bytes: it replays without the file
    recorder.emplace(scene.def, o.scene.scene, o.hash_every, *o.record, scene.text);
  }
  const std::uint64_t initial_hash = o.record ? sim.state_hash() : 0;
  bool torn = false;       // a stop request abandoned a tick half-way: the state is not a tick's
  std::uint64_t done = 0;  // ticks completed
  std::optional<SyncTest> sync;
  if (o.sync_test) sync.emplace(sim, *o.sync_test);
  const StopOnSignal signals;
  set_phase("stepping the world");
  Progress progress("run", "tick", ticks, !o.scene.quiet);
  // A clock read about every 2^20 body-substeps: every tick of a large world, every 1024th of
  // a small one.
  const std::uint64_t progress_every = std::clamp<std::uint64_t>((1u << 20) / (work + 1), 1, 1024);
  for (std::uint64_t i = 1; i <= ticks; ++i) {
    const TickInput in = player ? player->next() : TickInput{.tick = i - 1};
    try {
      if (sync) {
        if (!sync->step(in)) return sync_test_failed(*sync, *o.sync_test);
      } else {
        sim.step(in);
      }
    } catch (const StopRequested&) {  // inside the tick: discard it, keep the ticks before
      torn = true;
      break;
    }
    done = i;
    if (has_exact) touched.after_tick(sim);
    if (recorder) recorder->record(in, sim);
    if (i % progress_every == 0 || i == ticks) progress.update(i);
    const bool diverged = sim.fault().has_value();  // the runtime guard (World::fault)
    const bool stop = StopOnSignal::requested() != 0;
    if (csv && (i % static_cast<std::uint64_t>(o.every) == 0 || i == ticks || diverged || stop)) {
      append_rows(*csv, reference, touched, sim, has_exact, with_angles, e0, energies, buffer);
    }
    if (diverged || stop) break;
  }
  progress.finish();
  if (csv) csv->commit();  // the rows up to and including the last tick run
  // The recording of the ticks run, renamed into place; after a torn tick, up to its last hash.
  if (recorder && torn) recorder->finish_at_last_hash(initial_hash);
  if (recorder && !torn) recorder->finish(sim);
  fmt::print("{}\n", describe(scene));
  if (!torn) fmt::print("{}\n", summary_line(sim, e0));  // a torn state has no summary
  if (o.record) fmt::print("recording={}\n", *o.record);
  if (sync) {
    fmt::print(
        "sync_test: rolled back {} ticks at every tick, {} ticks re-simulated, every state "
        "equal\n",
        *o.sync_test, sync->resimulated());
  }
  if (const int sig = StopOnSignal::requested()) {
    if (o.csv) fmt::print("csv={}\n", *o.csv);
    std::fprintf(stderr, "fixstep: stopped by %s after tick %llu%s; output written\n",
                 StopOnSignal::name(), static_cast<unsigned long long>(done),
                 torn ? " (the tick in progress discarded)" : "");
    return 128 + sig;
  }
  if (sim.fault()) {
    if (o.csv) fmt::print("csv={}\n", *o.csv);
    std::fprintf(stderr, "fixstep: error: %s\n", explain_fault(scene, *sim.fault()).c_str());
    return exit_diverged;
  }
  if (has_exact) {
    const std::string clause = touched_clause(touched, sim.body_count());
    if (const auto error = exact_error(reference, sim, &touched)) {
      fmt::print("exact_error={:.6e} m (largest position error against the exact solution{})\n",
                 *error,
                 clause.empty() ? ""
                                : fmt::format(", over the bodies no contact touched: {}; the "
                                              "exact solutions know no contacts",
                                              clause));
    } else {  // every moving body with an exact solution was touched: no number to claim
      fmt::print(
          "exact_error=none ({}, every moving body that had an exact solution: the exact "
          "solutions know no contacts)\n",
          clause);
    }
  }
  if (o.csv) fmt::print("csv={}\n", *o.csv);
  return 0;
}

}  // namespace fixstep::cli
