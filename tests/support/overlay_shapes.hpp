// The overlay bench_overlay times and test_soft_shapes draws both ways: a game's 1000 shapes
// over a 1280x720 frame of a 160 m wide view.
#pragma once

#include <cmath>
#include <cstdint>

#include "fixstep/render/draw_list.hpp"

namespace fixstep::testing {

inline constexpr int overlay_shapes = 1000;

/// 1000 shapes of a game's size spread over the view (160 m wide: 8 px per m): 300 lines and
/// 100 polylines of 2 px, 200 discs of 6 px, 150 circles of 12 px, 100 hexagons of 10 px, 100
/// arrows of 60 px, 50 labels; a fifth in screen coordinates. Moves with `t` (s).
inline void record_overlay(DrawList& list, double t) {
  list.clear();
  for (int i = 0; i < overlay_shapes; ++i) {
    const double x = -75.0 + 150.0 * ((i * 37) % 100) / 100.0 + 2.0 * std::sin(t + i);
    const double y = -40.0 + 80.0 * ((i * 61) % 97) / 97.0;
    const Vec2 p{x, y};
    const Rgba8 c{static_cast<std::uint8_t>(80 + (i * 13) % 170),
                  static_cast<std::uint8_t>(80 + (i * 29) % 170), 230, 200};
    const Space space = i % 5 == 0 ? Space::screen : Space::world;
    const Vec2 at = space == Space::world ? p : Vec2{640.0 + x * 8.0, 360.0 - y * 8.0};
    const double u = space == Space::world ? 1.0 : 8.0;  // px per unit
    const int kind = i % 20;
    if (kind < 6) {
      list.line(at, {at.x + 6.0 * u, at.y + 3.0 * u}, 0.25 * u, c, space);
    } else if (kind < 8) {
      const Vec2 zig[4] = {
          at, {at.x + 2 * u, at.y + u}, {at.x + 4 * u, at.y}, {at.x + 6 * u, at.y + u}};
      list.polyline(zig, 0.25 * u, c, space);
    } else if (kind < 12) {
      list.disc(at, 0.75 * u, c, space);
    } else if (kind < 15) {
      list.circle(at, 1.5 * u, 0.25 * u, c, space);
    } else if (kind < 17) {
      Vec2 hexagon[6];
      for (int k = 0; k < 6; ++k) {
        hexagon[k] = {at.x + 1.25 * u * std::cos(k * 1.0471975512),
                      at.y + 1.25 * u * std::sin(k * 1.0471975512)};
      }
      list.polygon(hexagon, c, space);
    } else if (kind < 19) {
      list.arrow(at, {at.x + 7.5 * u, at.y}, 0.25 * u, 1.5 * u, c, space);
    } else {
      list.label(at, "score 12", 2.0, c, space);
    }
  }
}

}  // namespace fixstep::testing
