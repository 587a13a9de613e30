// Renderer::draw_body_shapes: the shapes bodies carry (RenderFrame::shapes) in the scene view,
// each a rounded polygon (Renderer::rounded_polygon) in its body's colour over an outline as
// wide as the discs', with a line that shows its turn, as rolling discs show theirs.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "fixstep/render/render.hpp"
#include "scene_palette.hpp"

namespace fixstep {

void Renderer::draw_body_shapes(const RenderFrame& s) {
  const double scale = width_ / camera_.width;  // px per m
  const bool turned = s.angle.size() == s.x.size();
  for (const RenderFrame::Shape& shape : s.shapes) {
    const std::size_t j = shape.body;
    if (j >= s.x.size() || shape.count < 1 || shape.count > max_polygon_vertices) continue;
    if (!scene_palette::body_visible(s, j)) continue;
    if (j < shaped_bodies_.size() && shaped_bodies_[j] == 2) continue;  // drawn as its sprite
    // Body-local (relative to the centre of mass) to pixels: turned by the body's angle, moved
    // to its centre, through the camera.
    const double angle = turned ? double(s.angle[j]) : 0.0;
    const double cos_a = std::cos(angle), sin_a = std::sin(angle);
    auto to_px = [&](float lx, float ly) {
      const auto p = to_pixel(s.x[j] + cos_a * lx - sin_a * ly, s.y[j] + sin_a * lx + cos_a * ly);
      return Point{float(p[0]), float(p[1])};
    };
    shape_scratch_.clear();
    Point centre{0.0f, 0.0f};
    for (std::size_t k = 0; k < shape.count; ++k) {
      shape_scratch_.push_back(to_px(shape.px[k], shape.py[k]));
      centre.x += shape_scratch_.back().x / float(shape.count);
      centre.y += shape_scratch_.back().y / float(shape.count);
    }
    const float radius = std::max(float(shape.radius * scale), 0.0f);
    rounded_polygon(shape_scratch_, radius + scene_palette::outline_px, scene_palette::outline);
    rounded_polygon(shape_scratch_, radius, scene_palette::body_color(s, j, shape.color));
    // The mark: from the shape's centre to `mark`, as wide as a rolling disc's of its length
    // (at most 4 px); none on a shape too small for it to show.
    const Point mark = to_px(shape.mark_x, shape.mark_y);
    const float length = std::hypot(mark.x - centre.x, mark.y - centre.y);
    if (length < 3.0f) continue;
    line(centre.x, centre.y, mark.x, mark.y, std::clamp(0.12f * length, 1.5f, 4.0f),
         scene_palette::outline);
  }
}

}  // namespace fixstep
