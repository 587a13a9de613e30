// The disc broadphase (engine/core/src/grid_broadphase.hpp): its pairs
// against a brute-force O(n^2) reference on random sets, one and two threads, fresh, reused and
// copied objects, its query() against every box, the max_pairs cap on a million discs at one point,
// no allocation once warm (its second thread: test_second_thread.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "grid_broadphase.hpp"

// count_new.cpp: this program's operator new, counting the bytes asked for while counting.
extern std::atomic<bool> counting;
extern std::atomic<std::size_t> counted_bytes;

namespace fixstep::detail {
namespace {

/// A set of boxes and which of them are dynamic.
struct BoxSet {
  std::vector<SweptBox> boxes;
  std::vector<std::uint8_t> active;
};

/// Every overlapping pair with a dynamic end, in (a, b) order: the reference.
std::vector<DiscPair> brute_force(const BoxSet& s) {
  std::vector<DiscPair> out;
  const auto n = static_cast<std::uint32_t>(s.boxes.size());
  for (std::uint32_t a = 0; a < n; ++a) {
    for (std::uint32_t b = a + 1; b < n; ++b) {
      if ((s.active[a] || s.active[b]) && boxes_overlap(s.boxes[a], s.boxes[b])) {
        out.push_back({a, b});
      }
    }
  }
  return out;
}

/// n discs of radius in [r_min, r_max] (log-uniform) at uniform positions in a square of side
/// `side` whose lower-left corner is (x0, y0), swept by up to `sweep` m; a fraction `dynamic`
/// of them active.
BoxSet random_set(std::size_t n, double r_min, double r_max, double side, double x0, double y0,
                  double sweep, double dynamic, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  BoxSet s;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = r_min * std::pow(r_max / r_min, u(rng));
    const double x = x0 + side * u(rng), y = y0 + side * u(rng);
    const double dx = sweep * (2 * u(rng) - 1), dy = sweep * (2 * u(rng) - 1);
    s.boxes.push_back({std::min(x, x + dx) - r, std::min(y, y + dy) - r, std::max(x, x + dx) + r,
                       std::max(y, y + dy) + r});
    s.active.push_back(u(rng) < dynamic ? 1 : 0);
  }
  return s;
}

std::vector<DiscPair> find(GridBroadphase& bp, const BoxSet& s, int threads,
                           std::size_t max_pairs = 1u << 30) {
  std::vector<DiscPair> pairs;
  EXPECT_TRUE(bp.find_pairs(s.boxes, s.active, max_pairs, pairs, threads));
  return pairs;
}

/// Checks the broadphase against the reference with one and two threads.
void expect_reference(const BoxSet& s) {
  const std::vector<DiscPair> want = brute_force(s);
  GridBroadphase bp;
  EXPECT_EQ(find(bp, s, 1), want);
  EXPECT_EQ(find(bp, s, 2), want);
}

/// A cell's index as std::floor and std::clamp give it, the reference for floor_cell.
std::int32_t floor_clamped(double v) {
  constexpr double limit = 1073741824.0;  // 2^30
  const double f = std::floor(v);
  return std::isnan(f) ? 0 : static_cast<std::int32_t>(std::clamp(f, -limit, limit));
}

TEST(GridBroadphase, ACellIndexIsTheFloorClampedToTwoToTheThirty) {
  // The edges (integers, the doubles next to them, the clamp's bounds, infinities, NaN,
  // subnormals, signed zeros), then doubles of every exponent from random bits and values
  // near the cells of the benchmarks' worlds.
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> values{
      0.0,          -0.0,          0.5,    -0.5,         1e300,
      -1e300,       inf,           -inf,   4294967296.5, -4294967296.5,
      1073741824.0, -1073741824.0, 5e-324, -5e-324,      std::numeric_limits<double>::quiet_NaN()};
  for (double k :
       {0.0, 1.0, -1.0, 7.0, -7.0, 1073741823.0, -1073741823.0, 1073741825.0, -1073741825.0}) {
    values.insert(values.end(), {k, std::nextafter(k, inf), std::nextafter(k, -inf)});
  }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> near(-3000.0, 3000.0);
  for (int i = 0; i < 200000; ++i) {
    const std::uint64_t bits = rng();
    // A NaN's bits made quiet, told from the bits alone: a comparison of a signalling NaN
    // (std::isnan's too, under clang) raises the invalid flag, which the tests trap.
    constexpr std::uint64_t exponent = 0x7ff0000000000000u, quiet = 0x0008000000000000u;
    const bool nan = (bits & exponent) == exponent && (bits & ~(exponent | 1ull << 63)) != 0;
    const double v = std::bit_cast<double>(nan ? bits | quiet : bits);
    const double w = near(rng), k = std::nearbyint(w);
    values.insert(values.end(), {v, w, k, std::nextafter(k, -inf), std::nextafter(k, inf)});
  }
  int wrong = 0;
  for (const double v : values) {
    if (floor_cell(v) != floor_clamped(v) && ++wrong <= 5) {
      ADD_FAILURE() << "v = " << v << ": " << floor_cell(v) << ", want " << floor_clamped(v);
    }
  }
  EXPECT_EQ(wrong, 0) << "of " << values.size();
}

TEST(GridBroadphase, MatchesBruteForceOnUniformSizes) {
  for (unsigned seed = 1; seed <= 3; ++seed) {  // a pile-like density, then a sparse gas
    expect_reference(random_set(3000, 0.05, 0.1, 8.0, 0.0, 0.0, 0.02, 0.9, seed));
    expect_reference(random_set(3000, 0.05, 0.05, 30.0, 0.0, 0.0, 0.2, 1.0, seed));
  }
}

TEST(GridBroadphase, MatchesBruteForceOnMixedSizes1To100) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    expect_reference(random_set(3000, 0.01, 1.0, 20.0, 0.0, 0.0, 0.05, 0.8, seed));
  }
  BoxSet s = random_set(10000, 0.01, 0.01, 10.0, 0.0, 0.0, 0.0, 1.0, 4);
  s.boxes.push_back({2.0, 3.0, 6.0, 7.0});  // one huge disc among 10^4 tiny ones, static
  s.active.push_back(0);
  expect_reference(s);
}

TEST(GridBroadphase, MatchesBruteForceAtNegativeAndLargeCoordinates) {
  expect_reference(random_set(3000, 0.05, 0.1, 8.0, -4.0, -4.0, 0.02, 0.9, 5));  // across 0
  expect_reference(random_set(3000, 0.05, 0.1, 8.0, -1e4, -3e4, 0.02, 0.9, 6));
  expect_reference(random_set(3000, 0.05, 0.1, 8.0, 1e9, -1e9, 0.02, 0.9, 7));
  BoxSet far = random_set(3000, 0.05, 0.1, 8.0, 0.0, 0.0, 0.02, 0.9, 16);
  for (int i = 0; i < 4; ++i) {  // outliers: a level's cells wrap into fewer buckets
    far.boxes.push_back({1e5 * i - 0.1, 3e4, 1e5 * i + 0.1, 3e4 + 0.2});
    far.active.push_back(1);
  }
  expect_reference(far);
}

/// Boxes in one row of cells, and in two rows, of a level whose table is then one row of
/// buckets: the rows above share their buckets with the boxes' own.
BoxSet rows_of_boxes(int rows) {
  BoxSet s;
  for (int r = 0; r < rows; ++r) {
    for (int i = 0; i < 40; ++i) {
      const double x = 0.13 * i + 0.01 * r, y = 0.26 * r;
      s.boxes.push_back({x, y, x + 0.2, y + 0.2});
      s.active.push_back(i % 7 == 3 ? 0 : 1);
    }
  }
  return s;
}

TEST(GridBroadphase, MatchesBruteForceWhereRowsShareBuckets) {
  expect_reference(rows_of_boxes(1));
  expect_reference(rows_of_boxes(2));
  expect_reference(rows_of_boxes(5));
}

/// Checks query() against every box that overlaps q, each once, after a find_pairs of s.
void expect_query_reference(const BoxSet& s, const std::vector<SweptBox>& queries) {
  GridBroadphase bp;
  find(bp, s, 1);
  for (const SweptBox& q : queries) {
    std::vector<std::uint32_t> got, want;
    bp.query(q, [&](std::uint32_t i, const SweptBox& box) {
      got.push_back(i);
      EXPECT_EQ(box.min_x, s.boxes[i].min_x);
    });
    for (std::uint32_t i = 0; i < s.boxes.size(); ++i) {
      if (boxes_overlap(q, s.boxes[i])) want.push_back(i);
    }
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want) << "query [" << q.min_x << ", " << q.max_x << "] x [" << q.min_y << ", "
                         << q.max_y << "]";
  }
}

TEST(GridBroadphase, AQueryFindsEveryBoxThatOverlapsItOnce) {
  std::vector<SweptBox> queries;
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 300; ++i) {  // points to boxes several cells wide
    const double x = -1.0 + 10.0 * u(rng), y = -1.0 + 10.0 * u(rng), w = 0.6 * u(rng) * u(rng);
    queries.push_back({x, y, x + w, y + w * u(rng)});
  }
  expect_query_reference(random_set(3000, 0.05, 0.1, 8.0, 0.0, 0.0, 0.02, 0.9, 19), queries);
  expect_query_reference(random_set(3000, 0.01, 1.0, 8.0, 0.0, 0.0, 0.05, 0.8, 20), queries);
  BoxSet far = random_set(3000, 0.05, 0.1, 8.0, 0.0, 0.0, 0.02, 0.9, 21);
  for (int i = 0; i < 4; ++i) {  // outliers: a level's cells wrap into fewer buckets
    far.boxes.push_back({1e5 * i - 0.1, 3e4, 1e5 * i + 0.1, 3e4 + 0.2});
    far.active.push_back(1);
  }
  expect_query_reference(far, queries);
  expect_query_reference(rows_of_boxes(1), queries);
  expect_query_reference(rows_of_boxes(2), queries);
}

TEST(GridBroadphase, ABoxOfHalfTheLargestExtentIsOnTheNextLevel) {
  // Level k holds the extents in (e_top 2^-(k+1), e_top 2^-k]; a query visits the levels in
  // order, and a cell's boxes in index order, so the order shows each box's level. Every box
  // here has its lower-left corner at the origin (one cell on every level).
  for (const double top : {1.0, 3.0, 1e-3, 7.3e5, 0x1.fffffffffffffp-3}) {
    const double above_half = std::nextafter(top / 2, top),
                 above_quarter = std::nextafter(top / 4, top);
    const std::vector<double> extents = {top,        top / 2,       above_half,
                                         0.75 * top, above_quarter, top / 4};
    for (const bool with_nan : {false, true}) {  // all finite, and one box not (checked alone)
      BoxSet s;
      for (const double e : extents)
        s.boxes.push_back({0.0, 0.0, e, 0.5 * e}), s.active.push_back(1);
      if (with_nan) s.boxes.push_back({0.0, 0.0, std::nan(""), 1.0}), s.active.push_back(1);
      GridBroadphase bp;
      bp.index(s.boxes);
      std::vector<std::uint32_t> order;
      bp.query({0.0, 0.0, top, top}, [&](std::uint32_t i, const SweptBox&) { order.push_back(i); });
      EXPECT_EQ(order, (std::vector<std::uint32_t>{0, 2, 3, 1, 4, 5})) << "e_top " << top;
    }
  }
}

TEST(GridBroadphase, BoxesThatTouchExactlyArePaired) {
  // Unit boxes on an integer lattice (x, y in -5..4) share edges and corners, on cell borders
  // of every level: each pairs with its 8 neighbours.
  BoxSet s;
  const int k = 10;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      s.boxes.push_back({i - 5.0, j - 5.0, i - 4.0, j - 4.0});
      s.active.push_back(1);
    }
  }
  const std::vector<DiscPair> want = brute_force(s);
  EXPECT_EQ(want.size(), static_cast<std::size_t>(2 * k * (k - 1) + 2 * (k - 1) * (k - 1)));
  GridBroadphase bp;
  EXPECT_EQ(find(bp, s, 1), want);
  // Unit boxes that touch at x = 1.25 j, the cell borders of level 0 (side 1.25 e_min).
  BoxSet t;
  for (int j = -20; j < 20; ++j) {
    t.boxes.push_back({1.25 * j, 0.0, 1.25 * j + 1, 1.0});
    t.boxes.push_back({1.25 * j - 1, 1.0, 1.25 * j, 2.0});  // corner to corner with the first
    t.active.push_back(1), t.active.push_back(j % 2 != 0);
  }
  const std::vector<DiscPair> touching = brute_force(t);
  EXPECT_GE(touching.size(), 40u);
  EXPECT_EQ(find(bp, t, 1), touching);
}

TEST(GridBroadphase, StaticDiscsAreNotPairedWithEachOther) {
  BoxSet s = random_set(3000, 0.05, 0.1, 8.0, 0.0, 0.0, 0.02, 0.0, 8);  // all static
  GridBroadphase bp;
  EXPECT_TRUE(find(bp, s, 1).empty());
  for (std::size_t i = 0; i < s.active.size(); i += 7) s.active[i] = 1;  // a few dynamic
  const std::vector<DiscPair> pairs = find(bp, s, 1);
  EXPECT_FALSE(pairs.empty());
  EXPECT_EQ(pairs, brute_force(s));
}

TEST(GridBroadphase, NonFiniteAndHugeBoxesTakeTheOverflowPath) {
  BoxSet s = random_set(2000, 0.05, 0.1, 8.0, 0.0, 0.0, 0.02, 0.9, 9);
  const double inf = std::numeric_limits<double>::infinity();
  s.boxes[10] = {-inf, -inf, inf, inf};  // a blown-up disc: overlaps everything
  s.boxes[20] = {-1e300, 2.0, 1e300, 2.5};
#ifndef FIXSTEP_FP_TRAPS  // (Debug builds trap the comparison of a NaN, as the engine's guard)
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s.boxes[30] = {nan, 1.0, 2.0, 2.0};  // overlaps nothing
#endif
  s.boxes[40] = {1.0, 1.0, 1e300, 1e300};
  s.boxes[50] = {-1.5e308, 3.0, 1.5e308, 3.5};  // finite corners, an extent past the largest double
  s.active[10] = 0, s.active[20] = 1, s.active[40] = 0, s.active[50] = 1;
  expect_reference(s);
  GridBroadphase bp;
  bp.index(s.boxes);
  EXPECT_TRUE(std::ranges::find(bp.unindexed(), 50u) != bp.unindexed().end());
  // Extents near the least normal number: the finest levels' cells are too small to represent
  // (1 / side overflows), and the points that would go there take the overflow path.
  BoxSet tiny;
  for (int i = 1; i <= 40; ++i) {
    const double x = 1e-300 * i, w = i % 4 == 0 ? 0.0 : 1.5e-300;  // every fourth a point
    tiny.boxes.push_back({x, x, x + w, x + w}), tiny.active.push_back(1);
  }
  expect_reference(tiny);
  bp.index(tiny.boxes);
  EXPECT_EQ(bp.unindexed().size(), 10u);
  BoxSet all;  // nothing on the grid
  all.boxes = {{-inf, 0, inf, 1}, {0, -inf, 1, inf}, {-inf, -inf, 0, 0}, {2, 2, inf, inf}};
  all.active = {1, 0, 0, 1};
  expect_reference(all);
  EXPECT_EQ(brute_force(all).size(), 2u);  // (0, 1), (0, 2)
}

TEST(GridBroadphase, TwoThreadsGiveTheSameBitsAsOne) {
  const BoxSet s = random_set(60000, 0.05, 0.1, 40.0, 0.0, 0.0, 0.02, 0.95, 10);
  GridBroadphase bp;
  const std::vector<DiscPair> one = find(bp, s, 1);
  EXPECT_GT(one.size(), s.boxes.size() / 2);
  EXPECT_EQ(find(bp, s, 2), one);
  GridBroadphase other;
  EXPECT_EQ(find(other, s, 2), one);
}

TEST(GridBroadphase, AReusedOrCopiedObjectGivesWhatAFreshOneGives) {
  BoxSet first = random_set(20000, 0.001, 0.5, 30.0, -3.0, 0.0, 0.1, 0.5, 11);
  first.boxes[7] = {0.0, 0.0, std::numeric_limits<double>::infinity(), 1.0};  // overflow
  const BoxSet second = random_set(5000, 0.05, 0.1, 8.0, 2.0, 1.0, 0.02, 0.9, 12);
  GridBroadphase used;
  find(used, first, 2);
  const GridBroadphase copy = used;  // a snapshot of a world holding it
  GridBroadphase fresh, copied = copy;
  const std::vector<DiscPair> want = find(fresh, second, 1);
  EXPECT_EQ(find(used, second, 1), want);
  EXPECT_EQ(find(copied, second, 2), want);
  EXPECT_EQ(want, brute_force(second));
}

TEST(GridBroadphase, TheCapIsHonoured) {
  BoxSet s;  // 1000 discs at one point: 499500 pairs
  for (int i = 0; i < 1000; ++i) s.boxes.push_back({1.0, 1.0, 1.2, 1.2}), s.active.push_back(1);
  GridBroadphase bp;
  std::vector<DiscPair> pairs;
  for (int threads : {1, 2}) {
    EXPECT_FALSE(bp.find_pairs(s.boxes, s.active, 100, pairs, threads));
    EXPECT_FALSE(bp.find_pairs(s.boxes, s.active, 499499, pairs, threads));
    EXPECT_TRUE(bp.find_pairs(s.boxes, s.active, 499500, pairs, threads));
    EXPECT_EQ(pairs, brute_force(s));
  }
}

// Which limit stopped a call is told of that call alone: a veto stop, then a call that finds
// its pairs, then one stopped by max_pairs.
TEST(GridBroadphase, StoppedByVetoTellsOfTheLastCallOnly) {
  BoxSet s;  // 100 discs at one point: 4950 pairs, every one vetoed
  for (int i = 0; i < 100; ++i) s.boxes.push_back({1.0, 1.0, 1.2, 1.2}), s.active.push_back(1);
  const GridBroadphase::PairVeto veto{
      [](const void*, std::uint32_t, std::uint32_t) { return true; }, nullptr, 1000};
  GridBroadphase bp;
  std::vector<DiscPair> pairs;
  for (int threads : {1, 2}) {
    bp.set_veto(&veto);
    EXPECT_FALSE(bp.find_pairs(s.boxes, s.active, 10000, pairs, threads));
    EXPECT_TRUE(bp.stopped_by_veto());
    bp.set_veto(nullptr);
    EXPECT_TRUE(bp.find_pairs(s.boxes, s.active, 10000, pairs, threads));
    EXPECT_FALSE(bp.stopped_by_veto());
    bp.set_veto(&veto);
    EXPECT_FALSE(bp.find_pairs(s.boxes, s.active, 10000, pairs, threads));
    bp.set_veto(nullptr);
    EXPECT_FALSE(bp.find_pairs(s.boxes, s.active, 100, pairs, threads));
    EXPECT_FALSE(bp.stopped_by_veto());
  }
}

TEST(GridBroadphase, AMillionDiscsAtOnePointStopAtTheCap) {
  BoxSet s;  // 5e11 pairs: returns false after about max_pairs of them
  s.boxes.assign(1000000, SweptBox{-0.1, -0.1, 0.1, 0.1});
  s.active.assign(s.boxes.size(), 1);
  GridBroadphase bp;
  std::vector<DiscPair> pairs;
  EXPECT_FALSE(bp.find_pairs(s.boxes, s.active, 4000000, pairs, 1));
  EXPECT_FALSE(bp.find_pairs(s.boxes, s.active, 4000000, pairs, 2));
  s.active.assign(s.boxes.size(), 0);  // all static: no pair, and no scan of 5e11 of them
  EXPECT_TRUE(bp.find_pairs(s.boxes, s.active, 4000000, pairs, 2));
  EXPECT_TRUE(pairs.empty());
  s.active[500000] = 1;  // one dynamic among them: paired with every other
  EXPECT_TRUE(bp.find_pairs(s.boxes, s.active, 4000000, pairs, 1));
  EXPECT_EQ(pairs.size(), s.boxes.size() - 1);
}

TEST(GridBroadphase, AllocatesNothingOnceWarm) {
  // n >= min_parallel_boxes, so that threads = 2 splits the work.
  const BoxSet big = random_set(40000, 0.05, 0.1, 25.0, 0.0, 0.0, 0.02, 0.9, 13);
  BoxSet moved = big;  // the same discs a tick later, off the cells' borders of before
  for (SweptBox& b : moved.boxes) {
    b = {b.min_x + 0.037, b.min_y - 0.051, b.max_x + 0.037, b.max_y - 0.051};
  }
  const BoxSet small = random_set(5000, 0.05, 0.1, 10.0, 0.0, 0.0, 0.02, 0.9, 15);
  const BoxSet sparse = random_set(40000, 0.05, 0.1, 2000.0, 0.0, 0.0, 0.02, 0.9, 17);
  ASSERT_GE(big.boxes.size(), GridBroadphase::min_parallel_boxes);
  GridBroadphase bp;
  std::vector<DiscPair> pairs;
  ASSERT_TRUE(bp.find_pairs(sparse.boxes, sparse.active, 1u << 30, pairs, 2));  // the worker
  ASSERT_TRUE(bp.find_pairs(big.boxes, big.active, 1u << 30, pairs, 1));        // the pairs
  const std::size_t warm_pairs = pairs.size();
  GridBroadphase other;
  ASSERT_LE(find(other, moved, 1).size(), warm_pairs);  // "the same or a smaller pair count"
  bool ok = true;
  counted_bytes = 0;
  counting = true;
  for (int threads : {2, 1}) {  // two first: its second thread's pairs need room of their own
    ok = ok && bp.find_pairs(big.boxes, big.active, 1u << 30, pairs, threads);
    ok = ok && bp.find_pairs(moved.boxes, moved.active, 1u << 30, pairs, threads);
    ok = ok && bp.find_pairs(small.boxes, small.active, 1u << 30, pairs, threads);
  }
  counting = false;
  EXPECT_TRUE(ok);
  EXPECT_EQ(counted_bytes.load(), 0u);
}

}  // namespace
}  // namespace fixstep::detail
