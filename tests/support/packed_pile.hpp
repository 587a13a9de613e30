// The pile of bench/discs_scene.cpp for tests: discs of radius r and 1 kg under gravity, packed
// hexagonally `rows` deep wall to wall in a box (the ground y = 0 and walls at x = 0 and at the
// width of `wide` discs), a millionth of a diameter apart, plastic (e = 0) with friction μ.
// Even rows hold `wide` discs, odd rows one fewer in the pockets between them.
#pragma once

#include <cmath>
#include <utility>

#include "fixstep/core/components.hpp"
#include "world_kernel.hpp"

namespace fixstep::test {

template <class Real>
void add_packed_pile(detail::WorldKernel<Real>& w, int rows, int wide, double r, double mu) {
  const double spacing = 2.0 * r * (1.0 + 1e-6), rise = std::sqrt(3.0) / 2.0 * spacing;
  const double width = wide * spacing;
  for (const auto& [n, offset] : {std::pair{Vec2{0.0, 1.0}, 0.0}, std::pair{Vec2{1.0, 0.0}, 0.0},
                                  std::pair{Vec2{-1.0, 0.0}, -width}}) {
    w.add_plane(PlaneDef{.normal = n, .offset = offset, .restitution = 0.0, .friction = mu});
  }
  for (int row = 0; row < rows; ++row) {
    const bool odd = row % 2 == 1;
    for (int i = 0; i < (odd ? wide - 1 : wide); ++i) {
      BodyDef b;
      b.body = Body{
          .mass = 1.0,
          .position = {(odd ? spacing : spacing / 2.0) + i * spacing, spacing / 2.0 + row * rise}};
      b.gravity = Gravity{{0.0, -9.81}};
      b.collider = Collider{.radius = r};
      w.create_body(b);
    }
  }
}

}  // namespace fixstep::test
