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
#include <algorithm>

#include "shape_world.hpp"

namespace fixstep::detail {

// The places the broadphase pairs: the live shapes' (rest_.boxes and rest_.active by place in
// live_shapes, vetoed by never_pair_live) or every shape's (boxes_, dynamic_, never_pair).
struct ShapeWorld::FatPlaces {
  std::span<const SweptBox> boxes;
  std::span<const std::uint8_t> active;
  std::span<const std::uint32_t> shapes;  ///< each place's shape (empty: place k is shape k)
  bool (*veto)(const void*, std::uint32_t, std::uint32_t);
};

ShapeWorld::FatPlaces ShapeWorld::fat_places(bool live) const {
  if (live) return {rest_.boxes, rest_.active, rest_.live_shapes, &ShapeWorld::never_pair_live};
  return {boxes_, dynamic_, {}, &ShapeWorld::never_pair};
}

bool ShapeWorld::recycle_pairs(bool live, std::uint64_t most_pairs, std::uint64_t most_vetoed,
                               std::uint64_t& vetoed, std::vector<DiscPair>& out,
                               SecondThread* thread) {
  const FatPlaces at = fat_places(live);
  ShapeFatPairs& f = fat_;
  const std::size_t n = at.boxes.size();
  bool inside = f.fat.valid && f.fat.boxes.size() == n &&
                std::equal(f.active.begin(), f.active.end(), at.active.begin(), at.active.end());
  for (std::size_t k = 0; inside && k < n; ++k) inside = box_within(at.boxes[k], f.fat.boxes[k]);
  if (!inside && !(f.fat.left() && make_fat_pairs(at, most_pairs, thread))) return false;
  if (inside) ++f.kept_ticks;
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

bool ShapeWorld::make_fat_pairs(const FatPlaces& at, std::uint64_t most_pairs,
                                SecondThread* thread) {
  ShapeFatPairs& f = fat_;
  const std::size_t n = at.boxes.size();
  f.fat.boxes.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t shape = at.shapes.empty() ? static_cast<std::uint32_t>(k) : at.shapes[k];
    const std::uint32_t body = shapes_[shape].owner;
    // (A static body's box moves only when the body is placed again: no margin.)
    const ShapedBody& owner = bodies_[body];
    const double m = owner.type == BodyType::static_body ? 0.0 : FatBoxes::margin * owner.extent;
    // A body that moves more than m in a tick leaves its fat box in the next one.
    if (margin_[body] - 2.0 * slop > m) return false;
    const SweptBox& b = at.boxes[k];
    f.fat.boxes[k] = SweptBox{b.min_x - m, b.min_y - m, b.max_x + m, b.max_y + m};
  }
  if (!grid_.find_pairs(f.fat.boxes, at.active, most_pairs, f.fat.pairs, thread ? 2 : 1, thread)) {
    f.fat.rest_longer();  // crowded: the grid of the fat boxes cost a tick's broadphase
    return false;
  }
  f.active.assign(at.active.begin(), at.active.end());
  f.fat.valid = true, f.fat.age = 0;
  return true;
}

}  // namespace fixstep::detail
