// The bodies a shape world's tick leaves alone: static bodies and sleepers (ContactSettings::
// sleep). Neither moves in a tick (a sleeper is solved as a static body until a moving body
// pairs with it, which wakes it and makes the lists again), so their state, their boxes and
// the grid of their boxes hold from one tick to the next, and the tick's passes visit only the
// live bodies: the awake dynamic ones and the kinematic ones. A resting body's state is the one
// the kernel gives it (WorldKernel::resolve_shapes): its position, zero velocity, its angle, the
// rotations of that angle, and the margin and box of its motion, which is none.
//
// The kernel makes the lists stale (ShapeWorld::unsettle) whenever a resting body may change:
// a body falls asleep or wakes, an edit (set_body, set_position, set_velocity), the shapes
// rebuilt; a copy (a snapshot, a rollback) is stale too. The next tick then fills every
// body's state and makes the lists again (ShapeWorld::rebuild_rest), O(bodies + shapes); the
// ticks between visit O(live bodies + the resting shapes their boxes meet).
//
// The broadphase's pairs are the same, in the same order: the pairs of live shapes from the
// grid of their boxes, and each live shape's pairs with resting ones from the resting grid
// (GridBroadphase::query), merged by (a, b). Two resting shapes are never a pair: neither moves
// nor wakes the other (ShapeWorld::never_pair). A sensor is live wherever its body is, so that
// what it senses at rest stays sensed. Below ShapeWorld::min_grid_shapes shapes nothing rests:
// every body is live, as before the lists.
//
// A joint is live where one of its ends is (live_joints): one whose two ends rest, asleep or
// static, would move neither, and its rows, its forest and the account of it are left as its
// last live tick left them (its impulses, for the warm start when its island wakes). Creating
// or destroying a joint rebuilds the shapes, which makes the lists stale.
#pragma once

#include <cstdint>
#include <vector>

#include "grid_broadphase.hpp"

namespace fixstep::detail {

struct ShapeRest {
  ShapeRest() = default;
  /// A copy is stale and holds nothing: its next tick makes its lists (a copy of the grid
  /// has no table either). Assigning keeps the target's storage and makes it stale.
  ShapeRest(const ShapeRest&) {}
  ShapeRest& operator=(const ShapeRest&) {
    stale = true;
    return *this;
  }
  ~ShapeRest() = default;

  bool stale = true;
  /// Whether resting shapes have their own grid (ShapeWorld::min_grid_shapes shapes or more);
  /// otherwise every body is live.
  bool split = false;
  std::vector<std::uint32_t> live;         ///< bodies the tick visits, ascending
  std::vector<std::uint32_t> live_shapes;  ///< the shapes boxed each tick, ascending
  std::vector<std::uint32_t> statics;      ///< the static bodies, ascending
  std::vector<std::uint32_t> resting;      ///< the resting grid's shapes, by its index
  std::vector<std::uint32_t> live_joints;  ///< the tick's joints (indices), ascending
  GridBroadphase grid;                     ///< the resting shapes' boxes (index() only)
  // Scratch: the live shapes' boxes and activity by their place in live_shapes (the
  // broadphase's; rebuild_rest first lends `boxes` the resting shapes' boxes for the grid,
  // which copies them), their pairs in those places, and the live-resting pairs.
  std::vector<SweptBox> boxes;
  std::vector<std::uint8_t> active;
  std::vector<DiscPair> pairs, cross;
};

}  // namespace fixstep::detail
