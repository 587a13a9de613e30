#include "figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fixstep/core/components.hpp>
#include <fixstep/core/exact.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world_settings.hpp>
#include <numbers>
#include <stdexcept>

#include "fixstep/core/world_def.hpp"

namespace fixstep::demo {

double Oscillator::omega() const {
  return std::sqrt(stiffness / mass);
}

double Oscillator::energy(double x, double v) const {
  return 0.5 * mass * v * v + 0.5 * stiffness * x * x;
}

void Trace::add(double time, double position, double velocity, double e) {
  t.push_back(time);
  x.push_back(position);
  v.push_back(velocity);
  energy.push_back(e);
}

OscillatorRun::OscillatorRun(const Oscillator& system, Integrator integrator, Precision precision,
                             double dt)
    : system_(system),
      integrator_(integrator),
      sim_(WorldDef::empty(precision, WorldSettings{.dt = dt, .integrator = integrator})) {
  // World itself runs any integrator at any dt; only the fixstep CLI's stability guard would
  // refuse explicit Euler on this spring, and showing that instability is the point here.
  BodyDef def;
  def.name = "bob";
  def.body = Body{.mass = system.mass, .position = {system.x0, 0.0}, .velocity = {system.v0, 0.0}};
  def.spring =
      SpringDamper{.anchor = {0.0, 0.0}, .stiffness = system.stiffness, .damping = system.damping};
  sim_.create_body(def);
  const Body b = sim_.body(sim_.bodies()[0]);
  trace_.add(0.0, b.position.x, b.velocity.x, sim_.energy().total());
}

void OscillatorRun::step() {
  sim_.step();
  const Body b = sim_.body(sim_.bodies()[0]);
  trace_.add(sim_.time(), b.position.x, b.velocity.x, sim_.energy().total());
}

Trace exact_trace(const Oscillator& s, double t_begin, double t_end, double step) {
  Trace out;
  const auto n = static_cast<std::int64_t>(std::floor((t_end - t_begin) / step + 1e-9));
  for (std::int64_t i = 0; i <= n; ++i) {
    const double t = t_begin + static_cast<double>(i) * step;
    const exact::AxisState e =
        exact::linear(s.x0, s.v0, s.stiffness / s.mass, s.gamma(), 0.0, 0.0, t);
    out.add(t, e.x, e.v, s.energy(e.x, e.v));
  }
  return out;
}

std::vector<double> unwrapped_phase(const Trace& trace, double omega) {
  std::vector<double> phase(trace.x.size());
  double previous = 0.0, total = 0.0;
  for (std::size_t i = 0; i < trace.x.size(); ++i) {
    const double a = std::atan2(-trace.v[i] / omega, trace.x[i]);
    total += i == 0 ? a : std::remainder(a - previous, 2.0 * std::numbers::pi);
    previous = a;
    phase[i] = total;
  }
  return phase;
}

namespace {

// Colours kept per method in every figure: the article draws semi-implicit Euler orange and
// RK4 green.
const Rgba8 exact_color = plot_palette()[6];     // dark grey
const Rgba8 explicit_color = plot_palette()[3];  // vermillion
const Rgba8 semi_color = plot_palette()[1];      // orange
const Rgba8 rk4_color = plot_palette()[2];       // bluish green

PlotSeries line(std::string label, const std::vector<double>& x, const std::vector<double>& y,
                Rgba8 color, float width = 2.0f) {
  PlotSeries s;
  s.label = std::move(label);
  s.x = x;
  s.y = y;
  s.color = color;
  s.line_width = width;
  return s;
}

PlotSeries with_markers(PlotSeries s, Marker m, float size = 3.5f) {
  s.marker = m;
  s.marker_size = size;
  return s;
}

std::vector<double> ratio(const std::vector<double>& v, double by) {
  std::vector<double> out(v.size());
  std::transform(v.begin(), v.end(), out.begin(), [&](double e) { return e / by; });
  return out;
}

Trace run(const Oscillator& s, Integrator integrator, Precision p, double dt, double duration) {
  OscillatorRun r(s, integrator, p, dt);
  const auto ticks = static_cast<std::uint64_t>(std::llround(duration / dt));
  while (r.ticks() < ticks) r.step();
  return r.trace();
}

// |x - x_exact| at every tick, and its largest value and time.
struct ErrorStats {
  std::vector<double> error;
  double max = 0.0, at = 0.0;
};
ErrorStats errors(const Trace& numeric, const Oscillator& s) {
  ErrorStats e;
  for (std::size_t i = 0; i < numeric.t.size(); ++i) {
    const double exact =
        exact::linear(s.x0, s.v0, s.stiffness / s.mass, s.gamma(), 0, 0, numeric.t[i]).x;
    e.error.push_back(std::abs(numeric.x[i] - exact));
    if (e.error.back() > e.max) {
      e.max = e.error.back();
      e.at = numeric.t[i];
    }
  }
  return e;
}

// Mean angular frequency (rad/s) of x(t) from its first and last downward zero crossings,
// each placed by linear interpolation between ticks; 0 with fewer than two crossings. Each
// crossing's interpolation error is bounded and does not accumulate, so over K periods the
// relative error falls like 1/K.
double crossing_frequency(const Trace& tr) {
  double first = -1, last = -1;
  int crossings = 0;
  for (std::size_t i = 1; i < tr.x.size(); ++i) {
    if (tr.x[i - 1] > 0 && tr.x[i] <= 0) {
      const double f = tr.x[i - 1] / (tr.x[i - 1] - tr.x[i]);
      const double tc = tr.t[i - 1] + f * (tr.t[i] - tr.t[i - 1]);
      if (crossings == 0) first = tc;
      last = tc;
      ++crossings;
    }
  }
  return crossings < 2 ? 0.0 : 2 * std::numbers::pi * (crossings - 1) / (last - first);
}

// Energy growth per tick: exp of the least-squares slope of ln E over the tick index, which
// averages out the energy's oscillation within each period.
double growth_per_tick(const std::vector<double>& energy) {
  const auto n = static_cast<double>(energy.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < energy.size(); ++i) {
    const double x = static_cast<double>(i), y = std::log(energy[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return std::exp((n * sxy - sx * sy) / (n * sxx - sx * sx));
}

// Two significant digits without an exponent for ratios like 37000.
std::string two_digits(double v) {
  if (!(v > 0) || !std::isfinite(v)) return fmt::format("{}", v);
  const double p = std::pow(10.0, std::floor(std::log10(v)) - 1);
  return fmt::format("{:.{}f}", std::round(v / p) * p,
                     std::max(0, -static_cast<int>(std::log10(p))));
}

std::string describe(const Oscillator& s) {
  return fmt::format("m = {:g} kg, x0 = {:g} m, k = {:g} N/m, b = {:g} N*s/m", s.mass, s.x0,
                     s.stiffness, s.damping);
}

PlotAxis time_axis(double t0, double t1) {
  PlotAxis a;
  a.label = "t (s)";
  a.min = t0;
  a.max = t1;
  return a;
}

PlotAxis position_axis() {
  PlotAxis a;
  a.label = "x (m)";
  return a;
}

}  // namespace

Report article_figures(Precision precision) {
  Report rep;
  const std::string prec{precision_name(precision)};
  auto note = [&](std::string key, double value, std::string unit) {
    rep.numbers.push_back({std::move(key), value, std::move(unit)});
  };

  // --- damped: (a) exact, (b) explicit Euler, (c) semi-implicit Euler, (d) RK4 ------------------
  const Oscillator& d = article_damped;
  const double T = damped_duration, h = damped_dt;
  const double w = d.omega(), g = d.gamma();
  const double wd = std::sqrt(w * w - g * g / 4);
  const Trace exact = exact_trace(d, 0.0, T, h);
  const Trace fine = exact_trace(d, 0.0, T, 0.001);
  const double e0 = exact.energy.front();
  const Trace ee = run(d, Integrator::explicit_euler, precision, h, T);
  const Trace sie = run(d, Integrator::semi_implicit_euler, precision, h, T);
  const Trace rk4 = run(d, Integrator::rk4, precision, h, T);
  const auto n = static_cast<double>(ee.t.size() - 1);

  note("a.omega", w, "rad/s");
  note("a.period", 2 * std::numbers::pi / wd, "s");
  note("a.exact_energy_ratio", exact.energy.back() / e0, "");
  {
    Figure f{"a_exact_damped", {}};
    f.spec.title = "(a) Damped spring: the exact solution";
    f.spec.x = time_axis(0, T);
    f.spec.y = position_axis();
    f.spec.series = {line("exact", fine.t, fine.x, exact_color)};
    f.spec.legend = LegendPlacement::none;
    f.spec.caption = {
        fmt::format("Integration Basics, 'Why explicit euler is not (always) so great': {}. "
                    "Exact solution (fixstep::exact::linear).",
                    describe(d)),
        fmt::format("omega = sqrt(k/m) = {:.4f} rad/s, damped period 2*pi/omega_d = {:.4f} s; "
                    "energy after {:g} s = {:.4f} E0 (e^(-b t/m) envelope = {:.4f}).",
                    w, 2 * std::numbers::pi / wd, T, exact.energy.back() / e0, std::exp(-g * T))};
    rep.figures.push_back(std::move(f));
  }

  const double ee_ratio = ee.energy.back() / e0;
  const double ee_growth = growth_per_tick(ee.energy);
  const double ee_growth_theory = 1 - h * g + h * h * w * w;
  double ee_peak = 0;
  for (double x : ee.x) ee_peak = std::max(ee_peak, std::abs(x));
  note("b.explicit_energy_ratio", ee_ratio, "");
  note("b.explicit_growth_per_tick", ee_growth, "");
  note("b.explicit_growth_theory", ee_growth_theory, "");
  note("b.explicit_peak", ee_peak, "m");
  {
    Figure f{"b_explicit_euler_damped", {}};
    f.spec.title = "(b) Explicit Euler gains energy (dt = 1/100 s)";
    f.spec.x = time_axis(0, T);
    f.spec.y = position_axis();
    f.spec.series = {line("exact", fine.t, fine.x, exact_color),
                     line("explicit Euler", ee.t, ee.x, explicit_color)};
    f.spec.caption = {
        fmt::format("{}, dt = {:g} s, {} ({:g} ticks). Explicit Euler grows instead of "
                    "damping: |x| reaches {:.1f} m.",
                    describe(d), h, prec, n, ee_peak),
        fmt::format("Energy after {:g} s: {:.4f} E0 (exact {:.4f} E0). Growth per tick (fit of "
                    "ln E): x{:.7f}; theory |1 + dt*lambda|^2 = 1 - dt*b/m + dt^2*k/m = {:.7f}.",
                    T, ee_ratio, exact.energy.back() / e0, ee_growth, ee_growth_theory)};
    rep.figures.push_back(std::move(f));
  }

  const ErrorStats sie_err = errors(sie, d), rk4_err = errors(rk4, d), ee_err = errors(ee, d);
  note("c.semi_implicit_max_error", sie_err.max, "m");
  note("c.semi_implicit_energy_ratio", sie.energy.back() / e0, "");
  {
    Figure f{"c_semi_implicit_damped", {}};
    f.spec.title = "(c) Semi-implicit Euler tracks the exact solution (dt = 1/100 s)";
    f.spec.x = time_axis(0, T);
    f.spec.y = position_axis();
    PlotSeries ex = line("exact", fine.t, fine.x, exact_color, 4.0f);
    f.spec.series = {ex, line("semi-implicit Euler", sie.t, sie.x, semi_color, 1.5f)};
    f.spec.caption = {
        fmt::format("{}, dt = {:g} s, {}. Stable, and at this scale on top of the exact "
                    "curve (drawn wider beneath it).",
                    describe(d), h, prec),
        fmt::format("Largest |x - x_exact| over {:g} s: {:.2f} m at t = {:.2f} s: first order, "
                    "its first step puts it about omega*dt/2 = {:.4f} rad ahead (x0*omega*dt/2 = "
                    "{:.1f} m). Energy after {:g} s: {:.5f} E0 (exact {:.5f} E0).",
                    T, sie_err.max, sie_err.at, w * h / 2, d.x0 * w * h / 2, T,
                    sie.energy.back() / e0, exact.energy.back() / e0)};
    rep.figures.push_back(std::move(f));
  }

  note("d.rk4_max_error", rk4_err.max, "m");
  note("d.semi_implicit_max_error", sie_err.max, "m");
  {
    // Zoom on the last downward zero crossing before T, where semi-implicit Euler's phase lag
    // shows as an offset of about x0 e^(-bt/2m) times its phase error.
    std::size_t c = exact.x.size() - 1;
    while (c > 0 && !(exact.x[c - 1] > 0 && exact.x[c] <= 0)) --c;
    const double tc = exact.t[c];
    const double t0 = exact.t[c - 4], t1 = exact.t[std::min(c + 4, exact.t.size() - 1)];
    const Trace zoom = exact_trace(d, t0, t1, h / 50);
    Figure f{"d_rk4_vs_semi_implicit_zoom", {}};
    f.spec.title = fmt::format("(d) Zoomed in near t = {:.2f} s: RK4 is closer", tc);
    f.spec.x = time_axis(t0, t1);
    f.spec.y = position_axis();
    f.spec.series = {
        line("exact (wide, beneath)", zoom.t, zoom.x, exact_color, 7.0f),
        with_markers(line("semi-implicit Euler", sie.t, sie.x, semi_color), Marker::square, 5.0f),
        with_markers(line("RK4", rk4.t, rk4.x, rk4_color, 1.5f), Marker::circle, 3.5f)};
    const auto at = [&](const Trace& tr) { return tr.x[c]; };
    f.spec.caption = {
        fmt::format("{}, dt = {:g} s, {}; markers are ticks. At t = {:.2f} s: exact {:.4f} m, "
                    "semi-implicit {:.4f} m, RK4 {:.4f} m.",
                    describe(d), h, prec, tc, exact.x[c], at(sie), at(rk4)),
        fmt::format("Largest |x - x_exact| over {:g} s: semi-implicit Euler {:.3g} m, RK4 "
                    "{:.3g} m ({} times smaller).",
                    T, sie_err.max, rk4_err.max, two_digits(sie_err.max / rk4_err.max))};
    rep.figures.push_back(std::move(f));
  }
  {
    Figure f{"d_error_damped", {}};
    f.spec.title = "(d) Position error against the exact solution (dt = 1/100 s)";
    f.spec.x = time_axis(0, T);
    f.spec.y.label = "|x - x_exact| (m)";
    f.spec.y.log = true;
    f.spec.series = {line("explicit Euler", ee.t, ee_err.error, explicit_color, 1.5f),
                     line("semi-implicit Euler", sie.t, sie_err.error, semi_color, 1.5f),
                     line("RK4", rk4.t, rk4_err.error, rk4_color, 1.5f)};
    f.spec.caption = {
        fmt::format("{}, dt = {:g} s, {}. Log scale; zeros (at t = 0 and where the curves "
                    "cross) are not drawn.",
                    describe(d), h, prec),
        fmt::format("Largest errors over {:g} s: explicit Euler {:.0f} m, semi-implicit Euler "
                    "{:.1f} m, RK4 {:.3g} m.",
                    T, ee_err.max, sie_err.max, rk4_err.max)};
    rep.figures.push_back(std::move(f));
  }

  // --- undamped: (e) dt = 0.1, (f) dt = 0.25 over 90 s -----------------------------------------
  const Oscillator& u = article_undamped;
  const double U = undamped_duration;
  const double wu = u.omega();
  const Trace ufine = exact_trace(u, 0.0, U, 0.002);
  for (const double dt : undamped_dts) {
    const char letter = dt == undamped_dts[0] ? 'e' : 'f';
    const std::string tag = fmt::format("{}_undamped_dt{:g}", letter, dt);
    const Trace s = run(u, Integrator::semi_implicit_euler, precision, dt, U);
    const Trace r = run(u, Integrator::rk4, precision, dt, U);
    const double ue0 = u.energy(u.x0, u.v0);
    const double th = wu * dt;  // ω·dt
    const auto ticks = static_cast<double>(s.t.size() - 1);
    const double t_end = s.t.back();
    // Semi-implicit Euler's step matrix on (x, v/omega) has trace 2 - θ² and determinant 1: it
    // turns by acos(1 - θ²/2) per tick, so it runs fast. RK4's is R(iθ) (a scaled rotation): it
    // turns by arg R(iθ) and scales energy by |R(iθ)|² per tick. The exact motion turns by θ.
    const double sie_freq = crossing_frequency(s) / wu;
    const double sie_freq_theory = std::acos(1 - th * th / 2) / th;
    const double sie_phase = unwrapped_phase(s, wu).back() - wu * t_end;
    const double rk4_phase = unwrapped_phase(r, wu).back() - wu * t_end;
    const double re = 1 - th * th / 2 + th * th * th * th / 24, im = th - th * th * th / 6;
    const double rk4_phase_theory = ticks * (std::atan2(im, re) - th);
    const double rk4_freq = crossing_frequency(r) / wu;
    const double rk4_ratio = r.energy.back() / ue0;
    const double rk4_ratio_theory = std::pow(re * re + im * im, ticks);
    double lo = 1e300, hi = 0, mean = 0, mean_first = 0, mean_second = 0;
    for (std::size_t i = 0; i < s.energy.size(); ++i) {
      const double e = s.energy[i] / ue0;
      lo = std::min(lo, e);
      hi = std::max(hi, e);
      mean += e;
      (2 * i < s.energy.size() ? mean_first : mean_second) += e;
    }
    const auto count = static_cast<double>(s.energy.size());
    mean /= count;
    mean_first /= std::ceil(count / 2);
    mean_second /= std::floor(count / 2);
    const std::string k(1, letter);
    note(k + ".dt", dt, "s");
    note(k + ".ticks", ticks, "");
    note(k + ".semi_implicit_frequency_ratio", sie_freq, "omega");
    note(k + ".semi_implicit_frequency_theory", sie_freq_theory, "omega");
    note(k + ".semi_implicit_phase_at_end", sie_phase, "rad");
    note(k + ".semi_implicit_energy_mean", mean, "E0");
    note(k + ".semi_implicit_energy_mean_first_half", mean_first, "E0");
    note(k + ".semi_implicit_energy_mean_second_half", mean_second, "E0");
    note(k + ".semi_implicit_energy_min", lo, "E0");
    note(k + ".semi_implicit_energy_max", hi, "E0");
    note(k + ".rk4_energy_ratio", rk4_ratio, "E0");
    note(k + ".rk4_energy_theory", rk4_ratio_theory, "E0");
    note(k + ".rk4_phase_error", rk4_phase, "rad");
    note(k + ".rk4_phase_theory", rk4_phase_theory, "rad");
    note(k + ".rk4_frequency_ratio", rk4_freq, "omega");

    const std::string setup = fmt::format("{}, dt = {:g} s (omega*dt = {:.4f}), {}, {:g} ticks",
                                          describe(u), dt, th, prec, ticks);
    const std::string sie_line = fmt::format(
        "Semi-implicit Euler runs fast: frequency {:.5f} omega from its zero crossings (theory "
        "acos(1 - (omega*dt)^2/2)/(omega*dt) = {:.5f}), gaining {:.2f} rad in {:g} s; {:+.2f} rad "
        "ahead at the end (angle of (x, v/omega)).",
        sie_freq, sie_freq_theory, (sie_freq - 1) * wu * U, U, sie_phase);
    const std::string rk4_line = fmt::format(
        "RK4 after {:g} s: energy {:.4f} E0 (theory |R(i*omega*dt)|^(2n) = {:.4f}); phase "
        "{:+.3f} rad (theory n*(arg R - omega*dt) = {:+.3f}), frequency {:.5f} omega.",
        U, rk4_ratio, rk4_ratio_theory, rk4_phase, rk4_phase_theory, rk4_freq);
    const double window = letter == 'e' ? 5.0 : 10.0;
    const auto markers = [&](PlotSeries p, Marker m) {
      return with_markers(std::move(p), m, 4.0f);
    };
    if (letter == 'e') {
      Figure f{tag + "_last5s", {}};
      f.spec.title =
          fmt::format("(e) No damping, dt = {:g} s: the last {:g} of {:g} s", dt, window, U);
      f.spec.x = time_axis(U - window, U);
      f.spec.y = position_axis();
      f.spec.series = {line("exact", ufine.t, ufine.x, exact_color, 1.5f),
                       markers(line("semi-implicit Euler", s.t, s.x, semi_color), Marker::square),
                       markers(line("RK4", r.t, r.x, rk4_color), Marker::circle)};
      f.spec.legend = LegendPlacement::outside_right;
      f.spec.caption = {setup + "; markers are ticks.", sie_line, rk4_line};
      rep.figures.push_back(std::move(f));
    } else {
      Figure f1{tag + "_rk4", {}};
      f1.spec.title =
          fmt::format("(f) dt = {:g} s: RK4 stays nearly in phase but loses energy", dt);
      f1.spec.x = time_axis(U - window, U);
      f1.spec.y = position_axis();
      f1.spec.series = {line("exact", ufine.t, ufine.x, exact_color, 1.5f),
                        markers(line("RK4", r.t, r.x, rk4_color), Marker::circle)};
      f1.spec.legend = LegendPlacement::outside_right;
      f1.spec.caption = {setup + fmt::format("; the last {:g} s, markers are ticks.", window),
                         rk4_line};
      rep.figures.push_back(std::move(f1));
      Figure f2{tag + "_semi_implicit", {}};
      f2.spec.title =
          fmt::format("(f) dt = {:g} s: semi-implicit Euler keeps energy, drifts in phase", dt);
      f2.spec.x = time_axis(U - window, U);
      f2.spec.y = position_axis();
      f2.spec.series = {line("exact", ufine.t, ufine.x, exact_color, 1.5f),
                        markers(line("semi-implicit Euler", s.t, s.x, semi_color), Marker::square)};
      f2.spec.legend = LegendPlacement::outside_right;
      f2.spec.caption = {setup + fmt::format("; the last {:g} s, markers are ticks.", window),
                         sie_line};
      rep.figures.push_back(std::move(f2));
    }
    Figure fe{tag + "_energy", {}};
    fe.spec.title = fmt::format("({}) No damping, dt = {:g} s: energy over {:g} s", letter, dt, U);
    fe.spec.x = time_axis(0, U);
    fe.spec.y.label = "E / E0";
    fe.spec.series = {line("semi-implicit Euler", s.t, ratio(s.energy, ue0), semi_color, 1.5f),
                      line("RK4", r.t, ratio(r.energy, ue0), rk4_color, 2.5f)};
    fe.spec.references = {{.orientation = ReferenceLine::Orientation::horizontal,
                           .value = 1.0,
                           .label = "exact (E = E0)",
                           .color = exact_color}};
    fe.spec.legend = LegendPlacement::outside_right;
    fe.spec.caption = {
        setup + ".",
        fmt::format("Semi-implicit Euler: E/E0 oscillates in [{:.4f}, {:.4f}], mean {:.4f} "
                    "(theory 1/(1 - (omega*dt)^2/4) = {:.4f}); mean of the first half {:.4f}, of "
                    "the second {:.4f}: no drift.",
                    lo, hi, mean, 1 / (1 - th * th / 4), mean_first, mean_second),
        rk4_line};
    rep.figures.push_back(std::move(fe));
  }
  return rep;
}

// --- the constant-force tables -----------------------------------------------------------------

namespace {

struct ForceRow {
  double t;
  float ee_x, ee_v, sie_x, sie_v;
  double exact_x, exact_v;
};

std::vector<ForceRow> force_rows(double dt, std::uint64_t first, std::uint64_t last) {
  // The article's setup: 1 kg at rest at the origin, a constant 10 N, float arithmetic.
  BodyDef def;
  def.body = Body{.mass = 1.0};
  def.constant_force = ConstantForce{.force = {10.0, 0.0}};
  World ee(WorldDef::empty(Precision::f32,
                           WorldSettings{.dt = dt, .integrator = Integrator::explicit_euler}));
  World sie(WorldDef::empty(
      Precision::f32, WorldSettings{.dt = dt, .integrator = Integrator::semi_implicit_euler}));
  const Entity ee_body = ee.create_body(def), sie_body = sie.create_body(def);
  std::vector<ForceRow> rows;
  for (std::uint64_t tick = 0; tick <= last; ++tick) {
    if (tick >= first) {
      const double t = static_cast<double>(tick) * dt;
      const exact::AxisState e = exact::linear(0, 0, 0, 0, 0, 10.0, t);
      const Body a = ee.body(ee_body), b = sie.body(sie_body);  // float values, exact in double
      rows.push_back({t, static_cast<float>(a.position.x), static_cast<float>(a.velocity.x),
                      static_cast<float>(b.position.x), static_cast<float>(b.velocity.x), e.x,
                      e.v});
    }
    if (tick < last) {
      ee.step();
      sie.step();
    }
  }
  return rows;
}

std::string markdown(const std::vector<ForceRow>& rows, bool article_decimals) {
  std::string out =
      "| t (s) | explicit Euler x (m) | explicit Euler v (m/s) | semi-implicit x (m) | "
      "semi-implicit v (m/s) | exact x (m) | exact v (m/s) |\n"
      "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const ForceRow& r : rows) {
    if (article_decimals) {
      out += fmt::format("| {:.2f} | {:.6f} | {:.6f} | {:.6f} | {:.6f} | {:.6f} | {:.6f} |\n", r.t,
                         r.ee_x, r.ee_v, r.sie_x, r.sie_v, r.exact_x, r.exact_v);
    } else {
      out += fmt::format("| {:g} | {} | {} | {} | {} | {:g} | {:g} |\n", r.t, r.ee_x, r.ee_v,
                         r.sie_x, r.sie_v, r.exact_x, r.exact_v);
    }
  }
  return out;
}

std::string csv(const std::vector<ForceRow>& rows) {
  // Shortest text that reads back to the same float (f32 columns) or double (t, exact).
  std::string out =
      "t,explicit_euler_x,explicit_euler_v,semi_implicit_x,semi_implicit_v,exact_x,exact_v\n";
  for (const ForceRow& r : rows) {
    out += fmt::format("{},{},{},{},{},{},{}\n", r.t, r.ee_x, r.ee_v, r.sie_x, r.sie_v, r.exact_x,
                       r.exact_v);
  }
  return out;
}

}  // namespace

ConstantForceTables constant_force_tables() {
  const std::vector<ForceRow> t1 = force_rows(1.0, 0, 10);
  const std::vector<ForceRow> t2 = force_rows(0.01, 990, 1000);
  ConstantForceTables out;
  out.markdown =
      "### Constant force, dt = 1 s (Integration Basics, 'Numerical Integration')\n\n"
      "1 kg at rest at the origin, F = 10 N, f32. The article prints the explicit Euler "
      "columns; exact: x = a t^2 / 2, v = a t.\n\n" +
      markdown(t1, false) +
      "\n### Constant force, dt = 1/100 s (Integration Basics, 'Explicit Euler'): t = 9.90 .. "
      "10.00 s\n\n"
      "Same body; printed with 6 decimals as the article's \"%f\".\n\n" +
      markdown(t2, true);
  out.csv_dt1 = csv(t1);
  out.csv_dt001 = csv(t2);
  return out;
}

}  // namespace fixstep::demo
