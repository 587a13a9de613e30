// integration_basics: the figures and tables of Glenn Fiedler's "Integration Basics",
// reproduced by stepping the article's systems through fixstep's engine.
//
//   integration_basics [--out DIR] [--size WxH] [--precision f32|f64]
//       writes DIR/*.png (the figures, with axes, legend and a caption of measured numbers),
//       DIR/constant_force.md and DIR/constant_force_dt*.csv (the article's tables),
//       DIR/numbers.txt (every measured number, KEY=VALUE) and prints the tables and captions.
//   integration_basics --window [--live damped|undamped] [--dt S] [--speed X] [--frames N] [--fps
//   F]
//       the same comparison live: one trace per integrator grows as the fixed-step loop ticks.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fixstep/app/key_bindings.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/loop.hpp>
#include <fixstep/window/window.hpp>
#include <optional>
#include <string>
#include <thread>

#include "figures.hpp"

namespace {

using namespace fixstep;
using namespace fixstep::demo;

struct Options {
  std::string out = "integration_basics";
  std::string size = "1280x720";
  std::string precision = "f64";
  bool window = false;
  std::string live = "undamped";
  std::optional<double> dt;
  double speed = 1.0;
  std::int64_t frames = 0;
  std::optional<double> fps;
};

std::pair<int, int> parse_size(const std::string& s) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' ||
      w < min_frame_size || h < min_frame_size || w > max_frame_size || h > max_frame_size) {
    throw std::invalid_argument(fmt::format("--size {}: expected WxH with each side in {}..{}", s,
                                            min_frame_size, max_frame_size));
  }
  return {w, h};
}

int write_figures(const Options& o) {
  const auto [width, height] = parse_size(o.size);
  const Precision precision = *parse_precision(o.precision);
  const std::filesystem::path out = o.out;
  prepare_output_dir(out);

  const ConstantForceTables tables = constant_force_tables();
  write_file_atomic(out / "constant_force.md", tables.markdown);
  write_file_atomic(out / "constant_force_dt1.csv", tables.csv_dt1);
  write_file_atomic(out / "constant_force_dt0.01.csv", tables.csv_dt001);
  fmt::print("{}\n", tables.markdown);

  const Report report = article_figures(precision);
  Renderer renderer(width, height);
  for (const Figure& f : report.figures) {
    draw_plot(renderer, f.spec);
    const std::filesystem::path file = out / (f.file + ".png");
    write_png(file, width, height, renderer.pixels());
    fmt::print("{}\n", file.string());
    for (const std::string& c : f.spec.caption) fmt::print("  {}\n", c);
  }
  std::string numbers;
  for (const Measurement& m : report.numbers) {
    numbers += fmt::format("{}={}{}\n", m.key, m.value, m.unit.empty() ? "" : " " + m.unit);
  }
  write_file_atomic(out / "numbers.txt", numbers);
  fmt::print("\n{}", numbers);
  fmt::print("wrote {} figures, 3 tables and numbers.txt to {} ({}x{}, {}, renderer \"{}\")\n",
             report.figures.size(), out.string(), width, height, o.precision,
             renderer.gl_renderer());
  return 0;
}

// --- the live window ------------------------------------------------------------------------

struct Live {
  Oscillator system;
  double dt, duration;
  Precision precision;
  std::vector<OscillatorRun> runs;
  Trace exact;  // sampled 8 times per tick, extended as time advances

  void restart() {
    runs.clear();
    const bool damped = system.damping > 0;
    // Explicit Euler only on the damped spring: undamped at dt = 0.1 its energy grows by
    // 1 + (omega*dt)^2 = 1.15 per tick and leaves any scale within seconds.
    if (damped) runs.emplace_back(system, Integrator::explicit_euler, precision, dt);
    runs.emplace_back(system, Integrator::semi_implicit_euler, precision, dt);
    runs.emplace_back(system, Integrator::rk4, precision, dt);
    exact = exact_trace(system, 0.0, 0.0, dt);
  }
  void tick() {
    if (runs.front().time() >= duration - 1e-9) return;  // done: hold the final state
    for (OscillatorRun& r : runs) r.step();
    const double t0 = exact.t.back(), t1 = runs.front().time();
    const Trace more = exact_trace(system, t0 + dt / 8, t1 + 1e-12, dt / 8);
    for (std::size_t i = 0; i < more.t.size(); ++i)
      exact.add(more.t[i], more.x[i], more.v[i], more.energy[i]);
  }
};

Rgba8 color_for(Integrator i) {
  switch (i) {
    case Integrator::explicit_euler:
      return plot_palette()[3];
    case Integrator::semi_implicit_euler:
      return plot_palette()[1];
    default:
      return plot_palette()[2];
  }
}
std::string label_for(Integrator i) {
  switch (i) {
    case Integrator::explicit_euler:
      return "explicit Euler";
    case Integrator::semi_implicit_euler:
      return "semi-implicit Euler";
    default:
      return "RK4";
  }
}

void draw_live(Renderer& r, const Live& live, const FixedStepLoop& loop) {
  const double t = live.runs.front().time();
  const double window = 10.0;
  const double t0 = std::max(0.0, t - window), t1 = std::max(window, t);
  const double e0 = live.system.energy(live.system.x0, live.system.v0);

  PlotSpec xs;
  xs.title = fmt::format("Integration Basics, live: {} spring, dt = {:g} s ({})",
                         live.system.damping > 0 ? "damped" : "undamped", live.dt,
                         precision_name(live.precision));
  xs.x = {.label = "t (s)", .min = t0, .max = t1};
  xs.y = {.label = "x (m)"};
  if (live.system.damping == 0) {
    xs.y.min = -1.15 * live.system.x0;
    xs.y.max = 1.15 * live.system.x0;
  }
  xs.legend = LegendPlacement::outside_right;
  xs.series.push_back({.label = "exact",
                       .x = live.exact.t,
                       .y = live.exact.x,
                       .color = plot_palette()[6],
                       .line_width = 1.5f});
  PlotSpec es;
  es.x = {.label = "t (s)", .min = 0.0, .max = live.duration};
  es.y = {.label = "E / E0", .log = live.system.damping > 0};
  es.legend = LegendPlacement::outside_right;
  std::vector<double> exact_e(live.exact.energy.size());
  for (std::size_t i = 0; i < exact_e.size(); ++i) exact_e[i] = live.exact.energy[i] / e0;
  es.series.push_back({.label = "exact",
                       .x = live.exact.t,
                       .y = exact_e,
                       .color = plot_palette()[6],
                       .line_width = 1.5f});
  std::string numbers;
  for (const OscillatorRun& run : live.runs) {
    const Trace& tr = run.trace();
    xs.series.push_back({.label = label_for(run.integrator()),
                         .x = tr.t,
                         .y = tr.x,
                         .color = color_for(run.integrator())});
    std::vector<double> e(tr.energy.size());
    for (std::size_t i = 0; i < e.size(); ++i) e[i] = tr.energy[i] / e0;
    es.series.push_back({.label = label_for(run.integrator()),
                         .x = tr.t,
                         .y = e,
                         .color = color_for(run.integrator())});
    numbers += fmt::format("{}{} {:.4f}", numbers.empty() ? "" : ", ", label_for(run.integrator()),
                           e.back());
  }
  es.caption = {
      fmt::format("t = {:.2f} s  tick {}  time scale x{:g}{}   E/E0: {}", t,
                  live.runs.front().ticks(), loop.time_scale(),
                  loop.paused() ? "  PAUSED" : (t >= live.duration - 1e-9 ? "  DONE" : ""),
                  numbers),
      "Esc quits   space pauses   . steps   + / - speed   r restarts"};

  // One text size for both panels: that of the whole window.
  xs.text_scale = es.text_scale = plot_text_scale(r.width(), r.height());
  const double w = r.width(), h = r.height();
  r.begin(Rgba8{255, 255, 255, 255});
  add_plot(r, xs, PixelBox{0, 0, w, std::floor(h * 0.5)});
  add_plot(r, es, PixelBox{0, std::floor(h * 0.5), w, h});
  r.finish();
}

int run_window(const Options& o) {
  const auto [width, height] = parse_size(o.size);
  Live live;
  live.system = o.live == "damped" ? article_damped : article_undamped;
  live.dt = o.dt.value_or(o.live == "damped" ? damped_dt : undamped_dts[0]);
  live.duration = o.live == "damped" ? damped_duration : undamped_duration;
  live.precision = *parse_precision(o.precision);

  std::optional<Window> window;
  try {
    window.emplace("fixstep - Integration Basics", width, height);
  } catch (const WindowError& e) {
    throw WindowError(fmt::format(
        "--window needs a display ({}). Without --window, integration_basics writes the "
        "figures as PNG files instead.",
        e.what()));
  }
  Renderer renderer(width, height);
  live.restart();
  FixedStepLoop loop(live.dt);
  loop.set_time_scale(o.speed);
  RealClock real_clock;
  const std::optional<VirtualClock> virtual_clock =
      o.fps ? std::optional<VirtualClock>(VirtualClock(*o.fps)) : std::nullopt;
  constexpr auto frame_budget = std::chrono::microseconds(16667);

  for (std::int64_t frame = 0; o.frames == 0 || frame < o.frames; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    const WindowEvents ev = window->poll();
    if (ev.quit) break;
    apply_loop_keys(ev, loop, 64.0);  // up to 64x: the article's runs last 90 s
    if (ev.restart) {
      live.restart();
      loop.reset();
    }
    const double seconds =
        virtual_clock ? virtual_clock->frame_seconds() : real_clock.frame_seconds();
    if (frame > 0) loop.advance(seconds, TickInput{}, [&](const TickInput&) { live.tick(); });
    draw_live(renderer, live, loop);
    window->present(renderer.pixels());
    if (!virtual_clock) std::this_thread::sleep_until(start + frame_budget);
  }
  fmt::print("window: driver={} t={:.2f} s ticks={}\n", window->driver(), live.runs.front().time(),
             live.runs.front().ticks());
  for (const OscillatorRun& run : live.runs) {
    const Trace& tr = run.trace();
    fmt::print("  {}: x={:.6f} m E/E0={:.6f}\n", label_for(run.integrator()), tr.x.back(),
               tr.energy.back() / tr.energy.front());
  }
  return 0;
}

}  // namespace

// One function-try-block: an exception from the CLI11 setup is reported like any other error.
int main(int argc, char** argv) try {
  CLI::App app{
      "integration_basics: the figures and constant-force tables of Glenn Fiedler's "
      "'Integration Basics', computed with fixstep's World and integrators, plotted with "
      "fixstep's OSMesa plots."};
  Options o;
  app.add_option("--out", o.out, "output directory for PNGs, tables and numbers.txt")
      ->capture_default_str();
  app.add_option("--size", o.size, "figure / window size in pixels, WxH")->capture_default_str();
  app.add_option("--precision", o.precision, "world precision for the figures (tables: f32)")
      ->check(CLI::IsMember({"f32", "f64"}))
      ->capture_default_str();
  app.add_flag("--window", o.window, "show the comparison live in an SDL window instead");
  app.add_option("--live", o.live,
                 "system shown live: damped (article, dt 0.01) or undamped (dt 0.1)")
      ->check(CLI::IsMember({"damped", "undamped"}))
      ->capture_default_str();
  app.add_option("--dt", o.dt, "live: physics tick (s)")->check(CLI::Range(1e-4, 1.0));
  app.add_option("--speed", o.speed, "live: initial time scale (simulated s per real s)")
      ->check(CLI::Range(1.0 / 16, 64.0))
      ->capture_default_str();
  app.add_option("--frames", o.frames, "live: quit after N frames (0 = run until Esc)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--fps", o.fps,
                 "live: virtual clock of F frames per second instead of the real clock")
      ->check(CLI::Range(1.0, 1000.0));
  CLI11_PARSE(app, argc, argv);
  return o.window ? run_window(o) : write_figures(o);
} catch (const std::exception& e) {
  std::fprintf(stderr, "integration_basics: error: %s\n", e.what());
  return 1;
}
