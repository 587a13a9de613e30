// Contact recycling: a pair's manifold kept in its two bodies' frames and made again from them
// while the bodies have barely moved relative to one another, instead of colliding the shapes
// again (Box2D v3.2's contact recycling, physics_world.c: a contact whose relative pose moved
// less than ten linear slops keeps its manifold and updates its separations by the relative
// motion). Internal to the engine: not installed.
//
// A manifold between A and B depends only on B's pose in A's frame, so while that pose has not
// changed the kept manifold is the one collide() would make. When it has changed by a little,
// every point of B has moved relative to A by at most |Δc| + extent_B |Δθ| (c: B's centre in
// A's frame, θ: B's angle less A's); the kept manifold's points follow the bodies and their
// separations follow the motion, and a point collide() would now add was, when the manifold
// was made, farther than its speculative distance, so it is still farther than the
// speculative distance less that motion: out of reach of a tick's motion while the motion
// and the speculative distance's growth stay within the tolerance. A kept point's separation
// is collide()'s for a vertex on a face (to rounding, and to the turn times half the
// separation); a point clipped at the end of a reference face lies on the incident edge, which
// slides along the face as B moves, so its separation can differ by up to the motion times the
// tangent of that edge's tilt to the face.
#pragma once

#include <array>
#include <cstdint>

#include "shape_geom.hpp"

namespace fixstep::detail {

/// A manifold kept in the frames of its two bodies, with the relative pose it was made at.
struct KeptManifold {
  struct Point {
    Vec2 on_a{}, on_b{};      ///< m: the point in A's frame and in B's, as made
    double separation = 0.0;  ///< m, as made
    std::uint32_t id = 0;     ///< ManifoldPoint::id
  };
  std::uint64_t pair = 0;    ///< the owner's key of the two shapes (ShapeWorld: a << 32 | b)
  Vec2 at{};                 ///< m: B's centre in A's frame when made
  double turn = 0.0;         ///< rad: B's angle less A's when made
  double speculative = 0.0;  ///< m: the speculative distance it was made with
  Vec2 normal{};             ///< unit, A towards B, in A's frame
  std::array<Point, 2> points{};
  int count = 0;
};

/// `m` (made by collide() between A at `ta`, angle `angle_a` (rad), and B at `tb`, angle
/// `angle_b`, with speculative distance `speculative`, m) kept under `pair`.
[[nodiscard]] KeptManifold keep_manifold(std::uint64_t pair, const Manifold& m, const Pose& ta,
                                         double angle_a, const Pose& tb, double angle_b,
                                         double speculative);

/// Whether `k` may stand for collide() at the new poses: every point of B (within `extent_b`,
/// m, of its centre) has moved relative to A by at most `tolerance` (m) less the growth of the
/// speculative distance to `speculative` since `k` was made. False for a NaN.
[[nodiscard]] bool kept_holds(const KeptManifold& k, const Pose& ta, double angle_a, const Pose& tb,
                              double angle_b, double extent_b, double speculative,
                              double tolerance);

/// `k` at the new poses: its normal turned with A, each point on each body carried with it,
/// the manifold's point midway between the two and each separation changed by their relative
/// motion along the normal (Box2D v3.2's update of a recycled contact's separation).
[[nodiscard]] Manifold recycle(const KeptManifold& k, const Pose& ta, const Pose& tb);

}  // namespace fixstep::detail
