// The character mover's geometry (mover.hpp): a capsule's contacts with the obstacles near it,
// what each contact is to a walker (floor, step corner, wall, ceiling), the plane solver that
// finds the motion those contacts allow, the sweep that stops it short of what it would enter,
// and one tick's collide-and-slide (docs/MOVER.md). Internal (not installed); the kernel's side
// (which obstacles, where, the pushes) is world_movers.cpp.
//
// The method is Box2D v3.2's mover (src/mover.c b2SolvePlanes, b2ClipVector; the Mover sample's
// loop: collide, solve the planes, cast along the solved motion, repeat) with Godot's walking
// rules (CharacterBody2D: floor angle, constant speed on slopes, stop on slopes, block on walls,
// snap to floor). Our own code; only + - * / and sqrt (GJK and conservative advancement from
// shape_distance.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "fixstep/core/entity.hpp"
#include "fixstep/core/mover.hpp"
#include "shape_geom.hpp"

namespace fixstep::detail {

/// One thing a mover may meet, in world coordinates: a shape or disc (convex placed at its
/// pose for this tick), a segment (a two-vertex convex with the normals of its chain's
/// neighbours), or a half-plane n·x >= offset.
struct MoverObstacle {
  static constexpr std::uint32_t none = ~std::uint32_t{0};
  Convex convex;
  bool plane = false;
  Vec2 plane_normal{};
  double plane_offset = 0.0;
  /// A segment's neighbours' unit normals (left of prev→a, of b→next), when it has them: a
  /// corner where two segments of a chain meet has the faces of both.
  std::array<Vec2, 2> ghost{};
  int ghosts = 0;
  bool segment = false;
  std::uint32_t body = none;  ///< dense index of a body (none: a plane or a static segment)
  Entity entity{};            ///< the body, or the kinematic body carrying the segment
  bool dynamic = false;       ///< pushed rather than stood against
  /// A one-way surface (SegmentDef::one_way, ShapeDef::one_way) of unit `up`: met only by a
  /// contact whose normal leans up (one_way.hpp); one the capsule was not above at the tick's
  /// start is not gathered at all.
  bool one_way = false;
  Vec2 up{};
};

/// What a contact is to a walker.
enum class MoverSurface : std::uint8_t { floor, ledge, wall, ceiling };

/// A contact of the mover's capsule with one obstacle.
struct MoverContact {
  Vec2 normal{};   ///< unit, from the obstacle towards the mover
  Vec2 support{};  ///< the surface's own normal: a floor's, or a ledge's face
  Vec2 point{};    ///< m, on the obstacle's surface
  double distance = 0.0;
  /// m: the least n·d a motion d must keep, skin − distance; a dynamic body's no more than 0
  /// (the mover may stay as close as the contact solver left it, and not go deeper).
  double need = 0.0;
  std::uint32_t obstacle = 0;
  MoverSurface surface = MoverSurface::wall;
};

/// The mover's shape and rules, in the kernel's double.
struct MoverGeometry {
  Convex capsule;       ///< in the body frame (origin: the body's position)
  double lowest = 0.0;  ///< m: the capsule's lowest point's height above the body's position
  double cos_floor = 0.0;
  MoverDef def;
};

/// One mover's collide-and-slide over one tick. Holds scratch vectors that a kernel keeps from
/// tick to tick (no allocation once warm).
class MoverSlide {
 public:
  /// The contacts of the capsule at `position` within 2·skin of an obstacle, classified.
  void contacts(const MoverGeometry& g, std::span<const MoverObstacle> obstacles, Vec2 position,
                std::vector<MoverContact>& out) const;
  /// The fraction in [0, 1] of `delta` the capsule at `position` moves before it comes within
  /// skin of an obstacle (one it starts within 2·skin of, a contact, stops it only when `delta`
  /// goes deeper than the plane solver allows); obstacles of entity `skip` (not null) are left
  /// out.
  [[nodiscard]] double cast(const MoverGeometry& g, std::span<const MoverObstacle> obstacles,
                            Vec2 position, Vec2 delta, Entity skip) const;
  /// The motion nearest `target` (m) that keeps every contact c at n·d >= c.need, each
  /// contact pushing along its own direction (a floor up, a wall too steep to climb
  /// horizontally while walking, anything else along its normal): projected Gauss-Seidel on
  /// the accumulated pushes, clamped at zero (b2SolvePlanes), at most 20 sweeps.
  [[nodiscard]] Vec2 solve(std::span<const MoverContact> contacts, Vec2 target, bool walking) const;
  /// Moves `position` towards position + delta in at most 5 rounds of contacts, solve and cast
  /// (Box2D's Mover sample); returns the new position.
  Vec2 slide(const MoverGeometry& g, std::span<const MoverObstacle> obstacles, Vec2 position,
             Vec2 delta, bool walking);

  std::vector<MoverContact> contacts_;  ///< scratch
};

/// The push direction of a contact (MoverSlide::solve).
[[nodiscard]] Vec2 mover_push_direction(const MoverContact& c, bool walking);

}  // namespace fixstep::detail
