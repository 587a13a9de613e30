// A character mover (Godot's CharacterBody2D.move_and_slide, Box2D v3.2's mover): a kinematic
// body with one capsule shape that the world moves by collide-and-slide each tick, at the
// velocity the game wants, over slopes and steps, riding platforms and pushing crates.
#pragma once

#include <optional>
#include <string>

#include "fixstep/core/entity.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

/// What makes a body a mover (BodyDef::mover). The body must be kinematic, carry exactly one
/// shape, a capsule (its segment upright or not, its radius r), at angle 0 with no angular
/// velocity; it never turns (angular inputs leave it as it is).
///
/// Each tick the body's velocity v (m/s; BodyInputKind::velocity or World::set_velocity, kept
/// until changed, as any kinematic body's) is the velocity the game WANTS. Gravity is the
/// game's: like Godot, a game adds g·dt to v.y while MoverState::on_floor is false. The world
/// moves the capsule by collide-and-slide (docs/MOVER.md) against the planes, segments and
/// polylines, and the shapes and discs of every other body (one-way ones only from their up
/// side: it jumps up through them and stands on them), and leaves in the body's velocity
/// the slid velocity (MoverState::velocity): its component into what it met taken out, and on
/// landing its vertical component zeroed, so the game's gravity sum starts again.
struct MoverDef {
  /// rad, in (0, π/2): a surface whose normal is within this angle of +y is a floor (it stands
  /// on it, walks up and down it at its wanted speed, and does not slide down it standing);
  /// steeper, a wall it cannot climb. Default 50°.
  double max_floor_angle = 0.8726646259971648;
  /// m, in [0, capsule radius): the highest step (a corner of a box, polygon or polyline above
  /// its foot) it walks up. A corner higher than this is a wall.
  double step_height = 0.2;
  /// m, finite and >= 0: walking off a floor (down a slope, a step, over a crest), it is moved
  /// down onto a floor within this distance below instead of leaving the ground.
  double snap_distance = 0.1;
  /// N, finite and >= 0: the most force it exerts on a dynamic body it walks into: an impulse
  /// of at most push_force·dt per tick at the contact point, along the contact normal (only
  /// what brings the body's point up to the mover's speed there). 0: it pushes nothing.
  double push_force = 0.0;
  /// m, finite, > 0 and below half the capsule radius: the gap it keeps from everything (its
  /// contact offset); a surface within 2·skin touches it (MoverState).
  double skin = 0.005;
  friend bool operator==(const MoverDef&, const MoverDef&) = default;
};

/// What a mover met in its last tick (World::mover_state). Normals are unit vectors from the
/// surface towards the mover; a floor's is the surface's own (a corner it stands on gives the
/// face beside it).
struct MoverState {
  bool on_floor = false;    ///< stands on a floor (within 2·skin, not moving up)
  bool on_wall = false;     ///< walked into a wall (a surface steeper than the floor angle)
  bool on_ceiling = false;  ///< moved into a surface facing down (within the floor angle of −y)
  Vec2 floor_normal{};      ///< when on_floor
  Vec2 wall_normal{};       ///< when on_wall
  /// The body it stands on (a body's shape or disc, or the kinematic body carrying the
  /// segment), or null (a plane, a static segment, or no floor). A kinematic floor carries the
  /// mover with its motion the next tick: its translation and its turn about its centre.
  Entity floor_body{};
  Vec2 velocity{};      ///< m/s: the slid velocity, the body's velocity after the tick
  Vec2 displacement{};  ///< m: how far the last tick moved it (carried and slid)
  friend bool operator==(const MoverState&, const MoverState&) = default;
};

/// What is wrong with `def` in words naming the field, or nothing: every value finite, the
/// floor angle in (0, π/2), step_height, snap_distance, push_force >= 0, skin > 0. The checks
/// against the capsule (step_height < r, skin < r/2) come with the body (World::create_body).
[[nodiscard]] std::optional<std::string> mover_problem(const MoverDef& def);

}  // namespace fixstep
