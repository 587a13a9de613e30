// What the per-body guard (stability.cpp) and the network guard (stability_network.cpp) call of
// each other; the bound and the verdict they share are in stability_verdict.hpp.
#pragma once

#include <span>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/stability.hpp"

namespace fixstep::detail {

/// check_network_stability with the links by place in `bodies` (fastest_body is then the handle
/// of bodies[i] as a definition's body).
[[nodiscard]] NetworkStability network_stability(std::span<const BodyDef> bodies,
                                                 std::span<const IndexLink> links,
                                                 Integrator integrator, double dt, int substeps);
/// linked_bodies with the links by place.
[[nodiscard]] std::vector<bool> linked_by_index(std::size_t body_count,
                                                std::span<const IndexLink> links);

}  // namespace fixstep::detail
