// Reading a rendered frame's pixels back in the render tests (test_camera, test_trail_frames).
#pragma once

#include <cstddef>
#include <cstdlib>

#include "fixstep/render/render.hpp"

namespace fixstep::testing {

/// One pixel's colour channels, 0..255.
struct Rgb {
  int r, g, b;
};

/// Whether each of p's channels is within `tol` (0..255) of c's (alpha not compared).
inline bool near(Rgb p, Rgba8 c, int tol) {
  return std::abs(p.r - c.r) <= tol && std::abs(p.g - c.g) <= tol && std::abs(p.b - c.b) <= tol;
}

/// Pure red, the colour the render tests give the bodies they look for.
inline constexpr Rgba8 red{255, 0, 0, 255};

/// The pixel at column x, row y (from the top) of the renderer's RGBA8 frame.
inline Rgb at(const Renderer& r, int x, int y) {
  const auto p = r.pixels().subspan((static_cast<std::size_t>(y) * r.width() + x) * 4, 4);
  return {p[0], p[1], p[2]};
}

}  // namespace fixstep::testing
