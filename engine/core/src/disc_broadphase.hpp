// The broadphase of disc-disc contacts (issue #19, point 4): which pairs of discs may touch
// within a tick, from the boxes their discs sweep over it. Internal to the engine: not installed.
//
// A hierarchical uniform grid with a spatial hash. Each box gets a level from its extent
// e = max(width, height) against the smallest positive extent e_min of the call: level k holds
// the boxes with e <= e_min 2^k, in cells of side cell_factor e_min 2^k, so a box covers at
// most 2 x 2 cells of its level and a cell holds a bounded number of boxes that do not overlap,
// whatever the mix of sizes. A box looks for partners in the cells it covers on its own level
// and every coarser one (a pair is found by its smaller box; on one level by the smaller
// index), and reports a pair only in the cell holding the lower-left corner of the two boxes'
// intersection, so each pair once. The cells of all levels share one open hash table of 2^k
// buckets (>= 4n), built by a counting sort; a collision merges cells, never changes the pairs.
// Boxes that would cover more than max_cells_per_box cells (non-finite or astronomically large
// boxes, a blown-up world) go to an overflow list every box checks. Pairs are then put in
// (a, b) order by a counting sort on a and a sort of each a's short list.
//
// Why a grid, measured (bench/bench_broadphase.cpp, GCC 12 -O2, this machine, preliminary: see
// the numbers in the commit message and bench's header): sweep-and-prune on x scans, for each
// box, every box of its x-strip; in a square scene that strip holds ~sqrt(n) boxes, so its cost
// per body grows with sqrt(n) (x2.9 from 10^3 to 10^5 on the settled pile), and a column of
// discs costs it n^2 with no pairs to stop at. The grid's cost per body stays flat.
//
// Bounded time: every scan of a cell either meets boxes that overlap the scanning one (pairs,
// counted against max_pairs) or a bounded number that do not, and a static box scans only the
// dynamic boxes of a cell, so a million discs at one point cost O(n + max_pairs).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fixstep/world.hpp"  // detail::CachePtr, detail::Workers (workers.hpp)

namespace fixstep::detail {

/// A disc's box swept over one tick, in m (closed: min <= max on each axis).
struct SweptBox {
  double min_x, min_y, max_x, max_y;
};

/// Two indices into the boxes, a < b.
struct DiscPair {
  std::uint32_t a, b;
  friend bool operator==(const DiscPair&, const DiscPair&) = default;
};

/// True when the closed boxes overlap (touching counts); false if any coordinate is NaN.
inline bool boxes_overlap(const SweptBox& p, const SweptBox& q) {
  return p.min_x <= q.max_x && q.min_x <= p.max_x && p.min_y <= q.max_y && q.min_y <= p.max_y;
}

/// Writes into `out` (resized) the pairs of `first` then `second` (each pair once, a < b <
/// n) sorted by (a, b): a counting sort on a (`offset`, n + 1 entries of scratch) and a sort of
/// each a's list. O(n + pairs); allocates only to grow `offset` or `out`.
void order_pairs(std::span<const DiscPair> first, std::span<const DiscPair> second, std::size_t n,
                 std::vector<std::uint32_t>& offset, std::vector<DiscPair>& out);

/// The broadphase a World keeps between ticks. Its members are scratch only: a copy (a
/// snapshot) or a fresh object gives the same pairs; copying it copies plain vectors and not
/// its worker thread (a copy starts its own when first asked for two threads).
class DiscBroadphase {
 public:
  /// Below this many boxes a call with threads = 2 runs on one thread: the second thread's
  /// hand-off costs more than it saves (measured in bench_broadphase).
  static constexpr std::size_t min_parallel_boxes = 8192;
  /// Cell side of a level over the largest extent it holds: > 1 leaves room for rounding.
  static constexpr double cell_factor = 1.25;
  static constexpr unsigned max_levels = 48;

  /// Writes to `pairs` (cleared first) every pair (a, b), a < b, whose boxes overlap (closed
  /// intervals: touching counts) and of which at least one has active[i] != 0 (static discs
  /// are not paired with each other), each once, sorted lexicographically by (a, b). Boxes
  /// with a NaN coordinate overlap nothing.
  ///
  /// Returns false when the count would exceed max_pairs (`pairs` then holds an unspecified
  /// prefix, possibly empty); the work done before it stops is O(n + max_pairs). threads: 1
  /// or 2 (below 1 is 1, above 2 is 2); the result is bit for bit the same for both. With 2 it
  /// runs half the boxes' searches on a worker thread it keeps (started on first use).
  /// Allocates nothing once warm (the same or a smaller n and pair count as an earlier call).
  /// Preconditions: active.size() == boxes.size() < 2^32 - 1, max_pairs < 2^32.
  bool find_pairs(std::span<const SweptBox> boxes, std::span<const std::uint8_t> active,
                  std::size_t max_pairs, std::vector<DiscPair>& pairs, int threads);

  /// Sets the n from which threads = 2 splits the work (min_parallel_boxes by default; 0 to
  /// split always, as the benchmark does to measure the hand-off).
  void set_parallel_min(std::size_t n) { parallel_min_ = n; }

 private:
  /// A box as the grid stores it, in its home cell (the cell of its lower-left corner) and
  /// next to its index, so that a scan of a cell reads memory in order.
  struct Entry {
    SweptBox box;
    std::uint32_t index;
    std::int32_t cx, cy;  // home cell on its level
  };
  /// One level's table: cell (cx, cy) is bucket base + (cx & wmask) + (cy & hmask) << wshift,
  /// a dense grid where the level's boxes span at most its size, a wrapped one beyond.
  struct Level {
    double inv_cell = 0;  // 1 / cell side, 1/m
    std::uint32_t base = 0, wmask = 0, hmask = 0, wshift = 0;
  };
  static constexpr std::uint32_t overflow = ~std::uint32_t{0};  // level_ of an overflow box

  void assign_levels(std::span<const SweptBox> boxes);
  void size_tables(std::span<const SweptBox> boxes);
  void build_table(std::span<const SweptBox> boxes, std::span<const std::uint8_t> active);
  /// The cell of coordinate x (m) on a level, clamped to +-2^30 (monotone: neighbours stay
  /// neighbours); 0 for NaN.
  [[nodiscard]] std::int32_t cell_of(double x, std::uint32_t level) const {
    constexpr double limit = 1073741824.0;
    const double v = std::floor(x * levels_[level].inv_cell);
    return std::isnan(v) ? 0 : static_cast<std::int32_t>(std::clamp(v, -limit, limit));
  }
  [[nodiscard]] std::size_t bucket(std::uint32_t level, std::int32_t cx, std::int32_t cy) const {
    const Level& l = levels_[level];
    return l.base + (static_cast<std::uint32_t>(cx) & l.wmask) +
           ((static_cast<std::uint32_t>(cy) & l.hmask) << l.wshift);
  }
  bool scan(std::size_t begin, std::size_t end, std::span<const SweptBox> boxes,
            std::span<const std::uint8_t> active, std::size_t max_pairs,
            std::vector<DiscPair>& out) const;
  void scan_entry(std::size_t at, std::uint32_t level, std::span<const SweptBox> boxes,
                  std::span<const std::uint8_t> active, std::vector<DiscPair>& out) const;
  void scan_cell(const Entry& q, bool act, std::uint32_t level, std::int32_t cx, std::int32_t cy,
                 std::vector<DiscPair>& out) const;
  void scan_own_cell(std::size_t at, std::size_t h, std::vector<DiscPair>& out) const;
  void scan_overflow(const SweptBox& box, std::uint32_t q, bool act,
                     std::span<const SweptBox> boxes, std::span<const std::uint8_t> active,
                     std::vector<DiscPair>& out) const;

  std::vector<std::uint32_t> level_;  // per box: its level, or `overflow`
  Level levels_[max_levels];
  std::uint64_t level_mask_ = 0;  // bit k: level k holds a box
  // Bucket h's entries: entry_[start_[2h] .. start_[2h+1]) dynamic, then .. start_[2h+2) static.
  std::vector<std::uint32_t> start_;
  std::vector<Entry> entry_;
  std::vector<std::uint32_t> overflow_;  // indices of the overflow boxes, in order
  std::vector<DiscPair> raw_[2];         // unsorted pairs found by each thread
  std::vector<std::uint32_t> offset_;    // order_pairs' scratch
  std::size_t parallel_min_ = min_parallel_boxes;
  CachePtr<Workers, WorkersDeleter> worker_;
};

}  // namespace fixstep::detail
