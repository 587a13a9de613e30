// Shape contacts, part 1b: the broadphase (shape_world.hpp has the whole tick): the shapes'
// boxes at the tick's start, grown by each body's speculative margin, sorted by their lower x
// and swept; the candidate pairs in one order.
#include <algorithm>

#include "fixstep/core/limits.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

// Sort and sweep on the lower x bound; ties by index, so the order is the same everywhere.
// The shapes seldom change places between ticks: last tick's order is sorted again by
// insertion, which costs a pass when nothing has passed anything (bounded: past a few moves
// a shape, a full sort). Any sort gives the one order, so the result is the same either way.
void ShapeWorld::sort_boxes() {
  const std::size_t n = boxes_.size();
  auto before = [&](std::uint32_t l, std::uint32_t r) {
    const double a = boxes_[l].lower.x, b = boxes_[r].lower.x;
    return a != b ? a < b : l < r;
  };
  bool sorted = order_.size() == n;
  std::size_t budget = 8 * n;
  for (std::size_t i = 1; sorted && i < n; ++i) {
    const std::uint32_t k = order_[i];
    if (k >= n) sorted = false;
    std::size_t j = i;
    for (; sorted && j > 0 && before(k, order_[j - 1]); --j) {
      order_[j] = order_[j - 1];
      if (--budget == 0) sorted = false;
    }
    order_[j] = k;
  }
  if (!sorted) {
    order_.resize(n);
    for (std::uint32_t k = 0; k < n; ++k) order_[k] = k;
    std::sort(order_.begin(), order_.end(), before);
  }
  sorted_.resize(n);
  for (std::size_t i = 0; i < n; ++i) sorted_[i] = boxes_[order_[i]];
}

// The candidates by (a, b): counted into one run per a, then each run (a shape's few
// partners) by b. Every pair appears once, so this is the one order any sort gives.
void ShapeWorld::sort_candidates() {
  const std::size_t n = shapes_.size();
  first_.assign(n + 1, 0);
  for (const Candidate& c : candidates_) ++first_[c.a + 1];
  for (std::size_t k = 0; k < n; ++k) first_[k + 1] += first_[k];
  by_a_.resize(candidates_.size());
  for (const Candidate& c : candidates_) by_a_[first_[c.a]++] = c;  // first_[a]: run a's end
  for (std::size_t k = n; k > 0; --k) first_[k] = first_[k - 1];    // back to its start
  first_[0] = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto run = by_a_.begin() + first_[k], end = by_a_.begin() + first_[k + 1];
    std::sort(run, end, [](const Candidate& l, const Candidate& r) { return l.b < r.b; });
  }
  candidates_.swap(by_a_);
}

bool ShapeWorld::broadphase(double dt, ShapeTally& tally) {
  const std::size_t n = shapes_.size();
  // The work limits (limits.hpp), as the disc broadphase's: candidate pairs kept, and box
  // tests made (boxes overlapping in x, a tall column's), each bounded by the shape count.
  const std::uint64_t most_pairs = max_candidate_pairs(n);
  const std::uint64_t most_tests = max_vetoed_pairs(n);
  std::uint64_t tests = 0;
  margin_.resize(bodies_.size());
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) margin_[i] = margin(i, dt);
  boxes_.resize(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t owner = shapes_[k].owner;
    boxes_[k] = convex_aabb(shapes_[k].convex, start_pose(owner), margin_[owner]);
  }
  sort_boxes();
  candidates_.clear(), sensor_candidates_.clear(), wake_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t a = order_[i];
    const ShapeEntry& sa = shapes_[a];
    const Aabb box = sorted_[i];
    for (std::size_t j = i + 1; j < n; ++j) {
      if (sorted_[j].lower.x > box.upper.x) break;
      if (++tests > most_tests || candidates_.size() >= most_pairs) {
        const bool work = tests > most_tests;
        tally.cap = work ? "max_vetoed_pairs" : "max_candidate_pairs";
        tally.limit = work ? most_tests : most_pairs;
        tally.cap_body = sa.owner;
        return false;
      }
      if (!boxes_overlap(box, sorted_[j])) continue;
      const std::uint32_t b = order_[j];
      const ShapeEntry& sb = shapes_[b];
      if (sa.owner == sb.owner) continue;
      const ShapedBody& ba = bodies_[sa.owner];
      const ShapedBody& bb = bodies_[sb.owner];
      if (ba.type != BodyType::dynamic && bb.type != BodyType::dynamic) continue;
      if (ba.disc && bb.disc) continue;  // the disc phase's
      if (!should_collide(sa.filter, sb.filter)) continue;
      if (!unpaired_.empty() && unpaired(sa.owner, sb.owner)) continue;
      if (sa.sensor || sb.sensor) {  // a sensor sees what is not one, asleep or not
        if (sa.sensor != sb.sensor)
          sensor_candidates_.push_back(sa.sensor ? Candidate{a, b} : Candidate{b, a});
        continue;
      }
      // A sleeper is solved as static: a pair of two that do not move is left out, and a
      // sleeper paired with a moving body wakes (ShapeTick::wake).
      const bool wake_a = ba.asleep && moving(sb.owner), wake_b = bb.asleep && moving(sa.owner);
      if (!awake(ba) && !awake(bb) && !wake_a && !wake_b) continue;
      if (wake_a) wake_.push_back(sa.owner);
      if (wake_b) wake_.push_back(sb.owner);
      candidates_.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  sort_candidates();
  return true;
}

}  // namespace fixstep::detail
