// Renderer::draw_joints: the joints (RenderFrame::joints) over the bodies, as Box2D's debug draw
// shows them, in a light colour edged in the bodies' outline colour so that they read over any
// body: a ring at a revolute, weld or wheel anchor (a weld's with a dot in it), a short line
// along a prismatic or wheel joint's axis, a distance joint's line between its ends (dashed for
// a rope), a motor joint's line from its target to B; with JointView::limits, a revolute joint's
// arc from its lower to its upper angle with a needle at its angle, and ticks at the lower and
// upper translation along a prismatic or wheel joint's axis (along a distance joint's line: its
// shortest and longest). Sizes are px: marks, not bodies, they keep their size at any zoom.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <utility>
#include <vector>

#include "fixstep/render/render.hpp"
#include "scene_palette.hpp"

namespace fixstep {

namespace {

using scene_palette::joint_color;
using scene_palette::joint_limit_color;
using scene_palette::outline;

constexpr float ring_px = 5.0f;        // a ring's radius
constexpr float mark_width_px = 2.0f;  // a mark's line, edged 1 px either side in `outline`
constexpr float edge_px = 1.0f;
constexpr float axis_half_px = 14.0f;           // half the axis line's length
constexpr float arc_px = 22.0f;                 // the radius of a revolute joint's limit arc
constexpr float tick_half_px = 7.0f;            // half a limit tick's length
constexpr float dash_px = 6.0f, gap_px = 4.0f;  // a rope's dashes
constexpr int max_dashes = 256;                 // a longer rope's dashes are longer, not more

/// A line `width` px wide from p to q over an edge `edge_px` wider on each side and at each end.
void edged_line(Renderer& canvas, Renderer::Point p, Renderer::Point q, float width, Rgba8 c) {
  const float dx = q.x - p.x, dy = q.y - p.y, len = std::hypot(dx, dy);
  if (len < 1e-3f) return;
  const float ux = dx / len * edge_px, uy = dy / len * edge_px;
  canvas.line(p.x - ux, p.y - uy, q.x + ux, q.y + uy, width + 2 * edge_px, outline);
  canvas.line(p.x, p.y, q.x, q.y, width, c);
}

/// A ring of radius r px round p over its edge.
void edged_ring(Renderer& canvas, Renderer::Point p, float r, Rgba8 c) {
  canvas.circle(p.x, p.y, r, mark_width_px + 2 * edge_px, outline);
  canvas.circle(p.x, p.y, r, mark_width_px, c);
}

/// A dot of radius r px at p over its edge.
void edged_dot(Renderer& canvas, Renderer::Point p, float r, Rgba8 c) {
  canvas.disc(p.x, p.y, r + edge_px, outline);
  canvas.disc(p.x, p.y, r, c);
}

/// The point `px` px from p in the direction of world angle `angle` (rad, y up).
Renderer::Point along(Renderer::Point p, double angle, float px) {
  return {p.x + px * float(std::cos(angle)), p.y - px * float(std::sin(angle))};
}

/// A dashed line from p to q (a rope), each dash edged.
void dashed_line(Renderer& canvas, Renderer::Point p, Renderer::Point q, float width, Rgba8 c) {
  const float dx = q.x - p.x, dy = q.y - p.y, len = std::hypot(dx, dy);
  if (len < 1e-3f) return;
  const float period = std::max(dash_px + gap_px, len / max_dashes);
  const float dash = period * dash_px / (dash_px + gap_px);
  for (int pass = 0; pass < 2; ++pass) {  // the edges under every dash first
    for (float t = 0.0f; t < len; t += period) {
      const float e = std::min(t + dash, len);
      const Renderer::Point a{p.x + dx * t / len, p.y + dy * t / len};
      const Renderer::Point b{p.x + dx * e / len, p.y + dy * e / len};
      if (pass == 0) {
        const float ux = dx / len * edge_px, uy = dy / len * edge_px;
        canvas.line(a.x - ux, a.y - uy, b.x + ux, b.y + uy, width + 2 * edge_px, outline);
      } else {
        canvas.line(a.x, a.y, b.x, b.y, width, c);
      }
    }
  }
}

}  // namespace

void Renderer::draw_joints(const RenderFrame& s) {
  if (s.joints.empty() || style_.joints == JointView::off) return;
  using Mark = RenderFrame::JointMark;
  const bool limits = style_.joints == JointView::limits;
  const double scale = width_ / camera_.width;  // px per m
  auto shown = [&](std::uint32_t j) {
    return j == Mark::world || (j < s.x.size() && scene_palette::body_visible(s, j));
  };
  auto px = [&](double x, double y) {
    const auto p = to_pixel(x, y);
    return Point{float(p[0]), float(p[1])};
  };
  // A limit tick across the line from p in unit direction (ux, uy) (px, y down), `t` m along it.
  auto tick = [&](Point p, float ux, float uy, double t) {
    const Point c{p.x + ux * float(t * scale), p.y + uy * float(t * scale)};
    edged_line(*this, {c.x + uy * tick_half_px, c.y - ux * tick_half_px},
               {c.x - uy * tick_half_px, c.y + ux * tick_half_px}, mark_width_px,
               joint_limit_color);
  };
  // The limits along a line from p (px) in unit direction (ux, uy): a rail between them and a
  // tick at each.
  auto travel = [&](const Mark& m, Point p, float ux, float uy) {
    if (!m.has_lower && !m.has_upper) return;
    if (m.has_lower && m.has_upper) {
      const float lo = float(m.lower * scale), hi = float(m.upper * scale);
      edged_line(*this, {p.x + ux * lo, p.y + uy * lo}, {p.x + ux * hi, p.y + uy * hi}, 1.0f,
                 joint_limit_color);
    }
    if (m.has_lower) tick(p, ux, uy, m.lower);
    if (m.has_upper) tick(p, ux, uy, m.upper);
  };
  for (const Mark& m : s.joints) {
    if (m.broken || !shown(m.body_a) || !shown(m.body_b)) continue;
    const Point a = px(m.ax, m.ay), b = px(m.bx, m.by);
    const float ux = m.axis_x, uy = -m.axis_y;  // the axis in px, y down
    switch (m.type) {
      case JointType::revolute:
        if (limits && (m.has_lower || m.has_upper)) draw_hinge_limits(m, b);
        edged_ring(*this, b, ring_px, joint_color);
        break;
      case JointType::weld:
        edged_ring(*this, b, ring_px, joint_color);
        edged_dot(*this, b, 2.0f, joint_color);
        break;
      case JointType::wheel:
      case JointType::prismatic: {
        if (limits) travel(m, a, ux, uy);
        const bool wheel = m.type == JointType::wheel;
        const float half = wheel ? ring_px + axis_half_px * 0.6f : axis_half_px;
        edged_line(*this, {b.x - ux * half, b.y - uy * half}, {b.x + ux * half, b.y + uy * half},
                   mark_width_px, joint_color);
        if (wheel) {
          edged_ring(*this, b, ring_px, joint_color);
        } else {
          edged_dot(*this, b, 3.0f, joint_color);
        }
        break;
      }
      case JointType::distance: {
        const float dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
        if (limits && len > 1e-3f) travel(m, a, dx / len, dy / len);
        if (m.rope) {
          dashed_line(*this, a, b, 1.5f, joint_color);
        } else {
          edged_line(*this, a, b, mark_width_px, joint_color);
        }
        edged_dot(*this, a, 2.5f, joint_color);
        edged_dot(*this, b, 2.5f, joint_color);
        break;
      }
      case JointType::motor:
        edged_line(*this, a, b, 1.0f, joint_color);
        edged_ring(*this, a, 4.0f, joint_color);
        break;
    }
  }
}

void Renderer::draw_hinge_limits(const RenderFrame::JointMark& m, Point b) {
  const double lo = m.has_lower ? m.lower : -std::numbers::pi;
  const double hi = m.has_upper ? m.upper : std::numbers::pi;
  const int sides = std::clamp(int(std::ceil((hi - lo) / (std::numbers::pi / 36))), 1, 72);
  std::vector<PolylinePoint>& arc = polyline_scratch_;
  arc.clear();
  for (int k = 0; k <= sides; ++k) {
    const double t = lo + (hi - lo) * k / sides;
    const Point p = along(b, m.zero_angle + m.sense * t, arc_px);
    arc.push_back({p.x, p.y, outline});
  }
  polyline(arc, 1.5f + 2 * edge_px);
  for (PolylinePoint& p : arc) p.c = joint_limit_color;
  polyline(arc, 1.5f);
  for (const auto& [set, t] : {std::pair{m.has_lower, lo}, std::pair{m.has_upper, hi}}) {
    const double angle = m.zero_angle + m.sense * t;
    if (set)
      edged_line(*this, along(b, angle, ring_px), along(b, angle, arc_px + 4.0f), mark_width_px,
                 joint_limit_color);
  }
  const double now = m.zero_angle + m.sense * m.value;
  edged_line(*this, along(b, now, ring_px), along(b, now, arc_px + 6.0f), mark_width_px,
             joint_color);
}

}  // namespace fixstep
