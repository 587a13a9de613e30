// Disc contacts, phase 2: the resting solver's contacts split into two halves of the pile and
// the contacts between them, so that two threads can solve the halves at once with the same
// result as one thread (the solver's state is bit for bit the same on one thread or two).
//
// The cut is the median of the dynamic discs' coordinate along the axis on which they spread
// the most. A contact belongs to a half when every dynamic disc it moves lies in that half
// (static and kinematic discs and planes are never moved by the solver, so they do not count);
// the others, across the cut, are solved after both halves. Within each part the contacts keep
// their key order, so an iteration runs through a pile as Gauss–Seidel in key order does
// (measured: graph colouring, as Box2D v3 does it, spreads each colour over the whole pile
// and left a deep pile of rigid contacts far from converged after a few iterations; see
// docs/perf/contact_solver_plan.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "disc_contacts.hpp"

namespace fixstep::detail {

template <class Real>
void DiscContacts<Real>::split_contacts(ContactStats& stats) {
  const std::size_t n = discs_.size(), m = contacts_.size();
  order_.resize(m);
  part_start_ = {0, std::uint32_t(m), std::uint32_t(m), std::uint32_t(m)};
  // Within a part the contacts keep contacts_'s order: disc pairs, then planes, each in key
  // order.
  if (m < min_split_contacts) {
    for (std::size_t i = 0; i < m; ++i) order_[i] = static_cast<std::uint32_t>(i);
    return;
  }
  // The wider axis of the dynamic discs, and the median coordinate along it.
  constexpr double inf = std::numeric_limits<double>::infinity();
  double lo[2] = {inf, inf}, hi[2] = {-inf, -inf};
  cut_.clear();
  const std::size_t live = live_count();
  live_range(0, live, [&](std::uint32_t k) {
    if (!discs_[k].dynamic) return;
    lo[0] = std::min(lo[0], ex_[k]), hi[0] = std::max(hi[0], ex_[k]);
    lo[1] = std::min(lo[1], ey_[k]), hi[1] = std::max(hi[1], ey_[k]);
  });
  const auto& along = hi[1] - lo[1] > hi[0] - lo[0] ? ey_ : ex_;
  bool nan = false;
  live_range(0, live, [&](std::uint32_t k) {
    if (!discs_[k].dynamic) return;
    nan = nan || std::isnan(along[k]);
    cut_.push_back(along[k]);
  });
  if (nan) {  // no order to cut by: one part (the world reports the NaN)
    for (std::size_t i = 0; i < m; ++i) order_[i] = static_cast<std::uint32_t>(i);
    return;
  }
  const auto mid = cut_.begin() + std::ptrdiff_t(cut_.size() / 2);
  std::nth_element(cut_.begin(), mid, cut_.end());
  const double median = *mid;  // the same value whatever the algorithm's order
  // Each contact's part (0, 1: a half; 2: across the cut), then a stable counting sort, both
  // over two halves of the contacts (on two threads within the tick's run of the second
  // thread; the first half's contacts go before the second's in each part).
  std::array<std::array<std::uint32_t, 3>, 2> in_half{};
  scratch_.resize(m);
  halves(m, [&](std::size_t begin, std::size_t end, int half) {
    std::array<std::uint32_t, 3> count{};
    for (std::size_t i = begin; i < end; ++i) {
      const RestContact& c = contacts_[i];
      const bool a_moves = c.inv_a > 0.0, b_moves = c.b < n && c.inv_b > 0.0;
      const std::uint32_t sa = along[c.a] < median ? 0 : 1;
      const std::uint32_t sb = b_moves && along[c.b] < median ? 0 : 1;
      const std::uint32_t part = !a_moves ? sb : !b_moves ? sa : sa == sb ? sa : 2;
      scratch_[i] = part;
      ++count[part];
    }
    in_half[half] = count;
  });
  std::uint32_t count[3];
  for (int part = 0; part < 3; ++part) count[part] = in_half[0][part] + in_half[1][part];
  part_start_ = {0, count[0], count[0] + count[1], std::uint32_t(m)};
  halves(m, [&](std::size_t begin, std::size_t end, int half) {
    std::uint32_t cursor[3];
    for (int part = 0; part < 3; ++part) {
      cursor[part] = part_start_[part] + (half == 1 ? in_half[0][part] : 0);
    }
    for (std::size_t i = begin; i < end; ++i) order_[cursor[scratch_[i]]++] = std::uint32_t(i);
  });
  stats.across = count[2];
}

}  // namespace fixstep::detail
