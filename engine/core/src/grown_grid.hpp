// The boxes of discs that an impact sent beyond the box the broadphase paired them by, within
// one tick (disc_reach.cpp): a uniform grid filled as boxes grow, so that a disc leaving its box
// finds the others that left theirs without a look at each of them. Internal to the engine: not
// installed.
//
// Cells have a fixed side (a few disc diameters); a box is entered in every cell it covers, up
// to max_cells of them, and a wider box (a fast disc's path) in a list every query looks at. A
// hash table of 2^k >= 2n buckets (n discs) holds the cells, each entry keeping its cell so that
// cells sharing a bucket are told apart; emptying it touches only the buckets used. Queries
// return a superset (boxes whose cells meet the query's), with a disc possibly more than once.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "copy_bytes.hpp"
#include "grid_broadphase.hpp"

namespace fixstep::detail {

class GrownGrid {
 public:
  /// Cells a box may cover before it goes to the list every query looks at.
  static constexpr std::int64_t max_cells = 16;

  /// Empties the grid and sets its cell side (m, > 0) for up to n discs.
  void reset(double side, std::size_t n) {
    for (const std::uint32_t b : used_) head_[b] = none;
    used_.clear(), entries_.clear(), wide_.clear();
    const std::size_t size = std::bit_ceil(std::max<std::size_t>(2 * n, 16));
    if (head_.size() != size) head_.assign(size, none);
    inv_ = 1.0 / side;
  }

  /// Enters `disc` with box b (a NaN box is not entered: it overlaps nothing).
  void insert(std::uint32_t disc, const SweptBox& b) {
    std::int64_t x0, y0, x1, y1;
    if (!cells_of(b, x0, y0, x1, y1)) {
      if (!std::isnan(b.min_x + b.min_y + b.max_x + b.max_y)) wide_.push_back(disc);
      return;
    }
    if ((x1 - x0 + 1) * (y1 - y0 + 1) > max_cells) {
      wide_.push_back(disc);
      return;
    }
    for (std::int64_t cy = y0; cy <= y1; ++cy) {
      for (std::int64_t cx = x0; cx <= x1; ++cx) {
        const std::uint32_t h = bucket(cx, cy);
        if (head_[h] == none) used_.push_back(h);
        entries_.push_back(Entry{cx, cy, disc, head_[h]});
        head_[h] = static_cast<std::uint32_t>(entries_.size() - 1);
      }
    }
  }

  /// Calls visit(disc) for each disc entered with a box whose cells meet q's (and each wide
  /// one); returns the work done (cells and entries looked at).
  template <class Visit>
  std::uint64_t query(const SweptBox& q, Visit&& visit) const {
    std::uint64_t work = wide_.size();
    for (const std::uint32_t d : wide_) visit(d);
    std::int64_t x0, y0, x1, y1;
    if (entries_.empty() || !cells_of(q, x0, y0, x1, y1)) return work;
    if ((x1 - x0 + 1) * (y1 - y0 + 1) > std::int64_t(entries_.size())) {  // every entry once
      for (const Entry& e : entries_) {
        if (e.cx >= x0 && e.cx <= x1 && e.cy >= y0 && e.cy <= y1) visit(e.disc);
      }
      return work + entries_.size();
    }
    for (std::int64_t cy = y0; cy <= y1; ++cy) {
      for (std::int64_t cx = x0; cx <= x1; ++cx) {
        ++work;
        for (std::uint32_t i = head_[bucket(cx, cy)]; i != none; i = entries_[i].next) {
          ++work;
          if (entries_[i].cx == cx && entries_[i].cy == cy) visit(entries_[i].disc);
        }
      }
    }
    return work;
  }

  /// Heap bytes held.
  [[nodiscard]] std::size_t bytes() const { return copy_bytes(head_, entries_, wide_, used_); }
  /// Wide boxes: a query looks at each.
  [[nodiscard]] std::uint64_t wide() const { return wide_.size(); }
  /// The longest list of entries in one bucket: a query's cell looks at most at that many.
  [[nodiscard]] std::uint64_t longest_bucket() const {
    std::uint64_t most = 0;
    for (const std::uint32_t b : used_) {
      std::uint64_t length = 0;
      for (std::uint32_t i = head_[b]; i != none; i = entries_[i].next) ++length;
      most = std::max(most, length);
    }
    return most;
  }
  /// The cells query(q) looks at (0 for a NaN box), before it looks at every entry instead.
  [[nodiscard]] std::uint64_t cells(const SweptBox& q) const {
    std::int64_t x0, y0, x1, y1;
    if (!cells_of(q, x0, y0, x1, y1)) return 0;
    return std::uint64_t(x1 - x0 + 1) * std::uint64_t(y1 - y0 + 1);
  }

 private:
  static constexpr std::uint32_t none = 0xffffffffu;
  struct Entry {
    std::int64_t cx, cy;
    std::uint32_t disc, next;
  };
  /// The cells box b covers; false when they are not finite or beyond ±2^50 cells.
  bool cells_of(const SweptBox& b, std::int64_t& x0, std::int64_t& y0, std::int64_t& x1,
                std::int64_t& y1) const {
    constexpr double limit = 1125899906842624.0;  // 2^50
    const double lx = std::floor(b.min_x * inv_), ly = std::floor(b.min_y * inv_);
    const double hx = std::floor(b.max_x * inv_), hy = std::floor(b.max_y * inv_);
    if (!(std::abs(lx) < limit && std::abs(ly) < limit && std::abs(hx) < limit &&
          std::abs(hy) < limit)) {
      return false;
    }
    x0 = std::int64_t(lx), y0 = std::int64_t(ly), x1 = std::int64_t(hx), y1 = std::int64_t(hy);
    return true;
  }
  [[nodiscard]] std::uint32_t bucket(std::int64_t cx, std::int64_t cy) const {
    const auto h =
        std::uint64_t(cx) * 0x9E3779B97F4A7C15ull ^ std::uint64_t(cy) * 0xC2B2AE3D27D4EB4Full;
    return static_cast<std::uint32_t>((h ^ (h >> 29)) & (head_.size() - 1));
  }

  std::vector<std::uint32_t> head_;  ///< per bucket: its last entry, or none
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> wide_, used_;
  double inv_ = 1.0;  ///< 1 / cell side, 1/m
};

}  // namespace fixstep::detail
