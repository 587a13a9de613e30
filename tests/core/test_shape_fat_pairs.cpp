// The shapes' pairs from fat boxes (shape_fat_pairs.cpp): while every live shape's box lies in
// its fat box, the tick's pairs are the fat pairs whose boxes overlap, without the grid (or, in
// a world of fewer than min_grid_shapes shapes, the sort and sweep). A world that keeps its fat
// boxes from tick to tick must step to the same bits as one that makes them again every tick (a
// copy holds none), through a stack settling and falling asleep (the live shapes change), a box
// dropped on it and a kinematic pusher driven into it (boxes that leave their fat boxes, pairs
// that begin inside them). Both must also pass the same pairs to the narrowphase.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world_settings.hpp"
#include "shape_exact.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

/// A pyramid of `rows` rows of 1 m boxes on the floor y = 0 (μ = 0.6), each row's boxes 2 cm apart;
/// a box dropped from 4 m above its top; a kinematic box driven at 1 m/s along the floor into its
/// base, which it reaches at about 2.5 s; with `shot`, a kinematic box at 20 m/s through its
/// top rows from 60 m away (reached at about 2.6 s). Sleeping on (0.25 s).
std::unique_ptr<detail::WorldKernel<double>> pushed_pyramid(int rows, bool shot = false) {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.contacts->sleep = true;
  s.contacts->sleep_time = 0.25;
  auto w = std::make_unique<detail::WorldKernel<double>>(s);
  w->add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  for (int row = 0; row < rows; ++row) {
    for (int i = 0; i < rows - row; ++i) {
      const double x = 1.02 * (i - 0.5 * (rows - row - 1));
      w->create_body(shape_exact::box_body(0.5, 0.5, {x, 0.5 + 1.0 * row}, 0.0));
    }
  }
  w->create_body(shape_exact::box_body(0.5, 0.5, {0.3, rows + 4.0}, 0.2));
  BodyDef pusher = shape_exact::box_body(0.5, 0.4, {-11.0, 0.45}, 0.0);
  pusher.type = BodyType::kinematic;
  pusher.gravity.reset();
  pusher.body.velocity = {1.0, 0.0};
  w->create_body(pusher);
  if (shot) {
    BodyDef bullet = shape_exact::box_body(0.3, 0.3, {-60.0, rows - 2.5}, 0.0);
    bullet.type = BodyType::kinematic;
    bullet.gravity.reset();
    bullet.body.velocity = {20.0, 0.0};
    w->create_body(bullet);
  }
  return w;
}

/// A kinematic 0.6 m box at (x, 1 m) rising at 10 km/s: its box and fat box hundreds of metres
/// tall, so that it leaves its fat box every few ticks.
BodyDef rising_box(double x) {
  BodyDef b = shape_exact::box_body(0.3, 0.3, {x, 1.0}, 0.0);
  b.type = BodyType::kinematic;
  b.gravity.reset();
  b.body.velocity = {0.0, 1.0e4};
  return b;
}

/// Whether two worlds' last broadphases passed on the same pairs, in the same order.
bool same_candidates(const detail::WorldKernel<double>& a, const detail::WorldKernel<double>& b) {
  const auto ca = a.shape_world()->candidates(), cb = b.shape_world()->candidates();
  return std::equal(ca.begin(), ca.end(), cb.begin(), cb.end(),
                    [](const auto& p, const auto& q) { return p.a == q.a && p.b == q.b; });
}

/// Steps a pushed pyramid of `rows` rows that keeps its fat boxes beside one made again from it
/// every tick, failing at the first tick their state hashes, candidate pairs (a fat pair whose
/// boxes do not overlap must not reach the narrowphase, though its shapes would not touch) or
/// manifold points differ; then checks what the run went through: fat boxes kept for many
/// ticks and made again, the pyramid asleep, and the pusher waking it.
void keeps_its_bits(int rows, bool shot = false) {
  auto kept = pushed_pyramid(rows, shot), fresh = pushed_pyramid(rows, shot);
  std::size_t most_asleep = 0, woken = 0;
  for (int t = 1; t <= 420; ++t) {
    *fresh = *kept;  // the same state, no fat boxes: they are made from this tick's boxes
    kept->step(), fresh->step();
    ASSERT_EQ(kept->state_hash(), fresh->state_hash()) << "first differs after tick " << t;
    ASSERT_TRUE(same_candidates(*kept, *fresh)) << "tick " << t;
    const ContactStats& a = kept->contact_stats();
    ASSERT_EQ(a.shape_points, fresh->contact_stats().shape_points) << "tick " << t;
    most_asleep = std::max(most_asleep, a.sleeping), woken += a.woken;
  }
  const std::uint64_t served = kept->shape_world()->fat_pair_ticks();
  EXPECT_GE(served, 100u);
  EXPECT_LE(served, 415u);  // and made again whole in some ticks
  const std::uint64_t refitted = kept->shape_world()->fat_refit_ticks();
  EXPECT_GE(refitted, shot ? 150u : 20u);  // the dropped box, the pusher, the shot
  EXPECT_GE(most_asleep, static_cast<std::size_t>(rows * (rows + 1) / 2));
  EXPECT_GT(woken, 0u);
  EXPECT_FALSE(kept->fault().has_value());
}

TEST(ShapeFatPairs, AWorldThatKeepsItsFatBoxesStepsAsOneThatMakesThemEveryTick) {
  keeps_its_bits(16);  // 138 shapes: the live shapes' grid (min_grid_shapes)
}

TEST(ShapeFatPairs, ASmallWorldThatKeepsItsFatBoxesStepsAsOneThatMakesThemEveryTick) {
  keeps_its_bits(12);  // 80 shapes: the sort and sweep of every shape
}

TEST(ShapeFatPairs, AFastBodyIsRefittedAloneAsTheOthersKeepTheirFatBoxes) {
  keeps_its_bits(16, true);  // and its pairs found again as it crosses the pyramid
}

// Two kinematic boxes rising at 10 km/s beside the pushed pyramid: boxes 334 m tall and fat
// boxes reaching 333 m further, refitted in some ticks (the grid of the fat boxes asked for
// boxes far larger than its cells) and made again whole in others: the same bits and pairs as
// a world that makes them every tick.
TEST(ShapeFatPairs, BodiesFarFasterThanTheirFatMarginsKeepTheBits) {
  auto kept = pushed_pyramid(16), fresh = pushed_pyramid(16);
  for (auto* w : {kept.get(), fresh.get()}) {
    for (int i = 0; i < 2; ++i) w->create_body(rising_box(40.0 + 1.0 * i));
  }
  for (int t = 1; t <= 120; ++t) {
    *fresh = *kept;
    kept->step(), fresh->step();
    ASSERT_EQ(kept->state_hash(), fresh->state_hash()) << "first differs after tick " << t;
    ASSERT_TRUE(same_candidates(*kept, *fresh)) << "tick " << t;
  }
  EXPECT_GE(kept->shape_world()->fat_refit_ticks(), 5u);
  EXPECT_FALSE(kept->fault().has_value());
}

// 400 boxes floating at rest (no gravity, no sleep) and beside them four kinematic boxes rising
// at 10 km/s, side by side, which leave their fat boxes in the same ticks. Each one's refitted
// fat box (667 m tall) covers more cells of the grid of the fat boxes than it has buckets, so
// its pairs are looked for among every entry (about 380 looked at): a refit of all four looks
// at more than the bound on its work (4 a place and 256), which must stop it and make the fat
// boxes again whole, with the same bits and pairs as a world that makes them every tick. Without
// the bound no refit stops (and one kept looked at 4.8 times it).
TEST(ShapeFatPairs, ARefitStopsAtTheBoundOnItsWork) {
  auto make = [] {
    auto w = std::make_unique<detail::WorldKernel<double>>(shape_exact::shape_settings(0.6));
    for (int i = 0; i < 400; ++i) {
      BodyDef b = shape_exact::box_body(0.4, 0.4, {2.0 * (i % 20), 2.0 * (i / 20)}, 0.0);
      b.gravity.reset();
      w->create_body(b);
    }
    for (int i = 0; i < 4; ++i) w->create_body(rising_box(60.0 + 1.0 * i));
    return w;
  };
  auto kept = make(), fresh = make();
  for (int t = 1; t <= 60; ++t) {
    *fresh = *kept;
    kept->step(), fresh->step();
    ASSERT_EQ(kept->state_hash(), fresh->state_hash()) << "first differs after tick " << t;
    ASSERT_TRUE(same_candidates(*kept, *fresh)) << "tick " << t;
  }
  const auto* shapes = kept->shape_world();
  EXPECT_GE(shapes->fat_pair_ticks(), 20u);
  EXPECT_GE(shapes->fat_refit_work_stops(), 5u);
  EXPECT_FALSE(kept->fault().has_value());
}

}  // namespace
}  // namespace fixstep
