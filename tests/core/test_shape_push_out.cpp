// The push-out's skipping of idle rows (ShapeWorld::PushRow::idle): a row that pushed nothing,
// whose bodies have not moved since, is skipped; the world steps to the same bits as when every
// row of every sweep is evaluated, on one thread and by halves on two.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <numeric>

#include "fixstep/core/components.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/world_def.hpp"
#include "shape_exact.hpp"
#include "shape_walls.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

using shape_exact::box_body;

/// 150 boxes of three sizes at many angles dropped in rows onto a floor between two walls, a
/// static shelf among them: rows against planes (A is none), against a static body and between
/// two boxes, which push for a while and then rest.
std::unique_ptr<detail::WorldKernel<double>> tumbling_boxes(int threads) {
  auto w = shape_walls::floor_world(threads);
  w->add_plane(PlaneDef{.normal = {1.0, 0.0}, .offset = -3.0, .friction = 0.6});
  w->add_plane(PlaneDef{.normal = {-1.0, 0.0}, .offset = -3.0, .friction = 0.6});
  for (int i = 0; i < 150; ++i) {
    const double half = 0.15 + 0.05 * (i % 3);
    w->create_body(box_body(half, half, {-2.5 + 0.5 * (i % 11), 0.4 + 0.45 * (i / 11)}, 0.3 * i));
  }
  BodyDef shelf;
  shelf.type = BodyType::static_body;
  shelf.body.position = {1.5, 2.0};
  shelf.shapes = {make_box(0.8, 0.1)};
  w->create_body(shelf);
  return w;
}

/// The wall of shape_walls::box_wall with its lower 18 rows pressed (past the push-out's split):
/// the push-out pushes from the bottom up while the upper rows' points, pushing nothing, wait.
std::unique_ptr<detail::WorldKernel<double>> half_pressed_wall(int threads) {
  return shape_walls::box_wall(threads, 18);
}

/// The tumbling boxes with a chain of 10 links of 0.5 m hinged end to end above them, the first
/// to the world: the joints' corrections move bodies between the push-out's sweeps.
std::unique_ptr<detail::WorldKernel<double>> boxes_and_chain(int threads) {
  auto w = tumbling_boxes(threads);
  Entity before{};
  for (int i = 0; i < 10; ++i) {
    const Entity link = w->create_body(box_body(0.25, 0.05, {-2.55 + 0.5 * i, 7.0}));
    w->create_joint({.type = JointType::revolute,
                     .body_a = before,
                     .body_b = link,
                     .anchor = {-2.8 + 0.5 * i, 7.0}},
                    "link");
    before = link;
  }
  return w;
}

std::uint64_t skipped(const detail::WorldKernel<double>& w) {
  const auto& s = w.shape_world()->push_split().skipped;
  return std::accumulate(s.begin(), s.end(), std::uint64_t{0});
}

/// Steps `ticks` ticks of the world with idle rows skipped and of a copy evaluating every row
/// from its second tick on (its shape world is made by its first); the state hashes of every
/// tick agree. Returns the world that skipped.
template <class Make>
std::unique_ptr<detail::WorldKernel<double>> same_bits(Make make, int threads, int ticks) {
  auto skipping = make(threads);
  auto every = make(threads);
  skipping->step();
  every->step();
  const std::uint64_t skipped_first = skipped(*every);
  every->shape_world()->skip_idle_rows(false);
  for (int t = 1; t < ticks; ++t) {
    skipping->step();
    every->step();
    EXPECT_EQ(skipping->state_hash(), every->state_hash()) << "first differs after tick " << t + 1;
    if (skipping->state_hash() != every->state_hash()) break;
  }
  EXPECT_EQ(skipped(*every), skipped_first);  // none from the second tick on
  EXPECT_FALSE(skipping->fault().has_value());
  return skipping;
}

TEST(ShapePushOut, SkippingIdleRowsStepsToTheBitsOfEvaluatingEveryRow) {
  const auto w = same_bits(tumbling_boxes, 1, 240);
  EXPECT_FALSE(w->shape_world()->push_split().on);
  EXPECT_GT(w->shape_world()->rows().size(), 150u);  // a pile, not a rain
  EXPECT_GT(skipped(*w), 1000u);
}

TEST(ShapePushOut, SkippingIdleRowsByHalvesStepsToTheBitsOfEvaluatingEveryRow) {
  const auto w = same_bits(half_pressed_wall, 2, 30);
  const auto& split = w->shape_world()->push_split();
  EXPECT_TRUE(split.on);
  EXPECT_GT(split.skipped[0], 0u);  // rows skipped in half 0,
  EXPECT_GT(split.skipped[1], 0u);  // in half 1,
  EXPECT_GT(split.skipped[2], 0u);  // and in the cut
}

// Where joints correct positions between the sweeps, no row is skipped: a joint moves bodies
// the rows' marks do not see.
TEST(ShapePushOut, WithJointsEveryRowIsEvaluated) {
  const auto w = same_bits(boxes_and_chain, 1, 240);
  EXPECT_EQ(skipped(*w), 0u);
}

}  // namespace
}  // namespace fixstep
