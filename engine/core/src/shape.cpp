// Shapes: the make_* helpers, the checks a definition passes (shape_problem), and where a shape
// lies in the world (shape_aabb, shape_outline). Rotations come from det::cos / det::sin and
// the rest is + - * / and sqrt, so every result is the same bits on every platform.
#include "fixstep/core/shape.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <string>

#include "fixstep/core/det_math.hpp"
#include "fixstep/core/value_ranges.hpp"
#include "shape_geom.hpp"

namespace fixstep {

namespace {

/// Sine of the smallest turn at a polygon vertex (or between an edge and any other vertex)
/// that shape_problem takes as a turn: smaller ones are three collinear vertices. Relative
/// (cross product over the two lengths), so it holds at every scale; 1e-9 rad is far above the
/// rounding of a cross product of coordinates within max_shape_extent.
constexpr double collinear_sine = 1e-9;

/// The rotation by `angle` (rad), through det::cos and det::sin.
detail::Rot shape_turn(double angle) {
  return {det::cos(angle), det::sin(angle)};
}

/// Finite and within max_shape_extent (m). isfinite first: an ordered comparison with NaN
/// raises FE_INVALID, which the Debug tests trap.
bool within_extent(double v) {
  return std::isfinite(v) && std::fabs(v) <= max_shape_extent;
}
bool within_extent(Vec2 v) {
  return within_extent(v.x) && within_extent(v.y);
}

/// The shape's core points in its own frame: a circle's centre, a capsule's two ends, a box's
/// four corners or a polygon's vertices, counter-clockwise.
struct CorePoints {
  std::array<Vec2, max_polygon_vertices> points{};
  int count = 0;
};
CorePoints core_points(const ShapeDef& s) {
  CorePoints c;
  switch (s.kind) {
    case ShapeKind::circle:
      c.count = 1;
      break;
    case ShapeKind::box: {
      const double hx = s.half_extents.x, hy = s.half_extents.y;
      c.points = {Vec2{-hx, -hy}, Vec2{hx, -hy}, Vec2{hx, hy}, Vec2{-hx, hy}};
      c.count = 4;
      break;
    }
    case ShapeKind::capsule:
    case ShapeKind::polygon:
      c.points = s.vertices;
      c.count = std::clamp(s.count, 0, max_polygon_vertices);
      break;
  }
  return c;
}

/// `s`'s core points placed at body position `position` and angle `angle`: first into the
/// body frame (offset + R(s.angle) v), then into the world (position + R(angle) that), the
/// order the kernel places them in (shape_geom.hpp's to_convex, then the body's pose).
CorePoints world_points(const ShapeDef& s, Vec2 position, double angle) {
  CorePoints c = core_points(s);
  const detail::Rot local = shape_turn(s.angle), body = shape_turn(angle);
  for (int i = 0; i < c.count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    c.points[k] = position + detail::rotate(body, s.offset + detail::rotate(local, c.points[k]));
  }
  return c;
}

std::optional<std::string> polygon_problem(const ShapeDef& s) {
  if (s.count < 3 || s.count > max_polygon_vertices) {
    return fmt::format("polygon count must be 3 to {} (got {})", max_polygon_vertices, s.count);
  }
  const auto n = static_cast<std::size_t>(s.count);
  const auto& v = s.vertices;
  for (std::size_t i = 0; i < n; ++i) {
    if (!within_extent(v[i])) {
      return fmt::format("polygon vertex {} must be finite with |x|, |y| <= {} m (got {}, {})", i,
                         max_shape_extent, v[i].x, v[i].y);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e = v[(i + 1) % n] - v[i];
    if (!(det::hypot(e.x, e.y) >= min_shape_edge)) {
      return fmt::format("polygon edge {} -> {} must be at least {} m long", i, (i + 1) % n,
                         min_shape_edge);
    }
  }
  // Twice the signed area, by the shoelace formula about vertex 0.
  double twice_area = 0.0;
  double size = 0.0;  // the largest |v_i - v_0|, m: the scale of the area test
  for (std::size_t i = 1; i < n; ++i) {
    size = std::max(size, length(v[i] - v[0]));
    if (i + 1 < n) twice_area += cross(v[i] - v[0], v[i + 1] - v[0]);
  }
  if (std::fabs(twice_area) <= collinear_sine * size * size) {
    return std::string("polygon has no area (its vertices are collinear)");
  }
  if (twice_area < 0.0) {
    return std::string("polygon vertices must run counter-clockwise (they run clockwise)");
  }
  // Every turn to the left, by more than collinear_sine.
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t prev = (i + n - 1) % n, next = (i + 1) % n;
    const Vec2 e1 = v[i] - v[prev], e2 = v[next] - v[i];
    const double turn = cross(e1, e2), tolerance = collinear_sine * length(e1) * length(e2);
    if (turn <= tolerance) {
      if (turn >= -tolerance) {
        return fmt::format(
            "polygon vertex {} lies on the line through vertices {} and {} (no "
            "three vertices may be collinear)",
            i, prev, next);
      }
      return fmt::format("polygon vertex {} makes it concave", i);
    }
  }
  // Going round once: every vertex off an edge lies strictly left of it (a pentagram turns
  // left at every vertex and goes round twice).
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = v[i], e = v[(i + 1) % n] - a;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || j == (i + 1) % n) continue;
      const Vec2 d = v[j] - a;
      if (cross(e, d) <= collinear_sine * length(e) * length(d)) {
        return fmt::format(
            "polygon must go round once, convex (vertex {} lies outside edge {} "
            "-> {})",
            j, i, (i + 1) % n);
      }
    }
  }
  return std::nullopt;
}

std::optional<std::string> geometry_problem(const ShapeDef& s) {
  const bool rounded = s.kind == ShapeKind::box || s.kind == ShapeKind::polygon;
  const bool radius_ok = within_extent(s.radius) && (rounded ? s.radius >= 0.0 : s.radius > 0.0);
  if (!radius_ok) {
    return fmt::format("radius must be finite, {} 0 and <= {} m (got {})", rounded ? ">=" : ">",
                       max_shape_extent, s.radius);
  }
  switch (s.kind) {
    case ShapeKind::circle:
      return std::nullopt;
    case ShapeKind::box:
      for (const double h : {s.half_extents.x, s.half_extents.y}) {
        if (!within_extent(h) || !(h >= 0.5 * min_shape_edge)) {
          return fmt::format("box half extents must be finite, >= {} and <= {} m (got {}, {})",
                             0.5 * min_shape_edge, max_shape_extent, s.half_extents.x,
                             s.half_extents.y);
        }
      }
      return std::nullopt;
    case ShapeKind::capsule: {
      if (s.count != 2) return fmt::format("capsule count must be 2 (got {})", s.count);
      for (std::size_t i = 0; i < 2; ++i) {
        if (!within_extent(s.vertices[i])) {
          return fmt::format("capsule vertex {} must be finite with |x|, |y| <= {} m (got {}, {})",
                             i, max_shape_extent, s.vertices[i].x, s.vertices[i].y);
        }
      }
      const double len = length(s.vertices[1] - s.vertices[0]);
      if (!(len >= min_shape_edge)) {
        return fmt::format("capsule length must be at least {} m (got {})", min_shape_edge, len);
      }
      return std::nullopt;
    }
    case ShapeKind::polygon:
      return polygon_problem(s);
  }
  return std::string("kind must be circle, capsule, box or polygon");
}

}  // namespace

const char* shape_kind_name(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::circle:
      return "circle";
    case ShapeKind::capsule:
      return "capsule";
    case ShapeKind::box:
      return "box";
    case ShapeKind::polygon:
      return "polygon";
  }
  return "unknown";
}

ShapeDef make_circle(double radius, Vec2 center) {
  ShapeDef s;
  s.kind = ShapeKind::circle;
  s.radius = radius;
  s.offset = center;
  return s;
}

ShapeDef make_capsule(Vec2 a, Vec2 b, double radius) {
  ShapeDef s;
  s.kind = ShapeKind::capsule;
  s.radius = radius;
  s.vertices[0] = a;
  s.vertices[1] = b;
  s.count = 2;
  return s;
}

ShapeDef make_box(double hx, double hy, Vec2 center, double angle, double rounding) {
  ShapeDef s;
  s.kind = ShapeKind::box;
  s.radius = rounding;
  s.half_extents = {hx, hy};
  s.offset = center;
  s.angle = angle;
  return s;
}

ShapeDef make_polygon(std::span<const Vec2> points, double rounding) {
  ShapeDef s;
  s.kind = ShapeKind::polygon;
  s.radius = rounding;
  // More points than a polygon holds: the count says so, and shape_problem refuses it.
  const std::size_t kept = std::min(points.size(), s.vertices.size());
  std::copy_n(points.begin(), kept, s.vertices.begin());
  s.count = static_cast<int>(std::min<std::size_t>(points.size(), max_polygon_vertices + 1));
  return s;
}

std::optional<std::string> shape_problem(const ShapeDef& s) {
  if (s.kind != ShapeKind::circle && s.kind != ShapeKind::capsule && s.kind != ShapeKind::box &&
      s.kind != ShapeKind::polygon) {
    return std::string("kind must be circle, capsule, box or polygon");
  }
  if (!within_extent(s.offset)) {
    return fmt::format("offset must be finite with |x|, |y| <= {} m (got {}, {})", max_shape_extent,
                       s.offset.x, s.offset.y);
  }
  if (!std::isfinite(s.angle) || std::fabs(s.angle) > det::trig_max_argument) {
    return fmt::format("angle must be finite with |angle| <= {} rad (got {})",
                       det::trig_max_argument, s.angle);
  }
  if (auto problem = geometry_problem(s)) return problem;
  if (s.density &&
      !(std::isfinite(*s.density) && *s.density >= 0.0 && *s.density <= max_coefficient)) {
    return fmt::format("density must be finite, >= 0 and <= 1e100 kg/m^2 (got {})", *s.density);
  }
  if (!(std::isfinite(s.rolling_resistance) && s.rolling_resistance >= 0.0 &&
        s.rolling_resistance <= max_coefficient)) {
    return fmt::format("rolling_resistance must be in [0, 1e100] (got {})", s.rolling_resistance);
  }
  if (s.friction &&
      !(std::isfinite(*s.friction) && *s.friction >= 0.0 && *s.friction <= max_coefficient)) {
    return fmt::format("friction must be in [0, 1e100] (got {})", *s.friction);
  }
  if (s.restitution &&
      !(std::isfinite(*s.restitution) && *s.restitution >= 0.0 && *s.restitution <= 1.0)) {
    return fmt::format("restitution must be in [0, 1] (got {})", *s.restitution);
  }
  return std::nullopt;
}

Aabb shape_aabb(const ShapeDef& shape, Vec2 position, double angle) {
  const CorePoints c = world_points(shape, position, angle);
  Aabb box{c.points[0], c.points[0]};
  for (int i = 1; i < c.count; ++i) {
    const Vec2 p = c.points[static_cast<std::size_t>(i)];
    box.lower = {std::min(box.lower.x, p.x), std::min(box.lower.y, p.y)};
    box.upper = {std::max(box.upper.x, p.x), std::max(box.upper.y, p.y)};
  }
  const Vec2 r{shape.radius, shape.radius};
  return {box.lower - r, box.upper + r};
}

ShapeOutline shape_outline(const ShapeDef& shape, Vec2 position, double angle) {
  const CorePoints c = world_points(shape, position, angle);
  ShapeOutline out;
  out.points = c.points;
  out.count = c.count;
  out.radius = shape.radius;
  return out;
}

}  // namespace fixstep
