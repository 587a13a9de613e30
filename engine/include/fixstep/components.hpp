// Components: plain data, SI units. A World stores and steps only the components a scene
// declares; see world.hpp.
#pragma once

#include <optional>
#include <string>

#include "fixstep/types.hpp"

namespace fixstep {

/// The rigid point body every other component acts on.
struct Body {
  double mass = 1.0;   ///< kg, finite and > 0
  Vec2 position{};     ///< m
  Vec2 velocity{};     ///< m/s
};

/// A spring-damper from the body to a fixed anchor point.
///
/// Force on the body, with d = position - anchor:
///   F = -k (|d| - L) d/|d| - b v          (Hooke's law plus a linear dashpot to the fixed frame)
/// With rest length L = 0 this is F = -k (x - anchor) - b v, the damped harmonic oscillator of
/// "Integration Basics" in each axis independently. The damping acts on the full velocity
/// (not only along the spring), which keeps it linear in v.
struct SpringDamper {
  Vec2 anchor{};             ///< m
  double stiffness = 0.0;    ///< k, N/m, finite and >= 0
  double damping = 0.0;      ///< b, N*s/m, finite and >= 0
  double rest_length = 0.0;  ///< L, m, finite and >= 0
};

/// A constant force, e.g. the 10 N push of the article's first example.
struct ConstantForce {
  Vec2 force{};  ///< N
};

/// A constant acceleration independent of mass: gravity on a projectile.
struct Gravity {
  Vec2 acceleration{0.0, -9.81};  ///< m/s^2
};

/// Linear drag F = -c v (Stokes drag, valid at low Reynolds number).
struct LinearDrag {
  double coefficient = 0.0;  ///< c, N*s/m, finite and >= 0
};

/// How a body is drawn. Bodies without one are drawn with a default size and palette colour.
struct Appearance {
  double radius = 0.5;  ///< m, finite and > 0
  Rgba8 color{230, 87, 46, 255};
};

/// Everything needed to create one body entity, in the spirit of Box2D's b2BodyDef: fill in
/// what the body has; components left empty are not stored and cost nothing when stepping.
struct BodyDef {
  std::string name;  ///< shown in CSV output and messages; may be empty
  Body body{};
  std::optional<SpringDamper> spring;
  std::optional<ConstantForce> constant_force;
  std::optional<Gravity> gravity;
  std::optional<LinearDrag> drag;
  std::optional<Appearance> appearance;
};

}  // namespace fixstep
