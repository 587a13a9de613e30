// Renderer::draw: a RenderFrame as the scene view — grid and scale bar, trails, links, springs,
// bodies and the HUD — drawn with the canvas primitives of render.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/render.hpp"

namespace fixstep {

namespace {

// The scene view's colours and sizes.
constexpr Rgba8 background{18, 21, 28, 255};
constexpr Rgba8 grid_minor{32, 37, 48, 255};
constexpr Rgba8 grid_axis{62, 70, 90, 255};
constexpr Rgba8 spring_color{170, 180, 200, 255};
constexpr Rgba8 link_color{170, 180, 200, 200};
constexpr Rgba8 anchor_color{120, 130, 150, 255};
constexpr Rgba8 outline{8, 10, 14, 255};
constexpr Rgba8 text_color{235, 238, 245, 255};
constexpr Rgba8 panel{0, 0, 0, 150};
constexpr Rgba8 palette[] = {{230, 87, 46, 255},   {76, 175, 240, 255},  {250, 200, 60, 255},
                             {120, 210, 110, 255}, {200, 120, 230, 255}, {240, 140, 170, 255},
                             {90, 220, 200, 255},  {240, 240, 240, 255}};
constexpr Rgba8 plane_solid{120, 132, 160, 60};
constexpr Rgba8 plane_line{150, 162, 190, 255};
constexpr float default_radius_px = 9.0f;
constexpr float min_radius_px = 3.0f;
constexpr float outline_px = 1.5f;      // bodies' outline, beyond their radius
constexpr float anchor_half_px = 5.0f;  // anchors are squares of twice this side

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
      canvas.triangle(a[0], a[1], b[0], b[1], c[0], c[1], plane_solid);
    }
    if (edges == 2) {
      const auto a = px(edge[0]), b = px(edge[1]);
      canvas.line(a[0], a[1], b[0], b[1], 2.5f, plane_line);
    }
  }
}

/// Body j's colour: its Appearance's, or a palette colour without one (alpha 0).
Rgba8 body_color(const RenderFrame& s, std::size_t j) {
  return s.color[j].a == 0 ? palette[j % std::size(palette)] : s.color[j];
}

/// Bodies are outlined discs of the body's radius (at least min_radius_px; `scale` px per m),
/// drawn last: what the other shapes draw right below a disc's centre or an anchor is hidden
/// (Renderer::hidden_under_disc), and they stop short there.
float body_radius_px(const RenderFrame& s, std::size_t j, double scale) {
  return s.radius[j] > 0.0f ? std::max(float(s.radius[j] * scale), min_radius_px)
                            : default_radius_px;
}

}  // namespace

void Renderer::grid() {
  // Grid spacing: the power of ten that gives 4..40 lines across the view.
  const double step = std::pow(10.0, std::floor(std::log10(camera_.width / 4.0)));
  const double half_w = camera_.width * 0.5, half_h = half_w * height_ / width_;
  const double scale = width_ / camera_.width;
  // Lines from `first` every `step` up to `last`: at most max_grid_lines (40 across the width,
  // 40·height/width across the height: 20 481 in the tallest frame), and none where `step`
  // is below the resolution of the coordinates (a centre 10^300 m out and 1 m wide: first +
  // step == first) or the camera is not finite. Each line is 4 vertices: no camera, however
  // far or narrow, makes a frame allocate without bound (set_camera takes any).
  auto lines = [&](double first, double last, auto draw_line) {
    if (!(first + step > first)) return;
    int n = 0;
    for (double g = first; g <= last && n < max_grid_lines; g += step, ++n) draw_line(g);
  };
  lines(std::ceil((camera_.center.x - half_w) / step) * step, camera_.center.x + half_w,
        [&](double gx) {
          const float px = static_cast<float>(to_pixel(gx, 0)[0]);
          const bool axis = std::abs(gx) < step * 1e-6;
          line(px, 0, px, float(height_), axis ? 2.0f : 1.0f, axis ? grid_axis : grid_minor);
        });
  lines(std::ceil((camera_.center.y - half_h) / step) * step, camera_.center.y + half_h,
        [&](double gy) {
          const float py = static_cast<float>(to_pixel(0, gy)[1]);
          const bool axis = std::abs(gy) < step * 1e-6;
          line(0, py, float(width_), py, axis ? 2.0f : 1.0f, axis ? grid_axis : grid_minor);
        });
  // Scale bar, bottom right: 1, 2, 5 or 10 grid steps, the first at least 40 px long.
  double length = step;
  for (const double m : {2.0, 5.0, 10.0})
    if (length * scale < 40.0) length = step * m;
  const float bar = static_cast<float>(length * scale);
  const float x1 = width_ - 20.0f, x0 = x1 - bar, y = height_ - 20.0f;
  line(x0, y, x1, y, 3.0f, text_color);
  line(x0, y - 5, x0, y + 5, 2.0f, text_color);
  line(x1, y - 5, x1, y + 5, 2.0f, text_color);
  const std::string label = fmt::format("{:g} m", length);
  const float label_w = text_width(label, 2.0f);
  text(x1 - label_w, y - 24, label, 2.0f, text_color);  // right-aligned: never off the frame
}

namespace {

// Trail samples may be left up to this far from the drawn polyline, px (see draw()).
constexpr float trail_tolerance_px = 0.2f;

// Four floats in one SSE register (GCC and clang vector extensions): each operation below acts on
// the four lanes exactly as the scalar one would on each.
using float4 = float __attribute__((vector_size(16)));

// Is any of the four points (xs[0..3], ys[0..3]) farther than sqrt(tol2) px from the segment from
// (ax, ay) to (ax + ux, ay + uy)? inv_len2 is 1 / (ux² + uy²), or 0 for a zero-length segment.
bool any_beyond(const float* xs, const float* ys, float ax, float ay, float ux, float uy,
                float inv_len2, float tol2) {
  float4 x, y;
  std::memcpy(&x, xs, sizeof x);
  std::memcpy(&y, ys, sizeof y);
  const float4 wx = x - ax, wy = y - ay;
  float4 t = (wx * ux + wy * uy) * inv_len2;
  t = t < 0.0f ? 0.0f : t;  // std::clamp(t, 0, 1), lane by lane
  t = 1.0f < t ? 1.0f : t;
  const float4 dx = wx - t * ux, dy = wy - t * uy;
  const auto beyond = dx * dx + dy * dy > tol2;  // lanes of all ones where true
  return (beyond[0] | beyond[1] | beyond[2] | beyond[3]) != 0;
}

// Chooses which of the n points (xs[i], ys[i]) a polyline keeps, greedily: from each kept point,
// the next one kept is the farthest along that leaves every point in between within `tolerance`
// px of the segment joining the two, and at most max_run points on. The first and last points
// are always kept. Writes the kept indices, in order, to `kept` (room for n) and returns their
// number. O(n * max_run) distance computations, on coordinate arrays (the trails' own layout),
// four at a time.
int simplify_polyline(const float* xs, const float* ys, int n, float tolerance, int* kept) {
  if (n < 3) {
    for (int i = 0; i < n; ++i) kept[i] = i;
    return n;
  }
  const float tol2 = tolerance * tolerance;
  constexpr int max_run = 12;
  // Is every point strictly between `from` and `to` within tolerance of the segment joining
  // them?
  auto fits = [&](int from, int to) {
    const float ax = xs[from], ay = ys[from];
    const float ux = xs[to] - ax, uy = ys[to] - ay, len2 = ux * ux + uy * uy;
    const float inv_len2 = len2 > 0.0f ? 1.0f / len2 : 0.0f;
    int i = from + 1;
    for (; i + 4 <= to; i += 4) {
      if (any_beyond(xs + i, ys + i, ax, ay, ux, uy, inv_len2, tol2)) return false;
    }
    for (; i < to; ++i) {
      const float wx = xs[i] - ax, wy = ys[i] - ay;
      const float t = std::clamp((wx * ux + wy * uy) * inv_len2, 0.0f, 1.0f);
      const float dx = wx - t * ux, dy = wy - t * uy;
      if (dx * dx + dy * dy > tol2) return false;
    }
    return true;
  };
  int count = 0, anchor = 0;
  kept[count++] = 0;
  while (anchor + 1 < n) {
    int end = anchor + 1;
    while (end + 1 < n && end - anchor < max_run && fits(anchor, end + 1)) ++end;
    kept[count++] = end;
    anchor = end;
  }
  return count;
}

}  // namespace

void Renderer::draw_trails(const RenderFrame& s, double scale) {
  // Trails: one polyline per body through its samples, fading from transparent (oldest) to
  // 60 % opaque (newest): sample k of count (0 = oldest) has alpha 150 (k + 0.5) / count, so
  // each segment has on average the alpha it had when every segment was a line() of alpha
  // 150 k / count. Samples are then dropped where the polyline can skip them without leaving
  // any of them more than trail_tolerance_px away (simplify_polyline): a trail of 44 sub-pixel
  // segments becomes a few segments of a few pixels, and a projectile's gentle parabola a few
  // long ones. Samples are kept in m and drawn through this frame's camera, so a moving camera
  // (Session::follow) shows where the body went, not where it was on the screen.
  for (std::size_t j = 0; j < trails_.size(); ++j) {
    std::array<float, trail_frames> xs, ys;  // oldest first
    const int count = trails_.samples(j, xs, ys);
    if (count < 2) continue;
    for (int k = 0; k < count; ++k) {
      const auto p = to_pixel(xs[k], ys[k]);
      xs[k] = static_cast<float>(p[0]);
      ys[k] = static_cast<float>(p[1]);
    }
    std::array<int, trail_frames> kept;
    const int simplified =
        simplify_polyline(xs.data(), ys.data(), count, trail_tolerance_px, kept.data());
    const Rgba8 c = body_color(s, j);
    polyline_scratch_.clear();
    for (int i = 0; i < simplified; ++i) {
      const int k = kept[i];
      Rgba8 ck = c;
      ck.a = static_cast<std::uint8_t>((300 * k + 150) / (2 * count));
      polyline_scratch_.push_back({xs[k], ys[k], ck});
    }
    // Its newest end is the body's centre, under the body's disc.
    shorten(polyline_scratch_, 0.0f,
            hidden_under_disc(body_radius_px(s, j, scale) + outline_px, 2.0f));
    polyline(polyline_scratch_, 2.0f);
  }
}

bool Renderer::reuse_backdrop(std::span<const PlaneDef> planes) {
  auto same = [](const PlaneDef& a, const PlaneDef& b) {
    return a.normal.x == b.normal.x && a.normal.y == b.normal.y && a.offset == b.offset;
  };
  if (!backdrop_recorded_ || !(backdrop_background_ == background_) ||
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
                           batches_.back().ring});  // the backdrop ends on a batch boundary
  backdrop_batches_ = batches_.size() - 1;
  backdrop_ = Backdrop::record;
  backdrop_recorded_ = true;
  backdrop_background_ = background_;
  backdrop_camera_ = camera_;
  backdrop_planes_.assign(planes.begin(), planes.end());
}

void Renderer::draw(const RenderFrame& s, std::span<const std::string> hud_lines) {
  begin(background);
  trails_.record(s);
  // The grid and the planes change only with the camera (or the planes): drawn once into the
  // backdrop, which every later frame starts from (a copy of 3.6 MB at 1280x720 instead of
  // clearing the frame and drawing the grid's long lines again).
  if (!reuse_backdrop(s.planes)) {
    grid();
    draw_planes(*this, s.planes);
    record_backdrop(s.planes);
  }

  const std::size_t n = s.x.size();
  const double scale = width_ / camera_.width;
  auto color_of = [&](std::size_t j) { return body_color(s, j); };
  auto radius_px = [&](std::size_t j) { return body_radius_px(s, j, scale); };
  auto under_body = [&](std::size_t j, float width) {
    return hidden_under_disc(radius_px(j) + outline_px, width);
  };

  // A scene with many links (a cloth, a soft body) draws no trails: hundreds of them would
  // hide the structure the links draw.
  const bool few_links = s.link_a.size() <= max_zigzag_links;
  if (few_links) draw_trails(s, scale);

  // Springs: a zigzag of 12 coils from (ax, ay) to (bx, by), with straight leads; the first
  // cut_start px and the last cut_end px are hidden by what is drawn over them later.
  auto zigzag = [&](float ax, float ay, float bx, float by, float cut_start, float cut_end) {
    const float dx = bx - ax, dy = by - ay, len = std::sqrt(dx * dx + dy * dy);
    if (len < 24.0f) {
      if (cut_start + cut_end + 0.01f >= len) return;  // wholly hidden
      const float ux = len > 0.0f ? dx / len : 0.0f, uy = len > 0.0f ? dy / len : 0.0f;
      line(ax + ux * cut_start, ay + uy * cut_start, bx - ux * cut_end, by - uy * cut_end, 2.0f,
           spring_color);
      return;
    }
    // One polyline: anchor, start of the coils, 2 * coils corners, the body.
    constexpr int coils = 12;
    const float nx = -dy / len * 7.0f, ny = dx / len * 7.0f;
    polyline_scratch_.clear();
    polyline_scratch_.push_back({ax, ay, spring_color});
    polyline_scratch_.push_back({ax + dx * 0.1f, ay + dy * 0.1f, spring_color});
    for (int k = 1; k <= 2 * coils; ++k) {
      const float f = 0.1f + 0.8f * float(k) / (2 * coils);
      const float side = k == 2 * coils ? 0.0f : (k % 2 ? 1.0f : -1.0f);
      polyline_scratch_.push_back({ax + dx * f + nx * side, ay + dy * f + ny * side, spring_color});
    }
    polyline_scratch_.push_back({bx, by, spring_color});
    shorten(polyline_scratch_, cut_start, cut_end);
    polyline(polyline_scratch_, 2.0f);
  };

  // Links (springs between bodies): zigzags like the anchored springs when there are few,
  // thin straight lines when there are many (a cloth's zigzags would merge into felt).
  for (std::size_t i = 0; i < s.link_a.size(); ++i) {
    const std::uint32_t la = s.link_a[i], lb = s.link_b[i];
    const auto a = to_pixel(s.x[la], s.y[la]);
    const auto b = to_pixel(s.x[lb], s.y[lb]);
    if (few_links) {
      zigzag(float(a[0]), float(a[1]), float(b[0]), float(b[1]), under_body(la, 2.0f),
             under_body(lb, 2.0f));
    } else {
      line(float(a[0]), float(a[1]), float(b[0]), float(b[1]), 1.25f, link_color);
    }
  }

  // Anchored springs, each with its anchor (a square drawn right over its start).
  for (const RenderFrame::SpringLine& sp : s.springs) {
    const auto a = to_pixel(sp.anchor_x, sp.anchor_y);
    const auto b = to_pixel(s.x[sp.body], s.y[sp.body]);
    const float ax = float(a[0]), ay = float(a[1]), bx = float(b[0]), by = float(b[1]);
    // The anchor hides the start of the spring's lead, which points at the coils' start: the
    // body, but for the coils' sideways offset on long springs (first lead: along (b - a)).
    const float len = std::hypot(bx - ax, by - ay);
    const float ux = len > 0.0f ? (bx - ax) / len : 0.0f, uy = len > 0.0f ? (by - ay) / len : 0.0f;
    zigzag(ax, ay, bx, by, hidden_under_square(anchor_half_px, 2.0f, ux, uy),
           under_body(sp.body, 2.0f));
    rect(ax - anchor_half_px, ay - anchor_half_px, ax + anchor_half_px, ay + anchor_half_px,
         anchor_color);
  }

  for (std::size_t j = 0; j < n; ++j) {
    const auto p = to_pixel(s.x[j], s.y[j]);
    disc(float(p[0]), float(p[1]), radius_px(j), color_of(j), outline_px, outline);
  }

  if (!hud_lines.empty()) hud(hud_lines);
  finish();
}

// The HUD: text lines on a translucent panel, top left; sizes in font pixels times the scale.
namespace {
constexpr float hud_margin = 10.0f;  // px from the frame's corner, at any scale
constexpr float hud_pad = 4.0f;      // font px round the text
constexpr float hud_line_h = 11.0f;  // font px between lines
}  // namespace

void Renderer::set_hud_text_scale(float scale) {
  if (!(scale >= 1.0f && scale <= 4.0f))
    throw std::invalid_argument(fmt::format("HUD text scale must be in [1, 4], got {}", scale));
  hud_text_scale_ = scale;
}

float Renderer::hud_height(std::size_t lines, float scale) {
  return hud_margin + (hud_pad + 1.0f + hud_line_h * float(lines)) * scale;
}

float Renderer::hud_width(const std::string& line, float scale) {
  return hud_margin + text_width(line, scale) + 2.0f * hud_pad * scale;
}

void Renderer::hud(std::span<const std::string> lines) {
  const float scale = hud_text_scale_;
  float widest = 0;
  for (const std::string& l : lines) widest = std::max(widest, text_width(l, scale));
  rect(hud_margin, hud_margin, hud_margin + widest + 2.0f * hud_pad * scale,
       hud_height(lines.size(), scale), panel);
  float y = hud_margin + hud_pad * scale;
  for (const std::string& l : lines) {
    text(hud_margin + hud_pad * scale, y, l, scale, text_color);
    y += hud_line_h * scale;
  }
}

}  // namespace fixstep
