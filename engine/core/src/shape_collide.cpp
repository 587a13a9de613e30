// Shapes in polygon form, their extents and boxes, and the manifolds between two shapes and
// between a shape and a half-plane. The SAT and clipping live in shape_clip.cpp, a static
// segment with ghost vertices in shape_segment.cpp.
#include <cmath>

#include "fixstep/core/det_math.hpp"
#include "shape_geom.hpp"

namespace fixstep::detail {

// shape_clip.cpp
Manifold collide_placed(const Convex& a, const Convex& b, double speculative);

Rot rot_of(double angle) {
  Rot q;
  det::sincos(trig_angle(angle), q.s, q.c);
  return q;
}

namespace {

/// Outward unit normals of a counter-clockwise vertex loop (for two vertices the segment's two
/// sides): the right perpendicular of each edge, divided by its length.
void convex_set_normals(Convex& c) {
  if (c.count < 2) return;
  for (int i = 0; i < c.count; ++i) {
    const Vec2 e = c.vertices[i + 1 < c.count ? i + 1 : 0] - c.vertices[i];
    const double len = std::sqrt(dot(e, e));
    c.normals[i] = Vec2{e.y, -e.x} / len;
  }
}

/// The pose of B in A's frame: ta⁻¹ · tb.
Pose convex_relative(const Pose& ta, const Pose& tb) {
  const Rot q{ta.q.c * tb.q.c + ta.q.s * tb.q.s, ta.q.c * tb.q.s - ta.q.s * tb.q.c};
  return {unrotate(ta.q, tb.p - ta.p), q};
}

}  // namespace

/// c with every vertex and normal carried by pose t (also used by shape_segment.cpp).
Convex convex_placed(const Convex& c, const Pose& t) {
  Convex out = c;
  for (int i = 0; i < c.count; ++i) {
    out.vertices[i] = transform(t, c.vertices[i]);
    out.normals[i] = rotate(t.q, c.normals[i]);
  }
  return out;
}

Convex to_convex(const ShapeDef& shape, Vec2 center) {
  Convex c;
  c.radius = shape.radius;
  switch (shape.kind) {
    case ShapeKind::circle:
      c.count = 1;
      break;
    case ShapeKind::capsule:
      c.count = 2;
      c.vertices[0] = shape.vertices[0];
      c.vertices[1] = shape.vertices[1];
      break;
    case ShapeKind::box: {
      const double hx = shape.half_extents.x, hy = shape.half_extents.y;
      c.count = 4;
      c.vertices = {Vec2{-hx, -hy}, Vec2{hx, -hy}, Vec2{hx, hy}, Vec2{-hx, hy}};
      break;
    }
    case ShapeKind::polygon:
      c.count = shape.count;
      for (int i = 0; i < shape.count; ++i) c.vertices[i] = shape.vertices[i];
      break;
  }
  const Pose frame{shape.offset, rot_of(shape.angle)};
  for (int i = 0; i < c.count; ++i) c.vertices[i] = transform(frame, c.vertices[i]) - center;
  convex_set_normals(c);
  return c;
}

Convex segment_convex(Vec2 a, Vec2 b) {
  Convex c;
  c.count = 2;
  c.vertices[0] = a;
  c.vertices[1] = b;
  convex_set_normals(c);
  return c;
}

double extent(const Convex& c) {
  double far2 = 0.0;
  for (int i = 0; i < c.count; ++i) {
    const double d2 = dot(c.vertices[i], c.vertices[i]);
    if (d2 > far2) far2 = d2;
  }
  return std::sqrt(far2) + c.radius;
}

Aabb convex_aabb(const Convex& c, const Pose& t, double margin) {
  Vec2 lo = transform(t, c.vertices[0]), hi = lo;
  for (int i = 1; i < c.count; ++i) {
    const Vec2 v = transform(t, c.vertices[i]);
    lo = {v.x < lo.x ? v.x : lo.x, v.y < lo.y ? v.y : lo.y};
    hi = {v.x > hi.x ? v.x : hi.x, v.y > hi.y ? v.y : hi.y};
  }
  const double grow = c.radius + margin;
  return {lo - Vec2{grow, grow}, hi + Vec2{grow, grow}};
}

Manifold collide(const Convex& a, const Pose& ta, const Convex& b, const Pose& tb,
                 double speculative) {
  // In A's frame, so that A's numbers are used as they are (Box2D: b2CollidePolygons).
  Manifold m = collide_placed(a, convex_placed(b, convex_relative(ta, tb)), speculative);
  m.normal = rotate(ta.q, m.normal);
  for (int i = 0; i < m.count; ++i) {
    ManifoldPoint& p = m.points[i];
    p.point = transform(ta, p.point);
    p.anchor_a = p.point - ta.p;
    p.anchor_b = p.point - tb.p;
  }
  return m;
}

Manifold collide_plane(Vec2 n, double offset, const Convex& b, const Pose& tb, double speculative) {
  // B's vertices by depth below the plane's surface: the deepest and, when B has an edge, the
  // deeper of its two neighbours (on a convex loop the second deepest vertex is adjacent).
  Manifold m;
  m.normal = n;
  double depth[max_polygon_vertices];
  int deepest = 0;
  for (int i = 0; i < b.count; ++i) {
    depth[i] = dot(n, transform(tb, b.vertices[i])) - offset - b.radius;
    if (depth[i] < depth[deepest]) deepest = i;
  }
  int order[2] = {deepest, -1};
  if (b.count >= 2) {
    const int before = deepest > 0 ? deepest - 1 : b.count - 1;
    const int after = deepest + 1 < b.count ? deepest + 1 : 0;
    order[1] = depth[after] <= depth[before] ? after : before;
  }
  for (const int i : order) {
    if (i < 0 || depth[i] > speculative) continue;
    const Vec2 v = transform(tb, b.vertices[i]);
    ManifoldPoint& p = m.points[m.count++];
    // Midway between the plane (at depth + radius below v) and B's surface (radius below v).
    p.point = v - (0.5 * depth[i] + b.radius) * n;
    p.separation = depth[i];
    p.anchor_a = p.point;
    p.anchor_b = p.point - tb.p;
    p.id = static_cast<std::uint32_t>(i);
  }
  return m;
}

}  // namespace fixstep::detail
