// The broadphase of contacts: which pairs of bodies may touch within a tick, from the boxes they
// sweep over it (the discs' swept boxes, disc_contacts.hpp; the shapes' boxes, shape_world.hpp).
// Internal to the engine: not installed.
//
// A hierarchical uniform grid. Levels halve from the largest finite extent e_top (extent =
// max(width, height)): level k holds the boxes with extent in (e_top 2^-(k+1), e_top 2^-k], in
// cells of side 1.25 e_top 2^-k (the 1.25 leaves room for rounding), the last level everything
// smaller. Each box is stored once, in its home cell (the cell of its lower-left corner); two
// boxes of one level that overlap have home cells at most one apart, so a box searches its own
// cell and half of its 8 neighbours (each pair of cells once), and the 3 x 3 home cells around
// its own on every coarser level (a pair is found by its smaller box). A level's cells are a
// dense grid over its boxes' home cells, wrapped to at most ~2 buckets per box where they
// spread further (an outlier far away): cells that share a bucket are told apart by the home
// cell stored with each box. The table is a counting sort by (bucket, static?), on two threads
// in two halves of the boxes (each bucket's boxes stay in index order, so the bits do not
// depend on the split). Boxes not finite (a coordinate, or the extent: corners near ±1.8e308
// can be farther apart than the largest double) go to an overflow list every box checks. The
// pairs are then put in (a, b) order by a counting sort on a and a sort of each a's short list.
//
// Why a grid, measured (bench/bench_broadphase.cpp, GCC 12 -O3, CPU time of one thread, ns per
// body per call at n = 10^3 / 10^4 / 10^5; preliminary: load average 8.7-9.5 on 2 cores while
// others compiled, ranges over three runs):
//   settled pile:  grid 58-64 / 68-85 / 73-83 (x1.25-1.31 from 10^3 to 10^5)
//                  sweep-and-prune, std::sort each call   45 / 328 / 570   (x12.6)
//                  sweep-and-prune, insertion sort kept   33 / 282 / 516   (x15.4)
//   moving gas:    grid 96-97 / 91-95 / 125-161 (x1.30-1.66)
//                  sweep-and-prune, std::sort each call  140 / 269 / 499   (x3.6)
//                  sweep-and-prune, insertion sort kept  110 / 224 / 425   (x3.9)
// Sweep-and-prune on x scans, for each box, every box of its x-strip; in a square scene that
// strip holds ~sqrt(n) boxes (a whole column of the pile's lattice), and a column of discs costs
// it n^2 with no pair to stop at. It wins only at 10^3 on the pile (33 vs 58 ns).
//
// Bounded time: a cell holds a bounded number of boxes of its level that do not overlap (their
// extents are at least 1/2.5 of its side), every other box it holds is a pair counted against
// max_pairs, and a static box searches only the dynamic boxes, so a million discs at one point
// cost O(n + max_pairs): 0.1-0.5 s a call for 10^6 discs at one point with max_pairs = 4 10^6
// (all dynamic: false; all static: true, 0.1 s), measured at load 9 on 2 cores.
// Only boxes below e_top 2^-47 (points, not discs) at distinct places can crowd a cell.
//
// Two threads (bench_broadphase's grid rows, wall time, medians of 5, twice, on an idle 2-core
// EPYC VM): split, a call at 10^4 boxes takes 414-475 instead of 641-716 us (pile) and 651-657
// instead of 892-961 us (gas); at 10^3 42-44 instead of 57-58 us (pile) but 63 or 120 instead
// of 95-96 us (gas): the serial rest is the levels' sizing, the prefix sums and the final sort,
// and the hand-over costs some microseconds when it wakes the worker. Within a tick's run of
// the second thread (second_thread.hpp) the worker spins and the hand-over is cheap: there the
// split pays from a few hundred boxes (docs/perf/contact_solver_plan.md has the measurements),
// so threads = 2 splits from min_parallel_boxes = 512 boxes.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "second_thread.hpp"

namespace fixstep::detail {

/// A body's box swept over one tick (a disc's, or a shape's), in m (closed: min <= max on each
/// axis).
struct SweptBox {
  double min_x, min_y, max_x, max_y;
};

/// Two indices into the boxes, a < b.
struct DiscPair {
  std::uint32_t a, b;
  friend bool operator==(const DiscPair&, const DiscPair&) = default;
};

/// The pair's key a << 32 | b: pairs in (a, b) order are in key order.
inline std::uint64_t pair_key(const DiscPair& p) {
  return (std::uint64_t(p.a) << 32) | p.b;
}

/// ⌊v⌋ clamped to ±2^30 (a grid cell's index from a coordinate over the cell's size), 0 for
/// NaN: the value std::floor and std::clamp give, taken by a truncation and one comparison
/// (floor is monotone and ±2^30 are integers, so clamping first gives the same integer, which
/// truncates exactly), without floor's branches on the argument's size.
inline std::int32_t floor_cell(double v) {
  constexpr double limit = 1073741824.0;
  if (std::isnan(v)) return 0;
  const double c = std::min(std::max(v, -limit), limit);
  const auto t = static_cast<std::int32_t>(c);  // towards zero, exact for |c| <= 2^30
  return t - static_cast<std::int32_t>(static_cast<double>(t) > c);
}

/// True when the closed boxes overlap (touching counts); false if any coordinate is NaN.
/// Every comparison is made (`&`, not `&&`): one branch where it is tested, which a scan of
/// candidates that mostly miss predicts, where the short-circuit gives four it cannot.
inline bool boxes_overlap(const SweptBox& p, const SweptBox& q) {
  return (p.min_x <= q.max_x) & (q.min_x <= p.max_x) & (p.min_y <= q.max_y) & (q.min_y <= p.max_y);
}

/// True when box `inner` lies within box `outer` (edges may touch); false if any coordinate
/// is NaN.
inline bool box_within(const SweptBox& inner, const SweptBox& outer) {
  return inner.min_x >= outer.min_x && inner.max_x <= outer.max_x && inner.min_y >= outer.min_y &&
         inner.max_y <= outer.max_y;
}

/// Writes into `out` (resized) the pairs of `first` then `second` (each pair once, a < b <
/// n) sorted by (a, b): a counting sort on a (`offset`, n + 1 entries of scratch) and a sort of
/// each a's list. O(n + pairs); allocates only to grow `offset` or `out`.
void order_pairs(std::span<const DiscPair> first, std::span<const DiscPair> second, std::size_t n,
                 std::vector<std::uint32_t>& offset, std::vector<DiscPair>& out);

/// The broadphase a World keeps between ticks. Its members are scratch only: a copy (a
/// snapshot) or a fresh object gives the same pairs; copying it copies its setting, neither the
/// scratch nor its worker thread (a copy starts its own when first asked for two threads).
class GridBroadphase {
 public:
  /// Below this many boxes a call with threads = 2 runs on one thread (see above: the disc
  /// contacts pass threads = 2 only within the tick's run of the second thread).
  static constexpr std::size_t min_parallel_boxes = 512;
  /// Keys (two a bucket) from which a split build starts them by halves (start_keys()).
  static constexpr std::size_t min_parallel_keys = 16384;
  /// Cell side of a level over the largest extent it holds: > 1 leaves room for rounding.
  static constexpr double cell_factor = 1.25;
  static constexpr unsigned max_levels = 48;

  GridBroadphase() = default;
  /// A copy takes the settings (set_parallel_min) and none of the scratch, which every
  /// find_pairs call builds anew, nor the thread. Assigning keeps the target's own scratch and
  /// thread: a World's restore (a rollback, every frame) then neither copies the grid nor
  /// stops a worker that its next tick would start again.
  GridBroadphase(const GridBroadphase& other) : parallel_min_(other.parallel_min_) {}
  GridBroadphase& operator=(const GridBroadphase& other) {
    if (this != &other) parallel_min_ = other.parallel_min_;
    return *this;
  }
  ~GridBroadphase() = default;

  /// Writes to `pairs` (cleared first) every pair (a, b), a < b, whose boxes overlap (closed
  /// intervals: touching counts) and of which at least one has active[i] != 0 (static discs
  /// are not paired with each other), each once, sorted lexicographically by (a, b). Boxes
  /// with a NaN coordinate overlap nothing.
  ///
  /// Returns false when the count would exceed max_pairs (`pairs` then holds an unspecified
  /// prefix; today empty); the work done before it stops is O(n + max_pairs). threads: 1
  /// or 2 (below 1 is 1, above 2 is 2); the result is bit for bit the same for both. With 2
  /// (and n >= min_parallel_boxes) it runs half of each pass (levels, table counts and fill,
  /// searches) on a worker thread it keeps (started on first use; the sizing, prefix sums and
  /// the final sort stay on the calling thread).
  /// Allocates nothing once warm (the same or a smaller n and pair count as an earlier call).
  /// `lent`, when given, is the second thread it splits on instead of its own (a caller that
  /// keeps a run of its own thread open, as the shape world does: one worker a world).
  /// Preconditions: active.size() == boxes.size() < 2^32 - 1, max_pairs < 2^32.
  bool find_pairs(std::span<const SweptBox> boxes, std::span<const std::uint8_t> active,
                  std::size_t max_pairs, std::vector<DiscPair>& pairs, int threads,
                  SecondThread* lent = nullptr);
  /// Whether the last find_pairs call stopped at the veto's max_rejected (false when it
  /// found its pairs, or max_pairs stopped it).
  [[nodiscard]] bool stopped_by_veto() const { return stopped_by_veto_; }
  /// The pairs the veto dropped in the last find_pairs call (where it stopped, those up to
  /// then).
  [[nodiscard]] std::uint64_t rejected() const { return rejected_; }

  /// Makes the table of `boxes` for query() alone, pairing none: O(n). Allocates nothing once
  /// warm. Preconditions: boxes.size() < 2^32 - 1.
  void index(std::span<const SweptBox> boxes);
  /// The boxes of the last find_pairs or index call that no level holds (a coordinate or the
  /// extent not finite, or cells too small to represent), ascending: query() leaves them out.
  [[nodiscard]] std::span<const std::uint32_t> unindexed() const { return overflow_; }

  /// Pairs that can never touch, which find_pairs leaves out and does not count against its
  /// max_pairs: reject(context, a, b) true drops the pair (a < b; called from both threads, so
  /// it must only read). More than max_rejected dropped in all makes find_pairs return false
  /// as max_pairs does, on one thread or two alike, which bounds its work: O(n + max_pairs +
  /// max_rejected).
  struct PairVeto {
    bool (*reject)(const void* context, std::uint32_t a, std::uint32_t b) = nullptr;
    const void* context = nullptr;
    std::uint64_t max_rejected = 0;
  };
  /// The veto of the next find_pairs calls (null: none; then every overlapping pair counts).
  /// It must outlive them.
  void set_veto(const PairVeto* veto) { veto_ = veto; }

  /// Calls visit(i, box) for each box i of the last find_pairs call whose box as it was then
  /// (`box`) overlaps q, static and dynamic, each once, in a fixed order. The overflow list's
  /// boxes are left out: non-finite, they overlapped every box already, or none (NaN). Returns the
  /// work it did: the cells and entries it looked at. O(min(cells q covers, buckets) per level +
  /// entries seen).
  template <class Visit>
  std::uint64_t query(const SweptBox& q, Visit&& visit) const;

  /// Sets the n from which threads = 2 splits the work (min_parallel_boxes by default; 0 to
  /// split always, as the benchmark does to measure the hand-off).
  void set_parallel_min(std::size_t n) { parallel_min_ = n; }

  /// The broadphase's second thread (its worker started on first use), lent to the impact
  /// predictions and the resting solver so that a world's discs keep one second thread; a
  /// tick's disc phase keeps a run of it open (SecondThread::open) around all of them.
  SecondThread& second_thread() { return second_; }
  [[nodiscard]] const SecondThread& second_thread() const { return second_; }

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
  /// What one thread finds over its share [begin, end) of the boxes: the largest finite extent
  /// (m), then per level the range of home cells and the count, and the overflow count and the
  /// boxes not finite.
  struct Share {
    std::size_t begin = 0, end = 0;
    double e_top = 0;
    std::array<std::int32_t, max_levels> lo_x, lo_y, hi_x, hi_y;
    std::array<std::uint32_t, max_levels> count;
    std::uint32_t overflow = 0;
    std::uint32_t not_finite = 0;  // boxes with a coordinate or the extent not finite
  };

  /// Runs job(0) here and job(1) on the worker when it splits, else both here in order.
  template <class Job>
  void both(bool split, Job& job);
  /// The levels, the tables and the overflow list of `boxes` (the searches' input), by halves
  /// when split.
  void build(std::span<const SweptBox> boxes, std::span<const std::uint8_t> active, bool split);
  void largest_extent(Share& s, std::span<const SweptBox> boxes) const;
  void set_levels(double e_top);
  void assign_levels(Share& s, std::span<const SweptBox> boxes);
  void size_tables();
  void count_keys(const Share& s, std::span<const std::uint8_t> active,
                  std::vector<std::uint32_t>& count) const;
  /// Each key's first entry (start_) and each thread's next slot in it (cursor_), from the
  /// counts: by halves of the keys when split, from min_parallel_keys keys.
  void start_keys(bool split);
  void fill_keys(const Share& s, std::span<const SweptBox> boxes,
                 std::span<const std::uint8_t> active, std::vector<std::uint32_t>& cursor);
  /// The cell of coordinate x (m) on a level, clamped to +-2^30 (monotone: neighbours stay
  /// neighbours); 0 for NaN.
  [[nodiscard]] std::int32_t cell_of(double x, std::uint32_t level) const {
    return floor_cell(x * levels_[level].inv_cell);
  }
  [[nodiscard]] std::size_t bucket(std::uint32_t level, std::int32_t cx, std::int32_t cy) const {
    const Level& l = levels_[level];
    return l.base + (static_cast<std::uint32_t>(cx) & l.wmask) +
           ((static_cast<std::uint32_t>(cy) & l.hmask) << l.wshift);
  }
  /// The searches of entries [begin, end) (and of the overflow boxes if with_overflow) into
  /// `out`, the pairs the veto dropped counted in `rejected`; false once out holds more than
  /// max_pairs or more than the veto's max_rejected were dropped.
  bool scan(std::size_t begin, std::size_t end, bool with_overflow, std::span<const SweptBox> boxes,
            std::span<const std::uint8_t> active, std::size_t max_pairs, std::vector<DiscPair>& out,
            std::uint64_t& rejected) const;
  /// Appends the pair (a, b) in (min, max) order to out, or counts it in `rejected` when the
  /// veto rejects it.
  void add(std::uint32_t a, std::uint32_t b, std::vector<DiscPair>& out,
           std::uint64_t& rejected) const;
  void scan_entry(std::size_t at, std::uint32_t level, std::span<const SweptBox> boxes,
                  std::span<const std::uint8_t> active, std::vector<DiscPair>& out,
                  std::uint64_t& rejected) const;
  void scan_cell(const Entry& q, bool act, std::uint32_t level, std::int32_t cx, std::int32_t cy,
                 std::vector<DiscPair>& out, std::uint64_t& rejected) const;
  /// For a dynamic box q: the entries of cells x0..x1 of row cy on a level (from entry `from`
  /// on) that overlap it, dynamic and static, in the order cell by cell gives; false (nothing
  /// done) when those cells' buckets are not one run (the row wraps).
  bool scan_row(const Entry& q, std::size_t from, std::uint32_t level, std::int32_t x0,
                std::int32_t x1, std::int32_t cy, std::vector<DiscPair>& out,
                std::uint64_t& rejected) const;
  void scan_own_cell(std::size_t at, std::size_t h, std::vector<DiscPair>& out,
                     std::uint64_t& rejected) const;
  void scan_overflow(const SweptBox& box, std::uint32_t q, bool act,
                     std::span<const SweptBox> boxes, std::span<const std::uint8_t> active,
                     std::vector<DiscPair>& out, std::uint64_t& rejected) const;

  std::vector<std::uint32_t> level_;  // per box: its level, or `overflow`
  struct Cell {
    std::int32_t cx, cy;
  };
  std::vector<Cell> home_;  // per box on a level: its home cell there
  std::array<Level, max_levels> levels_;
  double e_top_ = 1;              // the largest finite extent of the call, m
  std::uint64_t level_mask_ = 0;  // bit k: level k holds a box
  // Bucket h's entries: entry_[start_[2h] .. start_[2h+1]) dynamic, then .. start_[2h+2) static.
  std::vector<std::uint32_t> start_;
  std::array<std::vector<std::uint32_t>, 2>
      cursor_;  // per thread: its count, then its next slot, per key
  std::vector<Entry> entry_;
  std::array<Share, 2> share_;
  std::vector<std::uint32_t> overflow_;       // indices of the overflow boxes, in order
  std::array<std::vector<DiscPair>, 2> raw_;  // unsorted pairs found by each thread
  std::vector<std::uint32_t> offset_;         // order_pairs' scratch
  std::size_t parallel_min_ = min_parallel_boxes;
  const PairVeto* veto_ = nullptr;
  bool stopped_by_veto_ = false;
  std::uint64_t rejected_ = 0;
  std::vector<std::uint8_t> idle_;  // index()'s activity: none
  SecondThread* lent_ = nullptr;    // find_pairs' `lent` during the call
  SecondThread second_;
};

template <class Visit>
std::uint64_t GridBroadphase::query(const SweptBox& q, Visit&& visit) const {
  std::uint64_t work = 0;
  for (std::uint64_t m = level_mask_; m != 0; m &= m - 1) {
    const auto k = static_cast<std::uint32_t>(std::countr_zero(m));
    const Level& l = levels_[k];
    // A box of level k is narrower than a cell: its home cell (lower-left corner) is at most
    // one cell below and left of q's.
    const std::int32_t x0 = cell_of(q.min_x, k) - 1, x1 = cell_of(q.max_x, k);
    const std::int32_t y0 = cell_of(q.min_y, k) - 1, y1 = cell_of(q.max_y, k);
    auto seen = [&](const Entry& e) {
      return e.cx >= x0 && e.cx <= x1 && e.cy >= y0 && e.cy <= y1 && boxes_overlap(q, e.box);
    };
    const std::uint64_t cells =
        std::uint64_t(std::int64_t{x1} - x0 + 1) * std::uint64_t(std::int64_t{y1} - y0 + 1);
    const std::uint64_t buckets = std::uint64_t{l.wmask + 1} * (l.hmask + 1);
    if (cells >= buckets) {  // every entry of the level once
      const std::size_t first = start_[2 * std::size_t{l.base}];
      const std::size_t last = start_[2 * (std::size_t{l.base} + buckets)];
      work += buckets + (last - first);
      for (std::size_t p = first; p < last; ++p) {
        if (seen(entry_[p])) visit(entry_[p].index, entry_[p].box);
      }
      continue;
    }
    const auto span = static_cast<std::uint32_t>(x1 - x0);
    const bool rows = (static_cast<std::uint32_t>(x0) & l.wmask) + std::uint64_t{span} <= l.wmask;
    for (std::int32_t cy = y0; cy <= y1; ++cy) {
      if (rows) {  // cells x0..x1 of the row are adjacent buckets: one run, in the same order
        const std::size_t h = bucket(k, x0, cy);
        work += std::uint64_t{span} + 1;
        for (std::size_t p = start_[2 * h], end = start_[2 * (h + span) + 2]; p < end; ++p) {
          const Entry& e = entry_[p];
          ++work;
          if (e.cy == cy && seen(e)) visit(e.index, e.box);
        }
        continue;
      }
      for (std::int32_t cx = x0; cx <= x1; ++cx) {
        const std::size_t h = bucket(k, cx, cy);
        ++work;
        for (std::size_t p = start_[2 * h], end = start_[2 * h + 2]; p < end; ++p) {
          const Entry& e = entry_[p];
          ++work;
          if (e.cx == cx && e.cy == cy && seen(e)) visit(e.index, e.box);
        }
      }
    }
  }
  return work;
}

}  // namespace fixstep::detail
