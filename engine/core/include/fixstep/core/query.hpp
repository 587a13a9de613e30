// What World's spatial queries take and give: ray casts, point, box, circle and shape overlap
// queries against the bodies' discs (Collider) and shapes (BodyDef::shapes), the static
// half-planes (PlaneDef) and segments, in the spirit of Box2D's b2World_CastRay,
// b2World_OverlapAABB and b2QueryFilter.
#pragma once

#include <cstdint>

#include "fixstep/core/components.hpp"
#include "fixstep/core/entity.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

/// Which shapes a query sees (Box2D's b2QueryFilter): a disc or a body's shape is seen when its
/// category meets `mask` and its own mask meets `category` (the rule should_collide() applies
/// between two discs, without groups). Discs with collide = false are seen too: a query asks
/// about geometry, not contacts. `sensors` covers sensor discs and sensor shapes alike.
struct QueryFilter {
  std::uint64_t category = default_category;  ///< bits: what the query counts as
  std::uint64_t mask = all_categories;        ///< bits: the disc categories it sees
  bool sensors = false;                       ///< true: sensors are seen too
  bool planes = true;                         ///< false: planes are not seen
  bool segments = true;                       ///< false: segments are not seen
};

/// Whether `filter` sees a disc with filter `disc` (sensors and planes aside).
[[nodiscard]] constexpr bool query_sees(const QueryFilter& filter, const CollisionFilter& disc) {
  return (disc.category & filter.mask) != 0 && (disc.mask & filter.category) != 0;
}

/// Farthest a ray may reach from the origin, m (|origin.x| + |origin.y| + |translation|): a
/// thousand times max_state_magnitude, where no body is, and far below where the squares of a
/// ray's terms overflow.
inline constexpr double max_query_reach = 1e15;

/// Marks a hit that is no plane (QueryHit::plane, RayHit::plane).
inline constexpr std::uint32_t no_plane = 0xffffffffu;

/// A shape a query found: a body's disc (body), one of a body's shapes (body and shape, an
/// index into World::shapes(body)), a plane (plane, an index into World::planes()) or a segment
/// (segment, an index into World::segments()); body is the null entity for the last two.
struct QueryHit {
  Entity body{};
  std::uint32_t plane = no_plane;
  std::uint32_t segment = no_plane;  ///< no_plane: no segment
  std::uint32_t shape = no_plane;    ///< no_plane: no body shape (a disc, plane or segment)
  friend constexpr bool operator==(const QueryHit&, const QueryHit&) = default;
};

/// Where a ray first enters a shape: the ray is origin + s · translation for s in [0, 1].
struct RayHit {
  Entity body{};                   ///< the body whose disc or shape it hit, or null
  std::uint32_t plane = no_plane;  ///< the plane it hit (index into World::planes())
  double fraction = 0.0;           ///< s at the hit, in [0, 1]
  Vec2 point{};                    ///< m, origin + fraction · translation
  Vec2 normal{};                   ///< unit outward normal of the shape at point
  /// The segment it hit (index into World::segments(); its normal faces the ray's origin), or
  /// no_plane.
  std::uint32_t segment = no_plane;
  /// The body's shape it hit (index into World::shapes(body)), or no_plane (a disc, plane or
  /// segment).
  std::uint32_t shape = no_plane;
  friend constexpr bool operator==(const RayHit&, const RayHit&) = default;
};

}  // namespace fixstep
