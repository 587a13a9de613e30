// Disc contacts, phase 1, continued: a disc an impact sends beyond the box the broadphase paired
// it by (see disc_contacts.hpp) meets what lies on its new path. Its box grows to the bounding
// box of the rest of its motion too, and the discs whose boxes meet what it grew by (up to four
// bands) and that it was not paired with become new pairs of the tick, predicted from the impact
// on: the boxes as the broadphase stored them (GridBroadphase::query), and the bands grown
// earlier in the tick, which the broadphase never saw (a grid of them, where its bands are
// stored). A disc's box is then always its broadphase box and its bands, every pair of discs
// whose boxes overlap is paired, and two discs whose boxes do not overlap cannot touch (each box
// is padded by its disc's radius), so no contact is missed.
#include <array>

#include "disc_contacts.hpp"

namespace fixstep::detail {

template <class Real>
void DiscContacts<Real>::start_reach(ImpactLane& q) {
  for (const ExtraPair& e : q.extra) extra_head_[e.disc] = ExtraPair::none;
  q.extra.clear();
  for (const GrownBox& g : q.grown) grown_of_[g.disc] = GrownBox::none;
  q.grown.clear();
  q.grid.reset(4.0 * (1.0 + 2.0 * slop) * max_radius_, discs_.size());
  q.bands.clear();
  base_pairs_ = pairs_.size();
}

template <class Real>
std::uint64_t DiscContacts<Real>::reach(ImpactLane& q, const Tick& tick, std::uint32_t k,
                                        double now, double dt) {
  const DiscMotion& m = motion_[k];
  const double pad = box_pad(discs_[k]), h = horizon_ - m.t;
  SweptBox piece;
  motion_extent(m.x, m.ux, m.ax, h, pad, piece.min_x, piece.max_x);
  motion_extent(m.y, m.uy, m.ay, h, pad, piece.min_y, piece.max_y);
  SweptBox& box = boxes_[k];
  if (box_within(piece, box)) {
    return 0;  // inside its box (false for NaN: a NaN piece is looked at, and overlaps nothing)
  }
  if (grown_of_[k] == GrownBox::none) {  // its box as the broadphase paired it
    grown_of_[k] = static_cast<std::uint32_t>(q.grown.size());
    q.grown.push_back(GrownBox{k, box});
  }
  const SweptBox& first = q.grown[grown_of_[k]].first;
  // What the grown box covers beyond the box: up to four bands (closed, so they may share edges).
  SweptBox grown = box;
  grown.min_x = std::min(box.min_x, piece.min_x), grown.max_x = std::max(box.max_x, piece.max_x);
  grown.min_y = std::min(box.min_y, piece.min_y), grown.max_y = std::max(box.max_y, piece.max_y);
  std::array<SweptBox, 4> bands;
  std::size_t count = 0;
  if (grown.min_x < box.min_x) bands[count++] = {grown.min_x, grown.min_y, box.min_x, grown.max_y};
  if (grown.max_x > box.max_x) bands[count++] = {box.max_x, grown.min_y, grown.max_x, grown.max_y};
  if (grown.min_y < box.min_y) bands[count++] = {box.min_x, grown.min_y, box.max_x, box.min_y};
  if (grown.max_y > box.max_y) bands[count++] = {box.min_x, box.max_y, box.max_x, grown.max_y};
  if (count == 0) bands[count++] = piece;  // NaN
  box = grown;
  std::uint64_t work = 0;
  // k's extra pairs so far, marked by their partners (a fresh mark per call).
  const std::uint32_t mark = next_mark(q);
  for (std::uint32_t e = extra_head_[k]; e != ExtraPair::none; e = q.extra[e].next) {
    const DiscPair& p = pairs_[q.extra[e].pair];
    partner_mark_[p.a == k ? p.b : p.a] = mark, ++work;
  }
  // j, whose box the broadphase paired by is `paired_by`: a new pair if that box did not meet
  // k's (else the broadphase paired them, or they may not collide) and j's box now meets the
  // band, unless an earlier band paired them.
  const SweptBox* band = nullptr;
  auto meet = [&](std::uint32_t j, const SweptBox& paired_by) {
    ++work;
    if (q.split && lane(j) != q.id) {  // the other lane's: only where they may pair
      if (j != k && boxes_overlap(*band, paired_by) && may_pair(k, j)) meet_other_lane(q);
      return;
    }
    if (j == k || boxes_overlap(first, paired_by) || !boxes_overlap(*band, boxes_[j])) return;
    if (!may_pair(k, j)) return;
    if (partner_mark_[j] == mark) return;  // an extra pair already, or met by another band
    partner_mark_[j] = mark;
    const std::uint32_t index = add_extra_pair(q, DiscPair{std::min(k, j), std::max(k, j)});
    if (index == ExtraPair::none) return;  // its slots are full (q.met)
    predict(q, index, now, dt);
    work += 16;
  };
  for (std::size_t i = 0; i < count; ++i) {
    band = &bands[i];
    // The boxes as the broadphase stored them (a grown disc's too: it may move inside it), and
    // the bands grown earlier in the tick.
    if (live_all_ && !fat_.valid) {
      work += broadphase_.query(*band, meet);
    } else if (live_all_) {  // the grid holds the fat boxes (disc_fat.cpp): each disc's own box
      if (!fat_grid_.value) rebuild_fat_grid(pass_threads(tick));
      auto own = [&](std::uint32_t j, const SweptBox& fat) {
        meet(j, q.split && lane(j) != q.id ? fat : paired_box(q, j));
      };
      work += broadphase_.query(*band, own);
    } else {  // the broadphase holds the live discs by live position; a sleeper joins here
      auto live_meet = [&](std::uint32_t i, const SweptBox& b) { meet(live_[i], b); };
      work += broadphase_.query(*band, live_meet);
      sleepers_near(tick, *band, [&](std::uint32_t j) {
        add_live(tick, j);
        meet(j, boxes_[j]);
      });
    }
    work += q.grid.query(*band, [&](std::uint32_t j) { meet(j, q.grown[grown_of_[j]].first); });
  }
  for (std::size_t i = 0; i < count; ++i) {
    q.grid.insert(k, bands[i]);
    if (q.split) q.bands.emplace_back(k, bands[i]);
  }
  return work;
}

template <class Real>
bool DiscContacts<Real>::may_pair(std::uint32_t k, std::uint32_t j) const {
  if (!dynamic_[k] && !dynamic_[j]) return false;
  if (!filters_.empty()) {
    if (!should_collide(filters_[k], filters_[j])) return false;
    if (discs_[k].sensor || discs_[j].sensor) return false;  // sensors sense at the tick's end
  }
  if (linked_.empty()) return true;
  const std::uint64_t key = (std::uint64_t(std::min(k, j)) << 32) | std::max(k, j);
  return !std::binary_search(linked_.begin(), linked_.end(), key);
}

template <class Real>
std::uint32_t DiscContacts<Real>::next_mark(ImpactLane& q) {
  // Two lanes mark their own discs only, each with its own count: a lane's marks start past
  // every mark made before (disc_lanes.cpp sets both to the larger after a split tick).
  if (++q.mark == 0) std::fill(partner_mark_.begin(), partner_mark_.end(), 0u), q.mark = 1;
  return q.mark;
}

template <class Real>
std::uint32_t DiscContacts<Real>::add_extra_pair(ImpactLane& q, DiscPair p) {
  std::uint32_t index = 0;
  if (!q.split) {
    index = static_cast<std::uint32_t>(pairs_.size());
    pairs_.push_back(p);
  } else {  // its slot among the extra pairs: base + 2 i + id (disc_lanes.cpp)
    const std::size_t slot = base_pairs_ + 2 * std::size_t{q.next_extra} + q.id;
    if (slot >= pairs_.size()) {
      meet_other_lane(q);
      return ExtraPair::none;
    }
    ++q.next_extra;
    index = static_cast<std::uint32_t>(slot);
    pairs_[slot] = p;
  }
  for (const std::uint32_t d : {p.a, p.b}) {
    q.extra.push_back(ExtraPair{index, d, extra_head_[d]});
    extra_head_[d] = static_cast<std::uint32_t>(q.extra.size() - 1);
  }
  return index;
}

template <class Real>
void DiscContacts<Real>::finish_reach() {
  if (pairs_.size() == base_pairs_) return;
  // The resting contacts are gathered from the pairs in (a, b) order (their keys' order): the
  // few extra pairs sorted, then merged from the back into the broadphase's sorted ones.
  auto before = [](const DiscPair& p, const DiscPair& q) {
    return p.a < q.a || (p.a == q.a && p.b < q.b);
  };
  extra_sorted_.assign(pairs_.begin() + static_cast<std::ptrdiff_t>(base_pairs_), pairs_.end());
  std::sort(extra_sorted_.begin(), extra_sorted_.end(), before);
  std::size_t i = base_pairs_, j = extra_sorted_.size(), out = pairs_.size();
  while (j > 0) {
    if (i > 0 && before(extra_sorted_[j - 1], pairs_[i - 1])) {
      pairs_[--out] = pairs_[--i];
    } else {
      pairs_[--out] = extra_sorted_[--j];
    }
  }
}

}  // namespace fixstep::detail
