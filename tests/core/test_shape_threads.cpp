// The shape phase on two threads: the broadphase and the manifolds by halves, the velocity
// sweeps' large colours split and the push-out by halves, with the bits of one thread, also in
// an automatic world that switches between two threads and one as it tries them; a work limit
// met by halves is the fault one thread names.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "same_fault.hpp"
#include "shape_exact.hpp"
#include "shape_walls.hpp"
#include "shape_world.hpp"
#include "workers.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

using shape_exact::box_body;

/// 60 columns of 36 boxes of 1 m standing on a plane, a little apart (2160 shapes, past the
/// split of the broadphase and the manifolds): every box's manifolds exist from the first
/// tick, two or three colours of hundreds of manifolds each.
std::unique_ptr<detail::WorldKernel<double>> columns(int threads) {
  auto w = shape_walls::floor_world(threads);
  for (int c = 0; c < 60; ++c) {
    for (int r = 0; r < 36; ++r) {
      w->create_body(box_body(0.5, 0.5, {1.05 * c + 0.01 * (r % 3), 0.5 + 1.0 * r}, 0.0));
    }
  }
  return w;
}

TEST(ShapeThreads, TwoThreadsStepAPileToTheSameBitsAsOne) {
  auto one = columns(1);
  auto two = columns(2);
  std::uint64_t split = 0;
  for (int t = 0; t < 60; ++t) {
    one->step();
    two->step();
    ASSERT_GE(two->shape_world()->shapes_.size(), detail::ShapeWorld::min_split_shapes);
    ASSERT_EQ(one->state_hash(), two->state_hash()) << "first differs after tick " << t + 1;
    EXPECT_EQ(one->shape_world()->split_colors(), 0u);
    EXPECT_FALSE(one->shape_world()->halved());
    EXPECT_TRUE(two->shape_world()->halved());
    EXPECT_EQ(one->threads_used(), 1);
    EXPECT_EQ(two->threads_used(), 2);  // (World::threads_used(): the shape phase's passes too)
    split += two->shape_world()->split_colors();
  }
  EXPECT_GT(split, 60u * 20u);  // at least one colour in every sweep of every tick
  EXPECT_FALSE(two->fault().has_value());
}

TEST(ShapeThreads, AnAutomaticWorldStepsItsTrialsToTheSameBitsAsOneThread) {
  // threads = 0: the world tries two threads and one, two ticks each (thread_choice.hpp), then
  // holds its choice and tries again: 60 ticks hold two trials (ticks 1-12 and 29-40).
  auto one = columns(1);
  auto automatic = columns(0);
  bool halved = false, whole = false;
  for (int t = 0; t < 60; ++t) {
    one->step();
    automatic->step();
    ASSERT_EQ(one->state_hash(), automatic->state_hash()) << "first differs after tick " << t + 1;
    (automatic->shape_world()->halved() ? halved : whole) = true;
  }
  if (detail::threads_for(0) < 2) GTEST_SKIP() << "one core: an automatic world runs one thread";
  EXPECT_TRUE(halved && whole) << "the trial ran " << (halved ? "two threads" : "one thread")
                               << " only";
  EXPECT_FALSE(automatic->fault().has_value());
}

/// The wall of shape_walls::box_wall with every row pressed: the push-out pushes in every sweep
/// of the first ticks, on both sides of the line at the mean x (between columns 29 and 30) and
/// across it.
std::unique_ptr<detail::WorldKernel<double>> pressed_wall(int threads) {
  return shape_walls::box_wall(threads, 36);
}

TEST(ShapeThreads, ThePushOutByHalvesStepsToTheSameBitsAsOne) {
  auto one = pressed_wall(1);
  auto two = pressed_wall(2);
  for (int t = 0; t < 30; ++t) {
    one->step();
    two->step();
    ASSERT_EQ(one->state_hash(), two->state_hash()) << "first differs after tick " << t + 1;
  }
  const detail::ShapeWorld::PushSplit& split = two->shape_world()->push_split();
  ASSERT_GE(two->shape_world()->rows().size(), detail::ShapeWorld::min_split_rows);
  EXPECT_TRUE(one->shape_world()->push_split().on);
  EXPECT_TRUE(split.on);
  EXPECT_GT(split.ends[0], 0u);                                 // half 0 has rows,
  EXPECT_GT(split.ends[1], split.ends[0]);                      // so has half 1,
  EXPECT_GT(two->shape_world()->rows().size(), split.ends[1]);  // and the cut
  // The pushed rows are the tick's manifold points: half 0's, half 1's, the cut's, each in
  // row order.
  const std::span<const detail::ShapeRow> rows = two->shape_world()->rows();
  ASSERT_EQ(split.rows.size(), rows.size());
  std::array<std::size_t, 3> next{0, split.ends[0], split.ends[1]};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const detail::ShapeWorld::PushRow& p = split.rows[next[split.part[i]]++];
    ASSERT_TRUE(p.a == rows[i].a && p.b == rows[i].b && p.separation == rows[i].separation &&
                p.n.x == rows[i].n.x && p.rb.y == rows[i].rb.y)
        << "row " << i << " of part " << int{split.part[i]};
  }
  EXPECT_EQ(one->shape_world()->split_pushes(), 0u);
  EXPECT_GT(two->shape_world()->split_pushes(), 30u);  // more than a sweep a tick
  EXPECT_FALSE(two->fault().has_value());
}

/// A plank of 400 m on a plane with 360 boxes resting on it: the plank's manifolds outnumber the
/// colours, so most of them share the overflow colour, which moves the plank in every one of
/// them and so is solved one at a time, in order, on one thread.
std::unique_ptr<detail::WorldKernel<double>> loaded_plank(int threads) {
  auto w = shape_walls::floor_world(threads);
  w->create_body(box_body(200.0, 0.25, {0.0, 0.25}, 0.0, 500.0));
  for (int i = 0; i < 360; ++i) {
    w->create_body(box_body(0.25, 0.25, {-198.0 + 1.1 * i, 0.75 + 0.002 * (i % 5)}, 0.0));
  }
  return w;
}

TEST(ShapeThreads, TheOverflowColourStaysOnOneThread) {
  auto one = loaded_plank(1);
  auto two = loaded_plank(2);
  for (int t = 0; t < 60; ++t) {
    one->step();
    two->step();
    ASSERT_EQ(one->state_hash(), two->state_hash()) << "first differs after tick " << t + 1;
  }
  // Most of the plank's 720 points are in the overflow colour: its manifolds were many.
  EXPECT_GT(one->shape_world()->rows().size(), 700u);
  EXPECT_FALSE(two->fault().has_value());
}

TEST(ShapeThreads, ACapMetByHalvesIsTheFaultOneThreadNames) {
  auto crowd = [](int threads) {
    WorldSettings settings = shape_exact::shape_settings(0.5);
    settings.threads = threads;
    World w(WorldDef::empty(Precision::f64, settings));
    // Two crowds of 1050 far apart, each a half of the sorted boxes: each half's pairs
    // (551 775) are within max_candidate_pairs (10^6), both together are not.
    for (int i = 0; i < 2100; ++i) {
      w.create_body(box_body(0.5, 0.5, {(i < 1050 ? 0.0 : 1000.0) + 0.001 * i, 0.0}));
    }
    w.step();
    return w.fault();
  };
  test::expect_same_cap_fault(crowd(1), crowd(2), "max_candidate_pairs");
}

TEST(ShapeThreads, AFilteredCrowdPastTheVetoLimitFaultsAlike) {
  // 6000 boxes at one point that a filter keeps apart: the broadphase drops their 1.8·10^7
  // pairs, past max_vetoed_pairs (1.6·10^7), on one thread and on two alike.
  auto crowd = [](int threads) {
    WorldSettings settings = shape_exact::shape_settings(0.5);
    settings.threads = threads;
    World w(WorldDef::empty(Precision::f64, settings));
    for (int i = 0; i < 6000; ++i) {
      BodyDef b = box_body(0.5, 0.5, {0.0, 0.0});
      b.shapes[0].filter.group = -1;  // never with each other
      w.create_body(b);
    }
    w.step();
    return w.fault();
  };
  const auto one = crowd(1);
  test::expect_same_cap_fault(one, crowd(2), "max_vetoed_pairs", double(max_vetoed_pairs(6000)));
  ASSERT_TRUE(one.has_value());
  const std::string m = explain_fault({}, {}, shape_exact::shape_settings(0.5), *one);
  EXPECT_NE(m.find("dropped more pairs that can never touch"), std::string::npos) << m;
  EXPECT_NE(m.find("6000 shapes"), std::string::npos) << m;
}

}  // namespace
}  // namespace fixstep
