// The bodies' shapes in World's queries (query.hpp, world.hpp): their entries in the query grid
// at the bodies' poses, and the overlap query with a shape (World::overlap_shape).
#include <fmt/format.h>

#include <cmath>
#include <span>
#include <stdexcept>

#include "fixstep/core/query.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world.hpp"
#include "query_collect.hpp"
#include "query_grid.hpp"
#include "shape_query.hpp"
#include "world_state.hpp"

namespace fixstep {

// Each shape placed at its body's pose: the body's centre of mass (x, y) and angle, the shape
// in the body frame relative to that centre (to_convex), then carried into world coordinates.
// The grid holds the disc around the shape's box: its middle and half diagonal.
void detail::add_query_shapes(const WorldState& state, QueryGrid& g) {
  std::visit(
      [&](const auto& w) {
        if (!w.has_shapes()) return;
        const auto ids = w.entities();
        const auto x = w.x(), y = w.y();
        for (std::size_t i = 0; i < ids.size(); ++i) {
          const std::span<const ShapeDef> defs = w.shapes(ids[i]);
          if (defs.empty()) continue;
          const double angle = w.body(ids[i]).angle;
          // A body whose state left the finite range (World::fault) is nowhere.
          if (!std::isfinite(double(x[i])) || !std::isfinite(double(y[i])) ||
              !std::isfinite(angle)) {
            continue;
          }
          const Pose pose{Vec2{double(x[i]), double(y[i])}, rot_of(angle)};
          const Vec2 center = w.local_center(ids[i]);
          for (std::size_t k = 0; k < defs.size(); ++k) {
            const Convex c = convex_placed(to_convex(defs[k], center), pose);
            const Aabb box = convex_aabb(c, Pose{});
            const Vec2 mid = 0.5 * (box.lower + box.upper), half = 0.5 * (box.upper - box.lower);
            g.discs.push_back(QueryDisc{
                mid.x, mid.y, std::sqrt(dot(half, half)), ids[i], defs[k].filter, defs[k].sensor,
                static_cast<std::uint32_t>(g.shapes.size()), static_cast<std::uint32_t>(k)});
            g.shapes.push_back(QueryShape{c, box});
          }
        }
      },
      state.kernel);
}

std::size_t World::overlap_shape(const ShapeDef& shape, Vec2 position, double angle,
                                 std::span<QueryHit> out, const QueryFilter& filter) const {
  detail::require_finite_query(position, "overlap_shape", "position");
  if (!std::isfinite(angle)) {
    throw std::invalid_argument(fmt::format("overlap_shape: angle must be finite (got {})", angle));
  }
  if (auto problem = shape_problem(shape)) {
    throw std::invalid_argument(fmt::format("overlap_shape: shape: {}", *problem));
  }
  const detail::Convex c = detail::convex_placed(detail::to_convex(shape, Vec2{}),
                                                 detail::Pose{position, detail::rot_of(angle)});
  const Aabb box = detail::convex_aabb(c, detail::Pose{});
  detail::Collector<QueryHit, decltype(&detail::query_hit_less)> hits(out, &detail::query_hit_less);
  const detail::QueryGrid& g = detail::query_grid(*state_);
  g.for_each_near(box.lower.x, box.lower.y, box.upper.x, box.upper.y, [&](std::size_t i) {
    const detail::QueryDisc& d = g.discs[i];
    if (!detail::query_seen(filter, d)) return;
    if (d.shape == detail::QueryDisc::none) {  // the disc's centre within reach of the core
      const double reach = c.radius + d.r;
      if (detail::core_gap2(c, Vec2{d.x, d.y}) <= reach * reach) hits.add(QueryHit{d.body});
      return;
    }
    const detail::QueryShape& sh = g.shapes[d.shape];
    if (detail::boxes_meet(box.lower, box.upper, sh.box) && detail::convex_overlap(c, sh.convex)) {
      hits.add(detail::entry_hit(d));
    }
  });
  if (filter.planes) {  // the core's deepest vertex below the plane by more than the radius
    const std::span<const PlaneDef> ps = planes();
    for (std::uint32_t i = 0; i < ps.size(); ++i) {
      const PlaneDef& p = ps[i];
      double deepest = dot(p.normal, c.vertices[0]);
      for (int k = 1; k < c.count; ++k) deepest = std::min(deepest, dot(p.normal, c.vertices[k]));
      if (deepest - c.radius < p.offset) hits.add(QueryHit{Entity{}, i});
    }
  }
  if (filter.segments) {
    const std::span<const SegmentDef> ss = segments();
    for (std::uint32_t i = 0; i < ss.size(); ++i) {
      if (detail::convex_overlap(detail::segment_convex(ss[i].a, ss[i].b), c)) {
        hits.add(QueryHit{Entity{}, no_plane, i});
      }
    }
  }
  return hits.finish();
}

std::size_t World::overlap_shape(const ShapeDef& shape, Vec2 position, double angle,
                                 std::span<QueryHit> out) const {
  return overlap_shape(shape, position, angle, out, QueryFilter{});
}

}  // namespace fixstep
