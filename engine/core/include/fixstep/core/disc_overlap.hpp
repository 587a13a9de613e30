// Discs that overlap before the first tick: the check a world with body contacts
// (WorldSettings::contacts) makes of its starting positions, so that no contact starts deep
// inside another (the solver would push the pair apart with a jump nobody asked for).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <utility>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep {

/// Whether bodies a and b take part in disc-disc contacts with each other, leaving links
/// aside: both have a Collider with collide = true, neither is a sensor, their filters accept
/// each other (should_collide) and at least one of them is dynamic (two static or kinematic
/// bodies never touch: neither can be moved).
[[nodiscard]] bool discs_may_touch(const BodyDef& a, const BodyDef& b);

/// How deep the discs of a and b overlap at their starting positions, m:
/// r_a + r_b - |x_a - x_b| (> 0: overlapping; <= 0: apart or touching). Both need a Collider.
[[nodiscard]] double disc_overlap_depth(const BodyDef& a, const BodyDef& b);

/// An overlapping pair of discs among `bodies` as they start: a pair (i, j), i < j (indices
/// into bodies) with |x_i - x_j| < r_i + r_j - tol, overlapping by more than
/// tol = 1e-9 (r_i + r_j) + 4 ε max|coordinate| (ε = 2^-52; touching discs, and discs placed
/// touching whose distance rounds a little short, do not overlap), that may touch (discs_may_touch)
/// and that no link in `links` (as in a WorldDef) joins (linked bodies never collide, Box2D's
/// collideConnected = false); std::nullopt when there is none. When several pairs overlap, the one
/// returned is the first the sweep meets: the same for the same input.
///
/// Sweep and prune in one dimension (Baraff's sort and sweep: Dynamic World of
/// Non-Penetrating Rigid Bodies, PhD thesis, Cornell, 1992): discs sorted by the left end of their
/// x-interval [x - r, x + r], swept left to right; the discs whose interval is still open are kept
/// ordered by y, so each new disc is compared only with those whose centre lies within r + r_max in
/// y (r_max the largest radius of the side it is compared with). Dynamic discs are compared with
/// every other disc, static and kinematic ones only with dynamic ones. O(n log n) time and O(n + l)
/// memory for n discs and l links, as long as a disc's window holds few discs it may not touch
/// (discs of one size that do not overlap: a bounded number each); it stops at the first
/// overlap, so a million discs at one point cost two sorts. Its times on large piles:
/// docs/ROBUSTNESS.md, "The overlap check at load".
///
/// Throws std::invalid_argument for a disc (a body with a Collider that collides) whose
/// position is not finite or whose radius is not finite and > 0, and for a link whose end is
/// not among the bodies.
[[nodiscard]] std::optional<std::pair<std::size_t, std::size_t>> first_disc_overlap(
    std::span<const BodyDef> bodies, std::span<const LinkDef> links);

/// first_disc_overlap of def.bodies and def.links when def.settings.contacts is set;
/// std::nullopt without contacts (no disc-disc contact is ever computed then). Throws as the
/// overload above.
[[nodiscard]] std::optional<std::pair<std::size_t, std::size_t>> first_disc_overlap(
    const WorldDef& def);

}  // namespace fixstep
