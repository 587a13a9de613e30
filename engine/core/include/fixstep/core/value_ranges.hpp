// The ranges a world's inputs must lie in so that its arithmetic stays finite: every
// coefficient a body, link, plane or contact setting carries, and every starting value of the
// state. World(def) and the scene loader refuse values outside them, naming the field.
#pragma once

#include <cmath>

#include "fixstep/core/step_results.hpp"

namespace fixstep {

/// Largest magnitude of a coefficient: mass (kg), moment of inertia (kg·m²), stiffness (N/m),
/// damping and drag (N·s/m), friction μ, a constant force (N) and gravity (m/s²), each
/// component. With the state within max_state_magnitude M = 10¹² (positions, velocities,
/// angular velocities) and coefficients within [min_coefficient, max_coefficient], the worst
/// products the step and the energy account form stay finite in double: ½ m |v|² and ½ I ω²
/// ≤ 10¹²⁴ J, ½ k d² ≤ 10¹²⁵ J, m r² / I ≤ 10²²⁴, the turn r·P/I of an impulse P ≤ m·2M
/// ≤ 10²²⁵ rad/s, k/m ≤ 10²⁰⁰ s⁻², and a sum of 10⁹ such terms over 10⁹ ticks ≤ 10²⁴³, far
/// from double's 1.8·10³⁰⁸. A state pushed beyond M by them is then a finite value the
/// runtime guard (World::fault) sees and names, never a NaN it cannot.
inline constexpr double max_coefficient = 1e100;

/// Smallest positive value of anything a step divides by (mass, moment of inertia, radius):
/// 1/m, 1/I and r/I stay ≤ 10²⁰⁰ (a subnormal 5e-324 would make them infinite, and the state
/// NaN). 0 itself is refused where it is divided by.
inline constexpr double min_coefficient = 1e-100;

/// Whether v is finite with |v| <= max_coefficient (a force or gravity component, a
/// stiffness, damping, drag or friction; 0 allowed).
[[nodiscard]] inline bool within_coefficient(double v) {
  return std::isfinite(v) && std::abs(v) <= max_coefficient;
}

/// Whether v is a divisor in [min_coefficient, max_coefficient] (mass, moment of inertia).
[[nodiscard]] inline bool divisor_in_range(double v) {
  return std::isfinite(v) && v >= min_coefficient && v <= max_coefficient;
}

/// Whether v is finite with |v| <= max_state_magnitude (a position or velocity component,
/// an angle in rad, an angular velocity in rad/s, a rest length, an anchor, an offset).
[[nodiscard]] inline bool within_state(double v) {
  return std::isfinite(v) && std::abs(v) <= max_state_magnitude;
}

}  // namespace fixstep
