// Shape contacts, part 1b: the live shapes' pairs among themselves (or, in a world of fewer
// than min_grid_shapes shapes, every shape's: sweep_few) from fat boxes (fat_boxes.hpp), as the
// discs' are (disc_fat.cpp). A shape's box is its body's pose at the tick's start grown by the
// body's speculative margin (ShapeWorld::margin), so a stack that settles or a level that rests
// around a few movers moves its boxes by less than a fat box's margin, FatBoxes::margin of the
// body's extent, for many ticks; while every live box lies in its fat box, the grid's pairs of
// the live boxes are the fat pairs whose boxes overlap, in the grid's order, without building
// the grid. That holds whichever shape is at each place: two places whose boxes overlap have fat
// boxes that overlap, so the fat boxes serve while the live shapes come and go, as long as their
// count and each place's activity (a pair needs an active shape) are those the fat pairs were
// made with. The veto (never_pair) is applied to them as the grid applies it, since what it
// reads changes from tick to tick (a body's sleep and motion). The fat pairs are made without
// the veto, under the grid's memory limit, max_candidate_pairs.
//
// A fat box also reaches a few ticks of its body's motion ahead (ShapeFatPairs::ahead_ticks),
// and while few places have left their fat boxes since they were made, those are refitted
// alone, as Box2D's tree moves only the proxies that left theirs: a fresh fat box each, and
// their pairs found again (refit_fat_pairs), the others' pairs kept. So one fast body (a
// projectile over a settled level) no longer makes the whole world's fat boxes again each
// tick. Among few shapes (sweep_few) the sort and sweep costs less than fat boxes made again
// every few ticks: none are made there while a body moves more than its fat margin in a tick.
#include <algorithm>
#include <cmath>

#include "shape_world.hpp"

namespace fixstep::detail {

// The places the broadphase pairs: the live shapes' (rest_.boxes and rest_.active by place in
// live_shapes, vetoed by never_pair_live) or every shape's (boxes_, dynamic_, never_pair).
struct ShapeWorld::FatPlaces {
  std::span<const SweptBox> boxes;
  std::span<const std::uint8_t> active;
  std::span<const std::uint32_t> shapes;  ///< each place's shape (empty: place k is shape k)
  bool (*veto)(const void*, std::uint32_t, std::uint32_t);
  bool few;  ///< every shape of a world below min_grid_shapes (sweep_few's)
};

ShapeWorld::FatPlaces ShapeWorld::fat_places(bool live) const {
  if (live) {
    return {rest_.boxes, rest_.active, rest_.live_shapes, &ShapeWorld::never_pair_live, false};
  }
  return {boxes_, dynamic_, {}, &ShapeWorld::never_pair, true};
}

bool ShapeWorld::recycle_pairs(bool live, std::uint64_t most_pairs, std::uint64_t most_vetoed,
                               std::uint64_t& vetoed, std::vector<DiscPair>& out,
                               SecondThread* thread) {
  const FatPlaces at = fat_places(live);
  ShapeFatPairs& f = fat_;
  const std::size_t n = at.boxes.size();
  const bool same =
      f.fat.valid && f.fat.boxes.size() == n &&
      std::equal(f.active.begin(), f.active.end(), at.active.begin(), at.active.end());
  f.moved.clear();
  const std::size_t most_moved = ShapeFatPairs::most_stale(n);
  for (std::size_t k = 0; same && k < n && f.moved.size() <= most_moved; ++k) {
    if (!box_within(at.boxes[k], f.fat.boxes[k])) f.moved.push_back(static_cast<std::uint32_t>(k));
  }
  const bool kept = same && (f.moved.empty() || refit_fat_pairs(at, most_pairs));
  if (!kept && !(f.fat.left() && make_fat_pairs(at, most_pairs, thread))) return false;
  if (kept) ++f.kept_ticks, f.refit_ticks += f.moved.empty() ? 0 : 1;
  ++f.fat.age;
  out.clear();
  vetoed = 0;
  f.fat.each_overlapping(at.boxes, [&](const DiscPair& p) {  // then the veto, in one pass
    if (at.veto(this, p.a, p.b)) {
      ++vetoed;
    } else {
      out.push_back(p);
    }
  });
  return out.size() <= most_pairs && vetoed <= most_vetoed;
}

SweptBox ShapeWorld::fat_box(const FatPlaces& at, std::size_t k) const {
  const std::uint32_t shape = at.shapes.empty() ? static_cast<std::uint32_t>(k) : at.shapes[k];
  const std::uint32_t body = shapes_[shape].owner;
  const ShapedBody& owner = bodies_[body];
  const SweptBox& b = at.boxes[k];
  // (A static body's box moves only when the body is placed again.)
  if (owner.type == BodyType::static_body) return b;
  const double m = FatBoxes::margin * owner.extent;
  const double ahead = ShapeFatPairs::ahead_ticks * dt_;
  const double dx = ahead * state_[body].vx, dy = ahead * state_[body].vy;
  // (Written so that a NaN motion reaches nowhere ahead.)
  return SweptBox{b.min_x - m + (dx < 0.0 ? dx : 0.0), b.min_y - m + (dy < 0.0 ? dy : 0.0),
                  b.max_x + m + (dx > 0.0 ? dx : 0.0), b.max_y + m + (dy > 0.0 ? dy : 0.0)};
}

bool ShapeWorld::make_fat_pairs(const FatPlaces& at, std::uint64_t most_pairs,
                                SecondThread* thread) {
  ShapeFatPairs& f = fat_;
  const std::size_t n = at.boxes.size();
  f.fat.boxes.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    // Among few shapes, the sort and sweep costs less than fat boxes made again every few ticks:
    // none while a body moves more than its margin in a tick.
    const std::uint32_t body = shapes_[at.shapes.empty() ? k : at.shapes[k]].owner;
    if (at.few && margin_[body] - 2.0 * slop > FatBoxes::margin * bodies_[body].extent) {
      return false;
    }
    f.fat.boxes[k] = fat_box(at, k);
  }
  if (!f.grid.find_pairs(f.fat.boxes, at.active, most_pairs, f.fat.pairs, thread ? 2 : 1, thread)) {
    f.fat.rest_longer();  // crowded: the grid of the fat boxes cost a tick's broadphase
    return false;
  }
  f.active.assign(at.active.begin(), at.active.end());
  f.mark.assign(n, 0);
  f.stale.clear();
  f.fat.valid = true, f.fat.age = 0;
  return true;
}

// The pairs of the moved places, from the grid of the fat boxes as they were made (its
// entries of stale places skipped) and the stale places' fat boxes as they are now; each pair
// once (two moved places' by the first). The other pairs hold: neither fat box changed. Merged
// with them, the list is the grid's of today's fat boxes, in its (a, b) order. Bounded: past
// `most_work` (the grid's entries and the stale places looked at) or `most_pairs` found it
// stops, and the fat boxes are made again whole by the grid, whose own bound holds.
bool ShapeWorld::refit_fat_pairs(const FatPlaces& at, std::uint64_t most_pairs) {
  ShapeFatPairs& f = fat_;
  const std::size_t n = at.boxes.size();
  // (A box no level of the grid holds, not finite, is left to the grid made again.)
  if (f.stale.size() + f.moved.size() > ShapeFatPairs::most_stale(n) ||
      !f.grid.unindexed().empty()) {
    return false;
  }
  for (const std::uint32_t k : f.moved) {
    // (The grid's query needs finite bounds. Stopping here leaves the marks and fat boxes to
    // make_fat_pairs, which makes both again.)
    const SweptBox fat = fat_box(at, k);
    if (!std::isfinite(fat.min_x + fat.min_y + fat.max_x + fat.max_y)) return false;
    f.fat.boxes[k] = fat;
    if (f.mark[k] == 0) f.stale.push_back(k);
    f.mark[k] = 2;
  }
  const std::uint64_t most_work = 4 * std::uint64_t{n} + 256;
  std::uint64_t work = 0;
  f.fresh.clear();
  for (const std::uint32_t k : f.moved) {
    const SweptBox& q = f.fat.boxes[k];
    auto pair = [&](std::uint32_t i) {
      if (at.active[k] != 0 || at.active[i] != 0) {
        f.fresh.push_back({std::min(k, i), std::max(k, i)});
      }
    };
    work += f.grid.query(q, [&](std::uint32_t i, const SweptBox& /*then*/) {
      if (f.mark[i] == 0) pair(i);
    });
    for (const std::uint32_t i : f.stale) {
      if (i != k && !(f.mark[i] == 2 && i < k) && boxes_overlap(q, f.fat.boxes[i])) pair(i);
    }
    work += f.stale.size();
    if (work > most_work) {
      ++f.work_stops;
      return false;
    }
    if (f.fresh.size() > most_pairs) return false;
  }
  const auto before = [](const DiscPair& p, const DiscPair& q) {
    return pair_key(p) < pair_key(q);
  };
  std::sort(f.fresh.begin(), f.fresh.end(), before);
  // A moved place's old pairs out (found again), then the two sorted lists merged.
  std::erase_if(f.fat.pairs,
                [&](const DiscPair& p) { return f.mark[p.a] == 2 || f.mark[p.b] == 2; });
  for (const std::uint32_t k : f.moved) f.mark[k] = 1;
  if (f.fat.pairs.size() + f.fresh.size() > most_pairs) return false;
  f.merged.resize(f.fat.pairs.size() + f.fresh.size());
  std::merge(f.fat.pairs.begin(), f.fat.pairs.end(), f.fresh.begin(), f.fresh.end(),
             f.merged.begin(), before);
  std::swap(f.fat.pairs, f.merged);
  return true;
}

}  // namespace fixstep::detail
