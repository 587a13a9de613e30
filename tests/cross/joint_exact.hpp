// The exact checks of joints (docs/JOINTS.md): each a small world stepped to a measured outcome
// and the closed form or bound it must meet, in the form of the shapes' checks
// (shape_exact.hpp), run by the same two harnesses: test_shapes and shape_checks (the aarch64
// and wasm32 builds under their emulators).
#pragma once

#include <vector>

#include "shape_exact.hpp"

namespace fixstep::joint_exact {

/// Every exact check of joints: the rigid pendulum (small-angle and elliptic-integral periods,
/// energy bounded over 100 periods), a hanging chain of 30 boxes with and without a 10 kg
/// load, a revolute motor spinning a disc up at τ/I, a prismatic slide at g sin θ and its
/// limit, a welded L spinning with the composite inertia, and a rope slack below its length
/// and never longer than it past the slop.
[[nodiscard]] std::vector<shape_exact::Check> checks();

}  // namespace fixstep::joint_exact
