// The pre-solve hook: a game's function the world asks, once per tick before the contact solve,
// whether each contact of a body with shapes may act (World::set_pre_solve).
#pragma once

#include <array>

#include "fixstep/core/entity.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

/// One contact manifold of the shape phase as the pre-solve hook sees it (Box2D's
/// b2PreSolveFcn with its b2Manifold): A is a body with shapes or a disc, or a plane or a
/// segment; B is always a body (with shapes, or a disc meeting shapes). Points and separations
/// are at the tick's start poses (the speculative manifold the solver works on), so a point
/// may still be apart (separation > 0) and meet within the tick.
struct PreSolveContact {
  Entity a{};           ///< body A; null when A is a plane or a segment
  Entity b{};           ///< body B
  int shape_a = -1;     ///< A's shape: its index in A's BodyDef::shapes; -1 for a disc or none
  int shape_b = -1;     ///< B's shape: its index in B's BodyDef::shapes; -1 for a disc
  int plane = -1;       ///< when A is a plane: its index in World::planes(); else -1
  int segment = -1;     ///< when A is a segment: its index in World::segments(); else -1
  Vec2 normal{};        ///< unit, from A towards B
  int point_count = 0;  ///< 1 or 2
  std::array<Vec2, 2> points{};  ///< world, m: midway between the two surfaces
  /// m, along the normal, < 0: overlapping; one per point.
  std::array<double, 2> separations{};
};

/// A pre-solve hook: returns false to disable `contact` for this tick (no impulse, no
/// bounce, no push-out, no continuous collision against it, and no contact event from it), true
/// to let it act. `context` is the pointer given to World::set_pre_solve (a game's own state).
///
/// Called from World::step on the stepping thread, once per manifold per tick, after the
/// one-way rule (a contact a one-way shape or segment already disabled is not offered), in the
/// order the solver builds its rows: the pairs of shapes in ascending order of the shape
/// phase's shape indices (bodies in the world's dense order, each body's shapes in
/// BodyDef::shapes order), then each shape's planes in plane order and segments in segment
/// order. The order depends on the world's state only: the same on every run, thread count and
/// platform, and after a restore. It must not change the world (no step, no edit); it may read
/// it. Replays, rollback and sync tests stay deterministic when its answer depends only on the
/// contact, the world's state and the game's own state that is itself restored with the world.
///
/// Covered: every contact of the shape phase (shape–shape, shape–disc, shape–plane,
/// shape–segment). Not covered: disc–disc, disc–plane and disc–segment contacts (the disc
/// phases, whose times of impact within the tick are not manifolds).
using PreSolveFn = bool (*)(const PreSolveContact& contact, void* context);

}  // namespace fixstep
