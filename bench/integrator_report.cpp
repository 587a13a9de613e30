// Measures and prints (as Markdown) the tables of docs/INTEGRATORS.md:
//   1. each integrator's order, stability bound, force evaluations per tick, measured energy
//      behaviour on the undamped oscillator and measured convergence on a damped one;
//   2. the position error of f32 against f64 far from the origin.
//   build/release/bin/integrator_report
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/exact.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

using namespace fixstep;

namespace {

/// Force evaluations per tick as fixstep performs them (and the minimum with FSAL reuse).
std::string evaluations(Integrator i) {
  const int n = integrator_evaluations(i);
  if (i == Integrator::implicit_euler) return "1 (closed form; Newton for rest length > 0)";
  if (i == Integrator::velocity_verlet || i == Integrator::forest_ruth) {
    return fmt::format("{} ({} with FSAL)", n, n / 2);
  }
  return std::to_string(n);
}

/// Undamped unit oscillator at ω·dt = 0.1 for 10^5 ticks (~1600 periods). The trend compares
/// the mean energy of the first and the last 1000 ticks (~16 periods each); the band is the
/// largest |E/E0 - 1| seen.
std::string energy_behaviour(Integrator i) {
  fixstep::detail::WorldKernel<double> w(WorldSettings{.dt = 0.1, .integrator = i});
  BodyDef d;
  d.body.position = {1.0, 0.0};
  d.spring = SpringDamper{.anchor = {}, .stiffness = 1.0};
  w.create_body(d);
  const double e0 = w.energy().total();
  constexpr int n = 100'000, window = 1000;
  double worst = 0, first = 0, last = 0;
  for (int k = 0; k < n; ++k) {
    w.step();
    const double r = w.energy().total() / e0;
    worst = std::max(worst, std::abs(r - 1));
    if (k < window) first += r / window;
    if (k >= n - window) last += r / window;
  }
  if (!std::isfinite(last) || last > first * (1 + 1e-4)) {
    return fmt::format("growing: E/E0 = {:.3g} after 10^5 ticks", last);
  }
  if (last < first * (1 - 1e-4))
    return fmt::format("decaying: E/E0 = {:.4g} after 10^5 ticks", last);
  return fmt::format("bounded: E/E0 within 1 ± {:.2g}, no trend", worst);
}

/// Position error at t = 2 s on a damped oscillator (ζ = 0.15) at dt = 0.01 and the observed
/// order from dt = 0.02 -> 0.01.
std::pair<double, double> convergence(Integrator i) {
  BodyDef d;
  d.body = Body{.mass = 1.0, .position = {1.0, 0.5}, .velocity = {0.3, -0.2}};
  d.spring = SpringDamper{.anchor = {0.1, 0.0}, .stiffness = 4.0, .damping = 0.6};
  auto error = [&](double dt) {
    fixstep::detail::WorldKernel<double> w(WorldSettings{.dt = dt, .integrator = i});
    w.create_body(d);
    const long n = std::lround(2.0 / dt);
    for (long k = 0; k < n; ++k) w.step();
    const auto e = exact::solve(d, n * dt);
    return std::hypot(w.x()[0] - e->position.x, w.y()[0] - e->position.y);
  };
  const double fine = error(0.01);
  return {fine, std::log2(error(0.02) / fine)};
}

template <class Real>
Body run_far(const BodyDef& def, double dt, int ticks) {
  fixstep::detail::WorldKernel<Real> w(WorldSettings{.dt = dt});
  const Entity e = w.create_body(def);
  for (int k = 0; k < ticks; ++k) w.step();
  return w.body(e);
}

}  // namespace

int main() {
  std::puts(
      "| integrator | order | stable for ω·h < | force evaluations per tick "
      "| energy on the undamped oscillator, ω·dt = 0.1 | error at t = 2 s, dt = 0.01 "
      "(damped) | observed order |");
  std::puts("|---|---|---|---|---|---|---|");
  for (Integrator i : all_integrators) {
    const double bound = max_stable_step(i, 1.0, 0.0);
    const std::string b = std::isinf(bound) ? "∞ (A-stable)"
                          : bound == 0      ? "never (0)"
                                            : fmt::format("{:.4f}", bound);
    const auto [err, order] = convergence(i);
    fmt::print("| `{}` | {} | {} | {} | {} | {:.2e} m | {:.3f} |\n", integrator_name(i),
               integrator_order(i), b, evaluations(i), energy_behaviour(i), err, order);
  }

  std::puts("\n| scenario | offset X | f32 − f64 position difference | spacing of f32 at X |");
  std::puts("|---|---|---|---|");
  for (double x0 : {0.0, 1e3, 1e6}) {
    BodyDef p;  // projectile: 15 m/s across, 20 m/s up, 2 s at dt = 0.01
    p.body = Body{.mass = 1.0, .position = {x0, 0.0}, .velocity = {15.0, 20.0}};
    p.gravity = Gravity{{0.0, -9.81}};
    const Body a = run_far<float>(p, 0.01, 200), b = run_far<double>(p, 0.01, 200);
    const double ulp = std::nextafter(float(std::max(x0, 1.0)), 1e30f) - float(std::max(x0, 1.0));
    fmt::print("| projectile, 2 s | {:g} m | {:.3g} m | {:.3g} m |\n", x0,
               std::hypot(a.position.x - b.position.x, a.position.y - b.position.y), ulp);
  }
  for (double x0 : {0.0, 1e3, 1e6}) {
    BodyDef s;  // spring anchored at (X, 0), 1 m amplitude, the article's k and b, 10 s
    s.body = Body{.mass = 1.0, .position = {x0 + 1.0, 0.0}, .velocity = {}};
    s.spring = SpringDamper{.anchor = {x0, 0.0}, .stiffness = 15.0, .damping = 0.1};
    const Body a = run_far<float>(s, 0.01, 1000), b = run_far<double>(s, 0.01, 1000);
    const double ulp = std::nextafter(float(std::max(x0, 1.0)), 1e30f) - float(std::max(x0, 1.0));
    fmt::print("| spring, 1 m amplitude, 10 s | {:g} m | {:.3g} m | {:.3g} m |\n", x0,
               std::abs(a.position.x - b.position.x), ulp);
  }
  return 0;
}
