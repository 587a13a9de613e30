// DrawList (draw_list.hpp): recording the shapes, every argument checked.
#include "fixstep/render/draw_list.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace fixstep {

namespace {

void check_finite(double v, const char* call, const char* field) {
  if (!std::isfinite(v))
    throw std::invalid_argument(
        fmt::format("DrawList::{}: {} must be finite, got {}", call, field, v));
}

void check_point(Vec2 p, const char* call, const char* name) {
  if (std::isfinite(p.x) && std::isfinite(p.y)) return;  // names formatted only when refused
  check_finite(p.x, call, fmt::format("{}.x", name).c_str());
  check_finite(p.y, call, fmt::format("{}.y", name).c_str());
}

void check_points(std::span<const Vec2> points, const char* call) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2 p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      throw std::invalid_argument(
          fmt::format("DrawList::{}: points[{}] must be finite, got ({}, {})", call, i, p.x, p.y));
    }
  }
}

void check_size(double v, const char* call, const char* field) {
  if (!(std::isfinite(v) && v >= 0.0)) {
    throw std::invalid_argument(
        fmt::format("DrawList::{}: {} must be finite and >= 0, got {}", call, field, v));
  }
}

/// Whether `points` (at least 3, finite) bound a convex polygon: every turn the same way
/// (collinear points allowed) and the boundary winding once (the turns add up to one turn).
bool convex(std::span<const Vec2> points) {
  const std::size_t n = points.size();
  int sign = 0;
  double turned = 0.0;  // radians
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = points[i], b = points[(i + 1) % n], c = points[(i + 2) % n];
    const double ux = b.x - a.x, uy = b.y - a.y, vx = c.x - b.x, vy = c.y - b.y;
    const double cross = ux * vy - uy * vx, dot = ux * vx + uy * vy;
    if (cross != 0.0) {
      const int s = cross > 0.0 ? 1 : -1;
      if (sign != 0 && s != sign) return false;
      sign = s;
    }
    if ((ux != 0.0 || uy != 0.0) && (vx != 0.0 || vy != 0.0)) turned += std::atan2(cross, dot);
  }
  // A convex boundary turns once (2 pi); a star or a doubled loop more; all collinear: 0 or pi
  // per fold back, drawn as nothing anyway.
  return std::abs(std::abs(turned) - 2.0 * 3.141592653589793) < 1e-6 || sign == 0;
}

}  // namespace

void DrawList::push(Kind kind, Space space, Rgba8 color, double width, double size,
                    std::span<const Vec2> points) {
  if (points_.size() + points.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("DrawList: more than 2^32 points in one list");
  shapes_.push_back(Shape{.kind = kind,
                          .space = space,
                          .color = color,
                          .width = width,
                          .size = size,
                          .first = static_cast<std::uint32_t>(points_.size()),
                          .count = static_cast<std::uint32_t>(points.size())});
  points_.insert(points_.end(), points.begin(), points.end());
}

void DrawList::line(Vec2 a, Vec2 b, double width, Rgba8 color, Space space) {
  check_point(a, "line", "a");
  check_point(b, "line", "b");
  check_size(width, "line", "width");
  const Vec2 p[2] = {a, b};
  push(Kind::line, space, color, width, 0.0, p);
}

void DrawList::polyline(std::span<const Vec2> points, double width, Rgba8 color, Space space) {
  check_points(points, "polyline");
  check_size(width, "polyline", "width");
  push(Kind::polyline, space, color, width, 0.0, points);
}

void DrawList::circle(Vec2 center, double radius, double width, Rgba8 color, Space space) {
  check_point(center, "circle", "center");
  check_size(radius, "circle", "radius");
  check_size(width, "circle", "width");
  push(Kind::circle, space, color, radius, width, std::span(&center, 1));
}

void DrawList::disc(Vec2 center, double radius, Rgba8 color, Space space) {
  check_point(center, "disc", "center");
  check_size(radius, "disc", "radius");
  push(Kind::disc, space, color, radius, 0.0, std::span(&center, 1));
}

void DrawList::rect(Vec2 a, Vec2 b, Rgba8 color, Space space) {
  check_point(a, "rect", "a");
  check_point(b, "rect", "b");
  const Vec2 p[2] = {a, b};
  push(Kind::rect, space, color, 0.0, 0.0, p);
}

void DrawList::polygon(std::span<const Vec2> points, Rgba8 color, Space space) {
  check_points(points, "polygon");
  if (points.size() < 3) {
    throw std::invalid_argument(fmt::format(
        "DrawList::polygon: points must hold at least 3 points, got {}", points.size()));
  }
  if (!convex(points))
    throw std::invalid_argument("DrawList::polygon: points must bound a convex polygon");
  push(Kind::polygon, space, color, 0.0, 0.0, points);
}

void DrawList::arrow(Vec2 from, Vec2 to, double width, double head, Rgba8 color, Space space) {
  check_point(from, "arrow", "from");
  check_point(to, "arrow", "to");
  check_size(width, "arrow", "width");
  check_size(head, "arrow", "head");
  const Vec2 p[2] = {from, to};
  push(Kind::arrow, space, color, width, head, p);
}

void DrawList::label(Vec2 at, std::string_view text, double scale, Rgba8 color, Space space) {
  check_point(at, "label", "at");
  if (!std::isfinite(scale) || scale < min_text_scale || scale > max_text_scale) {
    throw std::invalid_argument(
        fmt::format("DrawList::label: scale must be in [{:g}, {:g}], got {}", min_text_scale,
                    max_text_scale, scale));
  }
  if (text_.size() + text.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("DrawList: more than 2^32 characters of text in one list");
  push(Kind::label, space, color, scale, 0.0, std::span(&at, 1));
  shapes_.back().text_first = static_cast<std::uint32_t>(text_.size());
  shapes_.back().text_count = static_cast<std::uint32_t>(text.size());
  text_.append(text);
}

void DrawList::image(std::string_view path, Vec2 center, Vec2 size, double angle, Space space) {
  check_point(center, "image", "center");
  check_size(size.x, "image", "size.x");
  check_size(size.y, "image", "size.y");
  if (!std::isfinite(angle))
    throw std::invalid_argument(
        fmt::format("DrawList::image: angle must be finite, got {}", angle));
  if (text_.size() + path.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("DrawList: more than 2^32 characters of text in one list");
  // The corners, top-left first and clockwise as seen: turned counter-clockwise as seen, which
  // in screen space (y down) is clockwise in its coordinates.
  const double c = std::cos(angle), si = std::sin(angle), hw = 0.5 * size.x, hh = 0.5 * size.y;
  const double up = space == Space::world ? 1.0 : -1.0;  // the coordinates' y per "up"
  const double local[4][2] = {{-hw, hh}, {hw, hh}, {hw, -hh}, {-hw, -hh}};
  Vec2 corners[4];
  for (int k = 0; k < 4; ++k) {
    const double x = c * local[k][0] - si * local[k][1], y = si * local[k][0] + c * local[k][1];
    corners[k] = {center.x + x, center.y + up * y};
  }
  push(Kind::image, space, Rgba8{255, 255, 255, 255}, 0.0, 0.0, corners);
  shapes_.back().text_first = static_cast<std::uint32_t>(text_.size());
  shapes_.back().text_count = static_cast<std::uint32_t>(path.size());
  text_.append(path);
}

void DrawList::clear() {
  shapes_.clear();
  points_.clear();
  text_.clear();
}

}  // namespace fixstep
