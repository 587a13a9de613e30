// The hierarchical grid of grid_broadphase.hpp (see its header for the method and why).
#include "grid_broadphase.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "binary_exponent.hpp"

namespace fixstep::detail {

namespace {

/// The box's extent max(width, height), m; NaN when a coordinate is.
double box_extent(const SweptBox& b) {
  return std::max(b.max_x - b.min_x, b.max_y - b.min_y);
}

bool box_finite(const SweptBox& b) {
  return std::isfinite(b.min_x) && std::isfinite(b.min_y) && std::isfinite(b.max_x) &&
         std::isfinite(b.max_y);
}

/// Whether a level can hold the box: its coordinates and its extent finite (finite corners
/// near ±1.8e308 can be farther apart than the largest double).
bool box_placeable(const SweptBox& b) {
  return box_finite(b) && box_extent(b) <= std::numeric_limits<double>::max();
}

/// Starts keys [begin, end) from entry `next` (returns the entry after their last): each key's
/// start[key] is next plus the counts c0 (and c1, when given) of the keys before it; c0[key]
/// becomes the first thread's next slot, start[key], and c1[key] the second's, after the
/// first's c0[key] entries. Four keys at a time where SSE2 is (a vector's sums by two shifted
/// adds, then the running total): integers, the same starts either way.
std::uint32_t prefix_keys(std::uint32_t* start, std::uint32_t* c0, std::uint32_t* c1,
                          std::size_t begin, std::size_t end, std::uint32_t next) {
  std::size_t key = begin;
#if defined(__SSE2__)
  const auto load = [](const std::uint32_t* p) {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  };
  const auto store = [](std::uint32_t* p, __m128i v) {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p), v);
  };
  __m128i total = _mm_set1_epi32(static_cast<int>(next));
  for (; key + 4 <= end; key += 4) {
    const __m128i n0 = load(c0 + key);
    const __m128i n = c1 != nullptr ? _mm_add_epi32(n0, load(c1 + key)) : n0;
    __m128i within = _mm_add_epi32(n, _mm_slli_si128(n, 4));  // sums up to each key, inclusive
    within = _mm_add_epi32(within, _mm_slli_si128(within, 8));
    const __m128i first = _mm_add_epi32(_mm_sub_epi32(within, n), total);
    store(start + key, first);
    store(c0 + key, first);
    if (c1 != nullptr) store(c1 + key, _mm_add_epi32(first, n0));
    total = _mm_add_epi32(total, _mm_shuffle_epi32(within, 0xff));
  }
  next = static_cast<std::uint32_t>(_mm_cvtsi128_si32(total));
#endif
  for (; key < end; ++key) {
    const std::uint32_t n0 = c0[key], n1 = c1 != nullptr ? c1[key] : 0;
    start[key] = next, c0[key] = next;
    if (c1 != nullptr) c1[key] = next + n0;
    next += n0 + n1;
  }
  return next;
}

}  // namespace

void order_pairs(std::span<const DiscPair> first, std::span<const DiscPair> second, std::size_t n,
                 std::vector<std::uint32_t>& offset, std::vector<DiscPair>& out) {
  offset.assign(n + 1, 0);
  for (const DiscPair& p : first) ++offset[p.a];
  for (const DiscPair& p : second) ++offset[p.a];
  for (std::size_t i = 1; i <= n; ++i) offset[i] += offset[i - 1];  // end of each a's list
  out.resize(first.size() + second.size());
  for (std::size_t k = second.size(); k-- > 0;) out[--offset[second[k].a]] = second[k];
  for (std::size_t k = first.size(); k-- > 0;) out[--offset[first[k].a]] = first[k];
  offset[n] = static_cast<std::uint32_t>(out.size());  // now offset[a] is the start of a's list
  const auto by_b = [](const DiscPair& p, const DiscPair& q) { return p.b < q.b; };
  // Each a's list, found as a run of out (O(pairs), not O(n): most a have none).
  DiscPair* const last = out.data() + out.size();
  for (DiscPair* begin = out.data(); begin < last;) {
    DiscPair* end = begin + 1;
    while (end < last && end->a == begin->a) ++end;
    if (end - begin > 16) {
      std::sort(begin, end, by_b);  // b is unique within a list: any sort gives one order
    } else {
      for (DiscPair* i = begin + 1; i < end; ++i) {  // insertion sort
        const DiscPair p = *i;
        DiscPair* j = i;
        for (; j > begin && j[-1].b > p.b; --j) *j = j[-1];
        *j = p;
      }
    }
    begin = end;
  }
}

template <class Job>
void GridBroadphase::both(bool split, Job& job) {
  if (!split) {
    job(0), job(1);
    return;
  }
  (lent_ != nullptr ? *lent_ : second_).both(job);
}

void GridBroadphase::largest_extent(Share& s, std::span<const SweptBox> boxes) const {
  // The largest width and the largest height apart, then the larger: the same maximum, without
  // a branch on each box (a moving box is as often wider as taller). A box not placeable counts,
  // and adds widths of 0 (its coordinates taken as 0 before any arithmetic: Debug builds trap
  // inf - inf), which leave the largest as they were.
  constexpr double most = std::numeric_limits<double>::max();
  double top_w = 0.0, top_h = 0.0;
  std::uint32_t not_placeable = 0;
  for (std::size_t i = s.begin; i < s.end; ++i) {
    const SweptBox& b = boxes[i];
    const bool finite = box_finite(b);  // (predicted: boxes are finite but for a fault)
    const double w = (finite ? b.max_x : 0.0) - (finite ? b.min_x : 0.0);
    const double h = (finite ? b.max_y : 0.0) - (finite ? b.min_y : 0.0);
    const bool placeable = finite & (w <= most) & (h <= most);  // box_placeable
    top_w = std::max(top_w, placeable ? w : 0.0);
    top_h = std::max(top_h, placeable ? h : 0.0);
    not_placeable += placeable ? 0u : 1u;
  }
  s.e_top = std::max(top_w, top_h);
  s.not_finite = not_placeable;
}

void GridBroadphase::set_levels(double e_top) {
  if (!(e_top > 0 && e_top < std::numeric_limits<double>::infinity())) e_top = 1.0;  // points
  for (unsigned k = 0; k < max_levels; ++k) {
    levels_[k].inv_cell = 1.0 / (cell_factor * std::ldexp(e_top, -static_cast<int>(k)));
  }
  e_top_ = e_top;
}

void GridBroadphase::assign_levels(Share& s, std::span<const SweptBox> boxes) {
  const double e_bottom = std::ldexp(e_top_, -static_cast<int>(max_levels - 1));
  // From e_top (1 + 2^-50) / 2 up, e_top / e rounds below 2 (it is at most 2 - 2^-50, four
  // units in the last place below 2): level 0 without the division. Where e_top / 2 would not
  // be exact (e_top near the least normal number), every box divides.
  const double e_first = e_top_ >= 0x1p-1000 ? (0.5 * e_top_) * (1.0 + 0x1p-50) : e_top_ * 2.0;
  // The first level whose cells are too small to represent (1 / side infinite): the sides fall
  // with the level, so every level after it too.
  std::uint32_t unplaced = 0;
  while (unplaced < max_levels && std::isfinite(levels_[unplaced].inv_cell)) ++unplaced;
  std::fill(std::begin(s.count), std::end(s.count), 0u);
  s.overflow = 0;
  // A share whose boxes all have a finite extent (largest_extent counted) skips the test of
  // each.
  auto assign = [&](auto checked) {
    for (std::size_t i = s.begin; i < s.end; ++i) {
      if (decltype(checked)::value && !box_placeable(boxes[i])) {
        // (finite first, before any arithmetic: Debug builds trap inf - inf)
        level_[i] = overflow, ++s.overflow;
        continue;
      }
      const double e = box_extent(boxes[i]);
      // Level k holds e in (e_top 2^-(k+1), e_top 2^-k], the last one everything smaller.
      std::uint32_t k = max_levels - 1;
      // (e_top / e is in [1, 2^47): a normal number, whose exponent is ilogb's)
      if (e >= e_first) {
        k = 0;
      } else if (e > e_bottom) {
        k = static_cast<std::uint32_t>(det::binary_exponent(e_top_ / e));
      }
      if (k >= unplaced) {
        level_[i] = overflow, ++s.overflow;
        continue;
      }
      level_[i] = k;
      const std::int32_t cx = cell_of(boxes[i].min_x, k), cy = cell_of(boxes[i].min_y, k);
      home_[i] = {cx, cy};
      if (s.count[k]++ == 0) s.lo_x[k] = s.hi_x[k] = cx, s.lo_y[k] = s.hi_y[k] = cy;
      s.lo_x[k] = std::min(s.lo_x[k], cx), s.hi_x[k] = std::max(s.hi_x[k], cx);
      s.lo_y[k] = std::min(s.lo_y[k], cy), s.hi_y[k] = std::max(s.hi_y[k], cy);
    }
  };
  if (s.not_finite == 0) {
    assign(std::false_type{});
  } else {
    assign(std::true_type{});
  }
}

void GridBroadphase::size_tables() {
  std::uint32_t base = 0;
  level_mask_ = 0;
  for (unsigned k = 0; k < max_levels; ++k) {
    Level& l = levels_[k];
    l.base = base;
    l.wmask = l.hmask = l.wshift = 0;
    const Share &s0 = share_[0], &s1 = share_[1];
    const std::size_t count = std::size_t{s0.count[k]} + s1.count[k];
    if (count == 0) continue;
    level_mask_ |= std::uint64_t{1} << k;
    const Share& a = s0.count[k] ? s0 : s1;
    const Share& b = s1.count[k] ? s1 : s0;
    // A dense grid over the level's home cells, wrapped to at most 2 buckets per box.
    const auto bits = [](std::int32_t lo, std::int32_t hi) {
      return static_cast<std::uint32_t>(std::bit_width(static_cast<std::uint64_t>(hi - lo)));
    };
    std::uint32_t wbits = bits(std::min(a.lo_x[k], b.lo_x[k]), std::max(a.hi_x[k], b.hi_x[k]));
    std::uint32_t hbits = bits(std::min(a.lo_y[k], b.lo_y[k]), std::max(a.hi_y[k], b.hi_y[k]));
    const auto budget = static_cast<std::uint32_t>(std::bit_width(2 * count - 1));
    // Rows of cells wrap last: a row is then one run of buckets (scan_row). A level wider than
    // tall by two binades or more wraps in x too.
    while (wbits + hbits > budget) (hbits + 1 >= wbits ? hbits : wbits) -= 1;
    l.wmask = (std::uint32_t{1} << wbits) - 1, l.hmask = (std::uint32_t{1} << hbits) - 1;
    l.wshift = wbits;
    base += std::uint32_t{1} << (wbits + hbits);
  }
  start_.resize(2 * std::size_t{base} + 1);  // each thread clears its own counts (build())
}

void GridBroadphase::count_keys(const Share& s, std::span<const std::uint8_t> active,
                                std::vector<std::uint32_t>& count) const {
  for (std::size_t i = s.begin; i < s.end; ++i) {  // the entries of each (bucket, static?) key
    const std::uint32_t k = level_[i];
    if (k == overflow) continue;
    ++count[2 * bucket(k, home_[i].cx, home_[i].cy) + (active[i] == 0)];
  }
}

void GridBroadphase::start_keys(bool split) {
  const std::size_t keys = start_.size() - 1;
  // Keys [begin, end) started from entry `next`, each key's first thread's entries, then its
  // second's; returns the entry after their last.
  auto both_threads = [&](std::size_t begin, std::size_t end, std::uint32_t next) {
    return prefix_keys(start_.data(), cursor_[0].data(), cursor_[1].data(), begin, end, next);
  };
  if (!split) {  // every entry counted by the first thread
    start_.back() = prefix_keys(start_.data(), cursor_[0].data(), nullptr, 0, keys, 0);
  } else if (keys < min_parallel_keys) {
    start_.back() = both_threads(0, keys, 0);
  } else {
    // Each half of the keys counted, then each started after the entries before it: the same
    // starts as one pass.
    const std::size_t mid = keys / 2;
    std::uint32_t in_half[2] = {0, 0};
    auto count = [&](int t) {
      std::uint32_t n = 0;
      for (std::size_t key = t == 0 ? 0 : mid; key < (t == 0 ? mid : keys); ++key) {
        n += cursor_[0][key] + cursor_[1][key];
      }
      in_half[t] = n;
    };
    both(true, count);
    auto start = [&](int t) {
      (void)(t == 0 ? both_threads(0, mid, 0) : both_threads(mid, keys, in_half[0]));
    };
    both(true, start);
    start_.back() = in_half[0] + in_half[1];
  }
  entry_.resize(start_.back());
}

void GridBroadphase::fill_keys(const Share& s, std::span<const SweptBox> boxes,
                               std::span<const std::uint8_t> active,
                               std::vector<std::uint32_t>& cursor) {
  for (std::size_t i = s.begin; i < s.end; ++i) {  // in index order within each key
    const std::uint32_t k = level_[i];
    if (k == overflow) continue;
    const auto [cx, cy] = home_[i];
    entry_[cursor[2 * bucket(k, cx, cy) + (active[i] == 0)]++] = {
        boxes[i], static_cast<std::uint32_t>(i), cx, cy};
  }
}

void GridBroadphase::add(std::uint32_t a, std::uint32_t b, std::vector<DiscPair>& out,
                         std::uint64_t& rejected) const {
  const DiscPair p{std::min(a, b), std::max(a, b)};
  if (veto_ && veto_->reject(veto_->context, p.a, p.b)) {
    ++rejected;
    return;
  }
  out.push_back(p);
}

void GridBroadphase::scan_own_cell(std::size_t at, std::size_t h, std::vector<DiscPair>& out,
                                   std::uint64_t& rejected) const {
  const Entry& q = entry_[at];  // dynamic: the dynamic boxes after it, then every static one
  for (std::size_t p = at + 1, end = start_[2 * h + 2]; p < end; ++p) {
    const Entry& e = entry_[p];
    if (e.cx != q.cx || e.cy != q.cy || !boxes_overlap(q.box, e.box)) continue;
    add(q.index, e.index, out, rejected);
  }
}

void GridBroadphase::scan_cell(const Entry& q, bool act, std::uint32_t level, std::int32_t cx,
                               std::int32_t cy, std::vector<DiscPair>& out,
                               std::uint64_t& rejected) const {
  const std::size_t h = bucket(level, cx, cy);
  for (std::size_t p = start_[2 * h], end = start_[2 * h + (act ? 2 : 1)]; p < end; ++p) {
    const Entry& e = entry_[p];
    if (e.cx != cx || e.cy != cy || !boxes_overlap(q.box, e.box)) continue;
    add(q.index, e.index, out, rejected);
  }
}

void GridBroadphase::scan_overflow(const SweptBox& box, std::uint32_t q, bool act,
                                   std::span<const SweptBox> boxes,
                                   std::span<const std::uint8_t> active, std::vector<DiscPair>& out,
                                   std::uint64_t& rejected) const {
  const bool own = level_[q] == overflow;  // overflow boxes pair among themselves by index
  for (const std::uint32_t o : overflow_) {
    if ((own && o <= q) || (!act && active[o] == 0)) continue;
    if (boxes_overlap(box, boxes[o])) add(q, o, out, rejected);
  }
}

[[gnu::always_inline]] inline bool GridBroadphase::scan_row(const Entry& q, std::size_t from,
                                                            std::uint32_t level, std::int32_t x0,
                                                            std::int32_t x1, std::int32_t cy,
                                                            std::vector<DiscPair>& out,
                                                            std::uint64_t& rejected) const {
  const Level& l = levels_[level];
  const auto b0 = static_cast<std::uint32_t>(x0) & l.wmask;
  if (b0 + static_cast<std::uint32_t>(x1 - x0) > l.wmask) return false;  // the row wraps
  const std::size_t h = bucket(level, x0, cy);
  const auto span = static_cast<std::uint32_t>(x1 - x0);
  for (std::size_t p = std::max(from, std::size_t{start_[2 * h]}), end = start_[2 * (h + span) + 2];
       p < end; ++p) {
    const Entry& e = entry_[p];
    const bool overlap = boxes_overlap(q.box, e.box);
    const bool hit =
        (e.cy == cy) & (static_cast<std::uint64_t>(std::int64_t{e.cx} - x0) <= span) & overlap;
    if (hit) add(q.index, e.index, out, rejected);
  }
  return true;
}

void GridBroadphase::scan_entry(std::size_t at, std::uint32_t level,
                                std::span<const SweptBox> boxes,
                                std::span<const std::uint8_t> active, std::vector<DiscPair>& out,
                                std::uint64_t& rejected) const {
  const Entry& q = entry_[at];
  const std::size_t h = bucket(level, q.cx, q.cy);
  const bool act = at < start_[2 * h + 1];
  // A dynamic box: its own cell after it and the next one in one run of entries, the three
  // cells above in another (cells in a row of a level's table are adjacent buckets unless the
  // row wraps); the same pairs in the same order as cell by cell. A static box finds its
  // partners from the other side, and searches only the dynamic boxes, cell by cell.
  if (!act || !scan_row(q, at + 1, level, q.cx, q.cx + 1, q.cy, out, rejected)) {
    if (act) scan_own_cell(at, h, out, rejected);
    scan_cell(q, act, level, q.cx + 1, q.cy, out, rejected);
  }
  if (!act || !scan_row(q, 0, level, q.cx - 1, q.cx + 1, q.cy + 1, out, rejected)) {
    for (std::int32_t dx = -1; dx <= 1; ++dx)
      scan_cell(q, act, level, q.cx + dx, q.cy + 1, out, rejected);
  }
  // Coarser levels: their boxes whose home cell is one of the 3 x 3 around this one's.
  for (std::uint64_t m = level_mask_ & ((std::uint64_t{1} << level) - 1); m != 0; m &= m - 1) {
    const auto k = static_cast<std::uint32_t>(std::countr_zero(m));
    const std::int32_t cx = cell_of(q.box.min_x, k), cy = cell_of(q.box.min_y, k);
    for (std::int32_t dy = -1; dy <= 1; ++dy) {
      if (act && scan_row(q, 0, k, cx - 1, cx + 1, cy + dy, out, rejected)) continue;
      for (std::int32_t dx = -1; dx <= 1; ++dx)
        scan_cell(q, act, k, cx + dx, cy + dy, out, rejected);
    }
  }
  if (!overflow_.empty()) scan_overflow(q.box, q.index, act, boxes, active, out, rejected);
}

bool GridBroadphase::scan(std::size_t begin, std::size_t end, bool with_overflow,
                          std::span<const SweptBox> boxes, std::span<const std::uint8_t> active,
                          std::size_t max_pairs, std::vector<DiscPair>& out,
                          std::uint64_t& rejected) const {
  out.clear();
  rejected = 0;
  const std::uint64_t most_rejected = veto_ ? veto_->max_rejected : 0;
  for (std::uint64_t m = level_mask_; m != 0; m &= m - 1) {
    const auto k = static_cast<std::uint32_t>(std::countr_zero(m));
    const std::size_t first = start_[2 * std::size_t{levels_[k].base}];
    const std::size_t last =
        start_[2 * (levels_[k].base + std::size_t{levels_[k].wmask + 1} * (levels_[k].hmask + 1))];
    for (std::size_t at = std::max(begin, first); at < std::min(end, last); ++at) {
      scan_entry(at, k, boxes, active, out, rejected);
      if (out.size() > max_pairs || rejected > most_rejected) return false;
    }
  }
  if (with_overflow) {  // the overflow boxes' own searches (on the first thread)
    for (const std::uint32_t o : overflow_) {
      scan_overflow(boxes[o], o, active[o] != 0, boxes, active, out, rejected);
      if (out.size() > max_pairs || rejected > most_rejected) return false;
    }
  }
  return true;
}

bool GridBroadphase::find_pairs(std::span<const SweptBox> boxes,
                                std::span<const std::uint8_t> active, std::size_t max_pairs,
                                std::vector<DiscPair>& pairs, int threads, SecondThread* lent) {
  pairs.clear();
  stopped_by_veto_ = false;  // of this call only
  rejected_ = 0;
  lent_ = lent;
  const std::size_t n = boxes.size();
  const bool split = threads >= 2 && n >= parallel_min_ && n >= 2;
  build(boxes, active, split);
  const std::size_t e = entry_.size(), mid = split ? e / 2 : e;
  bool ok[2] = {true, true};
  std::uint64_t rejected[2] = {0, 0};
  auto search = [&](int t) {
    ok[t] = scan(t == 0 ? 0 : mid, t == 0 ? mid : e, t == 0, boxes, active, max_pairs, raw_[t],
                 rejected[t]);
  };
  both(split, search);
  lent_ = nullptr;
  rejected_ = rejected[0] + rejected[1];
  // Both limits on the totals, so that one thread and two stop alike.
  const bool too_many = raw_[0].size() + raw_[1].size() > max_pairs;
  const bool vetoed = veto_ != nullptr && rejected_ > veto_->max_rejected;
  if (!ok[0] || !ok[1] || too_many || vetoed) {
    // A share stopped at max_pairs holds more than max_pairs; else the veto stopped one.
    stopped_by_veto_ = !too_many;
    return false;
  }
  order_pairs(raw_[0], raw_[1], n, offset_, pairs);
  // Either thread may find them all next time (threads = 1, or a shifted split): room for it.
  raw_[0].reserve(pairs.size()), raw_[1].reserve(pairs.size());
  return true;
}

void GridBroadphase::index(std::span<const SweptBox> boxes) {
  idle_.assign(boxes.size(), 0);
  lent_ = nullptr;
  build(boxes, idle_, false);
}

void GridBroadphase::build(std::span<const SweptBox> boxes, std::span<const std::uint8_t> active,
                           bool split) {
  const std::size_t n = boxes.size();
  share_[0].begin = 0, share_[0].end = share_[1].begin = split ? n / 2 : n, share_[1].end = n;
  level_.resize(n);
  home_.resize(n);
  auto extents = [&](int t) { largest_extent(share_[t], boxes); };
  both(split, extents);
  set_levels(std::max(share_[0].e_top, share_[1].e_top));
  auto levels = [&](int t) { assign_levels(share_[t], boxes); };
  both(split, levels);
  size_tables();
  auto count = [&](int t) {
    if (t == 1 && !split) return;  // one share: start_keys reads the first thread's counts alone
    cursor_[t].assign(start_.size() - 1, 0);
    count_keys(share_[t], active, cursor_[t]);
  };
  both(split, count);
  start_keys(split);
  auto fill = [&](int t) { fill_keys(share_[t], boxes, active, cursor_[t]); };
  both(split, fill);
  overflow_.clear();
  for (std::size_t i = 0; share_[0].overflow + share_[1].overflow > 0 && i < n; ++i) {
    if (level_[i] == overflow) overflow_.push_back(static_cast<std::uint32_t>(i));
  }
}

}  // namespace fixstep::detail
