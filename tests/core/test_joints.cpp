// Joints: the exact checks (tests/cross/joint_exact.cpp), definitions World refuses with the
// field named, a tick's input to a motor, breaking, the shapes a joint keeps apart, and the
// same bits after a snapshot and on two threads.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "joint_exact.hpp"
#include "shape_exact.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

class JointExact : public ::testing::TestWithParam<shape_exact::Check> {};

TEST_P(JointExact, Holds) {
  for (const shape_exact::Measure& m : GetParam().run()) {
    EXPECT_TRUE(m.holds()) << m.what << " = " << m.value << ", not in [" << m.low << ", " << m.high
                           << "]";
  }
}

INSTANTIATE_TEST_SUITE_P(Joints, JointExact, ::testing::ValuesIn(joint_exact::checks()),
                         [](const auto& info) { return info.param.name; });

World empty_world(double mu = 0.6) {
  return World(WorldDef::empty(Precision::f64, shape_exact::shape_settings(mu)));
}

std::string refusal(World& w, const JointDef& def) {
  try {
    w.create_joint(def);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(JointDefinitions, AreRefusedWithTheFieldNamed) {
  World w = empty_world();
  const Entity a = w.create_body(shape_exact::box_body(0.5, 0.5, {0.0, 0.0}));
  const Entity b = w.create_body(shape_exact::box_body(0.5, 0.5, {2.0, 0.0}));
  BodyDef point;
  point.body.mass = 1.0;
  const Entity bare = w.create_body(point);
  using T = JointType;
  const double nan = std::nan("");
  const std::pair<JointDef, const char*> cases[] = {
      {{.type = T::revolute}, "both the world"},
      {{.type = T::revolute, .body_a = a, .body_b = a}, "body_b is body_a"},
      {{.type = T::revolute, .body_a = a, .body_b = bare}, "body_b (\"\") has no shapes"},
      {{.type = T::revolute, .body_a = a, .body_b = b, .anchor = {nan, 0.0}}, "anchor"},
      {{.type = T::revolute, .body_a = a, .body_b = b, .lower = 1.0, .upper = 0.5},
       "lower (1) is above upper (0.5)"},
      {{.type = T::revolute, .body_a = a, .body_b = b, .lower = -4.0}, "lower must be in [-pi"},
      {{.type = T::revolute, .body_a = a, .body_b = b, .max_motor_torque = -1.0},
       "max_motor_torque must be in [0"},
      {{.type = T::revolute, .body_a = a, .body_b = b, .axis = {0.0, 1.0}},
       "a revolute joint has no axis"},
      {{.type = T::prismatic, .body_a = a, .body_b = b, .axis = {0.0, 0.0}},
       "axis must not be zero"},
      {{.type = T::wheel, .body_a = a, .body_b = b}, "needs frequency > 0"},
      {{.type = T::distance,
        .body_a = a,
        .body_b = b,
        .anchor = {0.0, 0.0},
        .anchor_b = Vec2{0.0, 0.0}},
       "length must be > 0"},
      {{.type = T::distance, .body_a = a, .body_b = b, .anchor_b = Vec2{2.0, 0.0}, .lower = -1.0},
       "lower must be >= 0"},
      {{.type = T::weld, .body_a = a, .body_b = b, .frequency = -1.0}, "frequency must be in [0"},
      {{.type = T::motor, .body_a = a, .body_b = b, .frequency = 1.0},
       "a motor joint has no frequency"},
      {{.type = T::revolute, .body_a = a, .body_b = b, .break_force = nan}, "break_force"},
  };
  for (const auto& [def, expected] : cases) {
    const std::string message = refusal(w, def);
    EXPECT_NE(message.find(expected), std::string::npos)
        << message << " (expected: " << expected << ")";
  }
  EXPECT_EQ(w.joint_count(), 0u);
}

TEST(JointDefinitions, AWorldDefNamesTheJointAndItsBodiesAreTheDefinitions) {
  WorldDef def = WorldDef::empty(Precision::f64, shape_exact::shape_settings(0.6));
  const Entity a = def.add_body(shape_exact::box_body(0.5, 0.5, {0.0, 0.0}));
  const Entity b = def.add_body(shape_exact::box_body(0.5, 0.5, {1.0, 0.0}));
  def.joints.push_back({.type = JointType::revolute,
                        .body_a = a,
                        .body_b = b,
                        .anchor = {0.5, 0.0},
                        .name = "hinge"});
  World w(def);
  ASSERT_EQ(w.defined_joints().size(), 1u);
  EXPECT_EQ(w.find_joint("hinge"), w.defined_joints()[0]);
  EXPECT_EQ(w.joint(w.find_joint("hinge")).body_b, w.defined_bodies()[1]);
  def.joints.push_back({.type = JointType::revolute, .body_a = a, .body_b = a, .name = "self"});
  try {
    World bad(def);
    FAIL() << "a joint of a body to itself was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint[1] (\"self\")"), std::string::npos) << e.what();
  }
}

TEST(Joints, DestroyingABodyDestroysItsJoints) {
  World w = empty_world();
  const Entity a = w.create_body(shape_exact::box_body(0.5, 0.5, {0.0, 0.0}));
  const Entity b = w.create_body(shape_exact::box_body(0.5, 0.5, {1.0, 0.0}));
  const Joint j = w.create_joint({.type = JointType::weld, .body_a = a, .body_b = b});
  w.destroy(b);
  EXPECT_FALSE(w.contains(j));
  EXPECT_EQ(w.joint_count(), 0u);
  EXPECT_THROW((void)w.joint_state(j), std::invalid_argument);
}

// A motor's speed set by a tick's input (and recorded as input, not as an edit): the disc
// turns at the new speed from that tick on.
TEST(Joints, AMotorFollowsTheTicksInput) {
  World w = empty_world();
  BodyDef disc = shape_exact::box_body(0.1, 0.1, {});
  disc.gravity.reset();
  disc.shapes = {make_circle(0.5)};
  const Entity e = w.create_body(disc);
  const Joint j = w.create_joint(
      {.type = JointType::revolute, .body_b = e, .motor_speed = 1.0, .max_motor_torque = 1e6});
  w.step();
  EXPECT_NEAR(w.body(e).angular_velocity, 1.0, 1e-12);
  TickInput in;
  in.joints.push_back({j, JointInputKind::motor_speed, {-3.0, 0.0}});
  w.check_input(in);
  w.step(in);
  EXPECT_NEAR(w.body(e).angular_velocity, -3.0, 1e-12);
  EXPECT_EQ(w.joint_state(j).motor_speed, -3.0);
  in.joints = {{j, JointInputKind::enable_motor, {0.0, 0.0}}};
  w.step(in);
  w.step();
  EXPECT_NEAR(w.body(e).angular_velocity, -3.0, 1e-12) << "a motor turned off holds nothing";
  in.joints = {{j, JointInputKind::max_motor_force, {1.0, 0.0}}};
  EXPECT_THROW(w.check_input(in), std::invalid_argument) << "a revolute joint has no force";
  in.joints = {{j, JointInputKind::enable_motor, {0.5, 0.0}}};
  EXPECT_THROW(w.check_input(in), std::invalid_argument);
}

// A joint whose reaction passes its break force breaks with an event, once, and stops acting;
// one below it holds.
TEST(Joints, AJointBreaksAboveItsBreakForce) {
  World w = empty_world();
  const Entity box = w.create_body(shape_exact::box_body(0.5, 0.5, {0.0, -1.0}, 0.0, 10.0));
  // 10 kg under gravity pulls 98.1 N on a 120 N joint; a 15 N push makes 113.1 N, a 30 N one
  // 128.1 N.
  const Joint j = w.create_joint(
      {.type = JointType::revolute, .body_b = box, .anchor = {0.0, -0.5}, .break_force = 120.0});
  TickInput push;
  push.bodies.push_back({box, BodyInputKind::force, {0.0, -15.0}});
  for (int t = 0; t < 60; ++t) {
    w.step(t < 30 ? TickInput{} : push);
    ASSERT_TRUE(w.joints_broken().empty()) << "broke below its bound, tick " << t;
  }
  EXPECT_NEAR(w.joint_state(j).force.y, 113.1, 0.5);
  push.bodies[0].value.y = -30.0;
  w.step(push);
  ASSERT_EQ(w.joints_broken().size(), 1u);
  EXPECT_EQ(w.joints_broken()[0].joint, j);
  EXPECT_NEAR(w.joints_broken()[0].force.y, 128.1, 0.5);
  EXPECT_TRUE(w.joint_state(j).broken);
  const double y = w.body(box).position.y;
  for (int t = 0; t < 30; ++t) w.step();
  EXPECT_TRUE(w.joints_broken().empty());
  EXPECT_LT(w.body(box).position.y, y - 1.0) << "a broken joint holds nothing";
}

/// A chain of `links` boxes 0.5 m × 0.125 m hinged end to end, the first to the world at
/// `at`, laid out horizontally; its bodies.
std::vector<Entity> hinged_chain(World& w, Vec2 at, int links) {
  std::vector<Entity> bodies;
  Entity before{};
  for (int i = 0; i < links; ++i) {
    const Entity link =
        w.create_body(shape_exact::box_body(0.25, 0.0625, {at.x + 0.5 * i + 0.25, at.y}));
    w.create_joint({.type = JointType::revolute,
                    .body_a = before,
                    .body_b = link,
                    .anchor = {at.x + 0.5 * i, at.y}});
    bodies.push_back(link);
    before = link;
  }
  return bodies;
}

// Each tree of hinged bodies is solved until its own error is within tolerance: a chain
// swinging in the air steps to the same bits beside two hinged boxes tumbling on the ground
// (contacts that take every sweep) as in a world of its own. Solved in every sweep that the
// contacts asked for, it took the roundoff of each extra solve.
TEST(Joints, AChainSwingsToTheSameBitsBesideABusyTreeAsAlone) {
  World alone = empty_world(), beside = empty_world();
  const std::vector<Entity> chain = hinged_chain(alone, {-6.0, 4.0}, 4);
  ASSERT_EQ(hinged_chain(beside, {-6.0, 4.0}, 4), chain);
  BodyDef ground = shape_exact::box_body(4.0, 0.5, {6.0, -0.5});
  ground.type = BodyType::static_body;
  beside.create_body(ground);
  const std::vector<Entity> pair = hinged_chain(beside, {5.0, 0.3}, 2);
  for (int t = 1; t <= 120; ++t) {
    alone.step(), beside.step();
    for (const Entity e : chain) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(alone.body(e).position.x),
                std::bit_cast<std::uint64_t>(beside.body(e).position.x))
          << "tick " << t;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(alone.body(e).angle),
                std::bit_cast<std::uint64_t>(beside.body(e).angle))
          << "tick " << t;
    }
  }
  EXPECT_GT(beside.contact_stats().shape_velocity_sweeps, 1u);
}

// Two boxes overlapping at a hinge: apart by default, colliding when asked.
TEST(Joints, JointedShapesCollideOnlyWhenAsked) {
  for (const bool collide : {false, true}) {
    World w = empty_world();
    BodyDef a = shape_exact::box_body(0.5, 0.5, {0.0, 0.0});
    a.gravity.reset();
    BodyDef b = a;
    b.body.position = {0.8, 0.0};  // overlapping by 0.2 m
    const Entity ea = w.create_body(a), eb = w.create_body(b);
    w.create_joint({.type = JointType::distance,
                    .body_a = ea,
                    .body_b = eb,
                    .anchor = {0.0, 0.0},
                    .anchor_b = Vec2{0.8, 0.0},
                    .upper = 5.0,
                    .collide_connected = collide});
    for (int t = 0; t < 60; ++t) w.step();
    const double apart = w.body(eb).position.x - w.body(ea).position.x;
    if (collide) {
      EXPECT_GT(apart, 0.99) << "colliding shapes are pushed apart";
    } else {
      EXPECT_NEAR(apart, 0.8, 1e-12) << "jointed shapes do not collide";
    }
  }
}

// The energy account: a motor's work enters as external work, so E + dissipated − external
// stays E0 while the motor spins a disc up (a joint to a kinematic body likewise).
TEST(Joints, AMotorsWorkIsExternalWorkInTheEnergyAccount) {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.track_dissipation = true;
  World w(WorldDef::empty(Precision::f64, s));
  BodyDef disc = shape_exact::box_body(0.1, 0.1, {});
  disc.gravity.reset();
  disc.shapes = {make_circle(0.5)};
  disc.body.mass = 2.0;
  const Entity e = w.create_body(disc);
  w.create_joint(
      {.type = JointType::revolute, .body_b = e, .motor_speed = 10.0, .max_motor_torque = 1.0});
  const double e0 = w.energy().total();
  for (int t = 0; t < 200; ++t) w.step();
  const double kinetic = 0.5 * 0.25 * 10.0 * 10.0;
  EXPECT_NEAR(w.external_work(), kinetic, 1e-9 * kinetic);
  EXPECT_NEAR(energy_balance(w, e0), 0.0, 1e-9 * kinetic);
}

// A heavy box resting on a ledge with a light box swinging from it on a hinge: the two are
// one island, so the still box stays awake while its partner swings; a joint's input wakes
// a sleeping island.
TEST(Joints, JointedBodiesAreOneIslandAndAJointsInputWakesThem) {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.contacts->sleep = true;
  s.contacts->sleep_time = 0.25;
  WorldDef def = WorldDef::empty(Precision::f64, s);
  def.segments.push_back(SegmentDef{.a = {-2.0, 0.0}, .b = {0.3, 0.0}, .friction = 0.9});
  const Entity heavy = def.add_body(shape_exact::box_body(0.5, 0.1, {0.0, 0.1}, 0.0, 100.0));
  const Entity light = def.add_body(shape_exact::box_body(0.05, 0.4, {0.5, -0.3}, 0.0, 0.1));
  def.joints.push_back(
      {.type = JointType::revolute, .body_a = heavy, .body_b = light, .anchor = {0.5, 0.1}});
  def.bodies[1].body.velocity = {1.0, 0.0};  // set swinging
  World w(def);
  for (int t = 1; t <= 120; ++t) {
    w.step();
    ASSERT_FALSE(w.asleep(heavy)) << "asleep while its partner swings, tick " << t;
  }
  // Held by its motor at speed 0, the light box stops, and the island falls asleep.
  TickInput hold;
  hold.joints.push_back({w.defined_joints()[0], JointInputKind::max_motor_torque, {5.0, 0.0}});
  w.step(hold);
  int asleep_at = -1;
  for (int t = 1; t <= 240 && asleep_at < 0; ++t) {
    w.step();
    EXPECT_EQ(w.asleep(heavy), w.asleep(light)) << "one island, tick " << t;
    if (w.asleep(heavy)) asleep_at = t;
  }
  ASSERT_GT(asleep_at, 0) << "never fell asleep";
  TickInput in;
  in.joints.push_back({w.defined_joints()[0], JointInputKind::motor_speed, {2.0, 0.0}});
  w.step(in);
  EXPECT_FALSE(w.asleep(heavy));
  EXPECT_FALSE(w.asleep(light));
  EXPECT_NE(w.body(light).angular_velocity, 0.0) << "the motor turns it";
}

// A tick of many joints stops within a second when asked: every joint sweep (20 velocity, 10
// of the tick's own error, 10 on positions at the defaults) polls a stop request first, so a
// request is seen within one sweep (a sweep of max_joints joints is a fraction of a second).
// Rigid distance joints (rows of their own, which always move) run every sweep; revolute
// joints solved at once end their sweeps when one moves nothing, and still poll each.
TEST(Joints, EveryJointSweepPollsAStopRequest) {
  for (const JointType type : {JointType::distance, JointType::revolute}) {
    detail::WorldKernel<double> w(shape_exact::shape_settings(0.6));
    Entity above{};
    for (int i = 0; i < 50; ++i) {
      const Entity box = w.create_body(shape_exact::box_body(0.05, 0.25, {0.0, -0.25 - 0.5 * i}));
      JointDef j{.type = type, .body_a = above, .body_b = box, .anchor = {0.0, -0.5 * i}};
      if (type == JointType::distance) j.anchor_b = Vec2{0.0, -0.5 * i - 0.25};
      w.create_joint(j, "link");
      above = box;
    }
    w.step();
    const std::uint64_t sweeps = ContactSettings::default_velocity_iterations +
                                 2 * ContactSettings::default_position_iterations;
    const std::uint64_t first = w.shape_world()->stop_polls();
    if (type == JointType::distance) {
      EXPECT_EQ(first, sweeps);
    } else {
      EXPECT_GT(first, 2U);
      EXPECT_LT(first, sweeps) << "the direct solve's sweeps end once one moves nothing";
    }
    request_stop(2);
    EXPECT_THROW(w.step(), StopRequested);
    clear_stop_request();
    w.step();
    // (the tick that threw stopped at its own first poll, before the joints)
    if (type == JointType::distance) {
      EXPECT_EQ(w.shape_world()->stop_polls(), 2 * sweeps);
    }
  }
}

/// A pile of ragdoll-like pairs: boxes hinged in twos with limits and a motor, falling on the
/// ground, for the determinism checks below.
WorldDef hinged_pile(int threads) {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.threads = threads;
  WorldDef def = WorldDef::empty(Precision::f64, s);
  def.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  for (int i = 0; i < 6; ++i) {
    const double x = 0.3 * (i % 3), y = 1.0 + 1.2 * i;
    const Entity a = def.add_body(shape_exact::box_body(0.4, 0.1, {x, y}, 0.1 * i));
    const Entity b = def.add_body(shape_exact::box_body(0.4, 0.1, {x + 0.8, y}, -0.1 * i));
    def.joints.push_back({.type = JointType::revolute,
                          .body_a = a,
                          .body_b = b,
                          .anchor = {x + 0.4, y},
                          .lower = -1.0,
                          .upper = 1.0,
                          .motor_speed = 0.5,
                          .max_motor_torque = 0.2});
  }
  return def;
}

TEST(Joints, StepToTheSameBitsAfterASnapshotAndOnTwoThreads) {
  World one(hinged_pile(1)), two(hinged_pile(2));
  WorldSnapshot snap;
  for (int t = 0; t < 90; ++t) {
    one.step(), two.step();
    if (t == 40) one.save(snap);
  }
  const std::uint64_t at90 = one.state_hash();
  EXPECT_EQ(two.state_hash(), at90);
  one.restore(snap);
  for (int t = 41; t < 90; ++t) one.step();
  EXPECT_EQ(one.state_hash(), at90);
}

}  // namespace
}  // namespace fixstep
