// Exact solutions of x'' + γ x' + ω² (x - anchor) = accel. Every formula below is derived
// in the comments; the physics is that of Thornton & Marion, Classical Dynamics, 5th ed., §3.5
// (damped oscillations) and Taylor, Classical Mechanics, §2.2–2.3 (linear air resistance).
#include "fixstep/core/exact.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "fixstep/core/components.hpp"

namespace fixstep::exact {
namespace {

void require_exact(bool ok, const char* name, const char* rule, double value) {
  if (!ok) {
    throw std::invalid_argument(
        fmt::format("fixstep::exact: {} must be {} (got {})", name, rule, value));
  }
}

void require_finite(double value, const char* name) {
  require_exact(std::isfinite(value), name, "finite", value);
}

void require_rate(double value, const char* name) {
  require_exact(std::isfinite(value) && value >= 0.0, name, "finite and >= 0", value);
}

// The two basis solutions of the homogeneous equation y'' + γ y' + ω² y = 0:
//   p(t): the response to a unit displacement, p(0) = 1, p'(0) = 0;
//   s(t): the response to a unit velocity,     s(0) = 0, s'(0) = 1 (the impulse response).
// Any solution is y(t) = y0 p(t) + v0 s(t). Its velocity needs p' and s'. p' solves the same
// equation and starts with p'(0) = 0 and p''(0) = -ω² p(0) - γ p'(0) = -ω², so p' = -ω² s:
//   y'(t) = -ω² y0 s(t) + v0 s'(t).
struct Basis {
  double p;
  double s;
  double ds;  // s'
};

// Trying y = e^{rt} gives r² + γ r + ω² = 0, so r = -γ/2 ± Δ with Δ² = γ²/4 - ω² (T&M §3.5:
// Δ² < 0 under-damped, = 0 critically damped, > 0 over-damped). Both branches below are
// written so that nothing cancels as Δ² -> 0: p, s and s' are entire functions of Δ², and
// sin(δt)/δ, expm1(-2δt)/δ keep full relative precision when δt is tiny, so the two branches
// meet continuously at ζ = 1 instead of dividing a vanishing difference by a vanishing δ.
Basis damped_basis(double omega2, double gamma, double t) {
  const double half_gamma = 0.5 * gamma;
  // fma: (γ/2)² is used unrounded, so Δ² is correctly rounded even right at ζ = 1.
  const double delta2 = std::fma(half_gamma, half_gamma, -omega2);
  if (delta2 < 0.0) {
    // Under-damped (and undamped, γ = 0): r = -γ/2 ± iδ with δ = sqrt(ω² - γ²/4), the damped
    // angular frequency ω_d = ω sqrt(1 - ζ²). With E = e^{-γt/2}, s = E sin(δt)/δ and
    //   p  = E (cos δt + (γ/2) sin(δt)/δ),   s' = E (cos δt - (γ/2) sin(δt)/δ).
    const double delta = std::sqrt(-delta2);
    const double e = std::exp(-half_gamma * t);
    const double c = std::cos(delta * t);
    const double sinc = std::sin(delta * t) / delta;
    return {e * (c + half_gamma * sinc), e * sinc, e * (c - half_gamma * sinc)};
  }
  // Critically and over-damped: two real roots. The larger one in magnitude,
  // r1 = -(γ/2 + δ), is a sum of positive terms; the other, r2 = -γ/2 + δ, would cancel when
  // γ >> ω, so it comes from the product of the roots instead: r1 r2 = ω² (Vieta).
  // (For γ/2 > 1.3e154, Δ² overflows while δ does not: factor the difference instead.)
  const double omega = std::sqrt(omega2);
  const double delta = std::isinf(delta2)
                           ? std::sqrt(half_gamma - omega) * std::sqrt(half_gamma + omega)
                           : std::sqrt(delta2);
  const double r1 = -(half_gamma + delta);
  const double r2 = omega2 / r1;
  // s = (e^{r2 t} - e^{r1 t}) / (r2 - r1) with r2 - r1 = 2δ. Factor out the slower exponential
  // e2 = e^{r2 t}: s = e2 q with q = (1 - e^{-2δt}) / (2δ) = -expm1(-2δt) / (2δ), which tends
  // to t as δ -> 0, giving the critically damped s = t e^{-ωt}. The same factoring gives
  //   p  = (r2 e^{r1 t} - r1 e^{r2 t}) / (r2 - r1) = e2 (1 - r2 q),
  //   s' = (r2 e^{r2 t} - r1 e^{r1 t}) / (r2 - r1) = e2 (e^{-2δt} + r2 q),
  // with no overflow for large t (e^{r1 t} and e^{-2δt} only ever shrink for t >= 0).
  const double e2 = std::exp(r2 * t);
  const double q = delta > 0.0 ? -std::expm1(-2.0 * delta * t) / (2.0 * delta) : t;
  return {e2 * (1.0 - r2 * q), e2 * q, e2 * (std::exp(-2.0 * delta * t) + r2 * q)};
}

// No spring: x'' = accel - γ x' (Taylor §2.2: vertical motion with linear drag). With the
// terminal velocity v_ter = accel/γ, v = v_ter + (v0 - v_ter) e^{-γt} and, integrating,
// x = x0 + v_ter t + (v0 - v_ter)(1 - e^{-γt})/γ. Written as stated these cancel for small γ
// (v_ter is huge), so they are regrouped by v0 and accel:
//   v = v0 e^{-γt} + accel q,   x = x0 + v0 q + accel (t - q)/γ,   q = (1 - e^{-γt})/γ,
// where (t - q)/γ = t² φ(γt) with φ(u) = (u - 1 + e^{-u})/u² = 1/2! - u/3! + u²/4! - ...
// For γ = 0 (q = t, φ = 1/2) this is the constant acceleration x0 + v0 t + accel t²/2.
AxisState free_motion(double x0, double v0, double gamma, double accel, double t) {
  const double u = gamma * t;
  const double q = gamma > 0.0 ? -std::expm1(-u) / gamma : t;
  double w = 0.0;  // (t - q)/γ
  if (std::abs(u) < 1.0) {
    // Alternating series with |terms| falling by at least 1/(k + 3) each: 20 terms reach
    // 1/22! < 1e-21 of the leading 1/2, below double precision.
    double phi = 0.0;
    double term = 0.5;
    for (int k = 0; k < 20; ++k) {
      phi += term;
      term *= -u / (k + 3);
    }
    w = t * t * phi;
  } else {
    // |u| >= 1: q/t = (1 - e^{-u})/u is <= 0.64 (u >= 1) or >= 1.7 (u <= -1, backwards in
    // time), so t - q loses at most 2 bits.
    w = (t - q) / gamma;
  }
  return {x0 + v0 * q + accel * w, v0 * std::exp(-u) + accel * q};
}

}  // namespace

Regime regime(double omega2, double gamma) {
  require_rate(omega2, "omega2");
  require_rate(gamma, "gamma");
  if (omega2 == 0.0) return Regime::none;
  if (gamma == 0.0) return Regime::undamped;
  const double zeta = gamma / (2.0 * std::sqrt(omega2));
  if (std::abs(zeta - 1.0) <= 1e-9) return Regime::critical;
  return zeta < 1.0 ? Regime::under : Regime::over;
}

AxisState linear(double x0, double v0, double omega2, double gamma, double anchor, double accel,
                 double t) {
  require_finite(x0, "x0");
  require_finite(v0, "v0");
  require_rate(omega2, "omega2");
  require_rate(gamma, "gamma");
  require_finite(anchor, "anchor");
  require_finite(accel, "accel");
  require_finite(t, "t");
  if (omega2 == 0.0) return free_motion(x0, v0, gamma, accel, t);
  // With a spring, y = x - x_eq about the equilibrium x_eq = anchor + accel/ω² obeys the
  // homogeneous equation y'' + γ y' + ω² y = 0.
  const double x_eq = anchor + accel / omega2;
  const double y0 = x0 - x_eq;
  const Basis b = damped_basis(omega2, gamma, t);
  return {x_eq + (y0 * b.p + v0 * b.s), -omega2 * y0 * b.s + v0 * b.ds};
}

std::optional<Body> solve(const BodyDef& def, double t) {
  const Body& body = def.body;
  require_exact(std::isfinite(body.mass) && body.mass > 0.0, "mass", "finite and > 0", body.mass);
  double omega2 = 0.0;
  double damping = 0.0;  // b + c, N*s/m
  Vec2 anchor{};
  if (def.spring) {
    const SpringDamper& spring = *def.spring;
    require_rate(spring.rest_length, "rest_length");
    if (spring.rest_length > 0.0) return std::nullopt;  // force along d/|d|: nonlinear
    require_rate(spring.stiffness, "stiffness");
    require_rate(spring.damping, "damping");
    omega2 = spring.stiffness / body.mass;
    damping = spring.damping;
    anchor = spring.anchor;
  }
  if (def.drag) {
    require_rate(def.drag->coefficient, "drag coefficient");
    damping += def.drag->coefficient;
  }
  const double gamma = damping / body.mass;
  Vec2 accel{};
  if (def.constant_force) {
    accel = {def.constant_force->force.x / body.mass, def.constant_force->force.y / body.mass};
  }
  if (def.gravity) {
    accel = {accel.x + def.gravity->acceleration.x, accel.y + def.gravity->acceleration.y};
  }
  const AxisState x = linear(body.position.x, body.velocity.x, omega2, gamma, anchor.x, accel.x, t);
  const AxisState y = linear(body.position.y, body.velocity.y, omega2, gamma, anchor.y, accel.y, t);
  Body out = body;
  out.position = {x.x, y.x};
  out.velocity = {x.v, y.v};
  return out;
}

}  // namespace fixstep::exact
