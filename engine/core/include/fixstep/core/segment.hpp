// Level geometry: static segments and polylines (chains of segments) that disc colliders meet.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "fixstep/core/entity.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

/// A line segment from a to b (m) that bodies with a Collider of radius r collide with, on both
/// of its faces: their centres stay at least r from every point of it. Box2D's b2Segment, and
/// with ghost vertices its b2ChainSegment. Static, or carried by a kinematic body (`body`).
///
/// A segment carried by a kinematic body (a moving platform, a lift, a sweeping paddle) moves
/// with it: its points are where they are when it is added, and it is displaced by however
/// far the body has moved since (kinematic bodies do not turn). Contacts with it are resolved
/// in its own frame, which moves at the body's velocity u, constant within a tick: a disc's
/// normal velocity relative to it becomes -e times what it was, friction acts on the relative
/// tangential velocity (a disc at rest on a platform is carried along), and the work it does
/// on the discs (J·u for an impulse J) is in World::external_work(). Destroying the body
/// leaves its segments where they are, static.
///
/// A contact is resolved at its time of impact inside the tick exactly as a plane's (PlaneDef):
/// Newton's restitution e on the normal velocity and a Coulomb-limited friction impulse μ on
/// the tangential one, or coming to rest and sliding with friction μ |a_n|. The contact's
/// normal is that of the closest point of the segment to the disc's centre: the segment's
/// normal on its interior, (centre - end point)/r at an end point (a disc of radius 0).
///
/// Ghost vertices (polylines, add_polyline). A segment whose end `a` joins a previous segment
/// of a chain holds that segment's other end as `prev` (and `next` beyond b likewise). A joint
/// is then no corner a disc sliding along the chain can catch on: a contact with the joint
/// vertex itself is kept only when the disc's centre lies in the joint's own region, past the
/// end of the segment before it (along that segment's direction) and before the start of the
/// one after it; that region is the wedge between the two segments' normals on a joint's
/// convex side and is empty on its concave side and at a straight joint. Everywhere else a
/// neighbour's interior contact covers the disc. A joint's vertex belongs to the segment that
/// starts there (its `a`): the segment ending there never reports it.
struct SegmentDef {
  Vec2 a{};                    ///< first end, m, finite
  Vec2 b{1.0, 0.0};            ///< second end, m, finite, != a
  double restitution = 0.0;    ///< e, finite, in [0, 1]
  double friction = 0.0;       ///< μ, finite and >= 0
  std::optional<Vec2> prev{};  ///< ghost vertex before a (a chain's previous point), m
  std::optional<Vec2> next{};  ///< ghost vertex after b (a chain's next point), m
  /// The kinematic body that carries it (null: static). For World::add_segment a live handle;
  /// in a WorldDef, a handle WorldDef::add_body returned.
  Entity body{};
  /// Drawing only (not in the definition or state hash): the segment's colour (alpha 0: the
  /// planes' colour) and line width, m (0: 2.5 px at any zoom), finite and >= 0.
  Rgba8 color{0, 0, 0, 0};
  double width = 0.0;
  /// One-way (a platform a body jumps up through): the segment blocks only what comes from
  /// its up side, the left normal of a -> b, up = (-(b - a).y, (b - a).x)/|b - a| (a -> b
  /// along +x: up = +y). A contact with it acts only when both
  ///   (a) its normal n, from the segment towards the other body, leans up: n·up > 0.1
  ///       (within about 84° of up; a touch at an end from the side or from below passes);
  ///   (b) the other body was not crossing at the tick's start: a disc's closest feature of
  ///       the segment then (the interior or an end) leaned up from it by (a) and it was no
  ///       more than 0.01 r (twice the disc slop) inside it, as is the contact itself; a
  ///       shape's manifold separation at the tick's start poses was at least -0.01 m (twice
  ///       the shape slop).
  /// Otherwise the body passes as if the segment were not there (its velocity the bits of
  /// free flight). Being a rule on each tick's start, a body half-way through stays
  /// unblocked until it is within that slop of clearing the surface: it is never snapped up.
  /// Landing on it is caught at any speed, as any segment's contact is. Default false:
  /// two-sided. docs/SHAPES.md, "One-way platforms".
  bool one_way = false;
  friend bool operator==(const SegmentDef&, const SegmentDef&) = default;
};

/// The segments of a polyline through `points` (m; at least 2, consecutive points distinct),
/// each joined to its neighbours by ghost vertices (SegmentDef); `closed` adds the segment from
/// the last point back to the first and joins it at both ends. Throws std::invalid_argument
/// for fewer than 2 points (3 when closed) or a zero-length segment (naming its index).
[[nodiscard]] std::vector<SegmentDef> polyline_segments(std::span<const Vec2> points,
                                                        double restitution, double friction,
                                                        bool closed = false);

}  // namespace fixstep
