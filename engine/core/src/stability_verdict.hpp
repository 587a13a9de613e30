// The part of the stability guard (stability.hpp) that single bodies (stability.cpp) and
// networks (stability_network.cpp) share: the bound (the largest stable step of a test mode,
// the smallest stable substep count for dt) and the verdict with its message, worded in one
// place (stability_verdict.cpp). Internal to the engine: not installed.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

#include "fixstep/core/stability.hpp"

namespace fixstep::detail {

// ρ <= 1 + tolerance counts as bounded. The round-off in ρ is ~1e-16; the smallest growth the
// scan must see is explicit Euler's 1 + s²/2 at its first point s = 1e-4, i.e. 5e-9.
inline constexpr double stability_tolerance = 1e-14;
inline constexpr double scan_from = 1e-4, scan_to = 1e6;  // dimensionless steps s = ω h (or γ h)
inline constexpr double stability_margin = 0.9;  // warn above 90 % of the largest stable step

/// A power of two c (1 when none is needed) such that a unit-mass test body of rate ω and
/// damping rate γ, scaled to ω/c and γ/c with the step h·c, has a stiffness (ω/c)² and a
/// damping γ/c within max_coefficient (value_ranges.hpp), which a world takes. Every product
/// of the scaled step is the unscaled one times a power of two, exactly (state x the same, v
/// divided by c), so its amplification matrix is D M D⁻¹ with D = diag(1, c) and the same
/// spectral radius, bit for bit.
[[nodiscard]] inline double unit_scale(double omega, double gamma) {
  constexpr double most = 1e99;  // a factor of 10 below max_coefficient (1e100)
  double c = 1.0;
  while ((omega / c) * (omega / c) > most || gamma / c > most) c = std::ldexp(c, 32);
  return c;
}

/// Spectral radius of the 2×2 step matrix [[a, b], [c, d]]: its eigenvalues are tr/2 ±
/// sqrt(disc) with disc = tr²/4 - det, written as ((a - d)/2)² + bc, which does not cancel
/// when both eigenvalues are near 1 (drag: 1 and 1 - γh). A complex pair has |λ|² = det exactly.
[[nodiscard]] inline double spectral_radius(double a, double b, double c, double d) {
  const double half_trace = 0.5 * (a + d), det = a * d - b * c;
  const double disc = 0.25 * (a - d) * (a - d) + b * c;
  if (disc < 0.0) return std::sqrt(det);
  const double root = std::sqrt(disc);
  return std::max(std::abs(half_trace + root), std::abs(half_trace - root));
}

/// Largest stable step (s) of a test mode whose rate (ω, or γ without a spring; 1/s) scales
/// the step: `stable(s)` says whether the dimensionless step s = rate·h is bounded. Scans s
/// from scan_from by factors of 1.25, then bisects to a relative 1e-12. 0 when not even
/// scan_from is stable; +infinity when every step up to scan_to is.
template <class Stable>
[[nodiscard]] double largest_stable_step(double rate, Stable&& stable) {
  double lo = scan_from;
  if (!stable(lo)) return 0.0;
  double hi = lo;
  while (hi < scan_to && stable(hi)) lo = hi, hi *= 1.25;
  if (hi >= scan_to) return std::numeric_limits<double>::infinity();
  for (int i = 0; i < 80 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo / rate;
}

/// Smallest substep count n for a tick of dt (s) whose step dt / n is not `unstable`: from
/// ceil(dt / max_step) (at least 1; max_step > 0 the largest stable step, s) upwards, at most
/// 10⁹.
template <class Unstable>
[[nodiscard]] int smallest_stable_substeps(double dt, double max_step, Unstable&& unstable) {
  int n = static_cast<int>(std::clamp(std::ceil(dt / max_step), 1.0, 1e9));
  while (n < 1000000000 && unstable(dt / n)) ++n;
  return n;
}

/// A rate the unstable message lists when it is not zero: "ω = 3.162 rad/s, ".
struct NamedRate {
  const char* name = nullptr;  ///< "ω", "γ", "ω_max", "λ_max(M⁻¹C)"; null: none
  double value = 0.0;
  const char* unit = "";  ///< "rad/s", "1/s"
};

/// What a guard judged, as its message words it.
struct GuardFinding {
  std::string subject{};       ///< "body 'bob'", "network of 3 bodies and 2 springs"
  std::string_view method{};   ///< the integrator's name
  double dt = 0.0;             ///< s
  int substeps = 1;            ///< >= 1
  double h = 0.0;              ///< dt / substeps, s
  double max_step = 0.0;       ///< largest stable step, s (inf: none needed): the verdict's
  double radius = 0.0;         ///< largest spectral radius at h
  const char* step_name = "";  ///< the dimensionless step named: "ω·h", "γ·h", "ω_max·h", ...
  double rate = 0.0;           ///< 1/s: step_name is rate·h
  double named_max_step = 0.0;  ///< largest stable step of the mode named, s: its bound
  const char* bound_name = "stability bound";
  std::array<NamedRate, 3> rates{};  ///< listed in the unstable message where not zero
  std::string naming{};  ///< what a network's message names (its links and fastest body), or ""
  /// Word an infinite radius "it diverges beyond it" (growth the network guard does not
  /// measure) instead of "growth infx per step".
  bool infinite_diverges = false;
};

/// A finding of `subject` at step dt / substeps (s) of `integrator`, its step, bound and radius
/// taken from the guard's result `r` (BodyStability or NetworkStability: h, max_step, radius);
/// the caller names the mode and its rates.
template <class Result>
[[nodiscard]] GuardFinding finding_of(std::string subject, Integrator integrator, double dt,
                                      int substeps, const Result& r) {
  GuardFinding f;
  f.subject = std::move(subject);
  f.method = integrator_name(integrator);
  f.dt = dt, f.substeps = substeps;
  f.h = r.h, f.max_step = r.max_step, f.radius = r.radius;
  return f;
}

/// A guard's verdict, the smallest stable substep count for dt (0 = none: stable, or
/// unstable at every step) and the message (empty when stable).
struct Judgement {
  Stability verdict = Stability::stable;
  int min_substeps = 0;
  std::string message;
};

/// The message of `f` for `verdict`, one line, e.g.
///   "body 'bob' is unstable with rk4 at dt = 0.1 s: ω·h = 3.162 exceeds the stability bound
///    2.785 (ω = 31.62 rad/s, growth 1.4x per step)",
///   "... is unstable with explicit_euler at every dt: its energy grows each step (...)",
///   "... is within 10 % of rk4's stability bound: ω·h = 2.6, bound 2.785";
/// empty when stable.
[[nodiscard]] std::string guard_message(Stability verdict, const GuardFinding& f);

/// The verdict on `f`: unstable when its radius exceeds 1 (then, when some step is stable,
/// the smallest substep count whose step dt / n is not `unstable(h)`), near_limit when h is
/// above 90 % of the largest stable step, else stable; with its message.
template <class Unstable>
[[nodiscard]] Judgement judge(const GuardFinding& f, Unstable&& unstable) {
  Judgement j;
  if (f.radius > 1.0 + stability_tolerance) {
    j.verdict = Stability::unstable;
    if (f.max_step > 0.0) j.min_substeps = smallest_stable_substeps(f.dt, f.max_step, unstable);
  } else if (f.h > stability_margin * f.max_step) {
    j.verdict = Stability::near_limit;
  }
  j.message = guard_message(j.verdict, f);
  return j;
}

/// "; stable from substeps = N (dt <= H s)" when a substep count N makes the step stable
/// (min_substeps > 0; H = max_step · substeps, the largest stable dt at the current substeps),
/// else "".
[[nodiscard]] std::string stable_from(int min_substeps, double max_step, int substeps);

}  // namespace fixstep::detail
