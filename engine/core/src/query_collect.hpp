// What World's query sources share (world_queries.cpp, world_shape_queries.cpp): the checks of
// their arguments, the fixed order of their results, the collector that keeps a prefix of that
// order in the caller's span without allocating, and the filter test of a grid entry.
// Internal (not installed).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <stdexcept>

#include "fixstep/core/query.hpp"
#include "query_grid.hpp"

namespace fixstep::detail {

inline void require_finite_query(Vec2 v, const char* query, const char* what) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y)) {
    throw std::invalid_argument(
        fmt::format("{}: {} must be finite (got ({}, {}))", query, what, v.x, v.y));
  }
}

/// The order of query results: bodies by slot (a body's shapes by index), then planes by
/// index, then segments by index.
inline bool query_hit_less(const QueryHit& l, const QueryHit& r) {
  if ((l.segment == no_plane) != (r.segment == no_plane)) return l.segment == no_plane;
  if (l.segment != no_plane) return l.segment < r.segment;
  if ((l.plane == no_plane) != (r.plane == no_plane)) return l.plane == no_plane;
  if (l.plane != no_plane) return l.plane < r.plane;
  if (l.body.slot() != r.body.slot()) return l.body.slot() < r.body.slot();
  return l.shape < r.shape;
}

/// The order of ray hits: by fraction, then as query_hit_less.
inline bool ray_hit_less(const RayHit& l, const RayHit& r) {
  if (l.fraction != r.fraction) return l.fraction < r.fraction;
  return query_hit_less(QueryHit{l.body, l.plane, l.segment, l.shape},
                        QueryHit{r.body, r.plane, r.segment, r.shape});
}

/// Keeps the first out.size() results of `less` seen so far in `out` (a max-heap while
/// collecting, sorted by finish()), and counts them all: no allocation.
template <class T, class Less>
class Collector {
 public:
  Collector(std::span<T> out, Less less) : out_(out), less_(less) {}
  void add(const T& hit) {
    ++total_;
    if (kept_ < out_.size()) {
      out_[kept_++] = hit;
      std::push_heap(out_.begin(), out_.begin() + std::ptrdiff_t(kept_), less_);
    } else if (kept_ > 0 && less_(hit, out_[0])) {
      std::pop_heap(out_.begin(), out_.begin() + std::ptrdiff_t(kept_), less_);
      out_[kept_ - 1] = hit;
      std::push_heap(out_.begin(), out_.begin() + std::ptrdiff_t(kept_), less_);
    }
  }
  std::size_t finish() {
    std::sort_heap(out_.begin(), out_.begin() + std::ptrdiff_t(kept_), less_);
    return total_;
  }

 private:
  std::span<T> out_;
  Less less_;
  std::size_t kept_ = 0, total_ = 0;
};

/// Whether `filter` sees the grid entry `d` (a disc or a body's shape).
inline bool query_seen(const QueryFilter& f, const QueryDisc& d) {
  return (f.sensors || !d.sensor) && query_sees(f, d.filter);
}

/// The hit of grid entry `d`: its body, and its shape's index for a shape.
inline QueryHit entry_hit(const QueryDisc& d) {
  return QueryHit{d.body, no_plane, no_plane, d.shape == QueryDisc::none ? no_plane : d.index};
}

/// Whether the boxes [lo, hi] and b overlap (touching included).
inline bool boxes_meet(Vec2 lo, Vec2 hi, const Aabb& b) {
  return !(b.lower.x > hi.x || b.upper.x < lo.x || b.lower.y > hi.y || b.upper.y < lo.y);
}

/// Fills g.discs and g.shapes with the bodies' shapes at their poses (world_shape_queries.cpp).
struct WorldState;
void add_query_shapes(const WorldState& state, QueryGrid& g);

}  // namespace fixstep::detail
