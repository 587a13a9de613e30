// The shape world's fat boxes (fat_boxes.hpp) for the places its broadphase pairs (the live
// shapes, by their places in ShapeRest::live_shapes, or in a world below min_grid_shapes every
// shape): the fat boxes and their pairs hold while the places' count and activity are the ones
// they were made for and each place's box lies in its fat box (ShapeWorld::recycle_pairs,
// shape_fat_pairs.cpp). A place whose box leaves its fat box is refitted alone while few have
// (a fresh fat box, its pairs found again through the grid of the fat boxes: `grid`, whose
// entries of the refitted places, `stale`, are out of date and checked one by one instead). A
// cache: a copy (a snapshot) holds none, and assigning drops the target's; its next tick builds
// them again when they pay.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fat_boxes.hpp"

namespace fixstep::detail {

struct ShapeFatPairs {
  ShapeFatPairs() = default;
  ShapeFatPairs(const ShapeFatPairs& /*other*/) {}
  ShapeFatPairs& operator=(const ShapeFatPairs& /*other*/) {
    fat.valid = false;
    return *this;
  }
  ~ShapeFatPairs() = default;

  /// The places refitted since the fat boxes were made, at most this many (beyond it they are
  /// made again whole): a refit checks each place that left against every stale one, work that
  /// grows as the square of their count where a rebuild's grows as n.
  static std::size_t most_stale(std::size_t places) { return 8 + places / 16; }
  /// The ticks of its present motion a fat box reaches ahead of its box, as Box2D v2.4's
  /// tree reaches b2_aabbMultiplier (4) displacements ahead: a body in flight keeps its fat box
  /// for some ticks. 2 and 4 cost about as little on the ragdoll and box piles, 0 more.
  static constexpr double ahead_ticks = 2.0;

  FatBoxes fat;                         ///< by place
  std::vector<std::uint8_t> active;     ///< each place's activity then (the grid's `active`)
  GridBroadphase grid;                  ///< the grid of the fat boxes as they were made
  std::vector<std::uint32_t> stale;     ///< the places refitted since then, in that order
  std::vector<std::uint8_t> mark;       ///< by place: 1 stale, 2 refitted this tick (and stale)
  std::vector<std::uint32_t> moved;     ///< this tick's places outside their fat boxes (scratch)
  std::vector<DiscPair> fresh, merged;  ///< their pairs, and the whole list (scratch)
  std::uint64_t kept_ticks = 0;   ///< ticks served by fat boxes made in an earlier tick (tests)
  std::uint64_t refit_ticks = 0;  ///< of those, ticks that refitted some places (tests)
  std::uint64_t work_stops = 0;   ///< refits stopped at their work's bound (tests)
};

}  // namespace fixstep::detail
