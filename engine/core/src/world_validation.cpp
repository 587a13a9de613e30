// A world's bodies, components and links checked against value_ranges.hpp before they enter the
// state (WorldKernel::validate*, called by create_body, the edit calls and create_link): a value
// out of range throws std::invalid_argument naming the body or link, the field and the range.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/value_ranges.hpp"
#include "value_checks.hpp"
#include "world_kernel.hpp"

namespace fixstep {

template <class Real>
void detail::WorldKernel<Real>::validate(const Body& b, const std::string& who) const {
  check_value<Real>(b.mass, divisor_in_range(b.mass), who, "mass", "in [1e-100, 1e100] kg");
  check_vec<Real>(b.position, who, "position");
  check_vec<Real>(b.velocity, who, "velocity");
  check_value<Real>(b.angle, within_state(b.angle), who, "angle",
                    "finite with |value| <= 1e12 rad");
  check_value<Real>(b.angular_velocity, within_state(b.angular_velocity), who, "angular_velocity",
                    "finite with |value| <= 1e12 rad/s");
}

template <class Real>
void detail::WorldKernel<Real>::validate_component(const SpringDamper& c, const std::string& who) {
  check_vec<Real>(c.anchor, who, "spring.anchor");
  check_spring_terms<Real>(c.stiffness, c.damping, c.rest_length, who,
                           {"spring.stiffness", "spring.damping", "spring.rest_length"});
}

template <class Real>
void detail::WorldKernel<Real>::validate_component(const ConstantForce& c, const std::string& who) {
  check_coefficients<Real>(c.force, who, "force");
}

template <class Real>
void detail::WorldKernel<Real>::validate_component(const Gravity& c, const std::string& who) {
  check_coefficients<Real>(c.acceleration, who, "gravity");
}

template <class Real>
void detail::WorldKernel<Real>::validate_component(const LinearDrag& c, const std::string& who) {
  check_value<Real>(c.coefficient, nonnegative_coefficient(c.coefficient), who, "drag",
                    "in [0, 1e100] N*s/m");
}

template <class Real>
void detail::WorldKernel<Real>::validate_component(const Appearance& c, const std::string& who) {
  check_value<Real>(c.radius, c.radius > 0.0 && c.radius <= max_state_magnitude, who, "radius",
                    "finite, > 0 and <= 1e12 m");
  check_value<Real>(c.trail_time, c.trail_time > 0.0 && c.trail_time <= max_trail_time, who,
                    "trail_time", "finite, > 0 and <= 10 s");
  for (const double side : {c.sprite_size.x, c.sprite_size.y}) {  // drawing only
    check_value<Real>(side, std::isfinite(side) && side >= 0.0 && side <= max_state_magnitude, who,
                      "sprite_size", "finite, >= 0 and <= 1e12 m");
  }
}

template <class Real>
void detail::WorldKernel<Real>::validate_component(const Collider& c, const std::string& who) {
  // r / I and m r² / I turn a disc (world_rolling.cpp): r is divided into as well.
  check_value<Real>(c.radius, c.radius >= min_coefficient && c.radius <= max_state_magnitude, who,
                    "collider.radius", "in [1e-100, 1e12] m");
  if (c.inertia) {
    check_value<Real>(*c.inertia, divisor_in_range(*c.inertia), who, "collider.inertia",
                      "in [1e-100, 1e100] kg*m^2");
  }
  if (c.friction) {
    check_value<Real>(*c.friction, nonnegative_coefficient(*c.friction), who, "collider.friction",
                      "in [0, 1e100]");
  }
  if (c.restitution) {
    const double e = *c.restitution;
    check_value<Real>(e, std::isfinite(e) && e >= 0.0 && e <= 1.0, who, "collider.restitution",
                      "in [0, 1]");
  }
}

template <class Real>
void detail::WorldKernel<Real>::validate_link(const LinkDef& def, const std::string& who) const {
  for (const Entity e : {def.body_a, def.body_b}) {
    if (!bodies_.contains(e)) {
      throw std::invalid_argument(
          fmt::format("{}: body {}:{} is null or was destroyed", who, e.index1, e.generation));
    }
  }
  if (def.body_a == def.body_b) {
    throw std::invalid_argument(fmt::format(
        "{}: both ends are {} (a link needs two different bodies)", who, describe(def.body_a)));
  }
  const LinkSpring& s = def.spring;
  check_spring_terms<Real>(s.stiffness, s.damping, s.rest_length, who,
                           {"stiffness", "damping", "rest_length"});
  if (s.rest_length > 0.0) {
    const std::size_t a = bodies_.index(def.body_a), b = bodies_.index(def.body_b);
    if (x_[a] == x_[b] && y_[a] == y_[b]) {
      throw std::invalid_argument(fmt::format(
          "{}: {} and {} are at the same point, so the direction of a link with rest length "
          "{:g} m is undefined; move one of them or use rest_length = 0",
          who, describe(def.body_a), describe(def.body_b), s.rest_length));
    }
  }
}

}  // namespace fixstep
