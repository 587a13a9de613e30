// Contact events: which disc pairs began and stopped touching in a tick, from the resting
// solver's touching pairs after the tick and before it, and the tick's impacts. O(touching +
// impacts log impacts) per tick, only in worlds with disc contacts; no allocation once warm.
#include <algorithm>
#include <span>

#include "disc_contacts.hpp"
#include "shape_world.hpp"
#include "sorted_diff.hpp"
#include "world_kernel.hpp"

namespace fixstep {

namespace {

// Function objects rather than functions, so that the sorts and searches inline them (a
// function passed by pointer was called for every comparison).
constexpr auto slot_less = [](const ContactEvent& l, const ContactEvent& r) {
  if (l.a.slot() != r.a.slot()) return l.a.slot() < r.a.slot();
  return l.b.slot() < r.b.slot();
};

constexpr auto same = [](const ContactEvent& l, const ContactEvent& r) {
  return l.a == r.a && l.b == r.b;
};

/// `list` sorted by slots; most often it already is (a pass to tell).
void sort_by_slots(std::span<ContactEvent> list) {
  if (!std::is_sorted(list.begin(), list.end(), slot_less)) {
    std::sort(list.begin(), list.end(), slot_less);
  }
}

/// `list`'s two runs in slot order, [0, first) and [first, end), merged into one in place
/// from the back (the second run copied to `scratch` first; no allocation once warm). On equal
/// slots the first run's pair goes first.
void merge_runs(std::vector<ContactEvent>& list, std::size_t first,
                std::vector<ContactEvent>& scratch) {
  scratch.assign(list.begin() + static_cast<std::ptrdiff_t>(first), list.end());
  std::size_t i = first, j = scratch.size(), out = list.size();
  while (j > 0) {
    list[--out] = i > 0 && slot_less(scratch[j - 1], list[i - 1]) ? list[--i] : scratch[--j];
  }
}

}  // namespace

template <class Real>
void detail::WorldKernel<Real>::update_contact_events(bool discs) {
  touching_before_.swap(touching_);
  begun_.clear();
  ended_.clear();
  hits_.clear();
  impacts_.clear();
  if (discs) {
    add_disc_touching();  // every entry of touching_ written anew
  } else {
    touching_.clear();
  }
  if (shape_world_) add_shape_touching();
  if (sleep_ || !asleep_touching_.empty()) set_asleep_pairs_apart();
  diff_contact_events(!discs);  // without discs, touching_ is the shapes' sorted run alone
}

// Two sleepers are not solved, and stay in touch (ContactSettings::sleep): their pairs are kept
// apart in asleep_touching_, out of the per-tick lists, so that a tick costs what its awake
// pairs do. A pair one of whose bodies woke since goes back among the pairs touching before
// the tick (it touched then); a pair whose bodies both fell asleep after the last tick leaves
// them, so that neither ends.
template <class Real>
void detail::WorldKernel<Real>::set_asleep_pairs_apart() {
  auto sleeping = [&](const ContactEvent& p) {
    return bodies_.contains(p.a) && bodies_.contains(p.b) && asleep(bodies_.index(p.a)) &&
           asleep(bodies_.index(p.b));
  };
  if ((asleep_pairs_stale_ || sleepers_ == 0) && !asleep_touching_.empty()) {
    const std::size_t before = touching_before_.size();
    auto keep = std::stable_partition(asleep_touching_.begin(), asleep_touching_.end(), sleeping);
    touching_before_.insert(touching_before_.end(), keep, asleep_touching_.end());
    asleep_touching_.erase(keep, asleep_touching_.end());
    if (touching_before_.size() != before) sort_by_slots(touching_before_);
  }
  asleep_pairs_stale_ = false;
  if (sleepers_ == 0) return;
  const std::size_t kept = asleep_touching_.size();
  auto out = touching_before_.begin();
  for (const ContactEvent& p : touching_before_) {
    if (sleeping(p)) {
      asleep_touching_.push_back(p);
    } else {
      *out++ = p;
    }
  }
  touching_before_.erase(out, touching_before_.end());
  if (asleep_touching_.size() != kept) {  // both runs sorted by slots: merged in place
    const auto middle = asleep_touching_.begin() + static_cast<std::ptrdiff_t>(kept);
    std::inplace_merge(asleep_touching_.begin(), middle, asleep_touching_.end(), slot_less);
  }
}

// Bodies with shapes (world_shapes.cpp): the pairs of bodies whose manifold points carry an
// impulse or overlap at the tick's end, each pair once, and as hits with the closing speed
// their points had before the solve.
template <class Real>
void detail::WorldKernel<Real>::add_shape_touching() {
  const ShapeWorld& w = *shape_world_;
  const std::span<const Entity> ids = bodies_.dense;
  const std::size_t first = touching_.size(), first_hit = hits_.size();
  // A manifold's rows (and a pair's manifolds, where its shapes' pairs are adjacent) follow one
  // another: a row of the pair just added adds nothing but its closing speed, of which a hit
  // keeps the largest (what speed_of reads).
  std::uint32_t last_a = ShapeWorld::none, last_b = ShapeWorld::none;
  for (const ShapeRow& r : w.rows()) {
    if (r.a == ShapeWorld::none || !(r.ln > 0.0 || r.bn > 0.0 || r.separation <= 0.0)) continue;
    if (r.a == last_a && r.b == last_b) {  // (r.a is never none here: the first row adds)
      const ContactEvent& p = touching_.back();
      if (r.approach <= 0.0) continue;
      if (hits_.size() > first_hit && same(hits_.back(), p)) {
        hits_.back().normal_speed = std::max(hits_.back().normal_speed, r.approach);
      } else {
        hits_.push_back({p.a, p.b, r.approach});
      }
      continue;
    }
    last_a = r.a, last_b = r.b;
    Entity a = ids[w.bodies_[r.a].body], b = ids[w.bodies_[r.b].body];
    if (b.slot() < a.slot()) std::swap(a, b);
    touching_.push_back({a, b, 0.0});
    if (r.approach > 0.0) hits_.push_back({a, b, r.approach});
  }
  // In row order the pairs come sorted by slots (rows follow the shapes' pairs, the shapes their
  // bodies' dense order) until a destroy breaks dense = slot order.
  sort_by_slots(std::span(touching_).subspan(first));
  const auto begin = touching_.begin() + static_cast<std::ptrdiff_t>(first);
  touching_.erase(std::unique(begin, touching_.end(), same), touching_.end());
}

template <class Real>
void detail::WorldKernel<Real>::add_disc_touching() {
  const detail::DiscContacts<Real>& dc = *discs_;
  const std::span<const Entity> ids = bodies_.dense;
  auto pair_of = [&](std::uint32_t ja, std::uint32_t jb, double speed) {
    const Entity a = ids[ja], b = ids[jb];
    return b.slot() < a.slot() ? ContactEvent{b, a, speed} : ContactEvent{a, b, speed};
  };
  // The disc pairs come first among the touching contacts; by halves on the discs' second
  // thread within the tick's run of it (world_step.cpp). touching_ holds the list of two ticks
  // ago (swapped out): resized, it constructs only the entries past its size, each of which
  // the halves then write.
  const auto touching = dc.touching_bodies();
  touching_.resize(dc.disc_pair_contacts());
  discs_->halves(touching_.size(), [&](std::size_t begin, std::size_t end, int /*half*/) {
    for (std::size_t i = begin; i < end; ++i) {
      touching_[i] = pair_of(touching[i].a, touching[i].b, 0.0);
    }
  });
  for (const DiscImpact& i : dc.impacts()) {
    hits_.push_back(pair_of(i.body_a, i.body_b, i.normal_speed));
    impacts_.push_back(Impact{ids[i.body_a], ids[i.body_b], i.time, i.normal_speed});
  }
}

namespace {

// The largest closing speed among the sorted hits of pair p, or 0.
double speed_of(std::span<const ContactEvent> hits, const ContactEvent& p) {
  double speed = 0.0;
  auto at = std::lower_bound(hits.begin(), hits.end(), p, slot_less);
  for (; at != hits.end() && same(*at, p); ++at) speed = std::max(speed, at->normal_speed);
  return speed;
}

}  // namespace

// One merge of a part of touching_ and the part of touching_before_ that holds the same slots.
template <class Real>
void detail::WorldKernel<Real>::diff_touching(std::size_t now_begin, std::size_t now_end,
                                              std::size_t before_begin, std::size_t before_end,
                                              std::vector<ContactEvent>& begun,
                                              std::vector<ContactEvent>& ended) const {
  const std::span<const ContactEvent> now(touching_), before(touching_before_);
  detail::sorted_diff<ContactEvent>(
      now.subspan(now_begin, now_end - now_begin),
      before.subspan(before_begin, before_end - before_begin), slot_less, same,
      [&](const ContactEvent& p) {
        begun.push_back({p.a, p.b, speed_of(hits_, p)});
      },
      [&](const ContactEvent& p) { ended.push_back(p); });
}

// Both lists sorted by slots: one merge finds what began and what ended. With many pairs and
// the discs' second thread in its run, by halves: the sorts side by side, then the pairs below
// the middle pair's slots and those from it on, each half's events in slot order.
template <class Real>
void detail::WorldKernel<Real>::diff_contact_events(bool touching_sorted) {
  const std::size_t n = touching_.size(), m = touching_before_.size();
  if (!discs_ || !discs_->sharing() || n < events_split) {
    // Already sorted until a destroy breaks dense = slot order.
    if (!touching_sorted) sort_by_slots(touching_);
    sort_by_slots(hits_);
    diff_touching(0, n, 0, m, begun_, ended_);
  } else {
    // Whether touching_ is sorted (it is until a destroy), by halves (each checks the pairs of
    // neighbours that start in it), the hits sorted beside the second; a touching_ out of order
    // is then sorted here.
    const auto middle = touching_.begin() + static_cast<std::ptrdiff_t>(n / 2);
    bool sorted[2] = {true, true};
    auto sorts = [&](int half) {
      if (half == 0) {
        sorted[0] = std::is_sorted(touching_.begin(), middle + 1, slot_less);
      } else {
        sorted[1] = std::is_sorted(middle, touching_.end(), slot_less);
        sort_by_slots(hits_);
      }
    };
    discs_->both_halves(sorts);
    if (!sorted[0] || !sorted[1]) sort_by_slots(touching_);
    std::size_t mid = n / 2;  // touching_[mid - 1] before touching_[mid] (pairs may repeat)
    while (mid < n && !slot_less(touching_[mid - 1], touching_[mid])) ++mid;
    const auto cut = std::lower_bound(touching_before_.begin(), touching_before_.end(),
                                      touching_[std::min(mid, n - 1)], slot_less);
    const std::size_t b = mid == n ? m : static_cast<std::size_t>(cut - touching_before_.begin());
    begun_half_.clear(), ended_half_.clear();
    auto halves = [&](int half) {
      half == 0 ? diff_touching(0, mid, 0, b, begun_, ended_)
                : diff_touching(mid, n, b, m, begun_half_, ended_half_);
    };
    discs_->both_halves(halves);
    begun_.insert(begun_.end(), begun_half_.begin(), begun_half_.end());
    ended_.insert(ended_.end(), ended_half_.begin(), ended_half_.end());
  }
  // Pairs that struck and parted within the tick: begun and ended at once. The hits in slot
  // order, each looked up in both sorted lists by a cursor that only moves on (the first entry
  // of its slots, as a binary search finds it).
  const std::size_t begun_diffed = begun_.size(), ended_diffed = ended_.size();
  bool struck = false;
  auto now = touching_.cbegin(), before = touching_before_.cbegin();
  auto held = [](auto& at, const std::vector<ContactEvent>& list, const ContactEvent& p) {
    while (at != list.end() && slot_less(*at, p)) ++at;
    return at != list.end() && same(*at, p);
  };
  for (std::size_t h = 0; h < hits_.size(); ++h) {
    const ContactEvent& p = hits_[h];
    if (h > 0 && same(hits_[h - 1], p)) continue;
    if (held(now, touching_, p) || held(before, touching_before_, p)) continue;
    begun_.push_back({p.a, p.b, speed_of(hits_, p)});
    ended_.push_back({p.a, p.b, 0.0});
    struck = true;
  }
  // Each list is two runs in slot order, the diff's and the struck pairs' (no pair in both: a
  // struck pair touched neither before nor after), so one merge orders it.
  if (struck) {
    merge_runs(begun_, begun_diffed, begun_half_);
    merge_runs(ended_, ended_diffed, ended_half_);
  }
}

// A tick without disc phases (no active discs): the pairs and sensor overlaps of the last tick
// with discs all end, and nothing begins.
template <class Real>
void detail::WorldKernel<Real>::end_disc_events() {
  if (profile_.step != 0.0) profile_ = StepProfile{};
  if (!begun_.empty() || !ended_.empty() || !touching_.empty() || !asleep_touching_.empty()) {
    ended_.assign(touching_.begin(), touching_.end());  // the last discs went: all end
    if (!asleep_touching_.empty()) {
      ended_.insert(ended_.end(), asleep_touching_.begin(), asleep_touching_.end());
      sort_by_slots(ended_);
    }
    begun_.clear(), touching_.clear(), asleep_touching_.clear();
  }
  if (!sensed_.empty() || !sensor_begun_.empty() || !sensor_ended_.empty()) {
    sensor_ended_.assign(sensed_.begin(), sensed_.end());
    sensor_begun_.clear(), sensed_.clear();
  }
}

}  // namespace fixstep
