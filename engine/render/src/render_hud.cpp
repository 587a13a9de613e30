// Renderer's HUD: text lines on a translucent panel in a corner of the frame.
#include <fmt/format.h>

#include <stdexcept>
#include <string>

#include "fixstep/render/hud_layout.hpp"
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
  // Wrapped to the frame's width, cut to its height (hud_layout.hpp): no text off the frame.
  const HudLayout hud = layout_hud(lines, hud_text_scale_, hud_corner_, width_, height_);
  if (hud.lines.empty()) return;
  rect(hud.x0, hud.y0, hud.x1, hud.y1, scene_palette::panel);
  for (const HudTextLine& l : hud.lines)
    text(l.x, l.y, l.text, hud.scale, scene_palette::text_color);
}

}  // namespace fixstep
