// DrawList::draw (draw_list.hpp): each shape through the camera into canvas primitives, culled
// and clipped in double so that no far-away coordinate reaches GL as a huge float.
#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "fixstep/render/draw_list.hpp"
#include "fixstep/render/render.hpp"

namespace fixstep {

namespace {

/// px beyond the frame's edges within which coordinates are passed to the canvas as they are;
/// lines reaching farther are clipped to it (a float keeps 1/16 px at this distance).
constexpr double reach_px = 4096.0;
/// Widest circle or disc drawn, px.
constexpr double max_round_px = 1e6;

/// The frame grown by reach_px on every side, px.
struct Box {
  double x0, y0, x1, y1;
  [[nodiscard]] bool holds(Vec2 p) const {
    return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1;
  }
};

/// Cuts the segment a-b to `box` (Liang–Barsky); false when none of it is inside.
bool clip(Vec2& a, Vec2& b, const Box& box) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x - box.x0, box.x1 - a.x, a.y - box.y0, box.y1 - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
    if (t0 > t1) return false;
  }
  const Vec2 start{a.x + t0 * dx, a.y + t0 * dy}, end{a.x + t1 * dx, a.y + t1 * dy};
  a = start;
  b = end;
  return true;
}

/// Clips the convex polygon `in` to `box` (Sutherland–Hodgman, one edge at a time) into `out`.
void clip_polygon(const std::vector<Vec2>& in, const Box& box, std::vector<Vec2>& out,
                  std::vector<Vec2>& scratch) {
  out = in;
  for (int edge = 0; edge < 4; ++edge) {
    auto inside = [&](Vec2 p) {
      switch (edge) {
        case 0:
          return p.x >= box.x0;
        case 1:
          return p.x <= box.x1;
        case 2:
          return p.y >= box.y0;
        default:
          return p.y <= box.y1;
      }
    };
    auto cut = [&](Vec2 a, Vec2 b) {
      const double t = edge < 2 ? ((edge == 0 ? box.x0 : box.x1) - a.x) / (b.x - a.x)
                                : ((edge == 2 ? box.y0 : box.y1) - a.y) / (b.y - a.y);
      return Vec2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
    };
    scratch.clear();
    for (std::size_t i = 0; i < out.size(); ++i) {
      const Vec2 a = out[i], b = out[(i + 1) % out.size()];
      if (inside(a)) scratch.push_back(a);
      if (inside(a) != inside(b)) scratch.push_back(cut(a, b));
    }
    out.swap(scratch);
    if (out.empty()) return;
  }
}

/// Scratch of the shapes being drawn, kept between frames (no allocation once warm).
struct Scratch {
  std::vector<Vec2> px, clipped, spare;
  std::vector<Renderer::PolylinePoint> strip;
  std::vector<Renderer::Point> points;
  std::string text;
};

/// A shape's `points` in px (double) into `px`: through the canvas's camera when they are in
/// world space, as they are in screen space.
void to_px(const Renderer& canvas, std::span<const Vec2> points, bool world,
           std::vector<Vec2>& px) {
  px.clear();
  for (const Vec2 p : points) {
    if (world) {
      const std::array<double, 2> q = canvas.to_pixel(p.x, p.y);
      px.push_back({q[0], q[1]});
    } else {
      px.push_back(p);
    }
  }
}

/// A line from a to b, `width` px wide, cut to `box`; an arrow (head `head` px) keeps its head
/// only while its tip is in reach: beyond it, the shaft is all that shows.
void draw_line(Renderer& canvas, const Box& box, Vec2 a, Vec2 b, bool arrow, float width,
               float head, Rgba8 c) {
  const Vec2 tip = b;
  if (!clip(a, b, box)) return;
  if (arrow && b.x == tip.x && b.y == tip.y) {
    canvas.arrow(float(a.x), float(a.y), float(b.x), float(b.y), width, head, c);
  } else {
    canvas.line(float(a.x), float(a.y), float(b.x), float(b.y), width, c);
  }
}

/// A polyline through px, `width` px wide: one strip when every point is in `box`, else segment
/// by segment, each cut to it.
void draw_polyline(Renderer& canvas, const Box& box, const std::vector<Vec2>& px, float width,
                   Rgba8 c, std::vector<Renderer::PolylinePoint>& strip) {
  if (std::all_of(px.begin(), px.end(), [&](Vec2 p) { return box.holds(p); })) {
    strip.clear();
    for (const Vec2 p : px) strip.push_back({float(p.x), float(p.y), c});
    canvas.polyline(strip, width);
    return;
  }
  for (std::size_t i = 0; i + 1 < px.size(); ++i) {
    Vec2 a = px[i], b = px[i + 1];
    if (clip(a, b, box)) canvas.line(float(a.x), float(a.y), float(b.x), float(b.y), width, c);
  }
}

/// A disc of radius r px at o, or a circle (`circle`) of radius r and line width `ring` px;
/// none when it reaches no pixel of the frame or is wider than max_round_px.
void draw_round(Renderer& canvas, Vec2 o, double r, double ring, bool circle, Rgba8 c) {
  const double reach = r + (circle ? ring : 0.0);
  if (2.0 * reach > max_round_px || o.x + reach < 0.0 || o.y + reach < 0.0 ||
      o.x - reach > canvas.width() || o.y - reach > canvas.height()) {
    return;
  }
  if (!circle) {
    if (r > 0.0) canvas.disc(float(o.x), float(o.y), float(r), c);
  } else {
    canvas.circle(float(o.x), float(o.y), float(r), float(ring), c);
  }
}

/// The rectangle with corners a and b, cut to `box`.
void draw_rect(Renderer& canvas, const Box& box, Vec2 a, Vec2 b, Rgba8 c) {
  const double x0 = std::clamp(std::min(a.x, b.x), box.x0, box.x1);
  const double x1 = std::clamp(std::max(a.x, b.x), box.x0, box.x1);
  const double y0 = std::clamp(std::min(a.y, b.y), box.y0, box.y1);
  const double y1 = std::clamp(std::max(a.y, b.y), box.y0, box.y1);
  if (x1 > x0 && y1 > y0) canvas.rect(float(x0), float(y0), float(x1), float(y1), c);
}

/// The convex polygon px, cut to `box`.
void draw_polygon(Renderer& canvas, const Box& box, const std::vector<Vec2>& px, Rgba8 c,
                  Scratch& scratch) {
  const bool inside = std::all_of(px.begin(), px.end(), [&](Vec2 p) { return box.holds(p); });
  if (!inside) clip_polygon(px, box, scratch.clipped, scratch.spare);
  const std::vector<Vec2>& shown = inside ? px : scratch.clipped;
  scratch.points.clear();
  for (const Vec2 p : shown) scratch.points.push_back({float(p.x), float(p.y)});
  canvas.polygon(scratch.points, c);
}

/// An image over the quad px (its corners, top-left first), when it reaches the frame and is
/// at most max_round_px across.
void draw_image(Renderer& canvas, const std::vector<Vec2>& px, const std::string& path, Rgba8 c) {
  double x0 = px[0].x, x1 = px[0].x, y0 = px[0].y, y1 = px[0].y;
  for (const Vec2 p : px) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  if (x1 < 0.0 || y1 < 0.0 || x0 > canvas.width() || y0 > canvas.height()) return;
  if (!(x1 - x0 <= max_round_px && y1 - y0 <= max_round_px) || x1 - x0 + (y1 - y0) <= 0.0) return;
  const Renderer::Point corners[4] = {{float(px[0].x), float(px[0].y)},
                                      {float(px[1].x), float(px[1].y)},
                                      {float(px[2].x), float(px[2].y)},
                                      {float(px[3].x), float(px[3].y)}};
  canvas.image(path, corners, c);
}

}  // namespace

void DrawList::draw(Renderer& canvas) const {
  thread_local Scratch scratch;
  const Camera& cam = canvas.camera();
  const double scale = canvas.width() / cam.width;  // px per m
  const Box box{-reach_px, -reach_px, canvas.width() + reach_px, canvas.height() + reach_px};
  for (const Shape& s : shapes_) {
    const bool world = s.space == Space::world;
    const double unit = world ? scale : 1.0;  // px per size unit
    to_px(canvas, points_of(s), world, scratch.px);
    const std::vector<Vec2>& px = scratch.px;
    const auto c = s.color;
    switch (s.kind) {
      case Kind::line:
      case Kind::arrow:
        draw_line(canvas, box, px[0], px[1], s.kind == Kind::arrow, float(s.width * unit),
                  float(s.size * unit), c);
        break;
      case Kind::polyline:
        draw_polyline(canvas, box, px, float(s.width * unit), c, scratch.strip);
        break;
      case Kind::circle:
      case Kind::disc:
        draw_round(canvas, px[0], s.width * unit, s.size * unit, s.kind == Kind::circle, c);
        break;
      case Kind::rect:
        draw_rect(canvas, box, px[0], px[1], c);
        break;
      case Kind::polygon:
        draw_polygon(canvas, box, px, c, scratch);
        break;
      case Kind::label:
        if (!box.holds(px[0])) break;  // text reaches at most a few thousand px
        scratch.text.assign(text_, s.text_first, s.text_count);
        canvas.text(float(px[0].x), float(px[0].y), scratch.text, float(s.width), c);
        break;
      case Kind::image:
        scratch.text.assign(text_, s.text_first, s.text_count);
        draw_image(canvas, px, scratch.text, c);
        break;
    }
  }
}

}  // namespace fixstep
