// Work-precision study: for each integrator, the error it makes against the exact solution
// versus what it costs, over a sweep of step sizes h = dt / substeps, on three systems with
// closed-form solutions (engine/core/include/fixstep/core/exact.hpp):
//   damped      spring-damper k = 4 N/m, b = 0.6 N·s/m, m = 1 kg (ω = 2 rad/s, ζ = 0.15), 10 s
//   projectile  gravity 9.81 m/s², wind 2 N, drag 0.2 N·s/m, m = 1 kg, thrown at 25 m/s, 4 s
//   undamped    k = 4 N/m, m = 1 kg on a circular orbit (ω = 2 rad/s), 100 s (~32 periods)
// Error: position error |x - x_exact| (m) at the end and its maximum over the run (sampled
// every tick), and the energy error |E - E_exact| / |E0| over the run. Cost: force
// evaluations and measured time per body per simulated second; the time per body-step of each
// integrator is measured on 4096 bodies (median of 7 runs) — the cost of one body alone would
// be dominated by per-tick overhead, not by the method.
//
// Writes DIR/work_precision.csv, DIR/work_precision.md (slopes and the cheapest integrator and
// step per target error) and the log-log plots DIR/work_precision_<system>.png, rendered by
// fixstep's own plot module through OSMesa. The slopes of log(error) against log(cost) are the
// methods' orders (error ∝ h^p, cost ∝ 1/h): they are checked against integrator_order() ± 0.2
// and the program exits 1 when one misses.
//
//   build/bench/bin/work_precision --out docs/perf
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "fixstep/capture/capture.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/exact.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/plot.hpp"
#include "world_kernel.hpp"

using namespace fixstep;

namespace {

struct System {
  const char* name;
  const char* title;
  BodyDef body;
  double duration;  ///< s
};

std::vector<System> systems() {
  System damped{"damped", "Damped spring (k = 4 N/m, b = 0.6 N*s/m, m = 1 kg), 10 s", {}, 10.0};
  damped.body.body.position = {1.0, 0.5};
  damped.body.body.velocity = {0.0, 0.3};
  damped.body.spring = SpringDamper{.anchor = {}, .stiffness = 4.0, .damping = 0.6};

  System projectile{"projectile", "Projectile with drag 0.2 N*s/m and 2 N wind, 4 s", {}, 4.0};
  projectile.body.body.velocity = {15.0, 20.0};
  projectile.body.gravity = Gravity{{0.0, -9.81}};
  projectile.body.constant_force = ConstantForce{{2.0, 0.0}};
  projectile.body.drag = LinearDrag{0.2};

  System undamped{
      "undamped", "Undamped spring, circular orbit (k = 4 N/m, m = 1 kg), 100 s", {}, 100.0};
  undamped.body.body.position = {1.0, 0.0};
  undamped.body.body.velocity = {0.0, 2.0};
  undamped.body.spring = SpringDamper{.anchor = {}, .stiffness = 4.0, .damping = 0.0};
  return {damped, projectile, undamped};
}

/// Mechanical energy of a body in state b under def's conservative forces, J (the World's
/// potentials: spring ½k|d|², gravity -m g·x, constant force -F·x).
double energy(const BodyDef& def, const Body& b) {
  double e = 0.5 * b.mass * (b.velocity.x * b.velocity.x + b.velocity.y * b.velocity.y);
  if (def.spring) {
    const double dx = b.position.x - def.spring->anchor.x, dy = b.position.y - def.spring->anchor.y;
    e += 0.5 * def.spring->stiffness * (dx * dx + dy * dy);
  }
  if (def.gravity)
    e -= b.mass *
         (def.gravity->acceleration.x * b.position.x + def.gravity->acceleration.y * b.position.y);
  if (def.constant_force)
    e -= def.constant_force->force.x * b.position.x + def.constant_force->force.y * b.position.y;
  return e;
}

struct Level {
  double dt;  ///< tick, s
  int substeps;
  [[nodiscard]] double h() const { return dt / substeps; }
};

/// Coarse ticks first, then the game's 1/60 s tick with more and more substeps.
std::vector<Level> levels() {
  std::vector<Level> out{{0.2, 1}, {0.1, 1}, {1.0 / 15, 1}, {1.0 / 30, 1}};
  for (int s = 1; s <= 1024; s *= 2) out.push_back({1.0 / 60, s});
  return out;
}

struct Point {
  std::string system;
  Integrator integrator;
  Level level;
  double err_end = 0, err_max = 0, energy_err_max = 0;  ///< m, m, relative
  double scale = 0;        ///< size of the motion: largest |x_exact - x0| over the run, m
  double evals_per_s = 0;  ///< force evaluations per body per simulated second
  double ns_per_s = 0;     ///< measured ns per body per simulated second
};

/// Steps one body for the system's duration and measures its errors; false if it blew up.
bool measure(const System& sys, Integrator integrator, Level level, Point& p) {
  fixstep::detail::WorldKernel<double> w(
      WorldSettings{.dt = level.dt, .integrator = integrator, .substeps = level.substeps});
  const Entity e = w.create_body(sys.body);
  const auto ticks = static_cast<std::uint64_t>(std::llround(sys.duration / level.dt));
  const double e0 = energy(sys.body, w.body(e));
  for (std::uint64_t t = 1; t <= ticks; ++t) {
    w.step();
    const Body b = w.body(e);
    const Body x = *exact::solve(sys.body, w.time());
    if (!std::isfinite(b.position.x) || !std::isfinite(b.position.y) ||
        std::abs(b.position.x) > 1e12)
      return false;
    const double err = std::hypot(b.position.x - x.position.x, b.position.y - x.position.y);
    p.scale = std::max(p.scale, std::hypot(x.position.x - sys.body.body.position.x,
                                           x.position.y - sys.body.body.position.y));
    p.err_max = std::max(p.err_max, err);
    p.energy_err_max = std::max(p.energy_err_max,
                                std::abs(energy(sys.body, b) - energy(sys.body, x)) / std::abs(e0));
    if (t == ticks) p.err_end = err;
  }
  return true;
}

/// Measured time per body-step (ns) of `integrator` on `sys`: 4096 copies of the body,
/// median of 7 runs of enough steps for ~20 ms each.
double ns_per_body_step(const System& sys, Integrator integrator) {
  constexpr std::size_t n = 4096;
  fixstep::detail::WorldKernel<double> w(WorldSettings{.dt = 1.0 / 60, .integrator = integrator});
  for (std::size_t j = 0; j < n; ++j) w.create_body(sys.body);
  w.step();
  using clock = std::chrono::steady_clock;
  int steps = 16;
  for (;;) {  // calibrate to ~20 ms
    const auto t0 = clock::now();
    for (int i = 0; i < steps; ++i) w.step();
    if (clock::now() - t0 > std::chrono::milliseconds(20)) break;
    steps *= 2;
  }
  std::vector<double> runs;
  for (int r = 0; r < 7; ++r) {
    const auto t0 = clock::now();
    for (int i = 0; i < steps; ++i) w.step();
    runs.push_back(std::chrono::duration<double, std::nano>(clock::now() - t0).count() /
                   (double(steps) * n));
  }
  std::sort(runs.begin(), runs.end());
  return runs[runs.size() / 2];
}

/// Least-squares slope of log10(error) against log10(cost) over a sweep's asymptotic points.
/// Taken in order of decreasing h, up to the smallest error (beyond it rounding, which grows
/// with the number of steps, outweighs the truncation error), keeping points with
/// h <= 0.1 s (ω·h <= 0.2 for the springs), error below 1 % of the motion's size (larger
/// errors are pre-asymptotic or saturated: a phase error cannot exceed the orbit) and above 100x
/// the smallest error (the round-off floor). NaN with fewer than 3 such points.
double order_slope(std::vector<Point> pts, double Point::*err) {
  std::sort(pts.begin(), pts.end(),
            [](const Point& a, const Point& b) { return a.level.h() > b.level.h(); });
  const auto min_it = std::min_element(
      pts.begin(), pts.end(), [err](const Point& a, const Point& b) { return a.*err < b.*err; });
  if (min_it == pts.end()) return std::nan("");
  // A minimum at the finest step is no floor: the sweep never reached round-off.
  const bool reached_floor = min_it + 1 != pts.end();
  const double floor = reached_floor ? (*min_it).*err : 0.0;
  std::vector<std::pair<double, double>> xy;
  for (auto it = pts.begin(); it != (reached_floor ? min_it : pts.end()); ++it) {
    const Point& p = *it;
    if (p.*err > 100.0 * floor && p.*err < 0.01 * p.scale && p.level.h() <= 0.1 + 1e-12) {
      xy.emplace_back(std::log10(p.ns_per_s), std::log10(p.*err));
    }
  }
  if (xy.size() < 3) return std::nan("");
  double mx = 0, my = 0;
  for (auto [x, y] : xy) mx += x, my += y;
  mx /= double(xy.size()), my /= double(xy.size());
  double sxy = 0, sxx = 0;
  for (auto [x, y] : xy) sxy += (x - mx) * (y - my), sxx += (x - mx) * (x - mx);
  return -sxy / sxx;
}

std::string level_text(Level l) {
  const std::string dt = std::abs(l.dt - 1.0 / 60) < 1e-12   ? "1/60"
                         : std::abs(l.dt - 1.0 / 30) < 1e-12 ? "1/30"
                         : std::abs(l.dt - 1.0 / 15) < 1e-12 ? "1/15"
                                                             : fmt::format("{}", l.dt);
  return l.substeps > 1 ? fmt::format("dt = {} s, {} substeps", dt, l.substeps)
                        : fmt::format("dt = {} s", dt);
}

Marker marker_for(Integrator i) {
  switch (i) {
    case Integrator::semi_implicit_euler:
      return Marker::circle;
    case Integrator::explicit_euler:
      return Marker::square;
    case Integrator::velocity_verlet:
      return Marker::diamond;
    case Integrator::rk4:
      return Marker::triangle;
    case Integrator::implicit_euler:
      return Marker::square;
    case Integrator::forest_ruth:
      return Marker::circle;
  }
  return Marker::circle;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "docs/perf";
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--out") == 0 && a + 1 < argc) {
      out = argv[++a];
    } else {
      std::fprintf(stderr, "usage: work_precision [--out DIR]   (unknown argument '%s')\n",
                   argv[a]);
      return 2;
    }
  }
  try {
    prepare_output_dir(out);
    std::vector<Point> all;
    std::string md, csv =
                        "system,integrator,dt,substeps,h,err_end_m,err_max_m,energy_err_max,evals_"
                        "per_body_s,ns_per_body_s\n";
    int misses = 0;
    Renderer renderer(1280, 800);
    md +=
        "| system | integrator | theoretical order | measured slope (max position error) | within "
        "±0.2 |\n";
    md += "|---|---|---|---|---|\n";
    std::string cheapest;
    for (const System& sys : systems()) {
      PlotSpec plot{.title = std::string("Work-precision: ") + sys.title,
                    .x = {.label = "measured cost: ns per body per simulated second", .log = true},
                    .y = {.label = "max position error over the run (m)", .log = true}};
      PlotSpec energy_plot{.title = std::string("Energy error: ") + sys.title,
                           .x = plot.x,
                           .y = {.label = "max |E - E_exact| / |E0| over the run", .log = true}};
      std::vector<std::string> caption;
      std::vector<Point> sys_points;
      for (Integrator i : all_integrators) {
        const double ns = ns_per_body_step(sys, i);
        std::vector<Point> pts;
        for (Level l : levels()) {
          Point p{.system = sys.name, .integrator = i, .level = l};
          if (!measure(sys, i, l, p)) continue;  // unstable at this h: no point
          const double steps_per_s = l.substeps / l.dt;
          p.evals_per_s = integrator_evaluations(i) * steps_per_s;
          p.ns_per_s = ns * steps_per_s;
          pts.push_back(p);
          csv += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", sys.name, integrator_name(i), l.dt,
                             l.substeps, l.h(), p.err_end, p.err_max, p.energy_err_max,
                             p.evals_per_s, p.ns_per_s);
        }
        const double slope = order_slope(pts, &Point::err_max);
        const int order = integrator_order(i);
        const bool ok = std::isfinite(slope) && std::abs(slope - order) <= 0.2;
        if (!ok) ++misses;
        md += fmt::format("| {} | `{}` | {} | {:.2f} | {} |\n", sys.name, integrator_name(i), order,
                          slope, ok ? "yes" : "**no**");
        caption.push_back(
            fmt::format("{}: slope {:.2f} (order {})", integrator_name(i), slope, order));
        PlotSeries s{.label = std::string(integrator_name(i)), .marker = marker_for(i)};
        PlotSeries se = s;
        for (const Point& p : pts) {
          s.x.push_back(p.ns_per_s), s.y.push_back(p.err_max);
          se.x.push_back(p.ns_per_s), se.y.push_back(p.energy_err_max);
        }
        plot.series.push_back(s);
        energy_plot.series.push_back(se);
        sys_points.insert(sys_points.end(), pts.begin(), pts.end());
      }
      for (double target : {1e-2, 1e-4, 1e-6}) {
        plot.references.push_back({.value = target});
        const Point* best = nullptr;
        for (const Point& p : sys_points) {
          if (p.err_max <= target && (!best || p.ns_per_s < best->ns_per_s)) best = &p;
        }
        cheapest +=
            best ? fmt::format("| {} | {:.0e} m | `{}` | {} | {:.3g} | {:.3g} | {:.2e} m |\n",
                               sys.name, target, integrator_name(best->integrator),
                               level_text(best->level), best->ns_per_s, best->evals_per_s,
                               best->err_max)
                 : fmt::format("| {} | {:.0e} m | none reached it | | | | |\n", sys.name, target);
      }
      std::string line;
      for (const std::string& c : caption) line += (line.empty() ? "" : "; ") + c;
      plot.caption = {
          "Slopes of log(error) vs log(cost) over the asymptotic points (h <= 0.1 s, error < 1 % "
          "of the motion, above 100x the round-off floor): " +
              line,
          "Dashed: target errors 1e-2, 1e-4, 1e-6 m. Points left out: unstable step sizes."};
      energy_plot.caption = {
          "Energy error relative to the initial energy, same runs as the position plot."};
      draw_plot(renderer, plot);
      write_png(fmt::format("{}/work_precision_{}.png", out, sys.name), renderer.width(),
                renderer.height(), renderer.pixels());
      draw_plot(renderer, energy_plot);
      write_png(fmt::format("{}/work_precision_{}_energy.png", out, sys.name), renderer.width(),
                renderer.height(), renderer.pixels());
      all.insert(all.end(), sys_points.begin(), sys_points.end());
    }
    md +=
        "\nCheapest configuration (by measured time) whose maximum position error over the run is "
        "at most the target:\n\n";
    md +=
        "| system | target error | integrator | step | ns per body per simulated s | force "
        "evaluations per body per simulated s | error reached |\n";
    md += "|---|---|---|---|---|---|---|\n" + cheapest;
    write_file_atomic(out + "/work_precision.csv", csv);
    write_file_atomic(out + "/work_precision.md", md);
    std::fputs(md.c_str(), stdout);
    std::printf("wrote %s/work_precision.{csv,md} and %s/work_precision_*.png (%zu points)\n",
                out.c_str(), out.c_str(), all.size());
    if (misses > 0) {
      std::fprintf(stderr, "work_precision: %d slope(s) outside theoretical order ± 0.2\n", misses);
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "work_precision: %s\n", e.what());
    return 1;
  }
  return 0;
}
