// The shape contacts' velocity sweeps with conjugate steps (sweep_conjugate.hpp): a stack
// settles and its sweeps end, where plain projected Gauss–Seidel sweeps run every iteration and
// leave it deeper in overlap; the bits are those of the plain solver's paths (lanes or not, one
// thread or two: tests/core/test_shape_lanes.cpp and test_shape_threads.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "plain_sweeps.hpp"
#include "shape_exact.hpp"

namespace fixstep {
namespace {

constexpr int tower_boxes = 20;

/// A tower of 1 m boxes (1 kg), each 1 cm above the one below, on the ground (μ = 0.6).
WorldDef tower() {
  WorldDef def = WorldDef::empty(Precision::f64, shape_exact::shape_settings(0.6));
  def.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  for (int k = 0; k < tower_boxes; ++k) {
    def.add_body(shape_exact::box_body(0.5, 0.5, {0.0, 0.51 + 1.01 * k}));
  }
  return def;
}

struct Settled {
  int most_sweeps = 0;      ///< over the last 60 ticks
  double deepest = 0.0;     ///< m, over the last 60 ticks
  double lowest_top = 0.0;  ///< m, the top box's centre at the end
  double drift = 0.0;       ///< m, the largest |x| of a box at the end
};

Settled settle(int ticks) {
  World w(tower());
  Settled out;
  for (int t = 1; t <= ticks; ++t) {
    w.step();
    if (t > ticks - 60) {
      out.most_sweeps = std::max(out.most_sweeps, w.contact_stats().shape_velocity_sweeps);
      out.deepest = std::max(out.deepest, w.contact_stats().deepest_shape_overlap);
    }
  }
  out.lowest_top = w.body(w.bodies().back()).position.y;
  for (const Entity e : w.bodies()) out.drift = std::max(out.drift, std::abs(w.body(e).position.x));
  return out;
}

TEST(ShapeConjugate, ATowerComesToRestAndItsSweepsEnd) {
  // Resting, each box's centre would be 0.5 m above the last one's less its contact's overlap,
  // which the push-out keeps within the 5 mm slop: the top one's at 19.5 m less at most 20
  // overlaps. With conjugate steps the tower's sweeps converge (no row's velocity changed by
  // more than 1e-9 m/s) at its first sweep of a tick by tick 240, every overlap is within
  // 2.5 mm (the top within 20 of them: 19.45 m), and the tower stands straight. Plain sweeps
  // (measured: 20 a tick, 5 mm, the top at 19.466 m, a box 8.5 mm aside) never converge: the
  // slow mode of a stack shrinks by a fraction of a percent a sweep.
  const Settled fast = settle(300);
  EXPECT_LE(fast.most_sweeps, 2);
  EXPECT_LE(fast.deepest, 0.0025);
  EXPECT_GT(fast.lowest_top, 19.5 - 20 * 0.0025);
  EXPECT_LT(fast.lowest_top, 19.5);
  EXPECT_LT(fast.drift, 1e-6);
  const test::PlainSweeps guard;
  const Settled plain = settle(300);
  EXPECT_EQ(plain.most_sweeps, ContactSettings::default_velocity_iterations);
  EXPECT_GT(plain.deepest, fast.deepest);
}

}  // namespace
}  // namespace fixstep
