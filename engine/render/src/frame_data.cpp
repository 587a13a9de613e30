// A RenderFrame taken from a World (frame_data.hpp).
#include "fixstep/render/frame_data.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "fixstep/core/components.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

namespace {

/// `shape` of body entry `body` as drawn (RenderFrame::Shape): its outline (shape_outline's
/// points) and mark in the body frame, less the body's centre of mass `center`. The mark: a
/// circle's rim on its x axis; a box's point min(hx, hy) along its x axis (its side for a
/// square, as short for a long box); a capsule's or polygon's first vertex.
RenderFrame::Shape drawn_shape(const ShapeDef& shape, Vec2 center, std::uint32_t body) {
  RenderFrame::Shape d;
  d.body = body;
  d.radius = static_cast<float>(shape.radius);
  const ShapeOutline outline = shape_outline(shape, Vec2{-center.x, -center.y}, 0.0);
  d.count = static_cast<std::uint32_t>(std::clamp(outline.count, 0, max_polygon_vertices));
  for (std::size_t k = 0; k < d.count; ++k) {
    d.px[k] = static_cast<float>(outline.points[k].x);
    d.py[k] = static_cast<float>(outline.points[k].y);
  }
  Vec2 mark = shape.vertices[0];  // in the shape's frame
  if (shape.kind == ShapeKind::circle) mark = {shape.radius, 0.0};
  if (shape.kind == ShapeKind::box)
    mark = {std::min(shape.half_extents.x, shape.half_extents.y), 0.0};
  const double c = std::cos(shape.angle), s = std::sin(shape.angle);
  d.mark_x = static_cast<float>(shape.offset.x + (c * mark.x - s * mark.y) - center.x);
  d.mark_y = static_cast<float>(shape.offset.y + (s * mark.x + c * mark.y) - center.y);
  return d;
}

}  // namespace

void fill_render_frame(const World& world, double alpha, RenderFrame& out) {
  const std::span<const Entity> bodies = world.bodies();
  const std::size_t n = bodies.size();
  out.x.resize(n);
  out.y.resize(n);
  world.interpolate_positions(alpha, out.x, out.y);
  out.ids.assign(bodies.begin(), bodies.end());
  out.radius.resize(n);
  out.color.resize(n);
  out.visible.resize(n);
  out.trail_time.resize(n);
  out.springs.clear();
  // Bodies with shapes: drawn as their shapes, turned by their angle.
  out.shapes.clear();
  for (std::size_t j = 0; j < n; ++j) {
    const std::span<const ShapeDef> shapes = world.shapes(bodies[j]);
    if (shapes.empty()) continue;
    const Vec2 center = world.local_center(bodies[j]);
    for (const ShapeDef& shape : shapes) {
      out.shapes.push_back(drawn_shape(shape, center, static_cast<std::uint32_t>(j)));
    }
  }
  const auto& contacts = world.settings().contacts;
  const bool rolling = contacts && contacts->rolling;
  out.spin_marks = rolling;
  out.angle.resize(rolling || !out.shapes.empty() ? n : 0);
  out.asleep.resize(contacts && contacts->sleep ? n : 0);
  for (std::size_t j = 0; j < n; ++j) {
    const Entity e = bodies[j];
    if (const std::optional<Appearance> a = world.get<Appearance>(e)) {
      out.radius[j] = static_cast<float>(a->radius);
      out.color[j] = a->color;
      out.visible[j] = a->visible ? 1 : 0;
      out.trail_time[j] = a->trail ? static_cast<float>(a->trail_time) : 0.0f;
    } else {
      out.radius[j] = 0.0f;
      out.color[j] = Rgba8{0, 0, 0, 0};
      out.visible[j] = 1;
      out.trail_time[j] = static_cast<float>(default_trail_time);
    }
    if (!out.angle.empty()) {  // θ at the frame's moment: the tick's θ less (1 - α) ω dt
      const Body b = world.body(e);
      const double back = (1.0 - alpha) * b.angular_velocity * world.settings().dt;
      // A body with shapes may have turned many times (|θ| up to 1e12): within one turn
      // first, for float to keep its angle to the pixel.
      const double angle = out.shapes.empty()
                               ? b.angle - back
                               : std::remainder(b.angle - back, 2 * std::numbers::pi);
      out.angle[j] = static_cast<float>(angle);
    }
    if (!out.asleep.empty()) out.asleep[j] = world.asleep(e) ? 1 : 0;
    if (const std::optional<SpringDamper> s = world.get<SpringDamper>(e)) {
      out.springs.push_back({static_cast<float>(s->anchor.x), static_cast<float>(s->anchor.y),
                             static_cast<std::uint32_t>(j)});
    }
  }
  const std::size_t links = world.link_count();
  out.link_a.resize(links);
  out.link_b.resize(links);
  world.link_ends(out.link_a, out.link_b);
  out.planes.assign(world.planes().begin(), world.planes().end());
  out.segments.assign(world.segments().begin(), world.segments().end());
  for (SegmentDef& s : out.segments) {  // a carried one where its body is at the frame's moment
    if (s.body.is_null() || !world.contains(s.body)) continue;
    const Vec2 v = world.body(s.body).velocity;
    const double back = (1.0 - alpha) * world.settings().dt;
    const auto moved = [&](Vec2 p) { return Vec2{p.x - v.x * back, p.y - v.y * back}; };
    s.a = moved(s.a), s.b = moved(s.b);
    if (s.prev) s.prev = moved(*s.prev);
    if (s.next) s.next = moved(*s.next);
  }
  out.tick = world.tick();
  out.dt = world.settings().dt;
  out.alpha = alpha;
}

}  // namespace fixstep
