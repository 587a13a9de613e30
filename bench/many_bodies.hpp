// The benchmarks' 1000-body scene (bench_capture, bench_overlay): built in code, deterministic.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <cstdint>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep::bench {

/// 1000 bodies on a 40 x 25 grid filling a 160 m x 90 m view: two in three hang on
/// spring-dampers (k = 5..15 N/m, released 1.5 m from their anchors, so they circle and
/// swing), one in three is a projectile thrown up at 25..33 m/s under gravity with a little
/// drag (they rise through the grid for the whole measured second). Deterministic.
inline Scene many_bodies(int n) {
  Scene s;
  s.file = fmt::format("many_bodies({})", n);
  s.def.settings.dt = 0.01;
  s.def.precision = Precision::f64;
  s.view.center = Vec2{0.0, 0.0};
  s.view.width = 160.0;
  constexpr int cols = 40;
  for (int i = 0; i < n; ++i) {
    BodyDef b;
    b.name = fmt::format("b{}", i);
    const double gx = -78.0 + 4.0 * (i % cols), gy = -40.0 + 3.3 * (i / cols);
    const double hue = double(i) / n;
    b.appearance = Appearance{.radius = 0.6 + 0.1 * ((i * 7) % 5),
                              .color = {static_cast<std::uint8_t>(60 + 190 * hue),
                                        static_cast<std::uint8_t>(120 + 100 * std::sin(7.0 * hue)),
                                        static_cast<std::uint8_t>(240 - 180 * hue), 255}};
    if (i % 3 != 2) {
      b.body = Body{.mass = 1.0,
                    .position = {gx + 1.5 * std::cos(i), gy + 1.5 * std::sin(i)},
                    .velocity = {0.0, 0.0}};
      b.spring =
          SpringDamper{.anchor = {gx, gy}, .stiffness = 5.0 + (i % 11), .damping = 0.05 * (i % 4)};
    } else {
      b.body = Body{
          .mass = 1.0, .position = {gx, -45.0}, .velocity = {2.0 * std::sin(i), 25.0 + (i % 9)}};
      b.gravity = Gravity{};
      b.drag = LinearDrag{.coefficient = 0.02 * (i % 5)};
    }
    s.def.bodies.push_back(b);
  }
  return s;
}

}  // namespace fixstep::bench
