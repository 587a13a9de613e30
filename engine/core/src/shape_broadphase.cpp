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

// The pairs of the sorted boxes from position `begin` to `end` with the boxes after them, into
// `out`: false, with the cap reached in `tally`, once more than `most_tests` boxes overlapping
// in x were tested or `most_pairs` candidates kept (counted from `out`'s start).
bool ShapeWorld::sweep_boxes(std::size_t begin, std::size_t end, Found& out,
                             std::uint64_t most_tests, std::uint64_t most_pairs,
                             ShapeTally& tally) const {
  // (Local copies: `out` could alias the members, which the loops would then load again.)
  const std::size_t n = sorted_.size();
  const Aabb* const sorted = sorted_.data();
  const std::uint32_t* const order = order_.data();
  std::uint64_t tests = 0, kept = out.candidates.size();
  for (std::size_t i = begin; i < end; ++i) {
    const std::uint32_t a = order[i];
    const ShapeEntry& sa = shapes_[a];
    const Aabb box = sorted[i];
    for (std::size_t j = i + 1; j < n; ++j) {
      if (sorted[j].lower.x > box.upper.x) break;
      if (++tests > most_tests || kept >= most_pairs) {
        const bool work = tests > most_tests;
        tally.cap = work ? "max_vetoed_pairs" : "max_candidate_pairs";
        tally.limit = work ? most_tests : most_pairs;
        tally.cap_body = sa.owner;
        return false;
      }
      if (!boxes_overlap(box, sorted[j])) continue;
      const std::uint32_t b = order[j];
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
          out.sensors.push_back(sa.sensor ? Candidate{a, b} : Candidate{b, a});
        continue;
      }
      // A sleeper is solved as static: a pair of two that do not move is left out, and a
      // sleeper paired with a moving body wakes (ShapeTick::wake).
      const bool wake_a = ba.asleep && moving(sb.owner), wake_b = bb.asleep && moving(sa.owner);
      if (!awake(ba) && !awake(bb) && !wake_a && !wake_b) continue;
      if (wake_a) out.wake.push_back(sa.owner);
      if (wake_b) out.wake.push_back(sb.owner);
      out.candidates.push_back({std::min(a, b), std::max(a, b)});
      ++kept;
    }
  }
  out.tests = tests;
  return true;
}

bool ShapeWorld::broadphase(double dt, ShapeTally& tally, SecondThread* thread) {
  const std::size_t n = shapes_.size();
  // The work limits (limits.hpp), as the disc broadphase's: candidate pairs kept, and box
  // tests made (boxes overlapping in x, a tall column's), each bounded by the shape count.
  const std::uint64_t most_pairs = max_candidate_pairs(n);
  const std::uint64_t most_tests = max_vetoed_pairs(n);
  margin_.resize(bodies_.size());
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) margin_[i] = margin(i, dt);
  boxes_.resize(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t owner = shapes_[k].owner;
    boxes_[k] = convex_aabb(shapes_[k].convex, start_pose(owner), margin_[owner]);
  }
  sort_boxes();
  found_[0].clear(), found_[1].clear();
  bool whole = false;
  if (thread != nullptr) {  // by halves of the sorted boxes, then joined in their order
    ShapeTally halves[2];
    bool done[2] = {false, false};
    auto job = [&](int h) {
      done[h] = sweep_boxes(h == 0 ? 0 : n / 2, h == 0 ? n / 2 : n, found_[h], most_tests,
                            most_pairs, halves[h]);
    };
    thread->both(job);
    // Within the limits together: the one result; else the cap as one sweep meets it.
    whole = done[0] && done[1] && found_[0].tests + found_[1].tests <= most_tests &&
            found_[0].candidates.size() + found_[1].candidates.size() < most_pairs;
    if (whole) {
      Found& f = found_[0];
      const Found& g = found_[1];
      f.candidates.insert(f.candidates.end(), g.candidates.begin(), g.candidates.end());
      f.sensors.insert(f.sensors.end(), g.sensors.begin(), g.sensors.end());
      f.wake.insert(f.wake.end(), g.wake.begin(), g.wake.end());
    } else {
      found_[0].clear();
    }
  }
  if (!whole && !sweep_boxes(0, n, found_[0], most_tests, most_pairs, tally)) return false;
  candidates_.swap(found_[0].candidates), sensor_candidates_.swap(found_[0].sensors);
  wake_.swap(found_[0].wake);
  sort_candidates();
  return true;
}

}  // namespace fixstep::detail
