// The one-way rule (SegmentDef::one_way, ShapeDef::one_way): whether a one-way surface blocks
// one contact. Every path that meets one calls one_way_blocks with the surface's up, the
// contact's normal and how far the other body was from the surface when its motion began: the
// disc contacts with segments (world_segments.cpp, disc_walls.cpp, disc_segments.cpp), the shape
// contacts with segments and one-way shapes (shape_world.cpp) and the character mover. Internal
// to core; not installed.
//
// The rule. A one-way surface of unit up u blocks a contact of unit normal n (pointing from the
// surface towards the other body) only when
//   (a) n·u > one_way_min_dot: the contact leans up (a box platform's top face, n = u, blocks;
//       its sides, n·u = 0 up to rounding, and its bottom, n·u = -1, do not), and
//   (b) s0 >= -slop, s0 the other body's separation from the surface (m, < 0: overlap) at the
//       start of its motion: it was not already crossing the surface then.
// Because (b) looks at where the motion starts, a body moving up through a platform is never
// caught half-way (its overlap at each tick's start is deeper than the slop until it has all
// but cleared the surface), and a body falling onto it from above is caught at any speed (its
// separation at the start is positive).
#pragma once

#include <cmath>

#include "fixstep/core/segment.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep::detail {

/// The least n·up (the cosine of the angle between a contact's normal and the surface's up)
/// at which a one-way surface blocks: 0.1, faces within about 84° of up. Above 0 by far more
/// than rounding, so that a face perpendicular to up (a rotated box platform's side) never
/// blocks by a rounding error.
inline constexpr double one_way_min_dot = 0.1;
/// The overlap (m) a shape may start a tick with and still be blocked: twice the shape
/// contacts' slop (ShapeWorld::slop, 5 mm), which a body resting on a platform stays within.
inline constexpr double one_way_shape_slop = 0.01;
/// The overlap a disc may start a tick with and still be blocked, as a fraction of its radius:
/// twice the disc contacts' slop (DiscContacts::slop, 0.5 % of the radius).
inline constexpr double one_way_disc_slop = 0.01;

/// Whether a one-way surface of unit up `up` blocks a contact of unit normal `normal` (from
/// the surface towards the other body) whose other body was `start_separation` (m, < 0:
/// overlapping) from the surface at the start of its motion, allowing `slop` (m, >= 0) of
/// overlap there: normal·up > one_way_min_dot and start_separation >= -slop.
///
/// For the character mover: a capsule at p moving by d meets a one-way surface first with
/// normal n (a sweep's hit normal, from the surface towards the capsule); it is blocked there
/// when one_way_blocks(up, n, s0, one_way_shape_slop), s0 the capsule's separation from the
/// surface at p (its distance, or minus its depth when overlapping at p). A capsule not
/// blocked passes the surface as if it were not there for the rest of that move.
[[nodiscard]] constexpr bool one_way_blocks(Vec2 up, Vec2 normal, double start_separation,
                                            double slop) {
  return dot(normal, up) > one_way_min_dot && start_separation >= -slop;
}

/// The up of a one-way segment a -> b: its left normal (-(b - a).y, (b - a).x)/|b - a|,
/// given the segment's unit direction (dx, dy).
[[nodiscard]] constexpr Vec2 one_way_segment_up(double dx, double dy) {
  return {-dy, dx};
}

/// The up of one-way segment `s` from its definition: the left normal of a -> b.
[[nodiscard]] inline Vec2 one_way_up_of(const SegmentDef& s) {
  const Vec2 d = s.b - s.a;
  const double len = std::sqrt(dot(d, d));
  return one_way_segment_up(d.x / len, d.y / len);
}

}  // namespace fixstep::detail
