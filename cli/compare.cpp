// `fixstep compare`: the command — tiles captured headless (PNG, video) or shown in the window,
// and the summary: a line and a CSV row per tile.
#include "compare.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fixstep/app/key_bindings.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/stop_signal.hpp>
#include <fixstep/scene/scene_stability.hpp>
#include <fixstep/window/window.hpp>
#include <span>
#include <thread>
#include <vector>

#include "capture_sink.hpp"
#include "command_memory.hpp"
#include "command_phase.hpp"
#include "comparison.hpp"
#include "csv_field.hpp"
#include "exact_reference.hpp"
#include "fixstep/io/command_limits.hpp"
#include "fixstep/io/summary.hpp"
#include "output_paths.hpp"
#include "progress.hpp"

namespace fixstep::cli {

namespace {

constexpr Rgba8 gap_color{78, 84, 98, 255};  // lines between the tiles

std::vector<std::uint8_t> blank_frame(int width, int height) {
  std::vector<std::uint8_t> frame(static_cast<std::size_t>(width) * height * 4);
  for (std::size_t i = 0; i < frame.size(); i += 4) {
    frame[i] = gap_color.r, frame[i + 1] = gap_color.g, frame[i + 2] = gap_color.b;
    frame[i + 3] = 255;
  }
  return frame;
}

/// The `fixstep run` command line that steps tile i's configuration to the same tick.
std::string same_as_run(const std::string& scene_file, const Tile& t) {
  const World& sim = t.session->simulation();
  const bool per_step = sim.settings().damping_split == DampingSplit::per_step;
  return fmt::format(
      "fixstep run {} --integrator {} --dt {} --substeps {} --precision {}{} --steps {}",
      scene_file, integrator_name(sim.settings().integrator), sim.settings().dt,
      sim.settings().substeps, precision_name(sim.precision()),
      per_step ? " --damping-split per_step" : "", sim.tick());
}

/// A line per tile on standard output and, when `csv` is set, a CSV row per tile.
void summarise(const CompareOptions& o, const Comparison& c,
               const std::optional<std::filesystem::path>& csv) {
  std::string rows =
      "tile,with,integrator,dt,substeps,precision,ticks,t,state_hash,error_m,error_against,"
      "error_t,max_error_m,balance,cost_s_per_simulated_s,in_loop_s_per_simulated_s\n";
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Tile& t = c.tile(i);
    const World& sim = t.session->simulation();
    const double balance = energy_balance(sim, t.session->initial_energy());
    const double in_loop = sim.time() > 0.0 ? t.wall_seconds / sim.time() : 0.0;
    const std::string error = t.error ? fmt::format("{:.6e}", *t.error) : "";
    // Without an error where the scene has an exact solution: why (a disc contact), if known.
    const std::string lost = c.exact_lost(i);
    const std::string against = t.error ? c.error_against(i) : lost.empty() ? "" : "none: " + lost;
    fmt::print(
        "tile={} with={} ticks={} t={:.6f} state_hash={} error={}{} balance={:.6e} "
        "cost={:.3e} s per simulated s\n",
        i + 1, t.spec.text, sim.tick(), sim.time(), hex_hash(sim.state_hash()),
        !error.empty()  ? fmt::format("{} m against {}", error, against)
        : !lost.empty() ? fmt::format("none (a {}: the exact solution knows no contacts)", lost)
        : c.has_exact() || i != c.reference() ? "none"
                                              : "reference",
        t.error && !c.has_exact() ? fmt::format(" at t={:.6f}", t.error_time) : "", balance,
        t.cost);
    fmt::print("  same state: {}\n", same_as_run(o.scene, t));
    rows +=
        fmt::format("{},{},{},{},{},{},{},{:.6f},{},{},{},{},{},{:.6e},{:.6e},{:.6e}\n", i + 1,
                    csv_field(t.spec.text), integrator_name(sim.settings().integrator),
                    sim.settings().dt, sim.settings().substeps, precision_name(sim.precision()),
                    sim.tick(), sim.time(), hex_hash(sim.state_hash()), error, against,
                    t.error ? fmt::format("{:.6f}", t.error_time) : "",
                    t.error ? fmt::format("{:.6e}", t.max_error) : "", balance, t.cost, in_loop);
  }
  if (csv) {
    write_file_atomic(*csv, rows);
    fmt::print("csv={}\n", csv->string());
  }
}

/// Warns about each --with that configures the same run as an earlier one (the same
/// integrator, dt, substeps and precision, however written): two identical tiles.
void warn_repeated(std::span<const TileSpec> specs) {
  for (std::size_t i = 1; i < specs.size(); ++i) {
    const TileSpec& s = specs[i];
    for (std::size_t j = 0; j < i; ++j) {
      const TileSpec& t = specs[j];
      if (s.integrator == t.integrator && s.dt == t.dt && s.substeps == t.substeps &&
          s.precision == t.precision && s.damping_split == t.damping_split) {
        std::fprintf(stderr,
                     "warning: --with '%s' (tile %zu) configures the same run as --with '%s' "
                     "(tile %zu): the two tiles will be identical\n",
                     s.text.c_str(), i + 1, t.text.c_str(), j + 1);
        break;
      }
    }
  }
}

/// Whether a moving body of `scene` has an exact solution at t = 0 (ExactReference): else each
/// tile but the reference is measured against a shadow world.
bool has_exact_solution(const Scene& scene) {
  const ExactReference reference(scene);
  std::vector<std::optional<Body>> exact;
  reference.at(0.0, exact);
  for (std::size_t j = 0; j < exact.size(); ++j) {
    if (exact[j] && scene.def.bodies[j].type != BodyType::static_body) return true;
  }
  return false;
}

/// Reports every tile the runtime guard stopped; exit_diverged if there is one, else 0.
int report_faults(const Comparison& c) {
  int status = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Tile& t = c.tile(i);
    if (const auto& fault = t.session->simulation().fault()) {
      std::fprintf(stderr, "fixstep: error: tile %zu (--with '%s'): %s\n", i + 1,
                   t.spec.text.c_str(), explain_fault(t.scene, *fault).c_str());
      status = exit_diverged;
    }
  }
  return status;
}

/// Throws LimitError when `frames` frames at `fps` ask the tiles together for more than a
/// command's work (limits.hpp): each tile steps frames/fps/dt ticks.
void check_capture_work(const Comparison& c, std::uint64_t frames, double fps) {
  std::uint64_t work = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const WorldDef& def = c.tile(i).session->definition();
    const double ticks = std::ceil(double(frames - 1) / fps / def.settings.dt);
    const std::string what =
        fmt::format("--frames {} at --fps {:g} (--with '{}')", frames, fps, c.tile(i).spec.text);
    const auto n = static_cast<std::uint64_t>(std::min(ticks, 1e18));
    check_command_work(n, tick_work(def), what);
    work += n * tick_work(def);  // each <= max_command_work: no overflow
  }
  if (work > max_command_work) {
    throw LimitError(fmt::format(
        "--frames {}: the {} tiles together would do {:.3g} body-substeps; a command may do at "
        "most {:.0e} (about a day of CPU): capture fewer frames",
        frames, c.size(), double(work), double(max_command_work)));
  }
}

int capture(const CompareOptions& o, Comparison& c, int width, int height) {
  const double fps = o.fps.value_or(60.0);
  const VirtualClock clock(fps);
  const auto frames = static_cast<std::uint64_t>(o.frames.value_or(default_compare_frames));
  check_capture_work(c, frames, fps);
  CaptureSink sink(
      {.out = o.out, .video = o.video, .png_level = o.png_level, .overwrite = o.overwrite}, width,
      height, fps, ManifestLayout::tiles);
  set_phase("capturing the frames");
  std::vector<std::uint8_t> frame = blank_frame(width, height);
  const StopOnSignal signals;
  Progress progress("compare", "frame", frames, !o.quiet);
  std::uint64_t written = 0;
  bool torn = false;  // a stop request inside a tick: that frame is not drawn
  for (std::uint64_t f = 0; f < frames && !StopOnSignal::requested(); ++f) {
    try {
      if (f > 0) c.advance(clock.frame_seconds());
    } catch (const StopRequested&) {
      torn = true;
      break;
    }
    c.draw(frame, width);
    sink.submit(frame);
    for (std::size_t i = 0; i < c.size(); ++i) sink.add_row(f, i + 1, *c.tile(i).session);
    progress.update(++written);
  }
  sink.finish();
  progress.finish();
  fmt::print("scene={} tiles={} fps={} size={}x{}\n", o.scene, c.size(), fps, width, height);
  sink.print_paths(written, StopOnSignal::requested() ? " (stopped)" : "");
  // A tile stopped inside a tick has a torn state: no summary (nor --csv) of it.
  if (!torn) summarise(o, c, summary_path(o));
  if (const int sig = StopOnSignal::requested()) {
    std::fprintf(stderr,
                 "fixstep: stopped by %s after %llu frames; every frame written is complete\n",
                 StopOnSignal::name(), static_cast<unsigned long long>(written));
    return 128 + sig;
  }
  return report_faults(c);
}

int show_comparison(const CompareOptions& o, Comparison& c, int width, int height) {
  Window window = open_window(fmt::format("fixstep compare - {}", o.scene), width, height,
                              "fixstep compare SCENE --with ... --out DIR");
  std::vector<std::uint8_t> frame = blank_frame(width, height);
  RealClock real_clock;
  const double virtual_frame = o.fps ? VirtualClock(*o.fps).frame_seconds() : 0.0;
  constexpr auto frame_budget = std::chrono::microseconds(16667);  // ~60 Hz presentation
  WindowEvents ev;
  const std::int64_t frames = o.frames.value_or(0);
  for (std::int64_t f = 0; frames == 0 || f < frames; ++f) {
    const auto frame_start = std::chrono::steady_clock::now();
    window.poll(ev);
    if (ev.quit) break;
    for (std::size_t i = 0; i < c.size(); ++i) apply_loop_keys(ev, c.tile(i).session->loop());
    if (ev.restart) c.restart();
    const double seconds = o.fps ? virtual_frame : real_clock.frame_seconds();
    if (f > 0) c.advance(seconds);
    c.draw(frame, width);
    window.present(frame);
    if (!o.fps) std::this_thread::sleep_until(frame_start + frame_budget);
  }
  fmt::print("scene={} tiles={} driver={}\n", o.scene, c.size(), window.driver());
  summarise(o, c, summary_path(o));
  return report_faults(c);
}

}  // namespace

std::optional<std::filesystem::path> summary_path(const CompareOptions& o) {
  if (o.csv) return std::filesystem::path(*o.csv);
  if (o.out) return std::filesystem::path(*o.out) / "compare.csv";
  if (o.video) return beside_video(*o.video, ".compare.csv");
  return std::nullopt;
}

int compare_command(const CompareOptions& o) {
  if (o.with.size() < min_tiles || o.with.size() > max_tiles) {
    throw std::invalid_argument(fmt::format("compare takes {} to {} --with configurations, got {}",
                                            min_tiles, max_tiles, o.with.size()));
  }
  check_paths(compare_paths(o));  // before any work: no output may be an input
  set_phase("loading the scene");
  Scene base = load_scene(o.scene);
  if (o.allow_unstable) base.def.allow_unstable = true;
  apply_joint_view(o.joints, base);
  if (!o.quiet) {
    for (const std::string& w : base.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  std::vector<TileSpec> specs;
  for (const std::string& w : o.with) specs.push_back(parse_tile_spec(w));
  if (!o.quiet) warn_repeated(specs);
  const auto [width, height] = parse_frame_size(o.size);
  const TileGrid grid = tile_grid(static_cast<int>(specs.size()), width, height);
  // Before any tile's world or frame buffer is allocated.
  check_memory("compare", o.scene,
               compare_memory(base, specs.size(), !has_exact_solution(base), width, height,
                              o.video.has_value()));
  set_phase("building the tiles");
  const bool headless = o.out || o.video;
  // A virtual clock (capture, or --fps in the window) is not clamped: frames 1/fps apart.
  const bool virtual_clock = headless || o.fps;
  const double frame = virtual_clock ? 1.0 / o.fps.value_or(60.0) : 0.0;
  Comparison comparison(base, specs, grid, o.quiet, std::max(LoopSettings{}.max_frame_time, frame));
  return headless ? capture(o, comparison, width, height)
                  : show_comparison(o, comparison, width, height);
}

}  // namespace fixstep::cli
