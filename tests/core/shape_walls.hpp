// Worlds of boxes on a floor for the shape phase's thread and push-out tests
// (test_shape_threads.cpp, test_shape_push_out.cpp): a kernel on a plane y = 0, and walls of
// 1 m boxes pressed into one another.
#pragma once

#include <cmath>
#include <memory>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world_settings.hpp"
#include "shape_exact.hpp"
#include "world_kernel.hpp"

namespace fixstep::shape_walls {

/// A kernel of shape_exact::shape_settings(0.6) on `threads` threads with a floor: the plane
/// y = 0, μ = 0.6.
inline std::unique_ptr<detail::WorldKernel<double>> floor_world(int threads) {
  WorldSettings settings = shape_exact::shape_settings(0.6);
  settings.threads = threads;
  auto w = std::make_unique<detail::WorldKernel<double>>(settings);
  w->add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  return w;
}

/// A wall of 60 columns of 36 boxes of 1 m on the floor: the lower `pressed` rows each box 1 cm
/// into the one below and 5 mm into its neighbours on each side (4000 and more manifold points
/// when all are, past the push-out's split), the rows above standing on them, touching their
/// neighbours without overlap.
inline std::unique_ptr<detail::WorldKernel<double>> box_wall(int threads, int pressed) {
  auto w = floor_world(threads);
  // The highest pressed row's centre to the centimetre (17.32 m for 18 rows).
  const double top = std::round(100.0 * (0.49 + 0.99 * (pressed - 1))) / 100.0;
  for (int c = 0; c < 60; ++c) {
    for (int r = 0; r < 36; ++r) {
      const Vec2 at = r < pressed ? Vec2{0.995 * c, 0.49 + 0.99 * r}
                                  : Vec2{1.0 * c, top + 1.0 * (r - pressed + 1)};
      w->create_body(shape_exact::box_body(0.5, 0.5, at, 0.0));
    }
  }
  return w;
}

}  // namespace fixstep::shape_walls
