// What began and what ended between two sorted lists of pairs (the touching discs, the discs in
// sensors, before and after a tick). Internal to the engine: not installed.
#pragma once

#include <cstddef>
#include <span>

namespace fixstep::detail {

/// Walks `now` and `before`, both sorted by `less` (slot order), in one merge: began(p) for each
/// pair of now not in before, ended(p) for each pair of before not in now. Two entries that
/// `less` orders neither way but that are not `same` (a slot reused by a new body since) are
/// ended and begun both. O(now + before), no allocation.
template <class E, class Less, class Same, class Began, class Ended>
void sorted_diff(std::span<const E> now, std::span<const E> before, Less less, Same same,
                 Began&& began, Ended&& ended) {
  std::size_t i = 0, k = 0;
  const std::size_t n = now.size(), m = before.size();
  while (i < n || k < m) {
    if (k == m || (i < n && less(now[i], before[k]))) {
      began(now[i++]);
    } else if (i == n || less(before[k], now[i])) {
      ended(before[k++]);
    } else {
      if (!same(now[i], before[k])) ended(before[k]), began(now[i]);
      ++i, ++k;
    }
  }
}

}  // namespace fixstep::detail
