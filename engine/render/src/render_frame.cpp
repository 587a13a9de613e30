// Renderer::draw_scene: a RenderFrame as the scene view — grid, axes and scale bar, planes,
// segments, trails, links, springs, bodies' shapes and discs, joints, in that order — drawn with
// the canvas primitives of render.cpp (trails in render_trails.cpp, shapes in
// render_body_shapes.cpp, joints in render_joints.cpp, the HUD in render_hud.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/render/render.hpp"
#include "occlusion.hpp"
#include "scene_palette.hpp"

namespace fixstep {

namespace {

/// Draws each plane n·x >= offset as a line across the view, its solid side n·x < offset
/// lightly shaded: the view rectangle (world coordinates) is cut by the plane (one step of
/// Sutherland–Hodgman polygon clipping) and the solid part drawn as a triangle fan.
void draw_planes(Renderer& canvas, std::span<const PlaneDef> planes) {
  const Camera& cam = canvas.camera();
  const double hw = 0.5 * cam.width, hh = hw * canvas.height() / canvas.width();
  const double cx = cam.center.x, cy = cam.center.y;
  const Vec2 view[4] = {
      {cx - hw, cy - hh}, {cx + hw, cy - hh}, {cx + hw, cy + hh}, {cx - hw, cy + hh}};
  for (const PlaneDef& p : planes) {
    auto depth = [&](Vec2 v) { return p.offset - (p.normal.x * v.x + p.normal.y * v.y); };
    Vec2 solid[5], edge[2];
    int count = 0, edges = 0;
    for (int i = 0; i < 4; ++i) {
      const Vec2 a = view[i], b = view[(i + 1) % 4];
      const double da = depth(a), db = depth(b);
      if (da >= 0.0) solid[count++] = a;
      if ((da >= 0.0) != (db >= 0.0)) {
        const double t = da / (da - db);
        const Vec2 cut{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
        solid[count++] = cut;
        if (edges < 2) edge[edges++] = cut;
      }
    }
    auto px = [&](Vec2 v) {
      const auto q = canvas.to_pixel(v.x, v.y);
      return std::array<float, 2>{float(q[0]), float(q[1])};
    };
    for (int i = 1; i + 1 < count; ++i) {
      const auto a = px(solid[0]), b = px(solid[i]), c = px(solid[i + 1]);
      canvas.triangle(a[0], a[1], b[0], b[1], c[0], c[1], scene_palette::plane_solid);
    }
    if (edges == 2) {
      const auto a = px(edge[0]), b = px(edge[1]);
      canvas.line(a[0], a[1], b[0], b[1], 2.5f, scene_palette::plane_line);
    }
  }
}

/// Draws each segment as a line of its colour (SegmentDef::color; alpha 0: the planes'), 2.5 px
/// wide, or with a width (SegmentDef::width, m) as a capsule of that width (round ends, so a
/// polyline's segments join without gaps) (above the backdrop: a level's segments are few
/// beside its bodies).
void draw_segments(Renderer& canvas, std::span<const SegmentDef> segments,
                   std::vector<Renderer::Point>& scratch) {
  const double scale = canvas.width() / canvas.camera().width;  // px per m
  for (const SegmentDef& s : segments) {
    const auto a = canvas.to_pixel(s.a.x, s.a.y), b = canvas.to_pixel(s.b.x, s.b.y);
    const Rgba8 c = s.color.a != 0 ? s.color : scene_palette::plane_line;
    const float width = s.width > 0.0 && std::isfinite(s.width)
                            ? static_cast<float>(std::min(s.width * scale, 1e7))
                            : 2.5f;
    if (s.width > 0.0 && width >= 2.0f) {  // a capsule (rounded_polygon smooths from 1 px)
      scratch.assign({{float(a[0]), float(a[1])}, {float(b[0]), float(b[1])}});
      canvas.rounded_polygon(scratch, 0.5f * width, c);
      continue;
    }
    canvas.line(float(a[0]), float(a[1]), float(b[0]), float(b[1]), width, c);
  }
}

/// What the steps of the scene view after the backdrop share: the canvas, the frame, its scale
/// and the canvas's polyline scratch (Renderer::polyline_scratch_, no allocation once warm).
struct SceneView {
  Renderer& canvas;
  const RenderFrame& s;
  double scale;  ///< px per m
  std::vector<Renderer::PolylinePoint>& scratch;
  /// Per body, 1 when it is drawn as its shapes, not as a disc (empty: none is).
  std::span<const std::uint8_t> shaped;

  [[nodiscard]] bool shown(std::size_t j) const { return scene_palette::body_visible(s, j); }
  [[nodiscard]] bool has_shapes(std::size_t j) const { return !shaped.empty() && shaped[j]; }
  [[nodiscard]] float radius_px(std::size_t j) const {
    return scene_palette::body_radius_px(s, j, scale);
  }
  /// px of a line `width` px wide ending at body j's centre that its disc hides (none for a
  /// body drawn as its shapes, which need not cover its centre).
  [[nodiscard]] float under_body(std::size_t j, float width) const {
    if (has_shapes(j)) return 0.0f;
    return detail::hidden_under_disc(radius_px(j) + scene_palette::outline_px, width);
  }
};

/// A spring: a zigzag of 12 coils from (ax, ay) to (bx, by), with straight leads (a straight
/// line when shorter than 24 px); the first cut_start px and the last cut_end px are hidden by
/// what is drawn over them later.
void draw_zigzag(SceneView& view, float ax, float ay, float bx, float by, float cut_start,
                 float cut_end) {
  const Rgba8 spring_color = scene_palette::spring_color;
  const float dx = bx - ax, dy = by - ay, len = std::sqrt(dx * dx + dy * dy);
  if (len < 24.0f) {
    if (cut_start + cut_end + 0.01f >= len) return;  // wholly hidden
    const float ux = len > 0.0f ? dx / len : 0.0f, uy = len > 0.0f ? dy / len : 0.0f;
    view.canvas.line(ax + ux * cut_start, ay + uy * cut_start, bx - ux * cut_end, by - uy * cut_end,
                     2.0f, spring_color);
    return;
  }
  // One polyline: anchor, start of the coils, 2 * coils corners, the body.
  constexpr int coils = 12;
  const float nx = -dy / len * 7.0f, ny = dx / len * 7.0f;
  std::vector<Renderer::PolylinePoint>& points = view.scratch;
  points.clear();
  points.push_back({ax, ay, spring_color});
  points.push_back({ax + dx * 0.1f, ay + dy * 0.1f, spring_color});
  for (int k = 1; k <= 2 * coils; ++k) {
    const float f = 0.1f + 0.8f * float(k) / (2 * coils);
    const float side = k == 2 * coils ? 0.0f : (k % 2 ? 1.0f : -1.0f);
    points.push_back({ax + dx * f + nx * side, ay + dy * f + ny * side, spring_color});
  }
  points.push_back({bx, by, spring_color});
  detail::shorten(points, cut_start, cut_end);
  view.canvas.polyline(points, 2.0f);
}

/// Links (springs between bodies): zigzags like the anchored springs when there are few,
/// thin straight lines when there are many (a cloth's zigzags would merge into felt).
void draw_links(SceneView& view, bool few_links) {
  const RenderFrame& s = view.s;
  for (std::size_t i = 0; i < s.link_a.size(); ++i) {
    const std::uint32_t la = s.link_a[i], lb = s.link_b[i];
    if (!view.shown(la) || !view.shown(lb)) continue;
    const auto a = view.canvas.to_pixel(s.x[la], s.y[la]);
    const auto b = view.canvas.to_pixel(s.x[lb], s.y[lb]);
    if (few_links) {
      draw_zigzag(view, float(a[0]), float(a[1]), float(b[0]), float(b[1]),
                  view.under_body(la, 2.0f), view.under_body(lb, 2.0f));
    } else {
      view.canvas.line(float(a[0]), float(a[1]), float(b[0]), float(b[1]), 1.25f,
                       scene_palette::link_color);
    }
  }
}

/// Anchored springs, each with its anchor (a square drawn right over its start).
void draw_springs(SceneView& view) {
  const RenderFrame& s = view.s;
  for (const RenderFrame::SpringLine& sp : s.springs) {
    if (!view.shown(sp.body)) continue;
    const auto a = view.canvas.to_pixel(sp.anchor_x, sp.anchor_y);
    const auto b = view.canvas.to_pixel(s.x[sp.body], s.y[sp.body]);
    const float ax = float(a[0]), ay = float(a[1]), bx = float(b[0]), by = float(b[1]);
    // The anchor hides the start of the spring's lead, which points at the coils' start: the
    // body, but for the coils' sideways offset on long springs (first lead: along (b - a)).
    const float len = std::hypot(bx - ax, by - ay);
    const float ux = len > 0.0f ? (bx - ax) / len : 0.0f, uy = len > 0.0f ? (by - ay) / len : 0.0f;
    const float half = scene_palette::anchor_half_px;
    draw_zigzag(view, ax, ay, bx, by, detail::hidden_under_square(half, 2.0f, ux, uy),
                view.under_body(sp.body, 2.0f));
    view.canvas.rect(ax - half, ay - half, ax + half, ay + half, scene_palette::anchor_color);
  }
}

/// The visible bodies without shapes: outlined discs.
void draw_bodies(SceneView& view) {
  const RenderFrame& s = view.s;
  for (std::size_t j = 0; j < s.x.size(); ++j) {
    if (!view.shown(j) || view.has_shapes(j)) continue;
    const auto p = view.canvas.to_pixel(s.x[j], s.y[j]);
    view.canvas.disc(float(p[0]), float(p[1]), view.radius_px(j), scene_palette::body_color(s, j),
                     scene_palette::outline_px, scene_palette::outline);
  }
}

}  // namespace

void Renderer::grid() {
  // Grid spacing: the power of ten that gives 4..40 lines across the view.
  const double step = std::pow(10.0, std::floor(std::log10(camera_.width / 4.0)));
  const double half_w = camera_.width * 0.5, half_h = half_w * height_ / width_;
  // Lines from `first` every `step` up to `last`: at most max_grid_lines (40 across the width,
  // 40·height/width across the height: 20 481 in the tallest frame), and none where `step`
  // is below the resolution of the coordinates (a centre 10^300 m out and 1 m wide: first +
  // step == first) or the camera is not finite. Each line is 4 vertices: no camera, however
  // far or narrow, makes a frame allocate without bound (set_camera takes any). The axes
  // (x = 0, y = 0) are the grid lines through the origin, drawn brighter, with or without the
  // others.
  auto lines = [&](double first, double last, auto draw_line) {
    if (!(first + step > first)) return;
    int n = 0;
    for (double g = first; g <= last && n < max_grid_lines; g += step, ++n) {
      const bool axis = std::abs(g) < step * 1e-6;
      if (axis ? style_.axes : style_.grid) draw_line(g, axis);
    }
  };
  if (style_.grid || style_.axes) {
    auto look = [](bool axis) {
      return axis ? scene_palette::grid_axis : scene_palette::grid_minor;
    };
    lines(std::ceil((camera_.center.x - half_w) / step) * step, camera_.center.x + half_w,
          [&](double gx, bool axis) {
            const float px = static_cast<float>(to_pixel(gx, 0)[0]);
            line(px, 0, px, float(height_), axis ? 2.0f : 1.0f, look(axis));
          });
    lines(std::ceil((camera_.center.y - half_h) / step) * step, camera_.center.y + half_h,
          [&](double gy, bool axis) {
            const float py = static_cast<float>(to_pixel(0, gy)[1]);
            line(0, py, float(width_), py, axis ? 2.0f : 1.0f, look(axis));
          });
  }
  if (style_.scale_bar) scale_bar(step);
}

void Renderer::scale_bar(double step) {
  // 1, 2, 5 or 10 grid steps, the first at least 40 px long, in the bottom corner the HUD does
  // not take.
  const double scale = width_ / camera_.width;
  double length = step;
  for (const double m : {2.0, 5.0, 10.0})
    if (length * scale < 40.0) length = step * m;
  const float bar = static_cast<float>(length * scale);
  const std::string label = fmt::format("{:g} m", length);
  const float label_w = text_width(label, 2.0f);
  const bool left = hud_corner_ == HudCorner::bottom_right;
  const float x0 = left ? 20.0f : width_ - 20.0f - bar, x1 = x0 + bar, y = height_ - 20.0f;
  const Rgba8 c = scene_palette::text_color;
  line(x0, y, x1, y, 3.0f, c);
  line(x0, y - 5, x0, y + 5, 2.0f, c);
  line(x1, y - 5, x1, y + 5, 2.0f, c);
  // Aligned with the bar's outer end: never off the frame.
  text(left ? x0 : x1 - label_w, y - 24, label, 2.0f, c);
}

bool Renderer::reuse_backdrop(std::span<const PlaneDef> planes) {
  auto same = [](const PlaneDef& a, const PlaneDef& b) {
    return a.normal.x == b.normal.x && a.normal.y == b.normal.y && a.offset == b.offset;
  };
  if (!backdrop_recorded_ || !(backdrop_style_ == style_) || backdrop_hud_corner_ != hud_corner_ ||
      backdrop_camera_.center.x != camera_.center.x ||
      backdrop_camera_.center.y != camera_.center.y || backdrop_camera_.width != camera_.width ||
      !std::equal(planes.begin(), planes.end(), backdrop_planes_.begin(), backdrop_planes_.end(),
                  same)) {
    return false;
  }
  backdrop_ = Backdrop::reuse;
  return true;
}

void Renderer::record_backdrop(std::span<const PlaneDef> planes) {
  batches_.push_back(Batch{indices_.size(), batches_.back().clip, batches_.back().program,
                           batches_.back().ring,
                           batches_.back().texture});  // the backdrop ends on a batch boundary
  backdrop_batches_ = batches_.size() - 1;
  backdrop_ = Backdrop::record;
  backdrop_recorded_ = true;
  backdrop_style_ = style_;
  backdrop_hud_corner_ = hud_corner_;
  backdrop_camera_ = camera_;
  backdrop_planes_.assign(planes.begin(), planes.end());
}

void Renderer::sample_trails(const World& world) {
  if (world.link_count() > max_zigzag_links) return;  // no trails drawn
  trails_.sample(world);
}

void Renderer::draw(const RenderFrame& s, std::span<const std::string> hud_lines) {
  draw_scene(s);
  draw_hud(hud_lines);
  finish();
}

void Renderer::draw_scene(const RenderFrame& s) {
  // A scene with many links (a cloth, a soft body) draws no trails: hundreds of them would
  // hide the structure the links draw.
  const bool few_links = s.link_a.size() <= max_zigzag_links;
  if (few_links) trails_.prepare(s);  // may throw: before begin() changes anything
  Rgba8 background = style_.background;
  background.a = 255;
  begin(background);
  // The grid and the planes change only with the camera (or the planes): drawn once into the
  // backdrop, which every later frame starts from (a copy of 3.6 MB at 1280x720 instead of
  // clearing the frame and drawing the grid's long lines again).
  if (!reuse_backdrop(s.planes)) {
    background_tiles();
    grid();
    draw_planes(*this, s.planes);
    record_backdrop(s.planes);
  }
  draw_segments(*this, s.segments, shape_scratch_);
  const double scale = width_ / camera_.width;
  if (few_links) draw_trails(s, scale);
  // Bodies with shapes: drawn as them (before the discs), not as discs.
  shaped_bodies_.assign(s.shapes.empty() ? 0 : s.x.size(), 0);
  for (const RenderFrame::Shape& shape : s.shapes) {
    if (shape.body < shaped_bodies_.size()) shaped_bodies_[shape.body] = 1;
  }
  if (!s.sprites.empty()) {  // drawn as their images: 2
    shaped_bodies_.resize(s.x.size(), 0);
    for (const RenderFrame::Sprite& sp : s.sprites) {
      if (sp.body < shaped_bodies_.size()) shaped_bodies_[sp.body] = 2;
    }
  }
  SceneView view{*this, s, scale, polyline_scratch_, shaped_bodies_};
  draw_links(view, few_links);
  draw_springs(view);
  draw_body_shapes(s);
  if (!s.sprites.empty()) draw_sprites(s);
  draw_bodies(view);
  if (s.spin_marks && s.angle.size() == s.x.size()) draw_spin_marks(s);
  if (!s.joints.empty()) draw_joints(s);
  // What follows (a game's overlay, the HUD) starts a batch of its own (finish()).
  batches_.push_back(Batch{indices_.size(), batches_.back().clip, batches_.back().program,
                           batches_.back().ring, batches_.back().texture});
  overlay_batch_ = batches_.size() - 1;
  overlay_vertex_ = vertices_.size();
}

void Renderer::draw_spin_marks(const RenderFrame& s) {
  // Rolling discs: a line from the centre to the rim at the disc's angle, so that the spin
  // shows (after every disc: one batch of lines, not a change of program per disc).
  const double scale = width_ / camera_.width;
  for (std::size_t j = 0; j < s.x.size(); ++j) {
    if (!scene_palette::body_visible(s, j)) continue;
    if (!shaped_bodies_.empty() && shaped_bodies_[j]) continue;  // its shapes show its turn
    const float r = scene_palette::body_radius_px(s, j, scale);
    if (r < 3.0f) continue;  // too small for a mark to show
    const auto p = to_pixel(s.x[j], s.y[j]);
    const float cx = float(p[0]), cy = float(p[1]);
    const float ex = cx + r * std::cos(s.angle[j]), ey = cy - r * std::sin(s.angle[j]);  // y down
    line(cx, cy, ex, ey, std::max(1.5f, 0.12f * r), scene_palette::outline);
  }
}

}  // namespace fixstep
