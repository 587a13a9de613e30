// Fat boxes (Box2D's enlarged AABBs, b2_aabbMargin): each box widened by a margin when the
// broadphase last ran on them, and their pairs. Two boxes that overlap lie in fat boxes that
// overlap, so while every box of the tick stays inside its fat box, the tick's pairs are the
// fat pairs whose boxes overlap: the broadphase's pairs, in its order, without running it. The
// discs keep one (disc_fat.cpp), the shape world another for the shapes its broadphase pairs
// (shape_fat_pairs.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "grid_broadphase.hpp"

namespace fixstep::detail {

struct FatBoxes {
  /// The margin, as a fraction of each body's size (a disc's radius, a shaped body's
  /// extent), and the ticks the fat boxes rest after a rebuild that served a single tick (a
  /// gas: its boxes leave them every tick), doubled for each such rebuild in a row up to
  /// rest_most.
  static constexpr double margin = 0.25;
  static constexpr std::uint32_t rest_first = 8, rest_most = 512;
  bool valid = false;      ///< the pairs are those of `boxes` under today's flags and filters
  std::uint32_t age = 0;   ///< ticks they served
  std::uint32_t rest = 0;  ///< ticks left before another try (after one that served one tick)
  std::uint32_t pause = rest_first;  ///< the next rest: doubled by each such try in a row
  std::vector<SweptBox> boxes;
  std::vector<DiscPair> pairs;

  /// Called when a tick's boxes do not all lie in the fat ones: drops them, and returns
  /// whether to build them again this tick (false while they rest: after a rebuild that served
  /// a single tick, for `pause` ticks, twice as long after each such rebuild in a row).
  bool left() {
    if (valid && age <= 1) {
      rest_longer();
    } else if (valid) {
      pause = rest_first;
    }
    valid = false;
    if (rest == 0) return true;
    --rest;
    return false;
  }
  /// Rests the fat boxes for `pause` ticks (a rebuild that served a single tick, or one the
  /// pairs' limit stopped), and doubles the next rest.
  void rest_longer() { rest = pause, pause = std::min(2 * pause, rest_most); }
  /// `f(pair)` for each fat pair among pairs[begin, end) (all of them by default) whose `now`
  /// boxes overlap (closed intervals), in their order: the broadphase's pairs of `now` while
  /// each lies in its fat box.
  template <class F>
  void each_overlapping(std::span<const SweptBox> now, F&& f, std::size_t begin = 0,
                        std::size_t end = SIZE_MAX) const {
    end = std::min(end, pairs.size());
    for (std::size_t i = begin; i < end; ++i) {
      if (boxes_overlap(now[pairs[i].a], now[pairs[i].b])) f(pairs[i]);
    }
  }
  /// Those pairs among pairs[begin, end) into `out` (cleared first), in their order.
  void overlapping(std::span<const SweptBox> now, std::vector<DiscPair>& out, std::size_t begin,
                   std::size_t end) const {
    out.clear();
    each_overlapping(
        now, [&](const DiscPair& p) { out.push_back(p); }, begin, end);
  }
};

}  // namespace fixstep::detail
