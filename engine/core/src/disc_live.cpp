// Disc contacts with sleeping islands: the discs a tick visits. A sleeper acts as a static disc
// that the broadphase pairs with no other sleeper (disc_contacts.hpp), so of the sleepers a
// tick needs only those an awake dynamic disc's box overlaps (and, within the impacts, those a
// disc's grown box reaches, disc_reach.cpp). When at most 1/live_share of the discs is awake,
// the tick's per-disc passes, its broadphase and its bookkeeping visit the live discs only:
// the awake ones, the discs woken in the tick, and the sleepers next to them, in index order.
// A sleeper that joins is at rest where it sleeps, so its start state, motion and box are
// those it would have had all along, and the broadphase, given the live boxes in index order,
// finds the same pairs in the same order: the states are the same as when every disc is
// visited. The sleepers are found through a grid of them where they sleep (query_grid.hpp),
// kept across changes of sleep (SleeperGrid, disc_caches.hpp); the world's wake tests ask it
// too.
#include <algorithm>
#include <cassert>

#include "disc_contacts.hpp"
#include "sorted_lists.hpp"

namespace fixstep::detail {

// Made from every disc after a rebuild, else updated from the discs flipped since by a merge:
// O(awake + flips), until the flips pass a quarter of the discs.
template <class Real>
std::span<const std::uint32_t> DiscContacts<Real>::awake() {
  if (!awake_dirty_) return awake_list_;
  std::vector<std::uint32_t>& flips = awake_flips_.discs;
  if (awake_flips_.whole) {
    awake_list_.clear();
    for (std::uint32_t k = 0; k < discs_.size(); ++k) {
      if (!asleep_[k]) awake_list_.push_back(k);
    }
  } else {
    sort_unique(flips);  // every flipped disc out, then those awake now back in
    remove_sorted(awake_list_, flips, awake_flips_.scratch);
    std::erase_if(flips, [&](std::uint32_t k) { return asleep_[k] != 0; });
    insert_sorted(awake_list_, flips, awake_flips_.scratch);
  }
  flips.clear();
  awake_flips_.whole = false, awake_dirty_ = false;
  return awake_list_;
}

template <class Real>
void DiscContacts<Real>::begin_live() {
  for (const std::uint32_t k : live_) in_live_[k] = 0;  // the last tick's
  live_.clear();
  // As save_start() decided: between it and the disc phases no disc wakes (input wakes its
  // islands before), so the awake list is the one it saved.
  live_all_ = !saved_live_;
  live_sorted_ = true;
  if (live_all_) return;
  assert(!awake_dirty_);
  live_.assign(awake_list_.begin(), awake_list_.end());
  for (const std::uint32_t k : live_) in_live_[k] = 1;
}

template <class Real>
void DiscContacts<Real>::add_live(const Tick& tick, std::uint32_t k) {
  const std::uint32_t j = discs_[k].body;
  x0_[k] = tick.x[j], y0_[k] = tick.y[j], vx0_[k] = tick.vx[j], vy0_[k] = tick.vy[j];
  d_begin_[k] = tick.dissipated ? double(tick.dissipated[j]) : 0.0;
  if (rolling_) ew0_[k] = ew_[k] = double(tick.spin[j]);
  build_motions(tick, k, k + 1, bounced_[0]);
  in_live_[k] = 1;
  if (!live_.empty() && live_.back() > k) live_sorted_ = false;
  live_.push_back(k);
}

template <class Real>
void DiscContacts<Real>::build_sleeper_grid(const Real* x, const Real* y) {
  SleeperGrid& s = sleepers_;
  QueryGrid& g = s.grid;
  g.discs.clear(), s.disc.clear(), s.extras.clear(), s.gone = 0, s.tested = 0;
  s.indexed.assign(discs_.size(), 0), s.extra.assign(discs_.size(), 0);
  for (std::uint32_t k = 0; k < discs_.size(); ++k) {
    if (!asleep_[k]) continue;
    const Disc& d = discs_[k];
    // A sleeper's box is its disc padded as build_motions() pads it (at rest).
    g.discs.push_back(
        {double(x[d.body]), double(y[d.body]), box_pad(d), Entity{}, CollisionFilter{}, false});
    s.disc.push_back(k), s.indexed[k] = 1;
  }
  g.build();  // (not stale)
}

template <class Real>
template <class Found>
void DiscContacts<Real>::for_each_sleeper_near(const Real* x, const Real* y, const SweptBox& b,
                                               Found&& found) {
  SleeperGrid& s = sleepers_;
  if (s.spent()) build_sleeper_grid(x, y);
  s.grid.for_each_near(b.min_x, b.min_y, b.max_x, b.max_y, [&](std::size_t i) {
    const std::uint32_t k = s.disc[i];
    if (s.indexed[k] != 0) found(k);
  });
  s.tested += s.extras.size();
  for (const std::uint32_t k : s.extras) {
    if (!asleep_[k]) continue;  // woke again since
    const Disc& d = discs_[k];
    const double px = double(x[d.body]), py = double(y[d.body]), r = box_pad(d);
    if (boxes_overlap(SweptBox{px - r, py - r, px + r, py + r}, b)) found(k);
  }
}

template <class Real>
template <class Found>
void DiscContacts<Real>::sleepers_near(const Tick& tick, const SweptBox& b, Found&& found) {
  for_each_sleeper_near(tick.x, tick.y, b, [&](std::uint32_t k) {
    if (!in_live_[k]) found(k);
  });
}

template <class Real>
void DiscContacts<Real>::add_woken_and_near(const Tick& tick) {
  for (const std::uint32_t k : woken_) {
    if (!in_live_[k]) add_live(tick, k);
  }
  woken_.clear();
  // The live list grows as sleepers join, but they are not dynamic: only the discs before them
  // can pair with a sleeper.
  const std::size_t movers = live_.size();
  for (std::size_t i = 0; i < movers; ++i) {
    const std::uint32_t k = live_[i];
    if (!dynamic_[k]) continue;
    const SweptBox b = boxes_[k];
    sleepers_near(tick, b, [&](std::uint32_t s) {
      add_live(tick, s);
      if (!boxes_overlap(b, boxes_[s])) in_live_[s] = 0, live_.pop_back();
    });
  }
  sort_live();
}

template <class Real>
void DiscContacts<Real>::sort_live() {
  if (!live_sorted_) std::sort(live_.begin(), live_.end());
  live_sorted_ = true;
}

template <class Real>
void DiscContacts<Real>::gather_live_boxes(std::span<const SweptBox> boxes) {
  const std::size_t m = live_.size();
  live_boxes_.resize(m), live_dynamic_.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    live_boxes_[i] = boxes[live_[i]], live_dynamic_[i] = dynamic_[live_[i]];
  }
}

}  // namespace fixstep::detail
