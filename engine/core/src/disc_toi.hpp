// The time of impact of two discs whose centres move on parabolas (constant accelerations):
// the first root, while approaching, of the quartic |d(τ)|² - R² in a time window. Internal
// to the engine (world_discs.cpp): not installed.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>

namespace fixstep::detail {

/// The relative motion of two discs over a window [0, horizon] s: centre offset
/// d(τ) = p + w τ + ½ c τ² (m; p = x_a - x_b, w = v_a - v_b, c = a_a - a_b at the window's
/// start) and the sum of the radii R (m).
struct RelativeMotion {
  double px = 0, py = 0, wx = 0, wy = 0, cx = 0, cy = 0, radius = 0;
};

/// f(τ) = |d(τ)|² - R² = k0 + k1 τ + k2 τ² + k3 τ³ + k4 τ⁴, m².
struct Quartic {
  std::array<double, 5> k{};
  [[nodiscard]] double operator()(double t) const {
    return k[0] + t * (k[1] + t * (k[2] + t * (k[3] + t * k[4])));
  }
  [[nodiscard]] double slope(double t) const {
    return k[1] + t * (2.0 * k[2] + t * (3.0 * k[3] + t * 4.0 * k[4]));
  }
};

/// f(τ) = k0 + k1 τ + k2 τ², m²: the gap quartic of a motion without relative acceleration
/// (k3 = k4 = 0). For τ >= 0 both evaluations round to the same bits as Quartic's on
/// {k0, k1, k2, ±0, +0}: there τ k4 = +0, k3 + 0 = +0, τ · 0 = +0 and k2 + 0 = k2 (k2 is never
/// -0: its first term |w|² is >= +0, and +0 + -0 is +0), so the roots bisected are the same to
/// the last bit.
struct Quadratic {
  double k0 = 0, k1 = 0, k2 = 0;
  [[nodiscard]] double operator()(double t) const { return k0 + t * (k1 + t * k2); }
  [[nodiscard]] double slope(double t) const { return k1 + t * (2.0 * k2); }
};

[[nodiscard]] inline Quartic gap_quartic(const RelativeMotion& m) {
  const double qx = 0.5 * m.cx, qy = 0.5 * m.cy;
  Quartic f;
  f.k[0] = m.px * m.px + m.py * m.py - m.radius * m.radius;
  f.k[1] = 2.0 * (m.px * m.wx + m.py * m.wy);
  f.k[2] = m.wx * m.wx + m.wy * m.wy + 2.0 * (m.px * qx + m.py * qy);
  f.k[3] = 2.0 * (m.wx * qx + m.wy * qy);
  f.k[4] = qx * qx + qy * qy;
  return f;
}

/// The real roots of a + b t + c t² in (lo, hi), ascending, into out; returns their count.
/// Cancellation-free form (Numerical Recipes §5.6).
inline int quadratic_roots(double a, double b, double c, double lo, double hi, double* out) {
  int n = 0;
  auto keep = [&](double t) {
    if (t > lo && t < hi) out[n++] = t;
  };
  if (c == 0.0) {
    if (b != 0.0) keep(-a / b);
    return n;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return 0;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  const double r1 = q != 0.0 ? a / q : 0.0, r2 = q / c;
  keep(std::min(r1, r2));
  if (r1 != r2) keep(std::max(r1, r2));
  return n;
}

/// The root of f in [lo, hi] where f(lo) > 0 >= f(hi) (f continuous), by bisection to the
/// last bit: deterministic, and exact to a double's resolution of the window.
template <class F>
double bisect_down(const F& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  return hi;
}

/// The least double t in (lo, hi] at which far(t) holds and does not at the double below it
/// (or that double is lo), stepped a double at a time from t; NaN after 64 steps. Where `far`
/// changes once across [lo, hi] (false at lo, true at hi) this is where it changes.
template <class Far>
double step_to_boundary(const Far& far, double t, double lo, double hi) {
  for (int i = 0; i < 64; ++i) {
    if (!far(t)) {
      t = std::nextafter(t, hi);
      continue;
    }
    const double below = std::nextafter(t, lo);
    if (!(below > lo && far(below))) return t;
    t = below;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// bisect_down(-f', 0, horizon)'s result for a Quadratic f with f'(0) < 0 < f'(horizon), or
/// NaN where it is not found this way. f'(t) = k1 + t (2 k2) with k2 > 0 rounds to a value
/// that never falls as t grows (each rounding is monotone), so the bisection, once its ends are
/// adjacent doubles, stops at the one boundary: the least double t with f'(t) >= 0. That is
/// found from the closed form -k1 / (2 k2) by stepping a few doubles, with the same bits. NaN
/// (bisect instead) when the closed form is below horizon 2^-100, where 200 halvings may stop
/// before the ends are adjacent, or when 64 steps do not reach the boundary.
inline double slope_root(const Quadratic& f, double horizon) {
  const double t = -f.k1 / (2.0 * f.k2);
  if (!(t >= std::ldexp(horizon, -100) && t <= horizon)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return step_to_boundary([&f](double s) { return f.slope(s) >= 0.0; }, t, 0.0, horizon);
}

/// The stationary points of f (roots of f', a cubic) in (0, horizon), ascending; returns
/// their count. The cubic's own stationary points (roots of f'', a quadratic) split the window
/// into intervals where f' is monotone, and each sign change is bisected. For a Quadratic f'
/// is monotone on the whole window (f'' = 2 k2, constant: what the quartic's f'' gives when
/// k3 = k4 = 0), and its root is found from the closed form (slope_root).
template <class Poly>
int stationary_points(const Poly& f, double horizon, double* out) {
  const auto d1 = [&f](double t) { return f.slope(t); };
  double cuts[4] = {0.0};
  int nc = 0;
  if constexpr (std::is_same_v<Poly, Quartic>) {
    nc = quadratic_roots(2.0 * f.k[2], 6.0 * f.k[3], 12.0 * f.k[4], 0.0, horizon, cuts + 1);
  }
  cuts[nc + 1] = horizon;
  int n = 0;
  for (int i = 0; i <= nc; ++i) {
    const double lo = cuts[i], hi = cuts[i + 1];
    const double flo = d1(lo), fhi = d1(hi);
    if ((flo > 0.0) == (fhi > 0.0) || flo == 0.0) continue;
    double root = std::numeric_limits<double>::quiet_NaN();
    if constexpr (std::is_same_v<Poly, Quadratic>) {
      if (flo < 0.0) root = slope_root(f, horizon);  // lo = 0, hi = horizon: no cuts
    }
    if (std::isnan(root)) {
      root = flo > 0.0 ? bisect_down(d1, lo, hi)
                       : bisect_down([&](double t) { return -d1(t); }, lo, hi);
    }
    if (root > 0.0 && root < horizon) out[n++] = root;
  }
  return n;
}

/// For a Quadratic f with f(lo) > 0 >= f(hi), f falling on [lo, hi]: a τ in (lo, hi] with
/// f(τ) <= 0 < f at the double below τ (or that double is lo), found from the smaller root
/// k0 / q, q = -(k1 - sqrt(k1² - 4 k0 k2)) / 2 (the cancellation-free form, Numerical Recipes
/// §5.6), by stepping a few doubles. NaN (bisect instead) when the closed form has no real
/// root or 64 steps do not reach a sign change.
inline double falling_root(const Quadratic& f, double lo, double hi) {
  constexpr double none = std::numeric_limits<double>::quiet_NaN();
  const double disc = f.k1 * f.k1 - 4.0 * f.k0 * f.k2;
  if (!(disc >= 0.0)) return none;  // (before the sqrt: Debug tests trap an invalid operation)
  const double q = -0.5 * (f.k1 - std::sqrt(disc));
  if (!(q > 0.0)) return none;
  const double t = std::clamp(f.k0 / q, std::nextafter(lo, hi), hi);
  if (!(t > lo)) return none;
  return step_to_boundary([&f](double s) { return f(s) <= 0.0; }, t, lo, hi);
}

/// The first τ in [0, horizon] at which f, positive at 0, falls through 0, or infinity: the
/// window split at f's stationary points, and the first interval where f changes sign bisected
/// (a Quadratic's from its closed form, falling_root).
template <class Poly>
double first_root(const Poly& f, double horizon) {
  double cuts[5] = {0.0};
  const int nc = stationary_points(f, horizon, cuts + 1);
  cuts[nc + 1] = horizon;
  for (int i = 0; i <= nc; ++i) {
    if (!(f(cuts[i + 1]) <= 0.0)) continue;
    if constexpr (std::is_same_v<Poly, Quadratic>) {
      const double t = falling_root(f, cuts[i], cuts[i + 1]);
      if (!std::isnan(t)) return t;
    }
    return bisect_down(f, cuts[i], cuts[i + 1]);
  }
  return std::numeric_limits<double>::infinity();
}

/// The first τ in [0, horizon] at which two separated discs (f(0) > 0) come into contact
/// (f falls through 0), or infinity. Exact to the last bit of τ: the window is split at the
/// stationary points of f, and the first interval where f changes sign is bisected. Without
/// relative acceleration (discs in a gas, or under one uniform field with equal velocity
/// changes) f is a quadratic, bisected with fewer operations a step and the same bits.
inline double first_contact(const RelativeMotion& m, double horizon) {
  constexpr double none = std::numeric_limits<double>::infinity();
  const Quartic f = gap_quartic(m);
  if (!(f.k[0] > 0.0)) return none;
  // Cheap rejection: the centres cannot close the gap within the window.
  const double gap = std::sqrt(m.px * m.px + m.py * m.py) - m.radius;
  const double reach = horizon * (std::sqrt(m.wx * m.wx + m.wy * m.wy) +
                                  0.5 * horizon * std::sqrt(m.cx * m.cx + m.cy * m.cy));
  if (gap > reach * (1.0 + 1e-12) + 1e-300) return none;
  if (f.k[3] == 0.0 && f.k[4] == 0.0) return first_root(Quadratic{f.k[0], f.k[1], f.k[2]}, horizon);
  return first_root(f, horizon);
}

}  // namespace fixstep::detail
