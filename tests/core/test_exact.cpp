// The exact reference solutions: initial conditions, the ODE itself (finite differences),
// continuity across critical damping, closed forms, an independent numerical reference
// (Boost.Odeint's Dormand–Prince 5(4)), the BodyDef front end and argument checking.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/exact.hpp"

namespace fixstep {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// One scalar problem x'' = -ω² (x - anchor) - γ x' + accel, x(0) = x0, x'(0) = v0.
struct Problem {
  const char* name;
  double x0, v0, omega2, gamma, anchor, accel;
  exact::Regime regime;
};

exact::AxisState at(const Problem& p, double t) {
  return exact::linear(p.x0, p.v0, p.omega2, p.gamma, p.anchor, p.accel, t);
}

/// The equilibrium the spring pulls towards (the anchor when there is no spring).
double equilibrium(const Problem& p) {
  return p.omega2 > 0.0 ? p.anchor + p.accel / p.omega2 : p.anchor;
}

/// An upper bound on the magnitude of every characteristic root, |r| <= γ/2 + |Δ| <= γ + ω,
/// floored at 1/s so that step sizes built from it stay finite without a spring or damping.
double rate(const Problem& p) {
  return std::max(p.gamma + std::sqrt(p.omega2), 1.0);
}

/// Magnitude of the terms x is built from up to time t (m): what rounding is relative to.
double x_scale(const Problem& p, double t) {
  const double tau =
      p.omega2 > 0.0 ? std::min(std::abs(t), 1.0 / std::sqrt(p.omega2)) : std::abs(t);
  return std::abs(p.x0) + std::abs(p.anchor) + std::abs(equilibrium(p) - p.anchor) +
         std::abs(p.x0 - equilibrium(p)) + std::abs(p.v0) * tau +
         (p.omega2 > 0.0 ? 0.0 : std::abs(p.accel) * t * t / 2.0);
}

/// Magnitude of the velocity terms up to time t (m/s).
double v_scale(const Problem& p, double t) {
  return std::abs(p.v0) + std::sqrt(p.omega2) * std::abs(p.x0 - equilibrium(p)) +
         (p.omega2 > 0.0 ? 0.0 : std::abs(p.accel * t));
}

/// One case per regime, with an anchor and a constant acceleration wherever a spring allows
/// them, so that every term of the equation takes part.
const std::vector<Problem>& problems() {
  using R = exact::Regime;
  static const std::vector<Problem> cases{
      {"undamped", 1.5, -0.7, 4.0, 0.0, 0.25, -2.0, R::undamped},
      {"under", 1.5, -0.7, 9.0, 0.6, 0.25, -2.0, R::under},           // ζ = 0.1
      {"critical", 1.5, -0.7, 4.0, 4.0, 0.25, -2.0, R::critical},     // ζ = 1 exactly
      {"over", 1.5, -0.7, 4.0, 10.0, 0.25, -2.0, R::over},            // ζ = 2.5
      {"strongly_over", 1.5, -0.7, 1.0, 200.0, 0.25, -2.0, R::over},  // ζ = 100
      {"drag_projectile", 0.0, 12.0, 0.0, 0.5, 0.0, -9.81, R::none},  // Stokes drag
      {"projectile", 2.0, 12.0, 0.0, 0.0, 0.0, -9.81, R::none},
      {"article_spring", 1000.0, 0.0, 15.0, 0.1, 0.0, 0.0, R::under},  // Fiedler's example
  };
  return cases;
}

TEST(ExactLinear, RegimesOfTheCases) {
  for (const Problem& p : problems()) {
    EXPECT_EQ(exact::regime(p.omega2, p.gamma), p.regime) << p.name;
  }
}

TEST(ExactLinear, ReproducesInitialConditions) {
  for (const Problem& p : problems()) {
    const exact::AxisState s = at(p, 0.0);
    // At t = 0 every basis function is exactly 0 or 1 (exp(0) = cos(0) = 1,
    // sin(0) = expm1(0) = 0), so v0 comes back bit for bit; x0 goes through
    // x_eq + (x0 - x_eq), two roundings of at most half an ulp of |x0| + |x_eq| each.
    EXPECT_EQ(s.v, p.v0) << p.name;
    EXPECT_NEAR(s.x, p.x0, kEps * (std::abs(p.x0) + std::abs(equilibrium(p)))) << p.name;
  }
}

// Central differences with step h against the equation. Derivation of the tolerance:
//  * truncation: (x(t+h) - 2x(t) + x(t-h))/h² = x'' + h² x''''(ξ)/12 and
//    (x(t+h) - x(t-h))/(2h) = x' + h² x'''(ξ)/6;
//  * derivative bound: along a solution x'' = a := accel - γv - ω²(x - anchor) and each higher
//    derivative follows D(n+2) = -γ D(n+1) - ω² D(n). With Λ >= γ + ω we have γΛ + ω² <= Λ²,
//    so by induction |x^(n)| <= K Λ^(n-1) for n >= 1 with K = max(|v|, |a|/Λ). Over the
//    stencil K changes by at most a factor 1 + 2Λh <= 1.02 (its rate of change is at most ΛK),
//    so 1.02 × its largest value at the stencil points bounds it in between;
//  * rounding: each x evaluation is good to 16 ulps of the terms it is built from (a dozen
//    operations and libm calls of <= 1 ulp each), ε_x = 16 eps x_scale, which enters the
//    second difference as 4ε_x/h² and the first as ε_x/h; v likewise with ε_v = 16 eps v_scale.
// Steps minimising each bound: h = (48 ε_x / (K Λ³))^(1/4) for the second difference and
// h1 = (3 ε_x / (K Λ²))^(1/3) for the first, both at most 0.01/Λ. (Undamped, the truncation
// bound is attained, |x'''| = ω²|v|: these bounds are sharp, not generous.)
struct FdCheck {
  double residual, residual_tol;  // x'' + γx' + ω²(x - anchor) - accel, and its bound
  double v_error, v_tol;          // v(t) - (x(t+h1) - x(t-h1))/(2h1), and its bound
  double term_size;               // |x''| + γ|x'| + ω²|x - anchor| + |accel|
};

/// K = max(|v|, |a|/Λ) of the derivative bound, at one state.
double derivative_scale(const Problem& p, const exact::AxisState& s, double lambda) {
  const double a = p.accel - p.gamma * s.v - p.omega2 * (s.x - p.anchor);
  return std::max(std::abs(s.v), std::abs(a) / lambda);
}

FdCheck fd_check(const Problem& p, double t) {
  const double lambda = rate(p);
  const double eps_x = 16.0 * kEps * x_scale(p, t + 0.01 / lambda);
  const double eps_v = 16.0 * kEps * v_scale(p, t + 0.01 / lambda);
  const exact::AxisState mid = at(p, t);
  const double k_mid = derivative_scale(p, mid, lambda);
  const double h = std::min(0.01, std::pow(48.0 * eps_x * lambda / k_mid, 0.25)) / lambda;
  const double h1 = std::min(0.01, std::cbrt(3.0 * eps_x * lambda / k_mid)) / lambda;
  const exact::AxisState lo = at(p, t - h), hi = at(p, t + h);
  const exact::AxisState lo1 = at(p, t - h1), hi1 = at(p, t + h1);
  double k = k_mid;
  for (const exact::AxisState& s : {lo, hi, lo1, hi1}) {
    k = std::max(k, derivative_scale(p, s, lambda));
  }
  k *= 1.02;
  const double d2 = (hi.x - 2.0 * mid.x + lo.x) / (h * h);
  const double d1 = (hi.x - lo.x) / (2.0 * h);
  const double d1_fine = (hi1.x - lo1.x) / (2.0 * h1);
  const double d2_err = h * h / 12.0 * k * std::pow(lambda, 3) + 4.0 * eps_x / (h * h);
  const double d1_err = h * h / 6.0 * k * lambda * lambda + eps_x / h;
  const double d1_fine_err = h1 * h1 / 6.0 * k * lambda * lambda + eps_x / h1;
  const double spring = p.omega2 * (mid.x - p.anchor);
  FdCheck c{};
  c.term_size = std::abs(d2) + p.gamma * std::abs(d1) + std::abs(spring) + std::abs(p.accel);
  c.residual = d2 + p.gamma * d1 + spring - p.accel;
  // The residual's own rounding: 4 ulps of the largest term.
  c.residual_tol = d2_err + p.gamma * d1_err + p.omega2 * eps_x + 4.0 * kEps * c.term_size;
  c.v_error = mid.v - d1_fine;
  c.v_tol = d1_fine_err + eps_v;
  return c;
}

TEST(ExactLinear, SatisfiesTheOdeByFiniteDifferences) {
  for (const Problem& p : problems()) {
    for (double t : {0.013, 0.3, 1.0, 2.7, 8.0}) {
      const FdCheck c = fd_check(p, t);
      SCOPED_TRACE(fmt::format("{} at t = {}: residual {:.2g}, tolerance {:.2g}, terms {:.2g}",
                               p.name, t, c.residual, c.residual_tol, c.term_size));
      EXPECT_LE(std::abs(c.residual), c.residual_tol);
      EXPECT_LE(std::abs(c.v_error), c.v_tol);
      // The check has teeth: the bound is a small fraction of the terms it balances, so any
      // wrong term (sign, factor 2, missing forcing) would exceed it by orders of magnitude.
      EXPECT_LT(c.residual_tol, 1e-4 * c.term_size);
    }
  }
}

// Sensitivity to ζ at critical damping. With y = x - x_eq and γ = 2ζω, s = ∂y/∂γ solves
// s'' + γs' + ω²s = -y', s(0) = s'(0) = 0, so s = -∫ G(t-τ) y'(τ) dτ with the critical
// impulse response G(t) = t e^{-ωt} >= 0, ∫G = 1/ω², ∫|G'| = 2/(eω). The critical solution
// y = e^{-ωt}(y0 + (v0 + ωy0)t) has |y'| <= |v0| + (|v0| + ω|y0|)/e <= (1 + 1/e) ω A with
// A = |y0| + |v0|/ω. Hence, for all t,
//   |∂x/∂ζ| = 2ω|s|  <= 2(1 + 1/e) A     ≈ 2.74 A,
//   |∂v/∂ζ| = 2ω|s'| <= (4/e)(1 + 1/e) ωA ≈ 2.01 ωA,
// and a step Δζ moves the state by at most Δζ times these (1 % added for the O(Δζ²) term),
// plus 16 ulps of rounding in each of the two evaluations compared.
void expect_continuous_at_critical(double dzeta) {
  const double omega = 2.0, y0 = 1.0, v0 = 0.5, anchor = 0.3, accel = 0.7;
  const double x_eq = anchor + accel / (omega * omega);
  const double amp = std::abs(y0) + std::abs(v0) / omega;
  const double dx_bound = 1.01 * dzeta * 2.0 * (1.0 + 1.0 / std::numbers::e) * amp +
                          32.0 * kEps * (std::abs(x_eq) + amp);
  const double dv_bound =
      1.01 * dzeta * 4.0 / std::numbers::e * (1.0 + 1.0 / std::numbers::e) * omega * amp +
      32.0 * kEps * omega * amp;
  for (double t : {0.05, 0.25, 0.5, 1.0, 2.5, 10.0}) {
    const auto state = [&](double zeta) {
      return exact::linear(x_eq + y0, v0, omega * omega, 2.0 * zeta * omega, anchor, accel, t);
    };
    const exact::AxisState crit = state(1.0);
    for (double zeta : {1.0 - dzeta, 1.0 + dzeta}) {
      const exact::AxisState s = state(zeta);
      SCOPED_TRACE(fmt::format("ζ = 1 {:+g}, t = {}", zeta - 1.0, t));
      EXPECT_NEAR(s.x, crit.x, dx_bound);
      EXPECT_NEAR(s.v, crit.v, dv_bound);
    }
  }
}

TEST(ExactLinear, ContinuousAcrossCriticalDamping) {
  expect_continuous_at_critical(1e-7);   // the sides use cos/sin and expm1; ~3e-7 A apart
  expect_continuous_at_critical(1e-12);  // no cancellation: ~3e-12 A, not eps/δ ~ 1e-10
  expect_continuous_at_critical(1e-15);  // δ ~ 1e-7.5 ω: still only rounding apart
}

TEST(ExactLinear, CriticalDampingClosedForm) {
  // x = x_eq + e^{-ωt}(y0 + (v0 + ωy0)t), v = e^{-ωt}(v0 - ω(v0 + ωy0)t) (T&M §3.5), with ω = 2,
  // γ = 4 exactly. Both sides are a handful of operations on O(1) numbers: 16 ulps of the scale.
  const Problem& p = problems()[2];
  ASSERT_EQ(p.regime, exact::Regime::critical);
  const double omega = 2.0, x_eq = equilibrium(p), y0 = p.x0 - x_eq;
  for (double t : {0.1, 0.5, 1.0, 3.0, 12.0}) {
    const exact::AxisState s = at(p, t);
    const double e = std::exp(-omega * t), c = p.v0 + omega * y0;
    EXPECT_NEAR(s.x, x_eq + e * (y0 + c * t), 16 * kEps * x_scale(p, t)) << t;
    EXPECT_NEAR(s.v, e * (p.v0 - omega * c * t), 16 * kEps * v_scale(p, t)) << t;
  }
}

TEST(ExactLinear, UndampedQuarterPeriods) {
  // x = x0 cos ωt for v0 = 0: zero at T/4, -x0 at T/2, x0 at T (T = 2π/ω). The times carry a
  // rounding of 1 ulp, i.e. a phase error of ~ eps·ωt <= 2π eps, so x is good to
  // |x0|·(2π + 16) eps; v = -x0 ω sin ωt likewise to ω|x0|·(2π + 16) eps.
  const double omega = 3.0, x0 = 0.8;
  const double tol = (2.0 * std::numbers::pi + 16.0) * kEps * std::abs(x0);
  const double period = 2.0 * std::numbers::pi / omega;
  const auto state = [&](double t) { return exact::linear(x0, 0.0, omega * omega, 0.0, 0, 0, t); };
  EXPECT_NEAR(state(period / 4).x, 0.0, tol);
  EXPECT_NEAR(state(period / 4).v, -omega * x0, omega * tol);
  EXPECT_NEAR(state(period / 2).x, -x0, tol);
  EXPECT_NEAR(state(period).x, x0, tol);
  EXPECT_NEAR(state(period).v, 0.0, omega * tol);
}

TEST(ExactLinear, UndampedHugePhaseStaysOnTheCircle) {
  // After ωt = 1e9 rad the energy v² + ω²x² must still be ω²x0²: the phase is uncertain by
  // eps·ωt ~ 2e-7 rad but cos² + sin² = 1 holds to a few ulps whatever the phase.
  const double omega = 1e3, x0 = 2.0;
  const exact::AxisState s = exact::linear(x0, 0.0, omega * omega, 0.0, 0.0, 0.0, 1e6);
  const double energy = s.v * s.v + omega * omega * s.x * s.x;
  EXPECT_NEAR(energy, omega * omega * x0 * x0, 8 * kEps * omega * omega * x0 * x0);
}

TEST(ExactLinear, ProjectileWithoutDragIsTheParabola) {
  // x0 + v0 t + g t²/2 is what the code evaluates too (q = t, φ = 1/2), up to the order of
  // the roundings: 1e-12 m is ~20 ulps of the largest term (g t²/2 ≈ 490 m) involved.
  const double x0 = 2.0, v0 = 12.0, g = -9.81;
  for (double t : {0.0, 0.5, 1.0, 2.446, 10.0}) {
    const exact::AxisState s = exact::linear(x0, v0, 0.0, 0.0, 0.0, g, t);
    EXPECT_NEAR(s.x, x0 + v0 * t + g * t * t / 2.0, 1e-12) << t;
    EXPECT_NEAR(s.v, v0 + g * t, 1e-12) << t;
  }
}

TEST(ExactLinear, DragProjectileReachesTerminalVelocity) {
  // v = v_ter + (v0 - v_ter) e^{-γt}, v_ter = g/γ (Taylor §2.2). At t = 50/γ the transient is
  // e^{-50} ≈ 2e-22 of |v0 - v_ter|, far below rounding (8 ulps of |v_ter|); the position is
  // then x0 + v_ter t + (v0 - v_ter)/γ to 16 ulps of its terms.
  const double gamma = 0.5, g = -9.81, x0 = 1.0, v0 = 12.0, v_ter = g / gamma;
  const double t = 50.0 / gamma;
  const exact::AxisState s = exact::linear(x0, v0, 0.0, gamma, 0.0, g, t);
  EXPECT_NEAR(s.v, v_ter, 8 * kEps * std::abs(v_ter));
  const double x = x0 + v_ter * t + (v0 - v_ter) / gamma;
  const double terms = std::abs(x0) + std::abs(v_ter * t) + std::abs((v0 - v_ter) / gamma);
  EXPECT_NEAR(s.x, x, 16 * kEps * terms);
}

TEST(ExactLinear, VanishingDragTendsToTheParabola) {
  // x_drag - x_parabola = -γ(v0 t²/2 + g t³/6) + O(γ²) (expand e^{-γt}), and v likewise
  // -γ(v0 t + g t²/2). With γ = 1e-12 that is ~1e-10 m; evaluating the textbook form
  // x0 + v_ter t + (v0 - v_ter)(1 - e^{-γt})/γ with v_ter = 1e13 m/s instead would be wrong by
  // ~eps·1e13 ≈ 2e-3 m. Tolerance: the first-order term (+1 %) plus 16 ulps of ~100 m.
  const double gamma = 1e-12, g = -9.81, x0 = 2.0, v0 = 12.0, t = 3.0;
  const exact::AxisState s = exact::linear(x0, v0, 0.0, gamma, 0.0, g, t);
  const double dx = gamma * (v0 * t * t / 2 + std::abs(g) * t * t * t / 6);
  const double dv = gamma * (v0 * t + std::abs(g) * t * t / 2);
  EXPECT_NEAR(s.x, x0 + v0 * t + g * t * t / 2, 1.01 * dx + 16 * kEps * 100.0);
  EXPECT_NEAR(s.v, v0 + g * t, 1.01 * dv + 16 * kEps * 100.0);
}

TEST(ExactLinear, WeakSpringTendsToTheParabolaWithinTheDocumentedRounding) {
  // x_spring - x_parabola = -ω²(v0 t³/6 + g t⁴/24) + O(ω⁴) for x0 = anchor = 0. The header
  // documents that the error is a few ulps of the equilibrium g/ω² (~1e9 m here): the bound is
  // the first-order term (+1 %) plus 16 ulps of |g|/ω².
  const double omega2 = 1e-8, g = -9.81, v0 = 10.0, t = 1.0;
  const exact::AxisState s = exact::linear(0.0, v0, omega2, 0.0, 0.0, g, t);
  const double dx = omega2 * (v0 * t * t * t / 6 + std::abs(g) * std::pow(t, 4) / 24);
  EXPECT_NEAR(s.x, v0 * t + g * t * t / 2, 1.01 * dx + 16 * kEps * std::abs(g) / omega2);
}

TEST(ExactLinear, HeavyDampingCreepsAtTheStokesRate) {
  // ζ = 5e7: inertia is negligible and γ x' = -ω² x gives x = x0 e^{-ω²t/γ}. Exactly, the slow
  // root is r2 = -ω²/(γ/2 + δ) = -(ω²/γ)(1 + ω²/γ² + ...), and with v0 = 0, x = e^{r2 t}
  // (1 - r2 q), |r2 q| <= ω²/γ², so at t = γ/ω² both corrections are ~1e-16 of x: 8 ulps. The
  // velocity -ω² x0 e^{r2 t} q, q = 1/(2δ) ≈ 1/γ, likewise. (Computing r2 = -γ/2 + δ directly
  // would lose all its digits to cancellation here: 5e7 - sqrt(2.5e15 - 1).)
  const double omega2 = 1.0, gamma = 1e8, x0 = 1.0, t = gamma / omega2;
  const exact::AxisState s = exact::linear(x0, 0.0, omega2, gamma, 0.0, 0.0, t);
  const double creep = x0 * std::exp(-omega2 * t / gamma);
  EXPECT_NEAR(s.x, creep, 8 * kEps * creep);
  EXPECT_NEAR(s.v, -omega2 / gamma * creep, 8 * kEps * omega2 / gamma * creep);
}

/// Flow property: the state after t1 + t2 is the state after t2 started from the state after
/// t1; with t2 = -t1, the state after going forward and back again is the initial one.
TEST(ExactLinear, FlowComposesForwardAndBackward) {
  for (const Problem& p : problems()) {
    for (const auto& [t1, t2] : {std::array{0.7, 1.9}, std::array{1.3, -1.3}}) {
      const exact::AxisState mid = at(p, t1);
      const exact::AxisState two =
          exact::linear(mid.x, mid.v, p.omega2, p.gamma, p.anchor, p.accel, t2);
      const exact::AxisState one = at(p, t1 + t2);
      // Rounding of the intermediate state (16 ulps) is carried through the second flow,
      // which magnifies a state error by at most e^{γ|t2|}(1 + Λ|t2|) (its exponential rate
      // is bounded by γ backwards, growth of s and p by Λ|t2|); 16 ulps for the final
      // evaluation.
      const double gain = std::exp(p.gamma * std::abs(t2)) * (1.0 + rate(p) * std::abs(t2));
      const double tmax = std::max(std::abs(t1), std::abs(t1 + t2));
      const double tol_x =
          16 * kEps * (gain + 1) * (x_scale(p, tmax) + v_scale(p, tmax) * std::abs(t2));
      const double tol_v = 16 * kEps * (gain + 1) * (v_scale(p, tmax) + rate(p) * x_scale(p, tmax));
      SCOPED_TRACE(fmt::format("{}: t1 = {}, t2 = {}", p.name, t1, t2));
      EXPECT_NEAR(two.x, one.x, tol_x);
      EXPECT_NEAR(two.v, one.v, tol_v);
    }
  }
}

// An independent reference: Boost.Odeint's adaptive Dormand–Prince 5(4) on the same equation,
// with absolute and relative error tolerances of 1e-12 per step.
struct Reference {
  exact::AxisState state;
  double steps;     // accepted steps
  double max_step;  // s
};

Reference integrate(const Problem& p, double t) {
  namespace odeint = boost::numeric::odeint;
  using State = std::array<double, 2>;
  State y{p.x0, p.v0};
  const auto rhs = [&p](const State& s, State& dsdt, double /*t*/) {
    dsdt[0] = s[1];
    dsdt[1] = p.accel - p.gamma * s[1] - p.omega2 * (s[0] - p.anchor);
  };
  double previous = 0.0, max_step = 0.0;
  const auto observe = [&](const State& /*s*/, double time) {
    max_step = std::max(max_step, time - previous);
    previous = time;
  };
  auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<State>());
  const std::size_t steps = odeint::integrate_adaptive(stepper, rhs, y, 0.0, t, 1e-4, observe);
  return {{y[0], y[1]}, static_cast<double>(steps), max_step};
}

/// Bound on |exact - odeint| for x and v at time t, and the amplitude it is relative to.
/// Odeint accepts a step when its error estimate for each component y_i is below
/// 1e-12 (1 + |y_i| + h |y_i'|) (its default error checker). The error committed in a step is
/// then carried by the exact flow of the homogeneous equation:
///  * with a spring, the norm sqrt(ω² x² + v²) of that flow never grows (its derivative is
///    -γ v² <= 0), and bounds the motion itself: |x - x_eq| <= E/ω, |v| <= E and
///    |x''| <= (γ + ω) E with E = sqrt(ω² (x0 - x_eq)² + v0²). N steps add at most N times a
///    step's error in that norm, and |δx| <= norm/ω, |δv| <= norm;
///  * without one, v' = accel - γ v never magnifies a velocity error, which moves x by at most
///    t times itself; |v| <= |v0| + (|accel| + γ|v0|) t along the way.
struct OdeintBound {
  double x, v;          // bounds on the differences
  double x_amp, v_amp;  // the amplitudes
};

OdeintBound odeint_bound(const Problem& p, double t, const Reference& ref) {
  const double n = ref.steps, h = ref.max_step, tol = 1e-12;
  if (p.omega2 > 0.0) {
    const double omega = std::sqrt(p.omega2), x_eq = equilibrium(p);
    const double e = std::hypot(omega * (p.x0 - x_eq), p.v0);
    const double x_amp = std::abs(x_eq) + e / omega;
    const double step_x = tol * (1.0 + x_amp + h * e);
    const double step_v = tol * (1.0 + e + h * (p.gamma + omega) * e);
    const double norm = n * (omega * step_x + step_v);
    return {norm / omega, norm, x_amp, e};
  }
  const double v_amp = std::abs(p.v0) + (std::abs(p.accel) + p.gamma * std::abs(p.v0)) * t;
  const double x_amp = std::abs(p.x0) + v_amp * t;
  const double step_v = tol * (1.0 + v_amp + h * (std::abs(p.accel) + p.gamma * v_amp));
  const double step_x = tol * (1.0 + x_amp + h * v_amp);
  return {n * (step_x + t * step_v), n * step_v, x_amp, v_amp};
}

TEST(ExactLinear, AgreesWithOdeintDopri5) {
  for (const Problem& p : problems()) {
    for (double t : {0.5, 3.0, 10.0}) {
      const Reference ref = integrate(p, t);
      const OdeintBound bound = odeint_bound(p, t, ref);
      const exact::AxisState s = at(p, t);
      SCOPED_TRACE(fmt::format("{} at t = {}: {} steps, bounds {:.2g} {:.2g} of amplitude", p.name,
                               t, ref.steps, bound.x / bound.x_amp, bound.v / bound.v_amp));
      EXPECT_NEAR(s.x, ref.state.x, bound.x);
      EXPECT_NEAR(s.v, ref.state.v, bound.v);
      // ~N·1e-12 of the amplitude, N <= a few thousand: the comparison is at the 1e-9 level.
      EXPECT_LT(bound.x, 1e-8 * bound.x_amp);
      EXPECT_LT(bound.v, 1e-8 * bound.v_amp);
    }
  }
}

TEST(ExactLinear, ArticleDampedSpringAtTenSeconds) {
  // "Integration Basics": m = 1 kg, x0 = 1000 m, k = 15 N/m, b = 0.1 N*s/m, t = 10 s. Against
  // odeint with the bound above (a few 1e-9 of the 1000 m amplitude), and against the textbook
  // under-damped form x = A e^{-ζωt} cos(ω_d t - φ), tan φ = ζ/sqrt(1 - ζ²), A = x0/cos φ
  // (T&M §3.5): a dozen roundings of ~1000 m plus a phase rounding of eps·ω_d t ≈ 40 eps,
  // i.e. 64 ulps of 1000 m.
  const Problem& p = problems().back();
  const Reference ref = integrate(p, 10.0);
  const OdeintBound bound = odeint_bound(p, 10.0, ref);
  const exact::AxisState s = at(p, 10.0);
  EXPECT_NEAR(s.x, ref.state.x, bound.x);
  EXPECT_NEAR(s.v, ref.state.v, bound.v);
  const double omega = std::sqrt(15.0), zeta = 0.1 / (2.0 * omega);
  const double wd = omega * std::sqrt(1 - zeta * zeta);
  const double phi = std::atan(zeta / std::sqrt(1 - zeta * zeta));
  const double x =
      1000.0 / std::cos(phi) * std::exp(-zeta * omega * 10.0) * std::cos(wd * 10.0 - phi);
  EXPECT_NEAR(s.x, x, 64 * kEps * 1000.0);
}

TEST(ExactLinear, ExtremeButValidInputsGiveFiniteStates) {
  // Rates and times over the whole double range: no overflow, 0·inf or 0/0 anywhere
  // (e.g. γ²/4 overflows for γ = 1e300; that case must freeze the body, x = x0, v -> 0).
  for (double omega2 : {0.0, 1e-300, 1e-8, 1.0, 1e8, 1e300}) {
    for (double gamma : {0.0, 1e-300, 1.0, 1e8, 1e300}) {
      for (double t : {0.0, 1e-300, 1e-3, 1.0, 1e6}) {
        const exact::AxisState s = exact::linear(1.0, 1.0, omega2, gamma, 0.0, 0.0, t);
        SCOPED_TRACE(fmt::format("ω² = {}, γ = {}, t = {}", omega2, gamma, t));
        EXPECT_TRUE(std::isfinite(s.x) && std::isfinite(s.v)) << s.x << " " << s.v;
      }
    }
  }
  // Infinite damping in all but name: the velocity is gone after 1 s (e^{-1e300}), the spring
  // has moved it by at most ω²·t²/2·|x0| ≈ 0 and the initial velocity by 1/γ = 1e-300 m.
  const exact::AxisState frozen = exact::linear(1.0, 1.0, 1.0, 1e300, 0.0, 0.0, 1.0);
  EXPECT_NEAR(frozen.x, 1.0, 2 * kEps);  // 1 - e2·(1 - r2 q) with r2 q ~ 1e-300: rounding
  EXPECT_NEAR(frozen.v, 0.0, 1e-299);    // -ω² y0 s with s = 1e-300 (and v0 e^{-γt} = 0)
}

TEST(ExactRegime, ClassifiesByDampingRatio) {
  using R = exact::Regime;
  // ω = 2, so ζ = γ/4; critical means |ζ - 1| <= 1e-9.
  EXPECT_EQ(exact::regime(0.0, 0.0), R::none);
  EXPECT_EQ(exact::regime(0.0, 3.0), R::none);
  EXPECT_EQ(exact::regime(4.0, 0.0), R::undamped);
  EXPECT_EQ(exact::regime(4.0, 4.0 * 0.5), R::under);
  EXPECT_EQ(exact::regime(4.0, 4.0 * (1 - 2e-9)), R::under);
  EXPECT_EQ(exact::regime(4.0, 4.0 * (1 - 5e-10)), R::critical);
  EXPECT_EQ(exact::regime(4.0, 4.0), R::critical);
  EXPECT_EQ(exact::regime(4.0, 4.0 * (1 + 5e-10)), R::critical);
  EXPECT_EQ(exact::regime(4.0, 4.0 * (1 + 2e-9)), R::over);
  EXPECT_EQ(exact::regime(4.0, 4.0 * 30), R::over);
}

/// The what() of the std::invalid_argument f throws, or a marker when it throws none.
std::string invalid_argument_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "<no std::invalid_argument>";
}

TEST(ExactLinear, RejectsInvalidArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const char* names[] = {"x0", "v0", "omega2", "gamma", "anchor", "accel", "t"};
  for (int i = 0; i < 7; ++i) {
    std::vector<double> bad{nan, inf, -inf};
    if (i == 2 || i == 3) bad.push_back(-1e-300);  // rates must also be >= 0
    for (double value : bad) {
      std::array<double, 7> a{1.0, 1.0, 4.0, 0.5, 0.0, 0.0, 1.0};
      a[i] = value;
      const std::string message = invalid_argument_message(
          [&] { (void)exact::linear(a[0], a[1], a[2], a[3], a[4], a[5], a[6]); });
      EXPECT_NE(message.find(fmt::format("exact: {} must be", names[i])), std::string::npos)
          << names[i] << " = " << value << ": " << message;
    }
  }
  EXPECT_THROW((void)exact::regime(-1.0, 0.0), std::invalid_argument);
  EXPECT_THROW((void)exact::regime(1.0, nan), std::invalid_argument);
}

/// A body with every linear component: spring (rest length 0), constant force, gravity, drag.
BodyDef everything() {
  BodyDef def;
  def.name = "everything";
  def.body = Body{.mass = 2.0, .position = {0.5, 3.0}, .velocity = {-1.0, 2.0}};
  def.spring = SpringDamper{.anchor = {1.0, -2.0}, .stiffness = 6.0, .damping = 0.4};
  def.constant_force = ConstantForce{{3.0, -1.0}};
  def.gravity = Gravity{};
  def.drag = LinearDrag{0.2};
  return def;
}

TEST(ExactSolve, EveryLinearComponentIsLinearPerAxis) {
  // ω² = k/m = 3, γ = (b + c)/m = 0.3, accel = F/m + g. solve() must compute exactly these
  // inputs and call linear() per axis; the same operations in the same order give the same
  // bits, so the only tolerance is none (checked to the last ulp).
  const BodyDef def = everything();
  const double m = def.body.mass, omega2 = 6.0 / m, gamma = (0.4 + 0.2) / m;
  const double ax = 3.0 / m + def.gravity->acceleration.x;
  const double ay = -1.0 / m + def.gravity->acceleration.y;
  for (double t : {0.0, 0.4, 2.0, 7.5}) {
    const std::optional<Body> body = exact::solve(def, t);
    ASSERT_TRUE(body.has_value());
    const exact::AxisState x = exact::linear(0.5, -1.0, omega2, gamma, 1.0, ax, t);
    const exact::AxisState y = exact::linear(3.0, 2.0, omega2, gamma, -2.0, ay, t);
    EXPECT_EQ(body->mass, m);
    EXPECT_EQ(body->position, (Vec2{x.x, y.x})) << t;
    EXPECT_EQ(body->velocity, (Vec2{x.v, y.v})) << t;
  }
  // Sanity of the physics, not just the plumbing: long after the transient (γt = 30) the body
  // rests where the spring balances the force, anchor + accel/ω², to e^{-15} ≈ 3e-7 of the
  // ~5 m initial offset plus rounding: 1e-5 m.
  const std::optional<Body> late = exact::solve(def, 200.0);
  ASSERT_TRUE(late.has_value());
  EXPECT_NEAR(late->position.x, 1.0 + ax / omega2, 1e-5);
  EXPECT_NEAR(late->position.y, -2.0 + ay / omega2, 1e-5);
}

TEST(ExactSolve, SpringWithRestLengthIsNotLinear) {
  BodyDef def = everything();
  def.spring->rest_length = 0.5;
  EXPECT_FALSE(exact::solve(def, 1.0).has_value());
  def.spring->rest_length = 0.0;
  EXPECT_TRUE(exact::solve(def, 1.0).has_value());
}

TEST(ExactSolve, FreeBodiesMoveInStraightLines) {
  // No components at all: x = x0 + v0 t, v = v0. One multiply-add per axis: within 1 ulp of
  // the result.
  BodyDef def;
  def.body = Body{.mass = 3.0, .position = {-4.0, 1.5}, .velocity = {0.25, -7.0}};
  for (double t : {0.0, 1.0, 33.3}) {
    const std::optional<Body> body = exact::solve(def, t);
    ASSERT_TRUE(body.has_value());
    EXPECT_DOUBLE_EQ(body->position.x, -4.0 + 0.25 * t);
    EXPECT_DOUBLE_EQ(body->position.y, 1.5 - 7.0 * t);
    EXPECT_EQ(body->velocity, def.body.velocity);
  }
}

TEST(ExactSolve, ArticleConstantForce) {
  // "Integration Basics": 10 N on 1 kg from rest, t = 10 s: x = a t²/2 = 500 m, v = 100 m/s.
  // All intermediate values are small integers or halves, exact in double: tolerance 1e-12.
  BodyDef def;
  def.constant_force = ConstantForce{{10.0, 0.0}};
  const std::optional<Body> body = exact::solve(def, 10.0);
  ASSERT_TRUE(body.has_value());
  EXPECT_NEAR(body->position.x, 500.0, 1e-12);
  EXPECT_NEAR(body->velocity.x, 100.0, 1e-12);
  EXPECT_EQ(body->position.y, 0.0);
  EXPECT_EQ(body->velocity.y, 0.0);
}

TEST(ExactSolve, RejectsInvalidBodies) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto message = [](const BodyDef& def, double t) {
    return invalid_argument_message([&] { (void)exact::solve(def, t); });
  };
  BodyDef pushed;  // no spring: a bad mass would otherwise slip through as a finite F/m
  pushed.constant_force = ConstantForce{{10.0, 0.0}};
  for (double mass : {0.0, -1.0, nan}) {
    pushed.body.mass = mass;
    EXPECT_NE(message(pushed, 1.0).find("exact: mass must be"), std::string::npos) << mass;
  }
  BodyDef def = everything();
  def.spring->stiffness = -1.0;
  EXPECT_NE(message(def, 1.0).find("exact: stiffness must be"), std::string::npos);
  def = everything();
  def.spring->damping = nan;
  EXPECT_NE(message(def, 1.0).find("exact: damping must be"), std::string::npos);
  def = everything();
  def.spring->rest_length = -0.5;
  EXPECT_NE(message(def, 1.0).find("exact: rest_length must be"), std::string::npos);
  def = everything();
  def.drag->coefficient = -0.1;
  EXPECT_NE(message(def, 1.0).find("exact: drag coefficient must be"), std::string::npos);
  EXPECT_NE(message(everything(), nan).find("exact: t must be"), std::string::npos);
}

}  // namespace
}  // namespace fixstep
