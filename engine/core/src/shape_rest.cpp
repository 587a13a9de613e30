// The resting lists of a shape world (shape_rest.hpp): made again when stale, and the
// broadphase of a large world over them.
#include <algorithm>
#include <iterator>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/limits.hpp"
#include "shape_world.hpp"
#include "sorted_lists.hpp"

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
  if (!r.whole && r.indexed && r.split && r.keyed_dt == dt) {
    rebuild_flipped(dt);
  } else {
    rebuild_whole(dt);
  }
  r.stale = false, r.whole = false;
  r.flipped.clear();
  rebuild_live_joints();
}

// What the tick's passes would make of a resting body, which none changes while it rests: made
// again only where the last rebuild did not find it resting with the same state. Returns
// whether it kept what that rebuild made (its shapes' boxes among it).
bool ShapeWorld::settle_body(std::uint32_t i, double dt) {
  ShapeRest& r = rest_;
  const ShapedBody& b = bodies_[i];
  ShapeState& s = state_[i];
  const ShapeRest::Key key = key_of(s);
  const bool kept = r.keyed[i] != 0 && r.keys[i] == key;
  if (!kept) {
    s.q0 = rot_of(s.a0), s.turn = rot_of(s.a - s.a0);
    margin_[i] = margin(i, dt);
    r.keys[i] = key, r.keyed[i] = 1;
    for (std::uint32_t k = b.first; k < b.first + b.count; ++k) box_shape(k);
  }
  s.q = s.q0, turned_at_[i] = s.a;
  velocity_[i] = {s.vx, s.vy, s.w};
  body_colors_[i] = 0;
  return kept;
}

void ShapeWorld::rebuild_whole(double dt) {
  ShapeRest& r = rest_;
  r.split = shapes_.size() >= min_grid_shapes;
  r.live.clear(), r.live_shapes.clear(), r.statics.clear();
  r.order.clear(), r.order_kept.clear();
  const std::size_t n = bodies_.size();
  margin_.resize(n), turned_at_.resize(n), body_colors_.resize(n);
  velocity_.resize(n + 1);  // and the zero slot (prepare_rows)
  boxes_.resize(shapes_.size()), dynamic_.resize(shapes_.size()), tags_.resize(shapes_.size());
  if (r.keyed_dt != dt) r.forget();
  r.keys.resize(n), r.keyed.resize(n), r.keyed_dt = dt;
  std::uint32_t kernel_bodies = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    const ShapedBody& b = bodies_[i];
    kernel_bodies = std::max(kernel_bodies, b.body + 1);
    if (b.type == BodyType::static_body) r.statics.push_back(i);
    if (!rests(b, r.split)) {
      state_[i].q0 = rot_of(state_[i].a0);
      r.keyed[i] = 0;
      r.live.push_back(i);
      for (std::uint32_t k = b.first; k < b.first + b.count; ++k) r.live_shapes.push_back(k);
      continue;
    }
    const bool kept = settle_body(i, dt);
    for (std::uint32_t k = b.first; k < b.first + b.count; ++k) {
      if (shapes_[k].sensor) {
        r.live_shapes.push_back(k);
        continue;
      }
      r.order.push_back(k), r.order_kept.push_back(kept ? 1 : 0);
    }
  }
  r.settle_grid(boxes_, r.live_shapes.size());
  r.of_body.assign(2 * std::size_t{kernel_bodies}, ShapeRest::none);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::size_t at = 2 * std::size_t{bodies_[i].body};
    r.of_body[r.of_body[at] == ShapeRest::none ? at : at + 1] = i;
  }
}

void ShapeWorld::unsettle_body(std::uint32_t body) {
  ShapeRest& r = rest_;
  if (r.stale && r.whole) return;
  const std::size_t at = 2 * std::size_t{body};
  if (at + 1 >= r.of_body.size() || r.flipped.size() > bodies_.size()) {
    unsettle();  // (a body the last whole rebuild did not know, or flips past counting)
    return;
  }
  for (const std::size_t slot : {at, at + 1}) {
    const std::uint32_t i = r.of_body[slot];
    if (i == ShapeRest::none) continue;
    if (!r.stale) r.stale = true, r.whole = false;
    r.flipped.push_back(i);
  }
}

std::span<const std::uint32_t> ShapeWorld::visit_few() {
  ShapeRest& r = rest_;
  r.merged.assign(r.flipped.begin(), r.flipped.end());
  std::sort(r.merged.begin(), r.merged.end());
  r.merged.erase(std::unique(r.merged.begin(), r.merged.end()), r.merged.end());
  r.visit.clear();
  std::set_union(r.live.begin(), r.live.end(), r.merged.begin(), r.merged.end(),
                 std::back_inserter(r.visit));
  return r.visit;
}

// The lists made again where only the bodies in `flipped` changed (fell asleep, woke, or had
// their position or velocity set), the others' state, boxes and places holding: a body that
// came to rest leaves the live ones and its shapes become extras; one that woke joins them and
// its shapes leave the grid (entries gone) or the extras; one that rests with another state
// (a static body moved) has its entries gone and is an extra with its new boxes.
// O(live + flipped + extras), and the grid indexed again once spent.
void ShapeWorld::rebuild_flipped(double dt) {
  ShapeRest& r = rest_;
  sort_unique(r.flipped);
  r.leave.clear(), r.join.clear(), r.to_extras.clear(), r.join_shapes.clear();
  r.from_extras.clear();
  auto leave_grid = [&](std::uint32_t k) {  // false: it is an extra
    const std::uint32_t g = r.slot[k];
    if (g == ShapeRest::none) return false;
    r.gone[g] = 1, r.slot[k] = ShapeRest::none, ++r.gone_count;
    return true;
  };
  for (const std::uint32_t i : r.flipped) {
    const ShapedBody& b = bodies_[i];
    const bool was_live = std::binary_search(r.live.begin(), r.live.end(), i);
    if (!rests(b, r.split)) {
      r.keyed[i] = 0;
      if (was_live) continue;
      r.join.push_back(i);
      for (std::uint32_t k = b.first; k < b.first + b.count; ++k) {
        if (shapes_[k].sensor) continue;
        r.join_shapes.push_back(k);
        if (!leave_grid(k)) r.from_extras.push_back(k);
      }
      continue;
    }
    const bool kept = settle_body(i, dt);
    if (was_live) r.leave.push_back(i);
    if (!was_live && kept) continue;
    for (std::uint32_t k = b.first; k < b.first + b.count; ++k) {
      if (shapes_[k].sensor) continue;
      // (An extra that rests again with another state keeps its place: its box is new.)
      if (was_live || leave_grid(k)) r.to_extras.push_back(k);
    }
  }
  // Every list ascending: the flipped bodies are, and each body's shapes follow one another.
  remove_sorted(r.live, r.leave, r.merged);
  insert_sorted(r.live, r.join, r.merged);
  remove_sorted(r.live_shapes, r.to_extras, r.merged);  // (those not live are not there)
  insert_sorted(r.live_shapes, r.join_shapes, r.merged);
  remove_sorted(r.extras, r.from_extras, r.merged);
  insert_sorted(r.extras, r.to_extras, r.merged);
  for (const std::uint32_t i : r.live) state_[i].q0 = rot_of(state_[i].a0);
  if (!r.grid_spent(r.live_shapes.size())) return;
  r.order.clear();
  for (std::uint32_t g = 0; g < r.resting.size(); ++g) {
    if (r.gone[g] == 0) r.order.push_back(r.resting[g]);
  }
  insert_sorted(r.order, r.extras, r.merged);
  r.index_grid(boxes_);
}

void ShapeRest::settle_grid(std::span<const SweptBox> all, std::size_t live_shapes) {
  extras.clear();
  gone_count = 0;
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
  if (!indexed || grid_spent(live_shapes)) index_grid(all);
}

bool ShapeRest::grid_spent(std::size_t live_shapes) const {
  const std::size_t n = resting.size() - gone_count + extras.size();
  return extras.size() * live_shapes > n || gone_count * 4 > resting.size();
}

void ShapeRest::index_grid(std::span<const SweptBox> all) {
  resting.assign(order.begin(), order.end());
  boxes.clear();  // (the broadphase's scratch, lent: the grid copies the boxes)
  for (const std::uint32_t k : resting) boxes.push_back(all[k]);
  grid.index(boxes);
  slot.assign(all.size(), none);
  for (std::uint32_t g = 0; g < resting.size(); ++g) slot[resting[g]] = g;
  gone.assign(resting.size(), 0);
  gone_count = 0;
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
// places; from the fat boxes while they hold, shape_fat_pairs.cpp), then each live shape's pairs
// with the resting shapes its box overlaps: a pair needs a dynamic shape (a sleeper's is), as the
// grid's does. Both limits count the totals.
bool ShapeWorld::pair_live(ShapeTally& tally, SecondThread* thread) {
  ShapeRest& r = rest_;
  const std::size_t n = shapes_.size();
  const std::uint64_t most_pairs = max_candidate_pairs(n), most_vetoed = max_vetoed_pairs(n);
  r.boxes.resize(r.live_shapes.size()), r.active.resize(r.live_shapes.size());
  for (std::size_t i = 0; i < r.live_shapes.size(); ++i) {
    r.boxes[i] = boxes_[r.live_shapes[i]], r.active[i] = dynamic_[r.live_shapes[i]];
  }
  std::uint64_t vetoed = 0;
  if (!recycle_pairs(true, most_pairs, most_vetoed, vetoed, r.pairs, thread)) {
    const GridBroadphase::PairVeto veto{&ShapeWorld::never_pair_live, this, most_vetoed};
    grid_.set_veto(&veto);
    const bool found =
        grid_.find_pairs(r.boxes, r.active, most_pairs, r.pairs, thread ? 2 : 1, thread);
    grid_.set_veto(nullptr);
    if (!found) {
      name_cap(tally, grid_.stopped_by_veto());
      return false;
    }
    vetoed = grid_.rejected();
  }
  for (DiscPair& p : r.pairs) p = {r.live_shapes[p.a], r.live_shapes[p.b]};
  r.cross.clear();
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
