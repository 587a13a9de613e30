// Disc contacts, phase 2: the resting solver's contacts split into two halves of the pile and
// the contacts between them, so that two threads can solve the halves at once with the same
// result as one thread (the solver's state is bit for bit the same on one thread or two).
//
// The cut is the median of the dynamic discs' coordinate along the axis on which they spread
// the most. A contact belongs to a half when every dynamic disc it moves lies in that half
// (static and kinematic discs and planes are never moved by the solver, so they do not count);
// the others, across the cut, are solved after both halves. In a large pile the cut is made
// before the contacts are gathered, and each disc pair's part found as it is gathered, while
// the contact is in the cache. Within each part the contacts keep their key order, so an
// iteration runs through a pile as Gauss–Seidel in key order does (measured: graph colouring,
// as Box2D v3 does it, spreads each colour over the whole pile and left a deep pile of rigid
// contacts far from converged after a few iterations; see docs/perf/contact_solver_plan.md).
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>

#include "disc_contacts.hpp"
#include "median_window.hpp"

namespace fixstep::detail {

namespace {
std::atomic<bool> median_window_on{true};
}  // namespace

void set_median_window(bool on) {
  median_window_on.store(on, std::memory_order_relaxed);
}

bool median_window() {
  return median_window_on.load(std::memory_order_relaxed);
}

template <class Real>
bool DiscContacts<Real>::cut_pile() {
  // The wider axis of the dynamic discs (their flags, not their records), and the median
  // coordinate along it.
  ++pile_cuts_;
  constexpr double inf = std::numeric_limits<double>::infinity();
  double lo[2] = {inf, inf}, hi[2] = {-inf, -inf};
  std::size_t count = 0;
  const std::size_t live = live_count();
  live_range(0, live, [&](std::uint32_t k) {
    if (!dynamic_[k]) return;
    ++count;
    lo[0] = std::min(lo[0], ex_[k]), hi[0] = std::max(hi[0], ex_[k]);
    lo[1] = std::min(lo[1], ey_[k]), hi[1] = std::max(hi[1], ey_[k]);
  });
  const bool along_y = hi[1] - lo[1] > hi[0] - lo[0];
  const auto& along = along_y ? ey_ : ex_;
  // The median is the count/2-th smallest coordinate. A pile moves little from one tick to the
  // next, so it is sought first among the coordinates within a sixty-fourth of the pile's span
  // of the last tick's median: those below the window are counted, and when the rank falls
  // within it, only the window's are ordered. The same value as ordering them all (it is the
  // same order statistic); otherwise they all are.
  const std::size_t rank = count / 2;
  const double span = along_y ? hi[1] - lo[1] : hi[0] - lo[0];
  const bool hint = median_window() && along_y == cut_along_y_ && std::isfinite(median_);
  const double low = hint ? median_ - span / 64 : inf, high = hint ? median_ + span / 64 : -inf;
  std::size_t below = 0;
  bool nan = false;
  cut_.clear();
  live_range(0, live, [&](std::uint32_t k) {
    if (!dynamic_[k]) return;
    const double v = along[k];
    nan = nan || std::isnan(v);
    below += v < low ? 1 : 0;
    if (v >= low && v <= high) cut_.push_back(v);
  });
  // No order to cut by (the world reports the NaN), or nothing to cut: one part.
  if (nan || count == 0) return false;
  std::size_t at = rank - below;
  if (rank < below || at >= cut_.size()) {  // not within the window: every coordinate
    cut_.clear();
    live_range(0, live, [&](std::uint32_t k) {
      if (dynamic_[k]) cut_.push_back(along[k]);
    });
    at = rank;
  }
  const auto mid = cut_.begin() + std::ptrdiff_t(at);
  std::nth_element(cut_.begin(), mid, cut_.end());
  median_ = *mid;  // the same value whatever the algorithm's order
  cut_along_y_ = along_y;
  return true;
}

template <class Real>
void DiscContacts<Real>::cut_before_gather() {
  // In a large world (warm_gathered_, gather_warm.hpp) whose last tick had contacts enough to
  // split (a gas of many candidate pairs has few: its cut would go unused); else the cut is
  // taken after the gather, and only when its contacts are enough to split. The same parts
  // either way. (contacts_ holds the last tick's contacts until the gather.)
  cut_state_ = cut_none;
  if (!warm_gathered_ || contacts_.size() < min_split_contacts) return;
  if (!cut_pile()) {
    cut_state_ = cut_failed;
    return;
  }
  // Each live disc's side: a disc the solver moves by its coordinate, any other none. The
  // solver moves a contact's disc when its 1/m > 0, which is when it is dynamic and awake
  // (dynamic_: a mass is at most 1e100 kg), so the flags are read, not the discs' records.
  const auto& along = cut_along_y_ ? ey_ : ex_;
  side_.resize(discs_.size());
  live_range(0, live_count(), [&](std::uint32_t k) {
    side_[k] = dynamic_[k] ? (along[k] < median_ ? side_low : side_high) : side_none;
  });
  cut_state_ = cut_made;
}

template <class Real>
void DiscContacts<Real>::split_contacts(ContactStats& stats) {
  const std::size_t n = discs_.size(), m = contacts_.size();
  order_.resize(m);
  part_start_ = {0, std::uint32_t(m), std::uint32_t(m), std::uint32_t(m)};
  // Within a part the contacts keep contacts_'s order: disc pairs, then planes, each in key
  // order.
  auto one_part = [&] {
    for (std::size_t i = 0; i < m; ++i) order_[i] = static_cast<std::uint32_t>(i);
  };
  if (m < min_split_contacts) return one_part();
  // The disc pairs' parts were found as they were gathered when the cut was made before the
  // gather (cut_before_gather()): then only the planes' and segments' are found here.
  std::size_t first = 0;
  if (cut_state_ == cut_made) {
    first = plane_contacts_;
  } else if (cut_state_ == cut_none) {
    cut_state_ = cut_pile() ? cut_made : cut_failed;
  }
  if (cut_state_ == cut_failed) return one_part();
  // Each contact's part (0, 1: a half; 2: across the cut), then a stable counting sort, both
  // over two halves of the contacts (on two threads within the tick's run of the second
  // thread; the first half's contacts go before the second's in each part).
  const auto& along = cut_along_y_ ? ey_ : ex_;
  const double median = median_;
  part_.resize(m);
  std::array<std::array<std::uint32_t, 3>, 2> in_half{};
  halves(m, [&](std::size_t begin, std::size_t end, int half) {
    std::array<std::uint32_t, 3> count{};
    const std::size_t found = std::clamp(first, begin, end);  // [begin, found): found already
    // Counted in registers (an indexed count is a store each contact that the next may wait
    // on).
    std::uint32_t c0 = 0, c1 = 0;
    for (std::size_t i = begin; i < found; ++i) c0 += part_[i] == 0, c1 += part_[i] == 1;
    count = {c0, c1, std::uint32_t(found - begin) - c0 - c1};
    for (std::size_t i = found; i < end; ++i) {
      const RestContact& c = contacts_[i];
      const bool b_moves = c.b < n && c.inv_b > 0.0;
      const std::uint8_t sa =
          c.inv_a > 0.0 ? (along[c.a] < median ? side_low : side_high) : side_none;
      const std::uint8_t sb = b_moves ? (along[c.b] < median ? side_low : side_high) : side_none;
      part_[i] = part_of(sa, sb);
      ++count[part_[i]];
    }
    in_half[half] = count;
  });
  std::uint32_t count[3];
  for (int part = 0; part < 3; ++part) count[part] = in_half[0][part] + in_half[1][part];
  part_start_ = {0, count[0], count[0] + count[1], std::uint32_t(m)};
  halves(m, [&](std::size_t begin, std::size_t end, int half) {
    // The cursors in registers, as the counts.
    std::uint32_t c0 = part_start_[0] + (half == 1 ? in_half[0][0] : 0);
    std::uint32_t c1 = part_start_[1] + (half == 1 ? in_half[0][1] : 0);
    std::uint32_t c2 = part_start_[2] + (half == 1 ? in_half[0][2] : 0);
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t part = part_[i];
      order_[part == 0 ? c0 : part == 1 ? c1 : c2] = std::uint32_t(i);
      c0 += part == 0, c1 += part == 1, c2 += part == 2;
    }
  });
  stats.across = count[2];
}

}  // namespace fixstep::detail
