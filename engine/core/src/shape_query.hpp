// The geometry World's queries ask of a shape (shape_raycast.cpp): where a ray enters a convex
// shape with radius, exactly, and how far a point lies from its core. Internal (not installed).
//
// A Convex here is in world coordinates (convex_placed at its body's pose): the queries place
// every shape once when the query grid is built. Only + - * / and sqrt.
#pragma once

#include "shape_geom.hpp"

namespace fixstep::detail {

/// Where the ray p + s t (s in [0, 1]) enters the disc (c, r), as s; NaN when it does not, or
/// when it starts inside the disc or on its circle (Box2D's rule), or t is zero: the smaller
/// root of |p + s t - c|² = r², written without cancellation.
[[nodiscard]] double ray_disc(Vec2 p, Vec2 t, Vec2 c, double r);

/// Where a ray enters a shape: s (NaN: it does not) and the unit outward normal there.
struct RayEntry {
  double s = 0.0;
  Vec2 normal{};
};

/// Where the ray o + s t (s in [0, 1]) enters `c` (world coordinates): its core polygon swept
/// by a disc of c.radius, exactly. The surface of a rounded polygon is its edges pushed out by
/// the radius along their normals and an arc of the radius about each vertex: the ray is
/// clipped by the pushed edges' half-planes (the mitered polygon, a slab for a capsule); an
/// entry within the entering edge's length is on its flat part, one beyond it lies in a
/// corner's miter, and the ray then enters on that corner's circle or not at all (a circle is
/// its one vertex's disc). A ray starting inside or on the surface does not enter (Box2D's
/// rule, as ray_disc); s is NaN then.
[[nodiscard]] RayEntry ray_convex(const Convex& c, Vec2 o, Vec2 t);

/// The squared distance from p to c's core (the polygon without its radius), m²: 0 inside it.
[[nodiscard]] double core_gap2(const Convex& c, Vec2 p);

/// Whether p lies in `c` (its surface included): core_gap2 <= radius².
[[nodiscard]] bool convex_contains(const Convex& c, Vec2 p);

/// Whether a and b (world coordinates) overlap or touch: distance() between them <= 0.
[[nodiscard]] bool convex_overlap(const Convex& a, const Convex& b);

}  // namespace fixstep::detail
