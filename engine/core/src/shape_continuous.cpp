// Shape contacts: continuous collision against what does not move (shape_world.hpp has the
// whole tick). A body that moved more than half its thinnest extent in the tick is swept from
// its start to its end against the planes, the segments and the static shapes near it, by
// conservative advancement, and stopped at its first touch.
#include <algorithm>
#include <cmath>

#include "fixstep/core/det_math.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

namespace {

Aabb merge(const Aabb& a, const Aabb& b) {
  return {{std::min(a.lower.x, b.lower.x), std::min(a.lower.y, b.lower.y)},
          {std::max(a.upper.x, b.upper.x), std::max(a.upper.y, b.upper.y)}};
}

/// The lowest value of n·x − offset over `c` at pose `t`, radius taken off: the distance of
/// the shape from the plane (< 0: across it).
double plane_distance(Vec2 n, double offset, const Convex& c, const Pose& t) {
  double lowest = INFINITY;
  for (int i = 0; i < c.count; ++i) lowest = std::min(lowest, dot(n, transform(t, c.vertices[i])));
  return lowest - offset - c.radius;
}

/// First fraction in [0, 1] at which `c` on sweep `s` comes within `target` of the plane, by
/// conservative advancement: the distance falls no faster than |n·Δc| + |Δa| · extent a unit
/// of t. 1 when it does not.
double plane_toi(Vec2 n, double offset, const Convex& c, const Sweep& s, double target) {
  const double bound = std::abs(dot(n, s.c1 - s.c0)) + std::abs(s.a1 - s.a0) * extent(c);
  if (!(bound > 0.0)) return 1.0;
  double t = 0.0;
  for (int i = 0; i < 64; ++i) {
    const double d = plane_distance(n, offset, c, pose_at(s, t));
    if (d <= target + 0.25 * target) return t;
    t += (d - target) / bound;
    if (t >= 1.0) return 1.0;
  }
  return t;
}

}  // namespace

void ShapeWorld::continuous(const ShapeTick& tick, ShapeTally& tally) {
  // Nothing that does not move to sweep against: no pass (what a world does not have, it does
  // not pay for). A body's rotation made here (pose()) is made again once the push-out ends.
  if (tick.planes.empty() && tick.segments.empty() && rest_.statics.empty()) return;
  bool ready = false;
  for (const std::uint32_t i : rest_.live) {
    const ShapedBody& b = bodies_[i];
    if (!awake(b) || b.disc) continue;
    ShapeState& s = state_[i];
    const double dx = s.x - s.x0, dy = s.y - s.y0, turned = std::abs(s.a - s.a0) * b.extent;
    // |dx| + |dy| bounds the distance from above: a body that moved less than 0.49 of the
    // thinnest by it is not fast, and the square root is left out (the same decision: the
    // bound and the test below differ by far more than their rounding).
    if (std::abs(dx) + std::abs(dy) + turned <= 0.49 * b.thinnest) continue;
    const double motion = det::hypot(dx, dy) + turned;
    if (!(motion > 0.5 * b.thinnest)) continue;  // Box2D v3's test of a fast body
    if (!ready) {                                // once a tick, and only in a tick with a fast body
      row_keys_.clear();
      for (const ShapeRow& r : rows_) row_keys_.push_back(r.pair);
      std::sort(row_keys_.begin(), row_keys_.end());
      ready = true;
    }
    s.q = rot_of(s.a);
    const double t = first_static_touch(i, tick);
    if (t >= 1.0) continue;
    const Sweep sweep{{s.x0, s.y0}, {s.x, s.y}, s.a0, s.a};
    const Pose at = pose_at(sweep, t);
    s.x = at.p.x, s.y = at.p.y, s.a = s.a0 + t * (s.a - s.a0), s.q = at.q;
    ++tally.ccd_hits;
  }
}

// Whether the tick has a row of this pair of shapes (a key names both, the body's among them).
bool ShapeWorld::has_row(std::uint64_t pair) const {
  return std::binary_search(row_keys_.begin(), row_keys_.end(), pair) ||
         std::binary_search(disabled_.begin(), disabled_.end(), pair);
}

// From the broadphase's grid where it made one this tick (its boxes hold the shapes' at the
// start, grown by a margin), else every static body's; in the order of the static bodies and
// their shapes (shapes_ holds each body's shapes together, in body order: ascending indices),
// so that each time of impact is bounded by the same earlier ones.
std::span<const std::uint32_t> ShapeWorld::static_shapes_near(const Aabb& box) {
  near_statics_.clear();
  if (rest_.split) {  // the resting shapes hold every static shape but the sensors
    const SweptBox q{box.lower.x, box.lower.y, box.upper.x, box.upper.y};
    rest_.near(q, boxes_, near_statics_);  // ascending
    auto moves = [&](std::uint32_t k) {
      return bodies_[shapes_[k].owner].type != BodyType::static_body;
    };
    near_statics_.erase(std::remove_if(near_statics_.begin(), near_statics_.end(), moves),
                        near_statics_.end());
    return near_statics_;
  }
  for (const std::uint32_t o : rest_.statics) {
    for (std::uint32_t q = bodies_[o].first; q < bodies_[o].first + bodies_[o].count; ++q) {
      near_statics_.push_back(q);
    }
  }
  return near_statics_;
}

double ShapeWorld::first_static_touch(std::uint32_t body, const ShapeTick& tick) {
  const ShapedBody& b = bodies_[body];
  const ShapeState& s = state_[body];
  const Sweep sweep{{s.x0, s.y0}, {s.x, s.y}, s.a0, s.a};
  const Pose start = start_pose(body);
  const double target = slop;
  double first = 1.0;
  for (std::uint32_t k = b.first; k < b.first + b.count; ++k) {
    const ShapeEntry& e = shapes_[k];
    if (e.sensor) continue;
    const Aabb swept = merge(convex_aabb(e.convex, start), convex_aabb(e.convex, pose(body)));
    for (std::uint32_t p = 0; p < tick.planes.size(); ++p) {
      if (has_row(std::uint64_t{0xF0000000u | p} << 32 | e.key)) continue;
      const PlaneDef& pl = tick.planes[p];
      const double len = det::hypot(pl.normal.x, pl.normal.y);
      const Vec2 n = pl.normal / len;
      const double off = pl.offset / len;
      if (plane_distance(n, off, e.convex, start) < 2.0 * target) continue;  // resting on it
      const double t = plane_toi(n, off, e.convex, sweep, target);
      if (e.one_way && t < 1.0 && !(dot(-n, rotate(pose_at(sweep, t).q, e.up)) > one_way_min_dot)) {
        continue;  // its one-way shape meets the plane from below: passes
      }
      first = std::min(first, t);
    }
    for (const std::uint32_t q : near_segments(tick, swept)) {
      const SegmentDef& seg = tick.segments[q];
      if (!boxes_overlap(swept, segment_bounds(seg))) continue;
      if (has_row(std::uint64_t{0xE0000000u | q} << 32 | e.key)) continue;
      const Convex c = segment_convex(seg.a, seg.b);
      const Sweep still{{0, 0}, {0, 0}, 0, 0};
      if (distance(c, Pose{}, e.convex, start).distance < 2.0 * target) continue;
      const Toi toi = time_of_impact(c, still, e.convex, sweep, target, 0.25 * target, first);
      if (!toi.hit) continue;
      if (seg.one_way || e.one_way) {  // the first touch must lean up for each one-way side
        const Pose hit = pose_at(sweep, toi.t);
        const Manifold m = collide_segment(seg, e.convex, hit, 4.0 * slop);
        if (seg.one_way && !one_way_touch(m, one_way_up_of(seg))) continue;
        if (e.one_way && !one_way_touch(m, -rotate(hit.q, e.up))) continue;
      }
      first = std::min(first, toi.t);
    }
    for (const std::uint32_t q : static_shapes_near(swept)) {
      const ShapeEntry& f = shapes_[q];
      const std::uint32_t o = f.owner;
      const Pose at = pose(o);
      const Sweep still{{at.p.x, at.p.y}, {at.p.x, at.p.y}, state_[o].a, state_[o].a};
      if (f.sensor || !should_collide(e.filter, f.filter)) continue;
      if (!boxes_overlap(swept, convex_aabb(f.convex, at))) continue;
      const std::uint32_t lo = std::min(q, k), hi = std::max(q, k);
      if (has_row(std::uint64_t{shapes_[lo].key} << 32 | shapes_[hi].key)) continue;
      if (distance(f.convex, at, e.convex, start).distance < 2.0 * target) continue;
      const Toi toi =
          time_of_impact(f.convex, still, e.convex, sweep, target, 0.25 * target, first);
      if (!toi.hit) continue;
      if (f.one_way || e.one_way) {  // the first touch must lean up for each one-way side
        const Pose hit = pose_at(sweep, toi.t);
        const Manifold m = collide(f.convex, at, e.convex, hit, 4.0 * slop);
        if (f.one_way && !one_way_touch(m, rotate(at.q, f.up))) continue;
        if (e.one_way && !one_way_touch(m, -rotate(hit.q, e.up))) continue;
      }
      first = std::min(first, toi.t);
    }
  }
  return first;
}

}  // namespace fixstep::detail
