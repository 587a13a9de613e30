// A dynamic body of a name, place and velocity, for tests that build worlds in code.
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

}  // namespace fixstep::test
