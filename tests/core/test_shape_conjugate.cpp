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
#include "fixstep/core/world_settings.hpp"
#include "plain_sweeps.hpp"
#include "shape_exact.hpp"
#include "shape_lanes.hpp"
#include "shape_walls.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

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
  // more than 1e-5 m/s) within two sweeps a tick by tick 240, every overlap is within
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

/// A pyramid of 1 m boxes (1 kg) `rows` high, each row one box shorter, each box touching
/// the one below, on the ground (μ = 0.6).
WorldDef pyramid(int rows) {
  WorldDef def = WorldDef::empty(Precision::f64, shape_exact::shape_settings(0.6));
  def.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  for (int r = 0; r < rows; ++r) {
    for (int k = 0; k < rows - r; ++k) {
      def.add_body(shape_exact::box_body(0.5, 0.5, {k + 0.5 * r, 0.5 + r}));
    }
  }
  return def;
}

TEST(ShapeConjugate, APyramidEndsItsSweepsWhileItSettles) {
  // The sweeps end once none changes a row's velocity by more than 1e-5 m/s
  // (ShapeWorld::velocity_sweep_tolerance). A 20-row pyramid (210 boxes) put down at rest a
  // second ago still settles: at 1e-9 m/s every one of the 20 sweeps ran in each of ticks 61–80
  // (measured), at 1e-5 m/s a few (the stack's sweeps end from tick 55 on, where 1e-9 waited
  // until about tick 110), while every overlap stays as shallow (the deepest 0.69 mm either
  // way) and nothing slides.
  World w(pyramid(20));
  int sweeps = 0;
  double deepest = 0.0;
  for (int t = 1; t <= 80; ++t) {
    w.step();
    if (t > 60) {
      sweeps += w.contact_stats().shape_velocity_sweeps;
      deepest = std::max(deepest, w.contact_stats().deepest_shape_overlap);
    }
  }
  EXPECT_LE(sweeps, 20 * 10);
  EXPECT_LE(deepest, 0.001);
  double fastest = 0.0;
  for (const Entity e : w.bodies()) {
    const Body b = w.body(e);
    fastest = std::max(fastest, std::hypot(b.velocity.x, b.velocity.y));
  }
  EXPECT_LT(fastest, 0.01);
}

/// 120 columns of 10 boxes standing a little apart on a plane, and a static box beside them
/// (1201 shapes: a large world, whose sweeps split their colours on two threads and whose
/// velocities are stepped by the live list, the static body not in it).
std::unique_ptr<detail::WorldKernel<double>> columns_and_shelf(int threads) {
  auto w = shape_walls::floor_world(threads);
  BodyDef shelf = shape_exact::box_body(2.0, 0.5, {-5.0, 0.5});
  shelf.type = BodyType::static_body;
  w->create_body(shelf);
  for (int c = 0; c < 120; ++c) {
    for (int r = 0; r < 10; ++r) {
      w->create_body(shape_exact::box_body(0.5, 0.5, {1.05 * c, 0.51 + 1.01 * r}));
    }
  }
  return w;
}

// The conjugate steps' bits on two threads (the passes by halves) and without the lanes (every
// manifold a unit) are one thread's with the lanes, in a world whose live bodies are not every
// body; and they run: the columns settle and their sweeps end before the count.
TEST(ShapeConjugate, TwoThreadsAndNoLanesStepTheSameBits) {
  auto one = columns_and_shelf(1);
  auto two = columns_and_shelf(2);
  auto alone = columns_and_shelf(1);
  int fewest = ContactSettings::default_velocity_iterations;
  for (int t = 0; t < 120; ++t) {
    one->step();
    two->step();
    detail::shape_lanes::set_lanes_enabled(false);
    alone->step();
    detail::shape_lanes::set_lanes_enabled(true);
    ASSERT_EQ(one->state_hash(), two->state_hash()) << "two threads, after tick " << t + 1;
    ASSERT_EQ(one->state_hash(), alone->state_hash()) << "no lanes, after tick " << t + 1;
    fewest = std::min(fewest, one->contact_stats().shape_velocity_sweeps);
  }
  EXPECT_LT(one->shape_world()->live().size(), one->shape_world()->shapes_.size());
  EXPECT_GT(two->shape_world()->split_colors(), 0u);
  EXPECT_LT(fewest, ContactSettings::default_velocity_iterations);
}

}  // namespace
}  // namespace fixstep
