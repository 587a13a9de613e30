#include "commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fixstep/capture.hpp>
#include <fixstep/exact.hpp>
#include <fixstep/input_script.hpp>
#include <fixstep/manifest.hpp>
#include <fixstep/scene_stability.hpp>
#include <fixstep/session.hpp>
#include <fixstep/stability.hpp>
#include <fixstep/sync_test.hpp>
#include <stdexcept>
#include <vector>

#include "progress.hpp"

namespace fixstep::cli {

namespace {

// SIGINT / SIGTERM during run or render: the handler only records the signal; the command
// finishes the tick or frame in progress, writes out everything produced so far (the CSV,
// every queued frame) and exits 128 + the signal number, as a shell reports a signal death.
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void request_stop(int signal) {
  stop_signal = signal;
}

/// Installs request_stop for SIGINT and SIGTERM for the lifetime of the object.
class StopOnSignal {
 public:
  StopOnSignal() {
    stop_signal = 0;
    previous_int_ = std::signal(SIGINT, request_stop);
    previous_term_ = std::signal(SIGTERM, request_stop);
  }
  ~StopOnSignal() {
    std::signal(SIGINT, previous_int_);
    std::signal(SIGTERM, previous_term_);
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  [[nodiscard]] static int requested() { return stop_signal; }
  [[nodiscard]] static const char* name() { return stop_signal == SIGINT ? "SIGINT" : "SIGTERM"; }

 private:
  void (*previous_int_)(int) = SIG_DFL;
  void (*previous_term_)(int) = SIG_DFL;
};

}  // namespace

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

Scene load_with_overrides(const SceneOptions& o) {
  Scene scene = load_scene(o.scene);
  if (o.integrator) scene.world.integrator = *parse_integrator(*o.integrator);
  if (o.dt) scene.world.dt = *o.dt;
  if (o.precision) scene.precision = *parse_precision(*o.precision);
  if (o.substeps) scene.world.substeps = *o.substeps;
  if (o.allow_unstable) scene.allow_unstable = true;
  const std::vector<std::string> guard = enforce_stability(scene);  // throws when unstable
  if (!o.quiet) {
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    for (const std::string& w : guard) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  return scene;
}

std::string describe(const Scene& scene) {
  return fmt::format(
      "scene={} integrator={} precision={} dt={}{}", scene.file,
      integrator_name(scene.world.integrator), precision_name(scene.precision), scene.world.dt,
      scene.world.substeps > 1 ? fmt::format(" substeps={}", scene.world.substeps) : std::string());
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

/// The exact solution of a scene where one exists: per body (exact::solve) when the scene has
/// no links, for the whole network (exact::LinearNetwork) when it has and they are linear
/// with proportional damping. Bodies that bounce on the scene's planes have none (the exact
/// solutions know no contacts), nor has a network holding one.
class ExactReference {
 public:
  explicit ExactReference(const Scene& scene) : scene_(scene) {
    const bool bounces = std::any_of(scene.bodies.begin(), scene.bodies.end(),
                                     [&](const BodyDef& b) { return bouncing(b); });
    if (!scene.links.empty() && !bounces) {
      network_ = exact::LinearNetwork::make(scene.bodies, scene.links);
    }
  }
  /// Fills out[j] with body j's exact state at t (s), or nullopt where there is none.
  void at(double t, std::vector<std::optional<Body>>& out) const {
    out.assign(scene_.bodies.size(), std::nullopt);
    if (network_) {
      states_.resize(scene_.bodies.size());
      network_->state(t, states_);
      for (std::size_t j = 0; j < states_.size(); ++j) out[j] = states_[j];
    } else if (scene_.links.empty()) {
      for (std::size_t j = 0; j < out.size(); ++j) {
        if (!bouncing(scene_.bodies[j])) out[j] = exact::solve(scene_.bodies[j], t);
      }
    }
  }

 private:
  [[nodiscard]] bool bouncing(const BodyDef& b) const {
    return b.collider && !scene_.planes.empty();
  }

  const Scene& scene_;
  std::optional<exact::LinearNetwork> network_;
  mutable std::vector<Body> states_;
};

/// Largest position error (m) against the exact solution over the bodies that have one;
/// nullopt when none has (rest-length springs, non-proportional damping of links).
std::optional<double> exact_error(const ExactReference& reference, const Simulation& sim) {
  std::vector<std::optional<Body>> exact;
  reference.at(sim.time(), exact);
  std::optional<double> worst;
  for (std::size_t j = 0; j < sim.body_count(); ++j) {
    if (exact[j]) {
      const Body b = sim.body_at(j);
      const double e =
          std::hypot(b.position.x - exact[j]->position.x, b.position.y - exact[j]->position.y);
      worst = std::max(worst.value_or(0.0), e);
    }
  }
  return worst;
}

void append_rows(AtomicFile& csv, const ExactReference& reference, const Simulation& sim,
                 bool with_exact, double e0, std::vector<double>& energies, std::string& buffer) {
  std::vector<std::optional<Body>> exact;
  if (with_exact) reference.at(sim.time(), exact);
  sim.visit([&](const auto& w) {
    energies.resize(w.body_count());
    w.body_energies(energies);
  });
  buffer.clear();
  auto out = std::back_inserter(buffer);
  const double world_energy = sim.energy().total(), dissipated = sim.dissipated_energy();
  const double balance = energy_balance(sim, e0);
  for (std::size_t j = 0; j < sim.body_count(); ++j) {
    const Body b = sim.body_at(j);
    // {} prints the shortest text that reads back as the same double: exact, no lost bits.
    fmt::format_to(out, "{},{},{},{},{},{},{},{},{},{},{}", sim.tick(), sim.time(), sim.name(j),
                   b.position.x, b.position.y, b.velocity.x, b.velocity.y, energies[j],
                   world_energy, dissipated, balance);
    if (with_exact) {
      if (const auto& e = exact[j]) {
        fmt::format_to(out, ",{},{},{}", e->position.x, e->position.y,
                       std::hypot(b.position.x - e->position.x, b.position.y - e->position.y));
      } else {
        fmt::format_to(out, ",,,");  // no closed form for this body (rest-length spring)
      }
    }
    buffer.push_back('\n');
  }
  csv.append(buffer);
}

}  // namespace

const std::string csv_header = "tick,t,body,x,y,vx,vy,energy,world_energy,world_dissipated,balance";

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
  const Scene scene = load_with_overrides(o.scene);
  Simulation sim = make_simulation(scene);
  const double e0 = sim.energy().total();
  const std::uint64_t ticks =
      o.steps ? static_cast<std::uint64_t>(*o.steps) : ticks_for(*o.duration, scene.world.dt);

  std::optional<AtomicFile> csv;
  std::vector<double> energies;
  std::string buffer;
  const ExactReference reference(scene);
  // The exact solutions are of the scene alone: with scripted input (pushes, drags) they do not
  // apply.
  const bool has_exact = !o.input && exact_error(reference, sim).has_value();
  if (o.csv) {
    csv.emplace(*o.csv);
    csv->append(has_exact ? csv_header + ",x_exact,y_exact,error\n" : csv_header + "\n");
    append_rows(*csv, reference, sim, has_exact, e0, energies, buffer);
  }
  std::optional<InputScript> script;
  std::optional<ScriptPlayer> player;
  if (o.input) {
    script = load_input_script(*o.input, scene.bodies);
    for (const std::string& w : script->warnings) {
      if (!o.scene.quiet) std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
    player.emplace(*script);
  }
  std::optional<Recorder> recorder;
  if (o.record) recorder.emplace(world_def(scene), o.scene.scene, o.hash_every);
  std::optional<SyncTest> sync;
  if (o.sync_test) sync.emplace(sim, *o.sync_test);
  const StopOnSignal signals;
  Progress progress("run", "tick", ticks, !o.scene.quiet);
  for (std::uint64_t i = 1; i <= ticks; ++i) {
    const TickInput in = player ? player->next() : TickInput{.tick = i - 1};
    if (sync) {
      if (!sync->step(in)) return sync_test_failed(*sync, *o.sync_test);
    } else {
      sim.step(in);
    }
    if (recorder) recorder->record(in, sim);
    if (i % 1024 == 0 || i == ticks) progress.update(i);  // a clock read per 1024 ticks
    const bool diverged = sim.fault().has_value();        // the runtime guard (World::fault)
    const bool stop = StopOnSignal::requested() != 0;
    if (csv && (i % static_cast<std::uint64_t>(o.every) == 0 || i == ticks || diverged || stop)) {
      append_rows(*csv, reference, sim, has_exact, e0, energies, buffer);
    }
    if (diverged || stop) break;
  }
  progress.finish();
  if (csv) csv->commit();  // the rows up to and including the last tick run
  if (recorder) write_recording(*o.record, recorder->finish(sim));  // the ticks run
  fmt::print("{}\n", describe(scene));
  fmt::print("{}\n", summary_line(sim, e0));
  if (o.record) fmt::print("recording={}\n", *o.record);
  if (sync) {
    fmt::print(
        "sync_test: rolled back {} ticks at every tick, {} ticks re-simulated, every state "
        "equal\n",
        *o.sync_test, sync->resimulated());
  }
  if (const int sig = StopOnSignal::requested()) {
    if (o.csv) fmt::print("csv={}\n", *o.csv);
    std::fprintf(stderr, "fixstep: stopped by %s after tick %llu; output written\n",
                 StopOnSignal::name(), static_cast<unsigned long long>(sim.tick()));
    return 128 + sig;
  }
  if (sim.fault()) {
    if (o.csv) fmt::print("csv={}\n", *o.csv);
    std::fprintf(stderr, "fixstep: error: %s\n", explain_fault(scene, *sim.fault()).c_str());
    return exit_diverged;
  }
  if (const auto error = has_exact ? exact_error(reference, sim) : std::nullopt) {
    fmt::print("exact_error={:.6e} m (largest position error against the exact solution)\n",
               *error);
  }
  if (o.csv) fmt::print("csv={}\n", *o.csv);
  return 0;
}

Session open_session(const Scene& scene, int width, int height) {
  return Session(world_def(scene),
                 SessionSettings{.width = width,
                                 .height = height,
                                 .title = std::filesystem::path(scene.file).filename().string(),
                                 .view_center = scene.view.center,
                                 .view_width = scene.view.width});
}

int render_command(const RenderOptions& o) {
  std::optional<Recording> rec;
  if (o.replay) rec = read_recording(*o.replay);
  const Scene scene =
      rec ? scene_for_recording(
                o.scene.scene.empty() ? recorded_scene(*rec, *o.replay) : o.scene.scene, *rec,
                o.scene.quiet)
          : load_with_overrides(o.scene);
  const auto [width, height] = parse_frame_size(o.size);
  prepare_output_dir(o.out);
  Session session = open_session(scene, width, height);
  const VirtualClock clock(o.fps);
  const auto frames = static_cast<std::uint64_t>(o.frames);
  // Frame f is encoded and written on the writer's thread while frame f + 1 renders here.
  FrameWriter writer(o.out, width, height, PngSettings{.level = o.png_level});
  FrameManifest manifest(o.out);  // frames.csv: a row per frame written
  std::uint64_t written = 0;
  const StopOnSignal signals;
  Progress progress("render", "frame", frames, !o.scene.quiet);
  for (std::uint64_t f = 0; f < frames && !StopOnSignal::requested(); ++f) {
    if (f > 0 && rec) {  // the recorded input of each tick; none past the recording's end
      session.advance_with(clock.frame_seconds(),
                           [&](std::uint64_t t, Simulation& sim) { sim.step(rec->input_at(t)); });
    } else if (f > 0) {
      session.advance(clock.frame_seconds());
    }
    session.draw();  // after a divergence: the last state, with the guard's message in the HUD
    writer.submit(session.renderer().pixels());
    manifest.add(f, session);
    ++written;
    progress.update(written);
    if (session.simulation().fault()) break;
  }
  writer.finish();  // every frame on disk, or the first failure's CaptureError
  manifest.commit();
  progress.finish();
  if (const int sig = StopOnSignal::requested()) {
    fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
    if (written > 0) {
      fmt::print("frames={} (stopped) size={}x{}: {} ... {}\n", written, width, height,
                 frame_path(o.out, 0).string(), frame_path(o.out, written - 1).string());
    }
    fmt::print("manifest={}\n", manifest.file().string());
    std::fprintf(stderr,
                 "fixstep: stopped by %s after %llu frames; every frame written is complete\n",
                 StopOnSignal::name(), static_cast<unsigned long long>(written));
    return 128 + sig;
  }
  if (const auto& fault = session.simulation().fault()) {
    fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
    fmt::print("frames={} (stopped early) size={}x{}: {} ... {}\n", written, width, height,
               frame_path(o.out, 0).string(), frame_path(o.out, written - 1).string());
    fmt::print("manifest={}\n", manifest.file().string());
    std::fprintf(stderr, "fixstep: error: %s\n", explain_fault(scene, *fault).c_str());
    return exit_diverged;
  }
  fmt::print("{} renderer=\"{}\"\n", describe(scene), session.renderer().gl_renderer());
  fmt::print("{}\n", summary_line(session.simulation(), session.initial_energy()));
  fmt::print("frames={} fps={} size={}x{}: {} ... {}\n", frames, o.fps, width, height,
             frame_path(o.out, 0).string(), frame_path(o.out, frames - 1).string());
  fmt::print("manifest={}\n", manifest.file().string());
  return 0;
}

}  // namespace fixstep::cli
