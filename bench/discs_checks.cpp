// bench_discs' physical checks of every engine, run before anything is timed (and alone with
// --verify-only): a dropped disc falls as gravity says and comes to rest on the ground, so a
// peer with a mis-set unit, gravity or radius cannot pass silently.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "discs.hpp"

namespace discs {

using fixstep::Vec2;

namespace {

/// One disc of the small radius dropped from rest at (0.5, 1) m onto the ground of a 1 m wide
/// box, with the pile's gravity, restitution and friction.
Scene drop_scene() {
  Scene s{.kind = SceneKind::pile,
          .radius = small_radius,
          .position = {{0.5, 1.0}},
          .velocity = {{0.0, 0.0}},
          .width = 1.0,
          .height = 2.0,
          .gravity = pile_gravity,
          .restitution = pile_restitution,
          .friction = pile_friction};
  return s;
}

}  // namespace

std::vector<std::string> check_drop(const std::string& key) {
  std::vector<std::string> failed;
  const Scene s = drop_scene();
  const auto p = make_stepper(key, s);
  std::vector<Vec2> x, v;
  // Free fall for 0.3 s (the disc meets the ground after 0.44 s): the drop and the speed
  // within 10 % of ½ g t² and g t. Fixed-step integrators differ from them by O(dt / t):
  // semi-implicit Euler by (n + 1) / n = 6 %, Box2D v3's 4 substeps by 1.4 %.
  constexpr int fall_ticks = 18;
  for (int t = 0; t < fall_ticks; ++t) p->step();
  p->state(x, v);
  const double time = fall_ticks * tick;
  const double drop = 0.5 * s.gravity * time * time, speed = s.gravity * time;
  const double fell = s.position[0].y - x[0].y;
  if (!(std::abs(fell - drop) <= 0.1 * drop && std::abs(-v[0].y - speed) <= 0.1 * speed)) {
    failed.push_back(fmt::format(
        "{}: a disc dropped from rest fell {:.4g} m at {:.4g} m/s in {:.3g} s; gravity {} m/s² "
        "gives {:.4g} m at {:.4g} m/s (10 % allowed)",
        key, fell, -v[0].y, time, s.gravity, drop, speed));
  }
  // At rest on the ground after 3 s: its centre within 20 % of r above the ground at r
  // (the peers rest at their slop, 0.1 r here), still, and not moved sideways.
  constexpr int rest_ticks = 180;
  for (int t = fall_ticks; t < rest_ticks; ++t) p->step();
  p->state(x, v);
  const double r = s.radius;
  if (!(std::abs(x[0].y - r) <= 0.2 * r && std::hypot(v[0].x, v[0].y) <= 1e-3 &&
        std::abs(x[0].x - s.position[0].x) <= 1e-4)) {
    failed.push_back(fmt::format(
        "{}: a dropped disc of r = {} m after {:.3g} s is at ({:.6g}, {:.6g}) m moving at ({:.3g}, "
        "{:.3g}) m/s; at rest on the ground it is at ({}, {}) ± (1e-4, {:.3g}) m, below 1e-3 m/s",
        key, r, rest_ticks * tick, x[0].x, x[0].y, v[0].x, v[0].y, s.position[0].x, r, 0.2 * r));
  }
  return failed;
}

}  // namespace discs
