// The shape world's fat boxes (fat_boxes.hpp) for the places its broadphase pairs (the live
// shapes, by their places in ShapeRest::live_shapes, or in a world below min_grid_shapes every
// shape): the fat boxes and their pairs hold while the places' count and activity are the ones
// they were made for and each place's box lies in its fat box (ShapeWorld::recycle_pairs,
// shape_fat_pairs.cpp). A cache: a copy (a snapshot) holds none, and assigning drops the
// target's; its next tick builds them again when they pay.
#pragma once

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

  FatBoxes fat;                      ///< by place
  std::vector<std::uint8_t> active;  ///< each place's activity then (the grid's `active`)
  std::uint64_t kept_ticks = 0;      ///< ticks served by fat boxes made in an earlier tick (tests)
};

}  // namespace fixstep::detail
