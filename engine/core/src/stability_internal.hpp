// Constants shared by the per-body guard (stability.cpp) and the network guard
// (stability_network.cpp).
#pragma once

#include <vector>

namespace fixstep::detail {

// ρ <= 1 + tolerance counts as bounded. The round-off in ρ is ~1e-16; the smallest growth the
// scan must see is explicit Euler's 1 + s²/2 at its first point s = 1e-4, i.e. 5e-9.
inline constexpr double stability_tolerance = 1e-14;
inline constexpr double scan_from = 1e-4, scan_to = 1e6;  // dimensionless steps s = ω h (or γ h)
inline constexpr double stability_margin = 0.9;  // warn above 90 % of the largest stable step

}  // namespace fixstep::detail
