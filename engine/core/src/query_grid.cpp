// The spatial index of World's queries (query_grid.hpp).
#include "query_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace fixstep::detail {

namespace {

/// Cell coordinates stay within ±2^61, so that a range of cells never overflows.
constexpr double max_cell = 0x1p61;

}  // namespace

std::int64_t QueryGrid::cell(double v) const {
  const double c = std::floor(v / h_);
  return static_cast<std::int64_t>(std::clamp(c, -max_cell, max_cell));
}

std::size_t QueryGrid::bucket(std::int64_t cx, std::int64_t cy) const {
  // A 64-bit mix of both coordinates (the multipliers of splitmix64 and of Fibonacci hashing).
  std::uint64_t k = std::uint64_t(cx) * 0x9e3779b97f4a7c15ull ^ std::uint64_t(cy);
  k = (k ^ (k >> 30)) * 0xbf58476d1ce4e5b9ull;
  k = (k ^ (k >> 27)) * 0x94d049bb133111ebull;
  return static_cast<std::size_t>((k ^ (k >> 31)) & (start_.size() - 2));
}

void QueryGrid::build() {
  stale = false;
  const std::size_t n = discs.size();
  marks_.assign(n, 0), mark_ = 0;
  entries_.clear(), big_.clear();
  small_r_ = 0.0;
  // Cell side: twice the radius 90 % of the finite discs do not exceed.
  scratch_.clear();
  for (const QueryDisc& d : discs) {
    if (std::isfinite(d.x) && std::isfinite(d.y)) scratch_.push_back(d.r);
  }
  if (scratch_.empty()) {
    for (std::uint32_t i = 0; i < n; ++i) big_.push_back(i);
    start_.assign(2, 0);
    return;
  }
  const std::size_t at = (scratch_.size() - 1) * 9 / 10;
  std::nth_element(scratch_.begin(), scratch_.begin() + std::ptrdiff_t(at), scratch_.end());
  h_ = 2.0 * scratch_[at];
  for (std::uint32_t i = 0; i < n; ++i) {
    const QueryDisc& d = discs[i];
    if (!(std::isfinite(d.x) && std::isfinite(d.y)) || d.r > h_) {
      big_.push_back(i);
      continue;
    }
    small_r_ = std::max(small_r_, d.r);
    entries_.push_back(Entry{cell(d.x), cell(d.y), i});
  }
  // Buckets: a power of two >= 2 entries (start_ holds one more, the end).
  const std::size_t buckets = std::bit_ceil(std::max<std::size_t>(2 * entries_.size(), 2));
  start_.assign(buckets + 1, 0);
  for (const Entry& e : entries_) ++start_[bucket(e.cx, e.cy) + 1];
  for (std::size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
  // Counting sort by bucket: entries_ rebuilt in bucket order, each bucket in disc order.
  std::vector<Entry>& sorted = sorted_;
  sorted.resize(entries_.size());
  std::vector<std::uint32_t>& cursor = cursor_;
  cursor.assign(start_.begin(), start_.end() - 1);
  for (const Entry& e : entries_) sorted[cursor[bucket(e.cx, e.cy)]++] = e;
  entries_.swap(sorted);
}

std::uint32_t QueryGrid::next_mark() {
  if (++mark_ == 0) {  // wrapped: forget every mark
    std::fill(marks_.begin(), marks_.end(), 0u);
    mark_ = 1;
  }
  return mark_;
}

}  // namespace fixstep::detail
