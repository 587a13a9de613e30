// Constants shared by the per-body guard (stability.cpp) and the network guard
// (stability_network.cpp).
#pragma once

#include <span>
#include <vector>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/stability.hpp"

namespace fixstep::detail {

// ρ <= 1 + tolerance counts as bounded. The round-off in ρ is ~1e-16; the smallest growth the
// scan must see is explicit Euler's 1 + s²/2 at its first point s = 1e-4, i.e. 5e-9.
inline constexpr double stability_tolerance = 1e-14;
inline constexpr double scan_from = 1e-4, scan_to = 1e6;  // dimensionless steps s = ω h (or γ h)
inline constexpr double stability_margin = 0.9;  // warn above 90 % of the largest stable step

/// check_network_stability with the links by place in `bodies` (fastest_body is then the handle
/// of bodies[i] as a definition's body).
[[nodiscard]] NetworkStability network_stability(std::span<const BodyDef> bodies,
                                                 std::span<const IndexLink> links,
                                                 Integrator integrator, double dt, int substeps);
/// linked_bodies with the links by place.
[[nodiscard]] std::vector<bool> linked_by_index(std::size_t body_count,
                                                std::span<const IndexLink> links);

}  // namespace fixstep::detail
