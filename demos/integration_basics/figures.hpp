// The systems, runs, measurements and charts of Glenn Fiedler's "Integration Basics" (2004),
// reproduced through fixstep's engine: every numerical trace is a fixstep::World stepped
// with the chosen Integrator; the references are fixstep::exact::linear.
#pragma once

#include <cstdint>
#include <fixstep/core/integrators.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/plot.hpp>
#include <string>
#include <vector>

namespace fixstep::demo {

/// A 1 kg-class mass on a spring-damper to the origin, moving along x: x'' = -(k/m) x - (b/m) x'.
struct Oscillator {
  double mass = 1.0;                   ///< kg
  double x0 = 1000.0;                  ///< initial position, m
  double v0 = 0.0;                     ///< initial velocity, m/s
  double stiffness = 15.0;             ///< k, N/m
  double damping = 0.1;                ///< b, N·s/m
  [[nodiscard]] double omega() const;  ///< undamped angular frequency √(k/m), rad/s
  [[nodiscard]] double gamma() const { return damping / mass; }  ///< b/m, 1/s
  /// Mechanical energy ½ m v² + ½ k x², J.
  [[nodiscard]] double energy(double x, double v) const;
};

/// "Why explicit euler is not (always) so great": mass 1 kg, initial position 1000 m from the
/// origin, k = 15, b = 0.1 (the article's acceleration() uses these, for unit mass).
inline constexpr Oscillator article_damped{};
/// "Semi-implicit euler vs. RK4": "a simple harmonic oscillator which oscillates forever
/// without any damping". The article prints no parameters for it; fixstep keeps the spring
/// above (k = 15 N/m, 1 kg, 1000 m) and sets b = 0.
inline constexpr Oscillator article_undamped{.damping = 0.0};

/// Samples of one run: time (s), position (m), velocity (m/s), mechanical energy (J).
struct Trace {
  std::vector<double> t, x, v, energy;
  void add(double time, double position, double velocity, double e);
};

/// An oscillator stepped through a fixstep World (f32 or f64) with one integrator at a fixed dt
/// (s); trace() holds tick 0 (the initial state) and every tick.
class OscillatorRun {
 public:
  /// Throws std::invalid_argument for a dt that is not finite and > 0 (from World).
  OscillatorRun(const Oscillator& system, Integrator integrator, Precision precision, double dt);
  void step();
  [[nodiscard]] const Trace& trace() const { return trace_; }
  [[nodiscard]] std::uint64_t ticks() const { return sim_.tick(); }
  [[nodiscard]] double time() const { return sim_.time(); }
  [[nodiscard]] Integrator integrator() const { return integrator_; }

 private:
  Oscillator system_;
  Integrator integrator_;
  World sim_;
  Trace trace_;
};

/// fixstep::exact::linear for the oscillator, sampled at t = t_begin + i·step <= t_end (s).
[[nodiscard]] Trace exact_trace(const Oscillator& system, double t_begin, double t_end,
                                double step);

/// The unwrapped phase angle of each sample, atan2(-v/ω, x) continued without 2π jumps
/// (rad); for the exact undamped motion it is ω t. Needs less than π of turn between samples.
[[nodiscard]] std::vector<double> unwrapped_phase(const Trace& trace, double omega);

/// One measured number: a key (figure letter + name), its value and unit.
struct Measurement {
  std::string key;
  double value;
  std::string unit;
};

/// A chart and the file stem it is written to (FILE.png).
struct Figure {
  std::string file;
  PlotSpec spec;
};

struct Report {
  std::vector<Figure> figures;
  std::vector<Measurement> numbers;
};

/// Durations shown (s). The article does not state how long its damped graphs run; 20 s is
/// 2/γ, where the exact amplitude has fallen to e⁻¹. The undamped runs last the article's 90 s.
inline constexpr double damped_duration = 20.0;
inline constexpr double undamped_duration = 90.0;
/// The article's time steps, s.
inline constexpr double damped_dt = 0.01;
inline constexpr double undamped_dts[] = {0.1, 0.25};

/// Every figure (a)–(f) of the article and the numbers their captions state, computed with the
/// world in `precision` (the article's code is float; f64 shows the integrators' own error).
[[nodiscard]] Report article_figures(Precision precision);

/// The article's two constant-force tables ("Numerical Integration" and "Explicit Euler"):
/// 1 kg at rest at the origin pushed by 10 N, stepped in f32 (the article's float) with
/// explicit Euler (the article's printed columns), semi-implicit Euler and the exact
/// s = ½ a t², v = a t. Table 1: dt = 1 s, t = 0..10 s, every tick. Table 2: dt = 1/100 s,
/// ticks 990..1000 (t = 9.90..10.00 s), the rows the article prints. Explicit Euler's numbers
/// are formatted as the article prints them: shortest digits for table 1, "%f" (6 decimals)
/// for table 2.
struct ConstantForceTables {
  std::string markdown;            ///< both tables with headings
  std::string csv_dt1, csv_dt001;  ///< t,explicit_euler_x,explicit_euler_v,semi_implicit_x,...
};
[[nodiscard]] ConstantForceTables constant_force_tables();

}  // namespace fixstep::demo
