// Shape contacts, part 1b: the broadphase (shape_world.hpp has the whole tick): the shapes'
// boxes at the tick's start, grown by each body's speculative margin, paired by the
// hierarchical grid the discs use (grid_broadphase.hpp: O(n + pairs), where a sweep and prune
// on x scans every box of a column of boxes), in (a, b) order; a hundred or so by a sort and
// sweep on x, whose work (n²/2 box tests at most) is then below the grid's fixed costs. Of a
// large world's shapes only the live ones are boxed and paired each tick, the resting ones
// found through their own grid (shape_rest.hpp, shape_rest.cpp). Either way, while every box
// lies in its fat box the pairs come from the fat boxes instead (shape_fat_pairs.cpp).
#include <algorithm>
#include <cmath>

#include "fixstep/core/limits.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

// The pairs the grid drops as it finds them (read only, from either thread): shapes of one
// body, two discs (the disc phase's), those a collision filter or a joint keeps apart, and two
// that neither move nor wake the other (a sleeper is solved as static). From the shapes' tags
// (32 bytes each, made with the boxes), not from their entries.
bool ShapeWorld::never_pair(const void* context, std::uint32_t a, std::uint32_t b) {
  const auto& w = *static_cast<const ShapeWorld*>(context);
  const PairTag &ta = w.tags_[a], &tb = w.tags_[b];
  if (ta.owner == tb.owner || (ta.flags & tb.flags & PairTag::disc) != 0) return true;
  if (!should_collide(ta.filter, tb.filter)) return true;
  if (!w.unpaired_.empty() && w.unpaired(ta.owner, tb.owner)) return true;
  if (((ta.flags | tb.flags) & PairTag::sensor) != 0) {  // a sensor sees what is not one
    return (ta.flags & PairTag::sensor) == (tb.flags & PairTag::sensor);
  }
  if (((ta.flags | tb.flags) & PairTag::awake) != 0) return false;
  return !wakes(ta, tb) && !wakes(tb, ta);
}

void ShapeWorld::box_shape(std::uint32_t k) {
  const ShapeEntry& e = shapes_[k];
  const ShapedBody& body = bodies_[e.owner];
  const Aabb b = convex_aabb(e.convex, start_pose(e.owner), margin_[e.owner]);
  boxes_[k] = SweptBox{b.lower.x, b.lower.y, b.upper.x, b.upper.y};
  dynamic_[k] = body.type == BodyType::dynamic ? 1 : 0;  // two others never pair
  const std::uint32_t none = 0;
  tags_[k] =
      PairTag{e.filter, e.owner,
              (e.sensor ? PairTag::sensor : none) | (body.disc ? PairTag::disc : none) |
                  (awake(body) ? PairTag::awake : none) | (body.asleep ? PairTag::asleep : none) |
                  (moving(e.owner) ? PairTag::moving : none)};
}

void ShapeWorld::name_cap(ShapeTally& tally, bool by_veto) const {
  const std::size_t n = shapes_.size();
  tally.cap = by_veto ? "max_vetoed_pairs" : "max_candidate_pairs";
  tally.limit = by_veto ? max_vetoed_pairs(n) : max_candidate_pairs(n);
  tally.cap_body = shapes_[largest_box()].owner;
}

bool ShapeWorld::broadphase(double dt, ShapeTally& tally, SecondThread* thread) {
  // The live bodies' margins and shapes' boxes; the resting ones' hold (shape_rest.hpp).
  for (const std::uint32_t i : rest_.live) margin_[i] = margin(i, dt);
  for (const std::uint32_t k : rest_.live_shapes) box_shape(k);
  candidates_.clear(), sensor_candidates_.clear(), wake_.clear();
  if (!rest_.split) {
    sweep_few();
  } else if (!pair_live(tally, thread)) {
    return false;
  }
  for (const DiscPair& p : pairs_) {
    const PairTag &ta = tags_[p.a], &tb = tags_[p.b];
    if (((ta.flags | tb.flags) & PairTag::sensor) != 0) {
      const bool a_senses = (ta.flags & PairTag::sensor) != 0;
      sensor_candidates_.push_back(a_senses ? Candidate{p.a, p.b} : Candidate{p.b, p.a});
      continue;
    }
    // A sleeper paired with a moving body wakes (ShapeTick::wake).
    if (wakes(tb, ta)) wake_.push_back(ta.owner);
    if (wakes(ta, tb)) wake_.push_back(tb.owner);
    candidates_.push_back({p.a, p.b});
  }
  return true;
}

// A few shapes: sorted by their boxes' lower x (from last tick's order, by insertion: a pass
// when nothing passed anything; ties by index, so any sort gives this order) and swept, the
// pairs then put in (a, b) order: the grid's pairs in the grid's order. Below min_grid_shapes
// neither limit can be reached (n(n - 1)/2 pairs at most).
void ShapeWorld::sweep_few() {
  const auto n = static_cast<std::uint32_t>(shapes_.size());
  std::uint64_t vetoed = 0;  // (neither limit can be reached)
  if (recycle_pairs(false, max_candidate_pairs(n), max_vetoed_pairs(n), vetoed, pairs_, nullptr)) {
    return;  // from the fat boxes (shape_fat_pairs.cpp)
  }
  const SweptBox* const box = boxes_.data();
  auto before = [&](std::uint32_t l, std::uint32_t r) {
    return box[l].min_x != box[r].min_x ? box[l].min_x < box[r].min_x : l < r;
  };
  // A box with a NaN bound on x overlaps nothing, and would not sort.
  auto sortable = [&](std::uint32_t k) { return !std::isnan(box[k].min_x + box[k].max_x); };
  bool same = order_.size() == n;
  for (std::uint32_t k = 0; same && k < n; ++k) same = sortable(k);
  if (!same) {
    order_.clear();
    for (std::uint32_t k = 0; k < n; ++k) {
      if (sortable(k)) order_.push_back(k);
    }
  }
  for (std::size_t i = 1; i < order_.size(); ++i) {
    const std::uint32_t k = order_[i];
    std::size_t j = i;
    for (; j > 0 && before(k, order_[j - 1]); --j) order_[j] = order_[j - 1];
    order_[j] = k;
  }
  swept_.clear();
  for (std::size_t i = 0; i < order_.size(); ++i) {
    const std::uint32_t a = order_[i];
    for (std::size_t j = i + 1; j < order_.size() && box[order_[j]].min_x <= box[a].max_x; ++j) {
      const std::uint32_t b = order_[j];
      if (!boxes_overlap(box[a], box[b]) || (dynamic_[a] == 0 && dynamic_[b] == 0)) continue;
      const DiscPair p{std::min(a, b), std::max(a, b)};
      if (!never_pair(this, p.a, p.b)) swept_.push_back(p);
    }
  }
  order_pairs(swept_, {}, n, first_, pairs_);
}

// The shape with the widest box (the first of equals; a NaN box first): the one a fault names.
std::uint32_t ShapeWorld::largest_box() const {
  std::uint32_t best = 0;
  double widest = -1.0;
  for (std::uint32_t k = 0; k < boxes_.size(); ++k) {
    const SweptBox& b = boxes_[k];
    const double w = std::max(b.max_x - b.min_x, b.max_y - b.min_y);
    if (std::isnan(w)) return k;
    if (w > widest) widest = w, best = k;
  }
  return best;
}

}  // namespace fixstep::detail
