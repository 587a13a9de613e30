// The spatial index World's queries run through (query.hpp): the bodies' discs at their current
// positions in a uniform grid, built on the first query after the world changed. Internal to
// the engine: not installed. A body's shape enters as the disc around its box at the body's
// pose (centre the box's middle, radius its half diagonal), the shape itself placed in world
// coordinates beside it (QueryShape) for the exact tests.
//
// Cells have side h = 2 r90, r90 being the radius 90 % of the discs do not exceed; each disc
// with r <= h lives in the cell of its centre (a loose grid: a query widens its box by the
// largest such radius), the few larger ones in a list every query checks. Cells are found
// through a hash table of 2^k >= 2n buckets filled by a counting sort, each entry keeping its
// cell so that cells sharing a bucket are told apart. A query visits the cells its widened box
// covers, or every disc when that box covers more cells than there are discs (a ray across
// the whole world, a box of a continent): its cost is bounded by min(cells, n) either way.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/entity.hpp"
#include "fixstep/core/shape.hpp"
#include "shape_geom.hpp"

namespace fixstep::detail {

/// One disc as the queries see it: centre and radius (m), body, filter, sensor flag; for a
/// shape the disc around its box, its place in QueryGrid::shapes and its index in the body.
struct QueryDisc {
  static constexpr std::uint32_t none = ~std::uint32_t{0};
  double x = 0, y = 0, r = 0;
  Entity body{};
  CollisionFilter filter{};
  bool sensor = false;
  std::uint32_t shape = none;  ///< index into QueryGrid::shapes; none: a disc
  std::uint32_t index = 0;     ///< the shape's index in World::shapes(body)
};

/// A shape placed at its body's pose (world coordinates, m) and its box.
struct QueryShape {
  Convex convex;
  Aabb box;
};

class QueryGrid {
 public:
  /// True when the world changed since build(): the next query rebuilds first.
  bool stale = true;
  /// The discs to index, filled by the caller before build() (storage kept between builds).
  std::vector<QueryDisc> discs;
  /// The shapes the discs name (QueryDisc::shape), filled with them.
  std::vector<QueryShape> shapes;

  /// Indexes `discs`. Allocates only to grow (no allocation once warm for a steady count).
  void build();
  /// Calls visit(i) once for every disc i whose centre may lie within the box [x0, x1] x
  /// [y0, y1] widened by its radius (a superset: the caller tests exactly). Returns false
  /// without visiting anything when the box is not finite.
  template <class Visit>
  bool for_each_near(double x0, double y0, double x1, double y1, Visit&& visit) const;
  /// Largest radius of the discs kept in cells, m.
  [[nodiscard]] double cell_radius() const { return small_r_; }
  /// The grid's cell side, m.
  [[nodiscard]] double cell_side() const { return h_; }
  /// A fresh visit mark (for callers visiting overlapping boxes): marks(i) == it after mark.
  std::uint32_t next_mark();
  /// Marks disc i visited with `mark`; returns false when it already was.
  bool mark(std::size_t i, std::uint32_t mark) {
    if (marks_[i] == mark) return false;
    marks_[i] = mark;
    return true;
  }

 private:
  struct Entry {
    std::int64_t cx, cy;
    std::uint32_t disc;
  };
  [[nodiscard]] std::size_t bucket(std::int64_t cx, std::int64_t cy) const;
  [[nodiscard]] std::int64_t cell(double v) const;

  double h_ = 1.0, small_r_ = 0.0;
  std::vector<double> scratch_;
  std::vector<std::uint32_t> start_;  ///< bucket b's entries: entries_[start_[b] .. start_[b+1])
  std::vector<Entry> entries_, sorted_;
  std::vector<std::uint32_t> cursor_;
  std::vector<std::uint32_t> big_;  ///< discs too large for a cell, or not finite
  std::vector<std::uint32_t> marks_;
  std::uint32_t mark_ = 0;
};

template <class Visit>
bool QueryGrid::for_each_near(double x0, double y0, double x1, double y1, Visit&& visit) const {
  for (const std::uint32_t i : big_) visit(std::size_t{i});
  if (entries_.empty()) return true;
  const double pad = small_r_;
  const double lx = x0 - pad, ly = y0 - pad, hx = x1 + pad, hy = y1 + pad;
  if (!(std::isfinite(lx) && std::isfinite(ly) && std::isfinite(hx) && std::isfinite(hy))) {
    return false;
  }
  const std::int64_t cx0 = cell(lx), cy0 = cell(ly), cx1 = cell(hx), cy1 = cell(hy);
  const double cells = (double(cx1 - cx0) + 1.0) * (double(cy1 - cy0) + 1.0);
  if (cells > double(entries_.size())) {  // wider than the world's discs: visit them all
    for (const Entry& e : entries_) visit(std::size_t{e.disc});
    return true;
  }
  for (std::int64_t cy = cy0; cy <= cy1; ++cy) {
    for (std::int64_t cx = cx0; cx <= cx1; ++cx) {
      const std::size_t b = bucket(cx, cy);
      for (std::uint32_t k = start_[b]; k < start_[b + 1]; ++k) {
        const Entry& e = entries_[k];
        if (e.cx == cx && e.cy == cy) visit(std::size_t{e.disc});
      }
    }
  }
  return true;
}

}  // namespace fixstep::detail
