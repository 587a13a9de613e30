// Images in the scene view and on the canvas: Renderer::image (a game's overlay images), the
// bodies' sprites (RenderFrame::sprites) and the tiled background (ViewStyle::background_image),
// all drawn by the images program (gl_shaders.hpp: one texel per pixel, by index).
#include <cmath>
#include <cstddef>

#include "fixstep/render/render.hpp"
#include "scene_palette.hpp"

namespace fixstep {

void Renderer::image_quad(std::size_t index, const float (&p)[4][2], const float (&uv)[4][2],
                          Rgba8 tint, bool repeat) {
  use(images_program, {}, static_cast<std::uint32_t>(index));
  quad(p, uv, tint, repeat ? 1.0f : no_hole);
}

void Renderer::image(const std::string& path, std::span<const Point, 4> corners, Rgba8 tint) {
  const std::size_t index = images_.index(path);  // may throw: nothing recorded yet
  const float p[4][2] = {{corners[0].x, corners[0].y},
                         {corners[1].x, corners[1].y},
                         {corners[2].x, corners[2].y},
                         {corners[3].x, corners[3].y}};
  image_quad(index, p, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, tint, false);
}

void Renderer::draw_sprites(const RenderFrame& s) {
  const bool turned = s.angle.size() == s.x.size();
  for (const RenderFrame::Sprite& sp : s.sprites) {
    const std::size_t j = sp.body;
    if (j >= s.x.size() || !scene_palette::body_visible(s, j)) continue;
    if (!(sp.width > 0.0f && sp.height > 0.0f)) continue;
    // The rectangle's corners in the body frame (top-left first, y up), turned by the body's
    // angle, moved to where the body is drawn, through the camera.
    const double angle = turned ? double(s.angle[j]) : 0.0;
    const double c = std::cos(angle), si = std::sin(angle);
    const double hw = 0.5 * sp.width, hh = 0.5 * sp.height;
    const double local[4][2] = {{sp.cx - hw, sp.cy + hh},
                                {sp.cx + hw, sp.cy + hh},
                                {sp.cx + hw, sp.cy - hh},
                                {sp.cx - hw, sp.cy - hh}};
    Point corners[4];
    for (int k = 0; k < 4; ++k) {
      const double lx = local[k][0], ly = local[k][1];
      const auto q = to_pixel(s.x[j] + c * lx - si * ly, s.y[j] + si * lx + c * ly);
      corners[k] = {float(q[0]), float(q[1])};
    }
    image(sp.path, corners);
  }
}

void Renderer::background_tiles() {
  const double tile = style_.background_tile;
  if (style_.background_image.empty() || !(tile > 0.0) || !std::isfinite(tile)) return;
  const std::size_t index = images_.index(style_.background_image);
  // The view's top-left corner in tiles from the tile corner at or left of and above it (small
  // numbers however far out the camera is: floats keep the texel to the pixel).
  const double hw = 0.5 * camera_.width, hh = hw * height_ / width_;
  const double left = camera_.center.x - hw, top = camera_.center.y + hh;
  const double u0 = left / tile - std::floor(left / tile);
  const double v0 = std::ceil(top / tile) - top / tile;
  const auto u1 = static_cast<float>(u0 + 2.0 * hw / tile);
  const auto v1 = static_cast<float>(v0 + 2.0 * hh / tile);
  const auto w = float(width_), h = float(height_), fu0 = float(u0), fv0 = float(v0);
  image_quad(index, {{0, 0}, {w, 0}, {w, h}, {0, h}}, {{fu0, fv0}, {u1, fv0}, {u1, v1}, {fu0, v1}},
             {255, 255, 255, 255}, true);
}

}  // namespace fixstep
