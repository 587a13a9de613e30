// Dynamic bodies for tests that build worlds in code: one of a name, place and velocity; a disc
// under gravity.
#pragma once

#include <string>

#include "fixstep/core/components.hpp"

namespace fixstep::test {

[[nodiscard]] inline BodyDef ball(const std::string& name, Vec2 at, Vec2 v = {},
                                  double mass = 1.0) {
  BodyDef b;
  b.name = name;
  b.body = Body{.mass = mass, .position = at, .velocity = v};
  return b;
}

/// A dynamic disc of `radius` (m) and `mass` (kg) at `at` (m) moving at `v` (m/s), under the
/// default gravity (0, -9.81) m/s².
[[nodiscard]] inline BodyDef falling_disc(Vec2 at, Vec2 v, double radius, double mass = 1.0) {
  BodyDef b;
  b.body = Body{.mass = mass, .position = at, .velocity = v};
  b.collider = Collider{.radius = radius};
  b.gravity = Gravity{};
  return b;
}

}  // namespace fixstep::test
