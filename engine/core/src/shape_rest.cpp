// The resting lists of a shape world (shape_rest.hpp): made again when stale, and the
// broadphase of a large world over them.
#include <algorithm>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/limits.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

namespace {

/// Whether a body rests in a world whose lists split: a static body, or a sleeper.
bool rests(const ShapedBody& b, bool split) {
  return split && (b.type == BodyType::static_body || (b.type == BodyType::dynamic && b.asleep));
}

ShapeRest::Key key_of(const ShapeState& s) {
  return {{bits_of(s.x0), bits_of(s.y0), bits_of(s.a0), bits_of(s.x), bits_of(s.y), bits_of(s.a),
           bits_of(s.vx), bits_of(s.vy), bits_of(s.w)}};
}

}  // namespace

void ShapeWorld::rebuild_rest(double dt) {
  ShapeRest& r = rest_;
  r.stale = false;
  r.split = shapes_.size() >= min_grid_shapes;
  r.live.clear(), r.live_shapes.clear(), r.statics.clear();
  r.order.clear(), r.order_kept.clear();
  const std::size_t n = bodies_.size();
  margin_.resize(n), turned_at_.resize(n), body_colors_.resize(n);
  velocity_.resize(n + 1);  // and the zero slot (prepare_rows)
  boxes_.resize(shapes_.size()), dynamic_.resize(shapes_.size()), tags_.resize(shapes_.size());
  if (r.keyed_dt != dt) r.forget();
  r.keys.resize(n), r.keyed.resize(n), r.keyed_dt = dt;
  for (std::uint32_t i = 0; i < n; ++i) {
    const ShapedBody& b = bodies_[i];
    ShapeState& s = state_[i];
    if (b.type == BodyType::static_body) r.statics.push_back(i);
    if (!rests(b, r.split)) {
      s.q0 = rot_of(s.a0);
      r.keyed[i] = 0;
      r.live.push_back(i);
      for (std::uint32_t k = b.first; k < b.first + b.count; ++k) r.live_shapes.push_back(k);
      continue;
    }
    // What the tick's passes would make of it, which none changes while it rests: made again
    // only where the last rebuild did not find it resting with the same state.
    const ShapeRest::Key key = key_of(s);
    const bool kept = r.keyed[i] != 0 && r.keys[i] == key;
    if (!kept) {
      s.q0 = rot_of(s.a0), s.turn = rot_of(s.a - s.a0);
      margin_[i] = margin(i, dt);
      r.keys[i] = key, r.keyed[i] = 1;
    }
    s.q = s.q0, turned_at_[i] = s.a;
    velocity_[i] = {s.vx, s.vy, s.w};
    body_colors_[i] = 0;
    for (std::uint32_t k = b.first; k < b.first + b.count; ++k) {
      if (!kept) box_shape(k);
      if (shapes_[k].sensor) {
        r.live_shapes.push_back(k);
        continue;
      }
      r.order.push_back(k), r.order_kept.push_back(kept ? 1 : 0);
    }
  }
  r.settle_grid(boxes_, r.live_shapes.size());
  rebuild_live_joints();
}

void ShapeRest::settle_grid(std::span<const SweptBox> all, std::size_t live_shapes) {
  extras.clear();
  std::size_t gone_count = 0;
  if (indexed) {
    std::fill(gone.begin(), gone.end(), std::uint8_t{1});
    for (std::size_t i = 0; i < order.size(); ++i) {
      const std::uint32_t k = order[i];
      const std::uint32_t g = k < slot.size() ? slot[k] : none;
      if (order_kept[i] != 0 && g != none) {
        gone[g] = 0;
      } else {
        extras.push_back(k);
      }
    }
    for (std::uint32_t g = 0; g < resting.size(); ++g) {
      if (gone[g] == 0) continue;
      ++gone_count;
      if (slot[resting[g]] == g) slot[resting[g]] = none;  // it left: it comes back an extra
    }
  }
  const std::size_t n = order.size();
  if (indexed && extras.size() * live_shapes <= n && gone_count * 4 <= resting.size()) return;
  resting.assign(order.begin(), order.end());
  boxes.clear();  // (the broadphase's scratch, lent: the grid copies the boxes)
  for (const std::uint32_t k : resting) boxes.push_back(all[k]);
  grid.index(boxes);
  slot.assign(all.size(), none);
  for (std::uint32_t g = 0; g < resting.size(); ++g) slot[resting[g]] = g;
  gone.assign(n, 0);
  extras.clear();
  indexed = true;
}

void ShapeRest::near(const SweptBox& q, std::span<const SweptBox> all,
                     std::vector<std::uint32_t>& out) const {
  out.clear();
  grid.query(q, [&](std::uint32_t g, const SweptBox&) {
    if (gone[g] == 0) out.push_back(resting[g]);
  });
  for (const std::uint32_t g : grid.unindexed()) {
    if (gone[g] == 0 && boxes_overlap(q, all[resting[g]])) out.push_back(resting[g]);
  }
  for (const std::uint32_t k : extras) {
    if (boxes_overlap(q, all[k])) out.push_back(k);
  }
  std::sort(out.begin(), out.end());
}

// The joints with a live end (shape_rest.hpp), from rebuild_rest's bodies.
void ShapeWorld::rebuild_live_joints() {
  ShapeRest& r = rest_;
  r.live_joints.clear();
  auto live = [&](std::uint32_t body) {
    return body != JointRecord::none && !rests(bodies_[body], r.split);
  };
  for (std::uint32_t i = 0; i < joints_.size(); ++i) {
    const JointRecord& j = joints_[i];
    if (live(j.a) || live(j.b)) r.live_joints.push_back(i);
  }
}

bool ShapeWorld::never_pair_live(const void* context, std::uint32_t a, std::uint32_t b) {
  const auto& w = *static_cast<const ShapeWorld*>(context);
  return never_pair(context, w.rest_.live_shapes[a], w.rest_.live_shapes[b]);
}

// The grid's pairs among the live shapes (the activity and veto of every shape's, in their
// places), then each live shape's pairs with the resting shapes its box overlaps: a pair
// needs a dynamic shape (a sleeper's is), as the grid's does. Both limits count the totals.
bool ShapeWorld::pair_live(ShapeTally& tally, SecondThread* thread) {
  ShapeRest& r = rest_;
  const std::size_t n = shapes_.size();
  const std::uint64_t most_pairs = max_candidate_pairs(n), most_vetoed = max_vetoed_pairs(n);
  r.boxes.resize(r.live_shapes.size()), r.active.resize(r.live_shapes.size());
  for (std::size_t i = 0; i < r.live_shapes.size(); ++i) {
    r.boxes[i] = boxes_[r.live_shapes[i]], r.active[i] = dynamic_[r.live_shapes[i]];
  }
  const GridBroadphase::PairVeto veto{&ShapeWorld::never_pair_live, this, most_vetoed};
  grid_.set_veto(&veto);
  const bool found =
      grid_.find_pairs(r.boxes, r.active, most_pairs, r.pairs, thread ? 2 : 1, thread);
  grid_.set_veto(nullptr);
  if (!found) {
    name_cap(tally, grid_.stopped_by_veto());
    return false;
  }
  for (DiscPair& p : r.pairs) p = {r.live_shapes[p.a], r.live_shapes[p.b]};
  r.cross.clear();
  std::uint64_t vetoed = grid_.rejected();
  bool over = false;
  auto meet = [&](std::uint32_t l, std::uint32_t k) {
    if (over || (dynamic_[l] == 0 && dynamic_[k] == 0)) return;
    const DiscPair p{std::min(l, k), std::max(l, k)};
    if (never_pair(this, p.a, p.b)) {
      over = ++vetoed > most_vetoed;
      if (over) name_cap(tally, true);
      return;
    }
    r.cross.push_back(p);
    over = r.pairs.size() + r.cross.size() > most_pairs;
    if (over) name_cap(tally, false);
  };
  for (const std::uint32_t l : r.live_shapes) {
    r.near(boxes_[l], boxes_, r.around);
    for (const std::uint32_t k : r.around) meet(l, k);
    if (over) return false;
  }
  // Both in (a, b) order, merged: O(pairs + c log c) for c live-resting pairs, where a sort
  // by a over every shape would cost each tick O(shapes).
  auto key_less = [](const DiscPair& p, const DiscPair& q) { return pair_key(p) < pair_key(q); };
  std::sort(r.cross.begin(), r.cross.end(), key_less);
  pairs_.resize(r.pairs.size() + r.cross.size());
  std::merge(r.pairs.begin(), r.pairs.end(), r.cross.begin(), r.cross.end(), pairs_.begin(),
             key_less);
  return true;
}

}  // namespace fixstep::detail
