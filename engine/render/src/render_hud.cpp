// Renderer's HUD: text lines on a translucent panel in a corner of the frame.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fixstep/render/render.hpp"
#include "scene_palette.hpp"

namespace fixstep {

// Sizes in font pixels times the scale.
namespace {
constexpr float hud_margin = 10.0f;  // px from the frame's corner, at any scale
constexpr float hud_pad = 4.0f;      // font px round the text
constexpr float hud_line_h = 11.0f;  // font px between lines
}  // namespace

void Renderer::set_hud_text_scale(float scale) {
  if (!(scale >= min_hud_text_scale && scale <= max_hud_text_scale))
    throw std::invalid_argument(fmt::format("HUD text scale must be in [{:g}, {:g}], got {}",
                                            min_hud_text_scale, max_hud_text_scale, scale));
  hud_text_scale_ = scale;
}

float Renderer::hud_height(std::size_t lines, float scale) {
  return hud_margin + (hud_pad + 1.0f + hud_line_h * float(lines)) * scale;
}

float Renderer::hud_width(const std::string& line, float scale) {
  return hud_margin + text_width(line, scale) + 2.0f * hud_pad * scale;
}

void Renderer::draw_hud(std::span<const std::string> lines) {
  if (lines.empty()) return;
  const float scale = hud_text_scale_;
  float widest = 0;
  for (const std::string& l : lines) widest = std::max(widest, text_width(l, scale));
  // The panel, hud_margin px from its corner's two edges (hud_height and hud_width include one
  // margin).
  const float w = widest + 2.0f * hud_pad * scale;
  const float h = hud_height(lines.size(), scale) - hud_margin;
  const bool right = hud_corner_ == HudCorner::top_right || hud_corner_ == HudCorner::bottom_right;
  const bool bottom =
      hud_corner_ == HudCorner::bottom_left || hud_corner_ == HudCorner::bottom_right;
  // A panel wider (taller) than the frame keeps its left (top) edge in view.
  const float x0 = right ? std::max(hud_margin, float(width_) - hud_margin - w) : hud_margin;
  const float y0 = bottom ? std::max(hud_margin, float(height_) - hud_margin - h) : hud_margin;
  rect(x0, y0, x0 + w, y0 + h, scene_palette::panel);
  float y = y0 + hud_pad * scale;
  for (const std::string& l : lines) {
    text(x0 + hud_pad * scale, y, l, scale, scene_palette::text_color);
    y += hud_line_h * scale;
  }
}

}  // namespace fixstep
