// The overlay test card: one of every DrawList shape, in world and screen coordinates, opaque and
// translucent, with a view style that switches the grid off, keeps the axes, takes a background
// of its own and puts the HUD bottom right. The page draws it over its scene with overlay=card
// (page_options.hpp), and the native golden frame test draws the same card
// (tests/render/test_golden_overlay.cpp), so the browser checks compare WebGL2's pixels of every
// shape with OSMesa's. Platform-neutral, header-only.
#pragma once

#include <array>
#include <cmath>

#include "fixstep/app/session.hpp"
#include "fixstep/render/draw_list.hpp"

namespace fixstep::web {

/// The card's view: background, no grid, the axes, a scale bar, the HUD bottom right in small
/// text.
inline void overlay_card_style(SessionSettings& s) {
  s.style = ViewStyle{.background = Rgba8{24, 30, 44, 255}, .grid = false};
  s.hud_corner = HudCorner::bottom_right;
  s.hud_text_scale = 1.0f;
}

/// Records the card into `list` (cleared first). `around` (m) is the world point the world
/// shapes are drawn about, `size` (m) their scale.
inline void overlay_card(DrawList& list, Vec2 around, double size) {
  list.clear();
  const Rgba8 orange{255, 150, 40, 255}, cyan{60, 220, 230, 200}, white{250, 250, 250, 255},
      magenta{230, 60, 200, 140}, green{90, 230, 110, 255};
  const double s = size;
  auto at = [&](double x, double y) { return Vec2{around.x + x * s, around.y + y * s}; };
  list.line(at(-1.0, -0.8), at(1.0, 0.8), 0.04 * s, orange);
  const std::array<Vec2, 5> zigzag{at(-1.0, 0.9), at(-0.5, 0.6), at(0.0, 0.9), at(0.5, 0.6),
                                   at(1.0, 0.9)};
  list.polyline(zigzag, 0.05 * s, cyan);
  list.circle(at(0.0, 0.0), 0.5 * s, 0.03 * s, white);
  list.disc(at(0.6, -0.5), 0.2 * s, magenta);
  list.rect(at(-0.9, -0.9), at(-0.5, -0.6), green);
  std::array<Vec2, 6> hexagon{};
  for (std::size_t k = 0; k < hexagon.size(); ++k) {
    const double a = double(k) * 3.141592653589793 / 3.0;
    hexagon[k] = at(-0.6 + 0.25 * std::cos(a), 0.25 * std::sin(a));
  }
  list.polygon(hexagon, Rgba8{120, 140, 255, 180});
  list.arrow(at(0.2, 0.2), at(0.9, 0.2), 0.03 * s, 0.15 * s, white);
  list.label(at(-0.4, -0.2), "world label", 2.0, white);
  // Screen: a translucent bar across the top, a framed box, an arrow and text.
  list.rect({0, 0}, {640, 28}, Rgba8{0, 0, 0, 120}, Space::screen);
  list.label({8, 8}, "overlay card: screen text", 2.0, orange, Space::screen);
  list.circle({600, 60}, 20, 3, cyan, Space::screen);
  list.arrow({520, 60}, {570, 60}, 3, 12, green, Space::screen);
}

}  // namespace fixstep::web
