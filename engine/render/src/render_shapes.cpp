// The canvas's strokes and shapes beyond render.cpp's rectangles, lines and discs: polylines
// (open and closed), circles (outlines), convex polygons and arrows.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "aa_pad.hpp"
#include "fixstep/render/render.hpp"

namespace fixstep {

void Renderer::strip_pair(float x, float y, float nx, float ny, float e, Rgba8 c, bool join) {
  const auto base = static_cast<std::uint32_t>(vertices_.size());
  vertex(x + nx, y + ny, 0.0f, e, c);
  vertex(x - nx, y - ny, 0.0f, -e, c);
  if (join) {
    for (std::uint32_t i : {0u, 1u, 3u, 0u, 3u, 2u}) indices_.push_back(base - 2 + i);
  }
}

void Renderer::polyline(std::span<const PolylinePoint> points, float width) {
  // The strip is a sequence of vertex pairs: left = point + normal * pad, right = point -
  // normal * pad, shape coordinate v = +e / -e, as in line() (pad includes detail::aa_pad_px for
  // the anti-aliased edge). A pair emitted with `join` is connected to the pair before it by two
  // triangles.
  use(shapes, {});
  const float h = 0.5f * width, pad = h + detail::aa_pad_px, e = pad / h;
  constexpr float min_step = 1e-3f;  // px, as line()
  // cos of the sharpest turn still mitred: 90°, where the mitre is sqrt(2) * pad long.
  constexpr float mitre_limit = 0.0f;
  auto pair = [&](const PolylinePoint& p, float nx, float ny, bool join) {
    strip_pair(p.x, p.y, nx, ny, e, p.c, join);
  };
  if (points.empty()) return;
  // `prev`: the last distinct point; (dx, dy): unit direction of the segment ending there.
  const PolylinePoint* prev = &points[0];
  float dx = 0, dy = 0;
  bool started = false;  // the first segment (and the pair at its start) has been emitted
  for (std::size_t i = 1; i < points.size(); ++i) {
    const PolylinePoint& p = points[i];
    const float sx = p.x - prev->x, sy = p.y - prev->y;
    const float len = std::sqrt(sx * sx + sy * sy);
    if (len < min_step) continue;
    const float ux = sx / len, uy = sy / len;
    if (!started) {
      pair(*prev, -uy * pad, ux * pad, false);
      started = true;
    } else if (dx * ux + dy * uy >= mitre_limit) {  // mitre: one pair on the bisector
      float mx = dx + ux, my = dy + uy;
      const float ml = std::sqrt(mx * mx + my * my);
      mx /= ml, my /= ml;
      // Offset pad / cos(half the turn) along the bisector's normal: pad from both segments.
      const float scale = pad / (mx * ux + my * uy);
      pair(*prev, -my * scale, mx * scale, true);
    } else {  // too sharp: end this strip flat and start the next one flat
      pair(*prev, -dy * pad, dx * pad, true);
      pair(*prev, -uy * pad, ux * pad, false);
    }
    dx = ux, dy = uy;
    prev = &p;
  }
  if (started) pair(*prev, -dy * pad, dx * pad, true);
}

void Renderer::closed_polyline(std::span<const Point> points, float width, Rgba8 c) {
  // As polyline(), with every point a join: point i joins the segment from point i - 1 (the
  // last, for i = 0) to the one towards point i + 1 (the first, for the last), and the strip's
  // last pair is joined to its first.
  constexpr float min_step = 1e-3f;  // px, as line()
  point_scratch_.clear();
  for (const Point& p : points) {
    if (point_scratch_.empty() ||
        std::hypot(p.x - point_scratch_.back().x, p.y - point_scratch_.back().y) >= min_step) {
      point_scratch_.push_back(p);
    }
  }
  while (point_scratch_.size() > 1 &&
         std::hypot(point_scratch_.back().x - point_scratch_[0].x,
                    point_scratch_.back().y - point_scratch_[0].y) < min_step) {
    point_scratch_.pop_back();
  }
  const std::size_t n = point_scratch_.size();
  if (n < 2) return;
  if (n == 2) {  // there and back: one line
    line(point_scratch_[0].x, point_scratch_[0].y, point_scratch_[1].x, point_scratch_[1].y, width,
         c);
    return;
  }
  use(shapes, {});
  const float h = 0.5f * width, pad = h + detail::aa_pad_px, e = pad / h;
  auto unit = [&](std::size_t from, std::size_t to) {
    const float dx = point_scratch_[to].x - point_scratch_[from].x;
    const float dy = point_scratch_[to].y - point_scratch_[from].y;
    const float len = std::sqrt(dx * dx + dy * dy);
    return std::array<float, 2>{dx / len, dy / len};
  };
  const auto first = static_cast<std::uint32_t>(vertices_.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p = point_scratch_[i];
    const auto in = unit((i + n - 1) % n, i), out = unit(i, (i + 1) % n);
    if (in[0] * out[0] + in[1] * out[1] >= 0.0f) {  // mitre: one pair on the bisector
      float mx = in[0] + out[0], my = in[1] + out[1];
      const float ml = std::sqrt(mx * mx + my * my);
      mx /= ml, my /= ml;
      const float scale = pad / (mx * out[0] + my * out[1]);
      strip_pair(p.x, p.y, -my * scale, mx * scale, e, c, i > 0);
    } else {  // too sharp: the incoming segment ends flat, the outgoing one starts flat
      strip_pair(p.x, p.y, -in[1] * pad, in[0] * pad, e, c, i > 0);
      strip_pair(p.x, p.y, -out[1] * pad, out[0] * pad, e, c, false);
    }
  }
  // The last pair to the first.
  const auto last = static_cast<std::uint32_t>(vertices_.size()) - 2;
  for (std::uint32_t i : {last, last + 1, first + 1, last, first + 1, first}) indices_.push_back(i);
}

void Renderer::circle(float cx, float cy, float r, float width, Rgba8 c) {
  if (!(r > 0.0f) || !(width > 0.0f)) return;
  const float outer = r + 0.5f * width, inner = std::max(r - 0.5f * width, 0.0f);
  const float pad = outer + detail::aa_pad_px;
  // Up to this width (px), a quad: the disc of radius `outer` with a hole (the shapes program,
  // gl_shaders.hpp), which shades every pixel of its square; wider, the ring alone, as a strip.
  constexpr float widest_quad = 255.0f;  // as wide as llvmpipe's widest point, where it was one
  if (2.0f * pad <= widest_quad) {
    use(shapes, {});
    const float e = pad / outer;
    quad({{cx - pad, cy - pad}, {cx + pad, cy - pad}, {cx + pad, cy + pad}, {cx - pad, cy + pad}},
         {{-e, -e}, {e, -e}, {e, e}, {-e, e}}, c, inner / outer);
    return;
  }
  // Sides such that the sagitta r (1 - cos(pi / sides)) stays within 0.05 px.
  const double half_angle = std::acos(std::max(-1.0, 1.0 - 0.05 / double(r)));
  const double wanted = half_angle > 0.0 ? std::ceil(std::numbers::pi / half_angle) : 1024.0;
  const int sides = static_cast<int>(std::clamp(wanted, 8.0, 1024.0));
  circle_scratch_.resize(static_cast<std::size_t>(sides));
  for (int k = 0; k < sides; ++k) {
    const double a = 2.0 * std::numbers::pi * k / sides;
    circle_scratch_[static_cast<std::size_t>(k)] = {cx + r * static_cast<float>(std::cos(a)),
                                                    cy + r * static_cast<float>(std::sin(a))};
  }
  closed_polyline(circle_scratch_, width, c);
}

void Renderer::polygon(std::span<const Point> points, Rgba8 c) {
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    triangle(points[0].x, points[0].y, points[i].x, points[i].y, points[i + 1].x, points[i + 1].y,
             c);
  }
}

void Renderer::arrow(float x0, float y0, float x1, float y1, float width, float head, Rgba8 c) {
  const float dx = x1 - x0, dy = y1 - y0, len = std::sqrt(dx * dx + dy * dy);
  if (len < 1e-3f) return;
  const float ux = dx / len, uy = dy / len;
  const float h = std::min(std::max(head, 0.0f), len);
  const float bx = x1 - ux * h, by = y1 - uy * h;  // the head's base, on the shaft
  if (len - h >= 1e-3f) line(x0, y0, bx, by, width, c);
  if (h > 0.0f) {
    const float nx = -uy * 0.5f * h, ny = ux * 0.5f * h;
    triangle(x1, y1, bx + nx, by + ny, bx - nx, by - ny, c);
  }
}

}  // namespace fixstep
