// The kernel's form of a shape and the geometry between two of them: poses, convex shapes in
// polygon form, contact manifolds, distances and times of impact. Internal (not installed).
//
// Every shape is a convex polygon of 1..8 vertices swept by a disc of `radius`: a circle is
// one vertex, a capsule two, a box four, a polygon 3..8 (rounded when radius > 0). All
// arithmetic is + - * / and sqrt in double, and rotations come from det::sin / det::cos, so
// the results are the same bits on every platform.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "fixstep/core/det_math.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep::detail {

/// A rotation by an angle θ as (cos θ, sin θ).
struct Rot {
  double c = 1.0, s = 0.0;
};
/// θ (rad) kept in [−π, π]: std::remainder is exact, so the wrap is the same bits everywhere.
[[nodiscard]] inline double wrap_angle(double a) {
  return std::abs(a) <= std::numbers::pi ? a : std::remainder(a, 2.0 * std::numbers::pi);
}
/// An angle (rad) as rot_of takes it to det's trig: beyond trig_max_argument (a body turning
/// near the 1e12 rad/s limit over a tick, which the guard then stops), reduced by 2π (IEEE
/// remainder, exact); within it, itself.
[[nodiscard]] inline double trig_angle(double angle) {
  if (std::abs(angle) > det::trig_max_argument && std::isfinite(angle)) {
    return std::remainder(angle, 2.0 * std::numbers::pi);
  }
  return angle;
}

/// Rot of `angle` (rad) through det::cos and det::sin, of trig_angle(angle).
[[nodiscard]] Rot rot_of(double angle);
[[nodiscard]] inline Vec2 rotate(Rot q, Vec2 v) {
  return {q.c * v.x - q.s * v.y, q.s * v.x + q.c * v.y};
}
[[nodiscard]] inline Vec2 unrotate(Rot q, Vec2 v) {
  return {q.c * v.x + q.s * v.y, -q.s * v.x + q.c * v.y};
}

/// A rigid placement: x_world = p + q·x_local.
struct Pose {
  Vec2 p{};
  Rot q{};
};
[[nodiscard]] inline Vec2 transform(const Pose& t, Vec2 v) {
  return t.p + rotate(t.q, v);
}
[[nodiscard]] inline Vec2 untransform(const Pose& t, Vec2 v) {
  return unrotate(t.q, v - t.p);
}

/// A convex shape in polygon form, in its body's frame relative to the body's centre of mass.
/// normals[i] is the outward unit normal of edge vertices[i] -> vertices[i+1 mod count] (for
/// count = 2 the two sides of the segment; unused for count = 1).
struct Convex {
  std::array<Vec2, max_polygon_vertices> vertices{};
  std::array<Vec2, max_polygon_vertices> normals{};
  int count = 1;
  double radius = 0.0;  ///< m: the sweep radius (a circle's radius, a capsule's, a rounding)
};

/// `shape` in polygon form in its body's frame, shifted by -`center` (the body's local centre
/// of mass), so that the body's state point is the origin.
[[nodiscard]] Convex to_convex(const ShapeDef& shape, Vec2 center);
/// c with every vertex and normal carried by pose t (shape_collide.cpp).
[[nodiscard]] Convex convex_placed(const Convex& c, const Pose& t);
/// A segment a..b (its own coordinates) as a Convex of two vertices and radius 0.
[[nodiscard]] Convex segment_convex(Vec2 a, Vec2 b);

/// The largest distance from the origin (the body's centre of mass) of any point of `c`, m.
[[nodiscard]] double extent(const Convex& c);
/// The world box around `c` at pose `t`, grown by `margin` (m) on every side.
[[nodiscard]] Aabb convex_aabb(const Convex& c, const Pose& t, double margin = 0.0);
/// Whether two boxes overlap (touching counts).
[[nodiscard]] inline bool boxes_overlap(const Aabb& a, const Aabb& b) {
  return a.lower.x <= b.upper.x && b.lower.x <= a.upper.x && a.lower.y <= b.upper.y &&
         b.lower.y <= a.upper.y;
}
/// The world box of a segment.
[[nodiscard]] inline Aabb segment_bounds(const SegmentDef& s) {
  return {{std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y)},
          {std::max(s.a.x, s.b.x), std::max(s.a.y, s.b.y)}};
}

/// One point of a contact manifold. Anchors are relative to the bodies' centres of mass, in
/// world orientation (the lever arms of the impulses).
struct ManifoldPoint {
  Vec2 point{};             ///< m, world: midway between the two surfaces
  Vec2 anchor_a{};          ///< m: point - centre of A
  Vec2 anchor_b{};          ///< m: point - centre of B
  double separation = 0.0;  ///< m, along the normal; < 0: overlap
  /// Which features meet (an edge of one and a vertex of the other), the same from tick to
  /// tick while they do, for warm starting: (reference edge, incident vertex, side) packed as
  /// bits 0-7 the reference edge, bits 8-15 the incident vertex the point comes from (clipped
  /// or not), bits 16-17 the side: 0 A holds the reference edge, 1 B does, 2 a single contact
  /// at the closest points of the two cores (then bits 0-7 A's nearest vertex, 8-15 B's). A
  /// segment is A (vertex 0 = a, 1 = b; edge 0 its right side, 1 its left). collide_plane: B's
  /// vertex index. A pair turning over from one reference face to the other changes its ids.
  std::uint32_t id = 0;
};

/// Up to two contact points and their normal, the unit vector from A towards B.
struct Manifold {
  Vec2 normal{};
  std::array<ManifoldPoint, 2> points{};
  int count = 0;
};

/// The manifold between A (at pose ta) and B (at pose tb): the points where they are closer
/// than `speculative` (m, >= 0), separations included (SAT over both shapes' edge normals and
/// reference-face clipping, Catto's "Contact Manifolds", GDC 2007; a circle or capsule meets
/// a polygon by its closest feature). count = 0 when they are farther apart.
///
/// Details: each point is kept while its own separation <= `speculative` (a box corner down
/// gives one point, a box face down two). A's reference face is preferred unless B's separates
/// by 0.5 mm more (no flip-flop between nearly equal axes). When the cores are apart and the
/// clipped points are more than 0.5 mm farther than the cores' closest points (two vertices
/// nearest), the one contact is at the closest points along their direction. Circles and
/// capsules use the exact closest points of their core segments first (their edge normals miss
/// the axis along a segment). Two concentric circles: the normal is A's +y. Computed in A's
/// frame (shape_clip.cpp).
[[nodiscard]] Manifold collide(const Convex& a, const Pose& ta, const Convex& b, const Pose& tb,
                               double speculative);

/// The manifold between B (at pose tb) and the static segment `seg` (world, A's side), or a
/// chain segment with ghost vertices: a contact whose normal would point into the chain's
/// neighbour (a joint's concave side, or a vertex not in its own region) is dropped, as the disc
/// contacts do (segment.hpp), so a shape sliding along a polyline does not catch on a joint.
/// The normal points from the segment towards B; anchor_a = point (a segment has no centre:
/// the world origin, which a carrying kinematic body, not turning, does not need).
///
/// The verdict on the manifold's normal n (shape_segment.cpp), on the side of the segment n
/// points to: the face normal is kept; leaning towards a free end (no ghost), kept; towards a
/// straight or concave joint (bend under 0.01 rad), snapped to the face normal and B's incident
/// edge clipped to the segment; towards a convex joint, kept within the joint's wedge (0.01
/// tolerance) and dropped beyond it, and at b the point at the joint vertex itself is left to
/// the next segment (the segment that starts at a joint owns its vertex).
[[nodiscard]] Manifold collide_segment(const SegmentDef& seg, const Convex& b, const Pose& tb,
                                       double speculative);

/// The manifold between B and the static half-plane n·x >= offset (n unit): up to two of B's
/// deepest vertices (the deepest and the deeper of its two neighbours). The normal is n;
/// anchor_a = point (the plane has no centre: the world origin).
[[nodiscard]] Manifold collide_plane(Vec2 n, double offset, const Convex& b, const Pose& tb,
                                     double speculative);

/// Closest points of two convex shapes (GJK on their cores, radii then taken off).
struct Distance {
  double distance = 0.0;      ///< m, between the rounded surfaces: < 0 when only the radii
                              ///< overlap; the cores' overlap is not measured (then 0, overlap
                              ///< = true, point_a = point_b a point of A's core, normal zero)
  Vec2 point_a{}, point_b{};  ///< world, on each surface
  Vec2 normal{};              ///< from A to B
  bool overlap = false;       ///< the cores intersect
};
[[nodiscard]] Distance distance(const Convex& a, const Pose& ta, const Convex& b, const Pose& tb);

/// A body's motion over a tick for the time of impact: its centre moves linearly from c0 to
/// c1 and its angle from a0 to a1 (rad) as the fraction t in [0, 1] goes.
struct Sweep {
  Vec2 c0{}, c1{};
  double a0 = 0.0, a1 = 0.0;
};
[[nodiscard]] Pose pose_at(const Sweep& s, double t);

/// The first fraction t in [0, t_max] at which A and B (each on its sweep) come within
/// `target` (m, > 0) of each other, by conservative advancement (Mirtich 1996; the bound on
/// the approach speed is |Δc| + |Δa| · extent for each body): exact to `tolerance` (m) in the
/// distance, never beyond the first touch. Returns t_max when they do not meet, and the count
/// of distance evaluations in `iterations` (at most 64; t is still conservative then).
/// Details (shape_distance.cpp): the bound is refined to |Δc_b - Δc_a| + |Δa_a| extent(a) +
/// |Δa_b| extent(b) (no more than the sum of the |Δc|); a hit has the distance at t in
/// [target, target + tolerance], or t = 0 when the shapes start within it (overlapping too);
/// out of evaluations before they meet: hit = true at the last t, which is still before the
/// touch, so a caller stops there safely.
struct Toi {
  double t = 1.0;
  bool hit = false;
  int iterations = 0;
};
[[nodiscard]] Toi time_of_impact(const Convex& a, const Sweep& sa, const Convex& b, const Sweep& sb,
                                 double target, double tolerance, double t_max = 1.0);

}  // namespace fixstep::detail
