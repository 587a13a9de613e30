// Tests write a definition's links by the places of their bodies: link_between(i, j) is the
// link WorldDef::add_body's handles for bodies i and j would make.
#pragma once

#include <cstddef>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"

namespace fixstep::test {

[[nodiscard]] inline LinkDef link_between(std::size_t a, std::size_t b, LinkSpring spring = {}) {
  return LinkDef{fixstep::defined_entity(a), fixstep::defined_entity(b), spring};
}

}  // namespace fixstep::test
