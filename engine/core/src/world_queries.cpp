// World's spatial queries (query.hpp, world.hpp): ray casts, point, box and circle queries
// through the grid of query_grid.hpp, results in a fixed order kept in the caller's span; the
// shape overlap query and the shapes' entries in the grid are in world_shape_queries.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/query.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/world.hpp"
#include "query_collect.hpp"
#include "query_grid.hpp"
#include "shape_query.hpp"
#include "world_state.hpp"

namespace fixstep {

void detail::QueryGridDeleter::operator()(QueryGrid* grid) const {
  delete grid;
}

using detail::Collector;
using detail::query_seen;
using detail::require_finite_query;

namespace {

/// The fraction s in [0, 1] at which the ray o + s t crosses segment (a, b), or NaN (parallel
/// rays, a ray along the segment's line included, never hit it).
double ray_segment(Vec2 o, Vec2 t, const SegmentDef& seg) {
  const double ex = seg.b.x - seg.a.x, ey = seg.b.y - seg.a.y;
  const double denom = t.x * ey - t.y * ex;
  if (denom == 0.0) return std::nan("");
  const double wx = seg.a.x - o.x, wy = seg.a.y - o.y;
  const double s = (wx * ey - wy * ex) / denom, u = (wx * t.y - wy * t.x) / denom;
  return s >= 0.0 && s <= 1.0 && u >= 0.0 && u <= 1.0 ? s : std::nan("");
}

/// The distance from c to the segment's closest point, m.
double segment_distance(Vec2 c, const SegmentDef& seg) {
  const double ex = seg.b.x - seg.a.x, ey = seg.b.y - seg.a.y;
  const double wx = c.x - seg.a.x, wy = c.y - seg.a.y;
  const double u = std::clamp((wx * ex + wy * ey) / (ex * ex + ey * ey), 0.0, 1.0);
  const double dx = wx - u * ex, dy = wy - u * ey;
  return std::sqrt(dx * dx + dy * dy);
}

/// Whether the segment meets the box [lo, hi] (Liang–Barsky clipping of a + u (b - a)).
bool segment_box(const SegmentDef& seg, Vec2 lo, Vec2 hi) {
  double u0 = 0.0, u1 = 1.0;
  const double d[2] = {seg.b.x - seg.a.x, seg.b.y - seg.a.y};
  const double a[2] = {seg.a.x, seg.a.y}, l[2] = {lo.x, lo.y}, h[2] = {hi.x, hi.y};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (a[k] < l[k] || a[k] > h[k]) return false;
      continue;
    }
    double t0 = (l[k] - a[k]) / d[k], t1 = (h[k] - a[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    u0 = std::max(u0, t0), u1 = std::min(u1, t1);
  }
  return u0 <= u1;
}

}  // namespace

void World::queries_changed() {
  if (state_->queries) state_->queries->stale = true;
}

const detail::QueryGrid& detail::query_grid(const WorldState& state) {
  if (!state.queries) state.queries.reset(new QueryGrid());
  QueryGrid& g = *state.queries;
  if (!g.stale) return g;
  g.discs.clear(), g.shapes.clear();
  std::visit(
      [&](const auto& w) {
        const auto ids = w.entities();
        const auto x = w.x(), y = w.y();
        for (std::size_t i = 0; i < ids.size(); ++i) {
          const Collider* c = w.template get<Collider>(ids[i]);
          // A disc whose state left the finite range (World::fault) is nowhere.
          if (c && std::isfinite(double(x[i])) && std::isfinite(double(y[i]))) {
            g.discs.push_back(
                {double(x[i]), double(y[i]), c->radius, ids[i], c->filter, c->sensor});
          }
        }
      },
      state.kernel);
  add_query_shapes(state, g);
  g.build();
  return g;
}

std::size_t World::cast_ray_all(Vec2 origin, Vec2 translation, std::span<RayHit> out,
                                const QueryFilter& filter) const {
  require_finite_query(origin, "cast_ray", "origin");
  require_finite_query(translation, "cast_ray", "translation");
  const double len = std::sqrt(translation.x * translation.x + translation.y * translation.y);
  if (!std::isfinite(len) || std::abs(origin.x) + std::abs(origin.y) + len > max_query_reach) {
    // Beyond it the ray-disc quadratic's terms overflow (a NaN, not a hit).
    throw std::invalid_argument(
        fmt::format("cast_ray: the ray from ({}, {}) over ({}, {}) reaches beyond {:g} m", origin.x,
                    origin.y, translation.x, translation.y, max_query_reach));
  }
  Collector<RayHit, decltype(&detail::ray_hit_less)> hits(out, &detail::ray_hit_less);
  const detail::QueryGrid& g = detail::query_grid(*state_);
  auto disc_hit = [&](std::size_t i) {
    const detail::QueryDisc& d = g.discs[i];
    if (!query_seen(filter, d)) return;
    if (d.shape != detail::QueryDisc::none) {  // exact against the shape's surface
      const detail::RayEntry e = detail::ray_convex(g.shapes[d.shape].convex, origin, translation);
      if (std::isnan(e.s)) return;
      const Vec2 at{origin.x + e.s * translation.x, origin.y + e.s * translation.y};
      hits.add(RayHit{d.body, no_plane, e.s, at, e.normal, no_plane, d.index});
      return;
    }
    const double s = detail::ray_disc(origin, translation, Vec2{d.x, d.y}, d.r);
    if (std::isnan(s)) return;
    const Vec2 at{origin.x + s * translation.x, origin.y + s * translation.y};
    hits.add(RayHit{d.body, no_plane, s, at, Vec2{(at.x - d.x) / d.r, (at.y - d.y) / d.r}});
  };
  // The ray in pieces one cell long, each piece's box visited once per disc (marks).
  const double pieces = std::ceil(len / g.cell_side());
  const std::uint32_t mark = state_->queries->next_mark();
  auto once = [&](std::size_t i) {
    if (state_->queries->mark(i, mark)) disc_hit(i);
  };
  if (!(pieces <= double(g.discs.size()))) {
    for (std::size_t i = 0; i < g.discs.size(); ++i) once(i);
  } else {
    const auto n = static_cast<std::size_t>(pieces);
    for (std::size_t k = 0; k < n; ++k) {
      const double s0 = double(k) / double(n), s1 = double(k + 1) / double(n);
      const double ax = origin.x + s0 * translation.x, ay = origin.y + s0 * translation.y;
      const double bx = origin.x + s1 * translation.x, by = origin.y + s1 * translation.y;
      g.for_each_near(std::min(ax, bx), std::min(ay, by), std::max(ax, bx), std::max(ay, by), once);
    }
  }
  if (filter.planes) {
    const std::span<const PlaneDef> ps = planes();
    for (std::uint32_t i = 0; i < ps.size(); ++i) {
      const PlaneDef& p = ps[i];
      const double start = p.normal.x * origin.x + p.normal.y * origin.y - p.offset;
      const double along = p.normal.x * translation.x + p.normal.y * translation.y;
      if (!(start >= 0.0) || !(along < 0.0) || !(start <= -along)) continue;
      const double s = -start / along;
      hits.add(RayHit{Entity{}, i, s,
                      Vec2{origin.x + s * translation.x, origin.y + s * translation.y}, p.normal});
    }
  }
  if (filter.segments) {  // every segment: a level's are few beside its discs
    const std::span<const SegmentDef> ss = segments();
    for (std::uint32_t i = 0; i < ss.size(); ++i) {
      const double s = ray_segment(origin, translation, ss[i]);
      if (std::isnan(s)) continue;
      const double ex = ss[i].b.x - ss[i].a.x, ey = ss[i].b.y - ss[i].a.y;
      const double len = std::sqrt(ex * ex + ey * ey);
      const double side = -ey * translation.x + ex * translation.y > 0.0 ? -1.0 : 1.0;
      hits.add(RayHit{Entity{}, no_plane, s,
                      Vec2{origin.x + s * translation.x, origin.y + s * translation.y},
                      Vec2{side * -ey / len, side * ex / len}, i});
    }
  }
  return hits.finish();
}

std::optional<RayHit> World::cast_ray(Vec2 origin, Vec2 translation,
                                      const QueryFilter& filter) const {
  RayHit first;
  if (cast_ray_all(origin, translation, std::span<RayHit>(&first, 1), filter) == 0) {
    return std::nullopt;
  }
  return first;
}

namespace {

/// Whether the disc (c, r) overlaps the box [lo, hi]: the box's point closest to c within r.
bool disc_box(const detail::QueryDisc& d, Vec2 lo, Vec2 hi, double pad) {
  const double dx = d.x - std::clamp(d.x, lo.x, hi.x), dy = d.y - std::clamp(d.y, lo.y, hi.y);
  const double reach = d.r + pad;
  return dx * dx + dy * dy <= reach * reach;
}

/// The box [lo, hi] as a Convex: four vertices, or fewer where it is flat on an axis (a
/// segment or a point; GJK needs no repeated vertices).
detail::Convex box_convex(Vec2 lo, Vec2 hi) {
  detail::Convex c;
  if (lo.x == hi.x || lo.y == hi.y) {
    c.vertices[0] = lo, c.vertices[1] = hi;
    c.count = lo == hi ? 1 : 2;
    const Vec2 e = hi - lo;
    const double len = std::sqrt(dot(e, e));
    if (c.count == 2) c.normals[0] = Vec2{e.y, -e.x} / len, c.normals[1] = -c.normals[0];
    return c;
  }
  c.count = 4;
  c.vertices = {lo, Vec2{hi.x, lo.y}, hi, Vec2{lo.x, hi.y}};
  c.normals = {Vec2{0, -1}, Vec2{1, 0}, Vec2{0, 1}, Vec2{-1, 0}};
  return c;
}

}  // namespace

std::size_t World::overlap_aabb(Vec2 lower, Vec2 upper, std::span<QueryHit> out,
                                const QueryFilter& filter) const {
  require_finite_query(lower, "overlap_aabb", "lower");
  require_finite_query(upper, "overlap_aabb", "upper");
  if (lower.x > upper.x || lower.y > upper.y) {
    throw std::invalid_argument(
        fmt::format("overlap_aabb: lower ({}, {}) must not exceed upper ({}, {})", lower.x, lower.y,
                    upper.x, upper.y));
  }
  Collector<QueryHit, decltype(&detail::query_hit_less)> hits(out, &detail::query_hit_less);
  const detail::QueryGrid& g = detail::query_grid(*state_);
  const detail::Convex box = box_convex(lower, upper);
  g.for_each_near(lower.x, lower.y, upper.x, upper.y, [&](std::size_t i) {
    const detail::QueryDisc& d = g.discs[i];
    if (!query_seen(filter, d)) return;
    if (d.shape == detail::QueryDisc::none) {
      if (disc_box(d, lower, upper, 0.0)) hits.add(QueryHit{d.body});
      return;
    }
    const detail::QueryShape& sh = g.shapes[d.shape];
    if (detail::boxes_meet(lower, upper, sh.box) && detail::convex_overlap(box, sh.convex)) {
      hits.add(detail::entry_hit(d));
    }
  });
  if (filter.planes) {
    const std::span<const PlaneDef> ps = planes();
    for (std::uint32_t i = 0; i < ps.size(); ++i) {
      const PlaneDef& p = ps[i];
      // The box's corner deepest along -n.
      const double x = p.normal.x > 0.0 ? lower.x : upper.x;
      const double y = p.normal.y > 0.0 ? lower.y : upper.y;
      if (p.normal.x * x + p.normal.y * y < p.offset) hits.add(QueryHit{Entity{}, i});
    }
  }
  if (filter.segments) {
    const std::span<const SegmentDef> ss = segments();
    for (std::uint32_t i = 0; i < ss.size(); ++i) {
      if (segment_box(ss[i], lower, upper)) hits.add(QueryHit{Entity{}, no_plane, i});
    }
  }
  return hits.finish();
}

std::size_t World::overlap_circle(Vec2 center, double radius, std::span<QueryHit> out,
                                  const QueryFilter& filter) const {
  require_finite_query(center, "overlap_circle", "center");
  if (!(std::isfinite(radius) && radius >= 0.0)) {
    throw std::invalid_argument(
        fmt::format("overlap_circle: radius must be finite and >= 0 m (got {})", radius));
  }
  Collector<QueryHit, decltype(&detail::query_hit_less)> hits(out, &detail::query_hit_less);
  const detail::QueryGrid& g = detail::query_grid(*state_);
  g.for_each_near(
      center.x - radius, center.y - radius, center.x + radius, center.y + radius,
      [&](std::size_t i) {
        const detail::QueryDisc& d = g.discs[i];
        if (!query_seen(filter, d)) return;
        if (d.shape != detail::QueryDisc::none) {  // the centre within reach of the core
          const detail::Convex& c = g.shapes[d.shape].convex;
          const double reach = c.radius + radius;
          if (detail::core_gap2(c, center) <= reach * reach) {
            hits.add(detail::entry_hit(d));
          }
          return;
        }
        const double dx = d.x - center.x, dy = d.y - center.y, reach = d.r + radius;
        if (dx * dx + dy * dy <= reach * reach) hits.add(QueryHit{d.body});
      });
  if (filter.planes) {
    const std::span<const PlaneDef> ps = planes();
    for (std::uint32_t i = 0; i < ps.size(); ++i) {
      const PlaneDef& p = ps[i];
      if (p.normal.x * center.x + p.normal.y * center.y - radius < p.offset) {
        hits.add(QueryHit{Entity{}, i});
      }
    }
  }
  if (filter.segments) {
    const std::span<const SegmentDef> ss = segments();
    for (std::uint32_t i = 0; i < ss.size(); ++i) {
      if (segment_distance(center, ss[i]) <= radius) hits.add(QueryHit{Entity{}, no_plane, i});
    }
  }
  return hits.finish();
}

std::size_t World::query_point(Vec2 point, std::span<QueryHit> out,
                               const QueryFilter& filter) const {
  require_finite_query(point, "query_point", "point");
  return overlap_circle(point, 0.0, out, filter);
}

// Each query without a filter: the same with QueryFilter{} (every body, plane and segment).
std::optional<RayHit> World::cast_ray(Vec2 origin, Vec2 translation) const {
  return cast_ray(origin, translation, QueryFilter{});
}
std::size_t World::cast_ray_all(Vec2 origin, Vec2 translation, std::span<RayHit> out) const {
  return cast_ray_all(origin, translation, out, QueryFilter{});
}
std::size_t World::query_point(Vec2 point, std::span<QueryHit> out) const {
  return query_point(point, out, QueryFilter{});
}
std::size_t World::overlap_aabb(Vec2 lower, Vec2 upper, std::span<QueryHit> out) const {
  return overlap_aabb(lower, upper, out, QueryFilter{});
}
std::size_t World::overlap_circle(Vec2 center, double radius, std::span<QueryHit> out) const {
  return overlap_circle(center, radius, out, QueryFilter{});
}

}  // namespace fixstep
