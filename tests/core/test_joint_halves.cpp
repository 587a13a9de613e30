// The joints by halves on two threads (joint_halves.hpp): which joints go together, and a pile
// of hinged trees, chains from one static beam and two trees tied by a slider stepped to the
// same bits on one thread and two.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "fixstep/core/world.hpp"
#include "joint_halves.hpp"
#include "shape_exact.hpp"
#include "shape_world.hpp"
#include "workers.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

using detail::JointBodies;
using detail::JointHalves;
using detail::JointRecord;
constexpr std::uint32_t no_body = JointRecord::none;

JointRecord joint(std::uint32_t a, std::uint32_t b) {
  JointRecord j;
  j.a = a, j.b = b;
  return j;
}

TEST(JointHalves, JointsThatShareABodyOfAnyTypeGoTogetherAndTheHalvesHoldHalfTheJoints) {
  // Groups, in the order of their first joint: {0, 1, 2} by joints 0, 1 and 6; {3, 4};
  // {5} (to the world only); {6, 7, 8}, 7 held by both of its joints (a static beam's body is
  // written by their position sweeps too); joint 5 broken (joins nothing, in no half).
  std::vector<JointRecord> joints = {joint(0, 1), joint(1, 2), joint(3, 4), joint(5, no_body),
                                     joint(6, 7), joint(9, 4), joint(2, 0), joint(8, 7)};
  joints[5].broken = true;
  JointHalves h;
  JointBodies numbered;
  auto split = [&](const std::vector<JointRecord>& js, std::vector<std::uint32_t> listed) {
    numbered.build(js, listed, 10);
    return h.split(js, listed, numbered);
  };
  ASSERT_TRUE(split(joints, {0, 1, 2, 3, 4, 5, 6, 7}));
  // 7 joints: the first half takes groups while it holds under 3.5 of them, {0, 1, 2} (3), then
  // {3, 4} (1 more: 4); {5} and {6, 7, 8} go to the second.
  EXPECT_EQ(std::vector<std::uint32_t>(h.joints(0).begin(), h.joints(0).end()),
            (std::vector<std::uint32_t>{0, 1, 2, 6}));
  EXPECT_EQ(std::vector<std::uint32_t>(h.joints(1).begin(), h.joints(1).end()),
            (std::vector<std::uint32_t>{3, 4, 7}));
  // By the bodies' numbers, in the order the joints name them (body 9 only in the broken one):
  // bodies 0 to 8 here.
  std::vector<std::uint8_t> half;
  for (std::uint32_t body = 0; body < 9; ++body)
    half.push_back(h.half_of_body()[numbered.local(body)]);
  EXPECT_EQ(half, (std::vector<std::uint8_t>{0, 0, 0, 0, 0, 1, 1, 1, 1}));
  EXPECT_EQ(numbered.size(), 9u);
  // Of a list, those alone: without joints 0 and 1, the groups come as {3, 4}, {5}, {6, 7, 8}
  // (4 of the 5 joints, the first half taking each while under 2.5) and {2, 0}.
  ASSERT_TRUE(split(joints, {2, 3, 4, 6, 7}));
  EXPECT_EQ(std::vector<std::uint32_t>(h.joints(0).begin(), h.joints(0).end()),
            (std::vector<std::uint32_t>{2, 3, 4, 7}));
  EXPECT_EQ(std::vector<std::uint32_t>(h.joints(1).begin(), h.joints(1).end()),
            (std::vector<std::uint32_t>{6}));
  // Joined by one body, they are one group: no halves.
  const std::vector<JointRecord> star = {joint(0, 1), joint(2, 1), joint(3, 1), joint(1, no_body)};
  EXPECT_FALSE(split(star, {0, 1, 2, 3}));
  EXPECT_FALSE(split({}, {}));
}

/// 128 trees of three boxes hinged in a row (limits, a motor on one hinge), dropped in a heap;
/// 4 chains of 4 links from one static beam; and two trees tied by a slider, the first and one
/// the second half would take without it. More than ShapeWorld::min_split_joints joints, in
/// many groups. `limits_alone`: no motor and no slider (every joint's own rows its limits: a
/// ragdoll's kind, swept packed).
std::unique_ptr<detail::WorldKernel<double>> hinged_heap(int threads, bool limits_alone = false) {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.threads = threads;
  auto w = std::make_unique<detail::WorldKernel<double>>(s);
  w->add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  std::vector<Entity> first;
  std::vector<Vec2> at;
  for (int i = 0; i < 128; ++i) {
    const double x = 0.9 * (i % 8) - 3.4, y = 0.6 + 0.5 * (i / 8);
    Entity last{};
    for (int k = 0; k < 3; ++k) {
      const Entity e =
          w->create_body(shape_exact::box_body(0.15, 0.05, {x + 0.3 * k, y}, 0.02 * i));
      if (k == 0) first.push_back(e), at.push_back({x, y});
      if (k > 0) {
        w->create_joint({.type = JointType::revolute,
                         .body_a = last,
                         .body_b = e,
                         .anchor = {x + 0.3 * k - 0.15, y},
                         .lower = -0.8,
                         .upper = 0.8,
                         .motor_speed = k == 1 && !limits_alone ? 1.0 : 0.0,
                         .max_motor_torque = k == 1 && !limits_alone ? 0.05 : 0.0},
                        "hinge");
      }
      last = e;
    }
  }
  BodyDef beam = shape_exact::box_body(3.0, 0.1, {0.0, 11.0});
  beam.type = BodyType::static_body;
  const Entity b = w->create_body(beam);
  for (int c = 0; c < 4; ++c) {
    Entity last = b;
    for (int k = 0; k < 4; ++k) {
      const double x = -2.4 + 1.6 * c + 0.3 * k;
      const Entity e = w->create_body(shape_exact::box_body(0.15, 0.04, {x + 0.15, 10.9}));
      w->create_joint(
          {.type = JointType::revolute, .body_a = last, .body_b = e, .anchor = {x, 10.9}}, "link");
      last = e;
    }
  }
  if (limits_alone) return w;
  w->create_joint({.type = JointType::prismatic,
                   .body_a = first[0],
                   .body_b = first[100],
                   .anchor = at[0],
                   .axis = {0.0, 1.0}},
                  "slider");
  return w;
}

/// Steps `one` and `two` `ticks` times, failing at the first tick their state hashes differ.
void step_alike(detail::WorldKernel<double>& one, detail::WorldKernel<double>& two, int ticks) {
  for (int t = 0; t < ticks; ++t) {
    one.step(), two.step();
    ASSERT_EQ(one.state_hash(), two.state_hash()) << "first differs after tick " << t + 1;
  }
}

TEST(JointHalves, TwoThreadsStepAHingedHeapToTheSameBitsAsOne) {
  auto one = hinged_heap(1), two = hinged_heap(2);
  step_alike(*one, *two, 120);
  if (HasFatalFailure()) return;
  EXPECT_EQ(one->shape_world()->halved_joint_passes(), 0u);
  EXPECT_FALSE(one->shape_world()->limit_rows_packed())
      << "a motor and a slider: rows of their own";
  // 273 joints (256 hinges, 16 links, a slider): every velocity and position sweep of every
  // tick by halves, two passes each at most.
  EXPECT_GT(two->shape_world()->halved_joint_passes(), 120u * 20u);
  EXPECT_FALSE(two->fault().has_value());
}

// The same heap with its hinges' limits as their only rows: those rows swept packed, each half's
// on its own thread.
TEST(JointHalves, TwoThreadsStepAHeapOfLimitedHingesToTheSameBitsAsOne) {
  auto one = hinged_heap(1, true), two = hinged_heap(2, true);
  for (int t = 0; t < 120; ++t) {
    one->step(), two->step();
    ASSERT_EQ(one->state_hash(), two->state_hash()) << "first differs after tick " << t + 1;
    ASSERT_TRUE(one->shape_world()->limit_rows_packed() && two->shape_world()->limit_rows_packed())
        << "tick " << t + 1;
  }
  EXPECT_GT(two->shape_world()->halved_joint_passes(), 120u * 20u);
}

/// Two chains of 200 and 100 boxes (bench_joints' links: 0.5 by 0.125 m, 0.0625 kg, 10 m/s²),
/// each hinged to the world at one end and released level, far enough apart never to touch:
/// two trees of the forest, one a half, whose whips come at different ticks. At Box2D v2.4's
/// 8 velocity and 3 position iterations.
std::unique_ptr<detail::WorldKernel<double>> two_chains(int threads) {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.threads = threads;
  s.contacts->velocity_iterations = 8;
  s.contacts->position_iterations = 3;
  auto w = std::make_unique<detail::WorldKernel<double>>(s);
  for (const auto& [x0, links] : {std::pair{0.0, 200}, std::pair{300.0, 100}}) {
    Entity before{};
    for (int i = 0; i < links; ++i) {
      BodyDef link = shape_exact::box_body(0.25, 0.0625, {x0 + 0.25 + 0.5 * i, 0.0}, 0.0, 0.0625);
      link.gravity = Gravity{{0.0, -10.0}};
      const Entity e = w->create_body(link);
      w->create_joint({.type = JointType::revolute,
                       .body_a = before,
                       .body_b = e,
                       .anchor = {x0 + 0.5 * i, 0.0}},
                      "link");
      before = e;
    }
  }
  return w;
}

// The forest's steps that keep, taken back and made shorter where they grew the error (as
// whipping chains' do), each half on its own thread: the same bits as one thread. Whether a
// step is taken back is decided by the whole forest's error (both halves'), so each chain's
// steps are taken back where either chain's grew.
TEST(JointHalves, TwoThreadsTakeBackTheSameStepsAsOne) {
  auto one = two_chains(1), two = two_chains(2);
  step_alike(*one, *two, 400);
  if (HasFatalFailure()) return;
  EXPECT_GT(one->shape_world()->kept_step_cuts(), 0u) << "no step was taken back";
  EXPECT_EQ(one->shape_world()->kept_step_cuts(), two->shape_world()->kept_step_cuts());
  EXPECT_GT(two->shape_world()->halved_joint_passes(), 400u * 8u);
}

// An automatic world (threads = 0) of 273 joints tries two threads and one, tick by tick, and
// holds its choice between trials (thread_choice.hpp): the joints' passes by halves in some
// ticks and not in others, with the bits of one thread in every tick.
TEST(JointHalves, AnAutomaticWorldStepsItsTrialsToTheSameBitsAsOneThread) {
  auto one = hinged_heap(1), automatic = hinged_heap(0);
  bool halved = false, whole = false;
  std::uint64_t passes = 0;
  for (int t = 0; t < 120; ++t) {
    one->step(), automatic->step();
    ASSERT_EQ(one->state_hash(), automatic->state_hash()) << "first differs after tick " << t + 1;
    const std::uint64_t now = automatic->shape_world()->halved_joint_passes();
    (now > passes ? halved : whole) = true;
    passes = now;
  }
  if (detail::threads_for(0) < 2) GTEST_SKIP() << "one core: an automatic world runs one thread";
  EXPECT_TRUE(halved && whole) << "the trials ran " << (halved ? "two threads" : "one thread")
                               << " only";
}

}  // namespace
}  // namespace fixstep
