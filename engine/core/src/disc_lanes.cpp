// Disc contacts, phase 1 on two threads: a tick's impacts in two lanes, with the bits of one.
// The candidate pairs join discs into groups (a pair's impact changes only its two discs, and
// their predictions read only their pairs); whole groups go to two lanes by a line across the
// discs' spread (assign_lanes()), and each lane runs its own events in its own time order on its
// own thread (disc_queue.cpp), changing its own discs only. The lanes can meet
// only where an impact sends a disc beyond its box (reach()): its new path meeting the other
// lane's disc (its box as paired, or a band it grew). Then, or where a lane's count of
// predictions passes its share of the cap or its slots for extra pairs run out, both stop; and
// where one lane's count of predictions could have passed the cap (check_lanes()), the lanes are
// not taken either: the tick's impacts run again in one lane from the motions at the tick's
// start. When they did
// not meet, the result is the one lane's: the lanes' impacts change disjoint discs, the events
// of a lane keep the one lane's order among them (extra pairs numbered in the order made, after
// the broadphase's), the impact logs merge by time (two at the same time in different lanes:
// run again), and the extra pairs are sorted (finish_reach) as one lane sorts them. See
// docs/perf/contact_solver_plan.md, "The gas's impacts on two threads".
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "disc_contacts.hpp"
#include "fixstep/core/limits.hpp"
#include "island_union.hpp"

namespace fixstep::detail {

template <class Real>
bool DiscContacts<Real>::lanes_met() {
  return lanes_met_.is_set();
}

template <class Real>
bool DiscContacts<Real>::meet_other_lane(ImpactLane& q) {
  q.met = true;
  lanes_met_.set();
  return false;
}

template <class Real>
bool DiscContacts<Real>::lanes_may_run(const Tick& tick) {
  if (!sharing() || !live_all_ || sleeper_count_ != 0 || tick.segments != nullptr ||
      pairs_.size() < min_lane_pairs) {
    return false;
  }
  if (lane_rest_ > 0) {  // after ticks in a row without lanes (rest_lanes())
    --lane_rest_;
    return false;
  }
  return true;
}

template <class Real>
double DiscContacts<Real>::centre(std::uint32_t k, int axis) const {
  return double(axis == 0 ? x0_[k] : y0_[k]);  // read only while the impacts run
}

template <class Real>
bool DiscContacts<Real>::assign_lanes() {
  // The pairs' groups (island_union.hpp: the least disc of a group is its root), cut by a line
  // across the wider side of the paired discs' spread, at their mean: a group goes with its
  // root, by where it was at the tick's start. (Discs wander from the order they were made in,
  // so an index would not cut space in two.)
  const auto n = static_cast<std::uint32_t>(discs_.size());
  lane_parent_.resize(n);
  for (const DiscPair& p : pairs_) lane_parent_[p.a] = p.a, lane_parent_[p.b] = p.b;
  for (const DiscPair& p : pairs_) join(lane_parent_, p.a, p.b);
  // The axis along which the cut best keeps the discs' index halves apart: the passes before
  // the impacts (build_motions) leave each index half in one thread's cache.
  const std::uint32_t half = n / 2;
  double sum[2] = {0, 0};
  for (const DiscPair& p : pairs_) sum[0] += centre(p.a, 0), sum[1] += centre(p.a, 1);
  std::size_t agree[2] = {0, 0};
  for (int axis = 0; axis < 2; ++axis) {
    const double cut = sum[axis] / double(pairs_.size());
    for (const DiscPair& p : pairs_) agree[axis] += (centre(p.a, axis) >= cut) == (p.a >= half);
  }
  lane_axis_ = agree[1] > agree[0] ? 1 : 0;
  lane_cut_ = sum[lane_axis_] / double(pairs_.size());
  if (!std::isfinite(lane_cut_)) return false;
  lane_of_.resize(n);  // the paired discs' (a disc in no pair: lane(), by its own box)
  for (const DiscPair& p : pairs_) {
    for (const std::uint32_t k : {p.a, p.b}) {
      lane_of_[k] = centre(find_root(lane_parent_, k), lane_axis_) >= lane_cut_ ? 1 : 0;
    }
  }
  std::size_t first = 0;
  for (const DiscPair& p : pairs_) first += lane_of_[p.a] == 0 ? 1 : 0;
  // Lanes of a quarter of the pairs or less would not pay for the split (a pile: one group).
  return 4 * first > pairs_.size() && 4 * (pairs_.size() - first) > pairs_.size();
}

template <class Real>
void DiscContacts<Real>::start_lanes(const Tick& tick) {
  // Both lanes mark on from the larger count: every mark left in partner_mark_ (by either lane,
  // or by lane 0 alone in the ticks since) is at most that, so no new mark equals a stale one.
  // A lane's marks stay below 2^31 in a tick (the cap), so neither wraps while they run.
  lanes_[0].mark = lanes_[1].mark = std::max(lanes_[0].mark, lanes_[1].mark);
  if (lanes_[0].mark >= 0x80000000u) {
    std::fill(partner_mark_.begin(), partner_mark_.end(), 0u);
    lanes_[0].mark = lanes_[1].mark = 0;
  }
  if (fat_.valid && !fat_grid_.value) rebuild_fat_grid(pass_threads(tick));  // read by both
  horizon_ = tick.dt;
  lanes_met_.clear();
  const std::uint64_t cap = max_tick_predictions(discs_.size());
  for (std::uint8_t h = 0; h < 2; ++h) {
    ImpactLane& q = lanes_[h];
    start_reach(q);
    q.split = true, q.id = h, q.met = false, q.next_extra = 0;
    q.stats = ContactStats{}, q.log.clear(), q.heap.clear(), q.held.clear();
    q.budget = EventBudget{0, 0, cap / 4};
  }
  // Each lane's slots for its extra pairs: base + 2 i + id, i < extra_slots.
  const std::size_t extra_slots = std::max<std::size_t>(256, base_pairs_ / 2);
  pairs_.resize(base_pairs_ + 2 * extra_slots);
}

template <class Real>
void DiscContacts<Real>::first_lane_events(ImpactLane& q, const Tick& tick) {
  DiscEvent ev;
  for (std::uint32_t i = 0; i < base_pairs_; ++i) {
    if (lane(pairs_[i].a) == q.id && next_event(i, 0.0, tick.dt, ev)) q.heap.push_back(ev);
  }
  if (!tick.planes.empty()) {  // bounced by the plane pass
    each_bounced([&](std::uint32_t k) {
      if (lane(k) == q.id) q.heap.push_back(switch_of(tick, k));
    });
  }
  std::make_heap(q.heap.begin(), q.heap.end(), later_event);
}

template <class Real>
void DiscContacts<Real>::check_lanes() {
  // Where a lane's band meets the other lane's grown box (its box as paired was asked while it
  // ran), one lane would have paired them: only bands that reach across the other lane's bands'
  // extent on the cut's axis can.
  auto low = [&](const SweptBox& b) { return lane_axis_ == 0 ? b.min_x : b.min_y; };
  auto high = [&](const SweptBox& b) { return lane_axis_ == 0 ? b.max_x : b.max_y; };
  double lo[2] = {0, 0}, hi[2] = {0, 0};
  for (std::uint8_t h = 0; h < 2; ++h) {
    lo[h] = std::numeric_limits<double>::infinity(), hi[h] = -lo[h];
    for (const auto& [k, band] : lanes_[h].bands) {
      lo[h] = std::min(lo[h], low(band)), hi[h] = std::max(hi[h], high(band));
    }
  }
  for (std::uint8_t h = 0; h < 2 && !lanes_[0].met; ++h) {
    const ImpactLane& other = lanes_[1 - h];
    for (const auto& grown : lanes_[h].bands) {
      const std::uint32_t k = grown.first;
      const SweptBox& band = grown.second;
      if (high(band) < lo[1 - h] || low(band) > hi[1 - h]) continue;  // clear of its bands
      other.grid.query(band, [&](std::uint32_t j) {
        if (boxes_overlap(band, boxes_[j]) && may_pair(k, j)) lanes_[0].met = true;
      });
    }
  }
  if (!lanes_[0].met && one_lane_count() > max_tick_predictions(discs_.size())) {
    lanes_[0].met = true;  // the one lane might have stopped at the cap: it decides
  }
}

template <class Real>
std::uint64_t DiscContacts<Real>::one_lane_count() const {
  // At most what one lane would have counted: each lane's count, except that one lane's grid
  // holds both lanes' entries. A query (one a band, over the band's cells) looks at the wide
  // boxes, then at each cell's bucket or, past as many cells as entries, at every entry, and
  // reach() counts each disc it is given once more: with both grids' longest buckets and wide
  // boxes as they are at the end, at most 2 wide + cells (1 + 2 longest), over 16 and rounded
  // up, for every band of both lanes.
  const ImpactLane &a = lanes_[0], &b = lanes_[1];
  const std::uint64_t wide = a.grid.wide() + b.grid.wide();
  const std::uint64_t longest = a.grid.longest_bucket() + b.grid.longest_bucket();
  std::uint64_t count = a.budget.again + b.budget.again;
  for (const ImpactLane& q : lanes_) {
    for (const auto& [k, band] : q.bands) {
      count += (2 * wide + a.grid.cells(band) * (1 + 2 * longest)) / 16 + 1;
    }
  }
  return count;
}

template <class Real>
bool DiscContacts<Real>::merge_lane_logs() {
  // By time; two impacts at one time in different lanes keep the one lane's order by pair
  // index, which the extra pairs' numbering does not give: run again.
  std::vector<DiscImpact>& out = lane_log_;
  const std::vector<DiscImpact>&a = lanes_[0].log, &b = lanes_[1].log;
  out.clear();
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i].time == b[j].time) return false;
    out.push_back(a[i].time < b[j].time ? a[i++] : b[j++]);
  }
  out.insert(out.end(), a.begin() + static_cast<std::ptrdiff_t>(i), a.end());
  out.insert(out.end(), b.begin() + static_cast<std::ptrdiff_t>(j), b.end());
  lanes_[0].log.swap(out);
  return true;
}

template <class Real>
void DiscContacts<Real>::end_lanes() {
  // Lane 1's extra pairs and grown boxes forgotten (lane 0's are, lazily, by start_reach).
  ImpactLane& second = lanes_[1];
  for (const ExtraPair& e : second.extra) extra_head_[e.disc] = ExtraPair::none;
  for (const GrownBox& g : second.grown) grown_of_[g.disc] = GrownBox::none;
  second.extra.clear(), second.grown.clear(), second.bands.clear(), lanes_[0].bands.clear();
  lanes_[0].mark = lanes_[1].mark = std::max(lanes_[0].mark, lanes_[1].mark);
  for (ImpactLane& q : lanes_) q.split = false;
}

template <class Real>
void DiscContacts<Real>::forget_lanes() {
  for (ImpactLane& q : lanes_) {
    for (const std::uint32_t k : q.held) held_[k].on = held_[k].released = 0;
    q.held.clear(), q.log.clear(), q.heap.clear();
  }
  pairs_.resize(base_pairs_);
  end_lanes();
}

template <class Real>
void DiscContacts<Real>::undo_lanes(const Tick& tick) {
  forget_lanes();
  // The motions at the tick's start again (rolling: the spins too, as resolve() takes them).
  if (rolling_) {
    for (std::size_t k = 0; k < discs_.size(); ++k) ew_[k] = double(tick.spin[discs_[k].body]);
  }
  build_motions(tick);
  rest_lanes();
}

template <class Real>
void DiscContacts<Real>::rest_lanes() {
  // A pile stays one group tick after tick: its union-find would cost as much as its
  // impacts phase, every tick, for no lanes.
  lane_rest_ = ++lane_misses_in_a_row_ < 4 ? 0 : 1u << std::min(lane_misses_in_a_row_, 6u);
}

template <class Real>
void DiscContacts<Real>::merge_lanes(ContactStats& stats) {
  ImpactLane &first = lanes_[0], &second = lanes_[1];
  for (const ImpactLane& q : lanes_) {
    stats.impacts += q.stats.impacts;
    stats.held += q.stats.held;
    stats.wall_impacts += q.stats.wall_impacts;
  }
  first.held.insert(first.held.end(), second.held.begin(), second.held.end());
  second.held.clear();
  // The extra pairs out of their slots, after the broadphase's, in any order (finish_reach).
  std::vector<DiscPair>& extras = extra_sorted_;
  extras.clear();
  for (std::uint8_t h = 0; h < 2; ++h) {
    for (std::uint32_t i = 0; i < lanes_[h].next_extra; ++i) {
      extras.push_back(pairs_[base_pairs_ + 2 * std::size_t{i} + h]);
    }
  }
  pairs_.resize(base_pairs_);
  pairs_.insert(pairs_.end(), extras.begin(), extras.end());
  end_lanes();
  finish_reach();
  lane_misses_in_a_row_ = 0;
}

template <class Real>
bool DiscContacts<Real>::run_lanes(const Tick& tick, ContactStats& stats) {
  if (!lanes_may_run(tick)) return false;
  ++lane_cuts_;
  if (!assign_lanes()) {
    rest_lanes();
    return false;
  }
  start_lanes(tick);
  auto job = [&](int h) {
    ImpactLane& q = lanes_[h];
    first_lane_events(q, tick);
    run_window(q, tick, q.stats);
  };
  try {
    broadphase_.second_thread().both(job);
  } catch (...) {  // a stop request (or std::bad_alloc): no lane's pairs outlive the tick
    forget_lanes();
    throw;
  }
  if (!lanes_[0].met && !lanes_[1].met) check_lanes();
  if (lanes_[0].met || lanes_[1].met || !merge_lane_logs()) {
    undo_lanes(tick);
    ++lanes_undone_;
    return false;
  }
  merge_lanes(stats);
  ++lane_ticks_;
  return true;
}

}  // namespace fixstep::detail
