// Ascending lists of indices without repeats, as the sleep bookkeeping keeps them (the shape
// world's resting lists, the kernel's flips, the discs' awake list): sorted in place, and
// values taken out or put in by a merge through a scratch list. Internal to the engine: not
// installed.
#pragma once

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <span>
#include <vector>

namespace fixstep::detail {

/// a sorted ascending, without repeats.
inline void sort_unique(std::vector<std::uint32_t>& a) {
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
}

/// a := what `op` (std::set_difference or std::merge) makes of a and b, both ascending, through
/// `scratch`.
template <class Op>
void combine_sorted(std::vector<std::uint32_t>& a, std::span<const std::uint32_t> b,
                    std::vector<std::uint32_t>& scratch, Op op) {
  if (b.empty()) return;
  scratch.clear();
  op(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(scratch));
  a.swap(scratch);
}

/// a := a without the values of b (both ascending).
inline void remove_sorted(std::vector<std::uint32_t>& a, std::span<const std::uint32_t> b,
                          std::vector<std::uint32_t>& scratch) {
  combine_sorted(a, b, scratch, [](auto... args) { return std::set_difference(args...); });
}

/// a := a with the values of b (both ascending, none in both).
inline void insert_sorted(std::vector<std::uint32_t>& a, std::span<const std::uint32_t> b,
                          std::vector<std::uint32_t>& scratch) {
  combine_sorted(a, b, scratch, [](auto... args) { return std::merge(args...); });
}

}  // namespace fixstep::detail
