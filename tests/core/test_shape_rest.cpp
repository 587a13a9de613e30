// The bodies a shape world's tick leaves alone (shape_rest.hpp): static bodies and sleepers,
// and the joints whose ends they all are. A large world steps to the same bits, events and
// sleep as the same world made to visit every body every tick, while its ticks visit only the
// bodies and joints that move.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "shape_exact.hpp"

namespace fixstep {
namespace {

constexpr int rest_tiles = 64;    // static, 1 m wide, their tops at y = 0
constexpr int rest_columns = 40;  // of two boxes each, 1.5 m apart, on the tiles

struct RestScene {
  WorldDef def;
  std::size_t shaped = 0;  // bodies with shapes
};

/// Static tiles under 40 columns of two boxes that settle and fall asleep; a static sensor
/// over the first columns; a kinematic box that reaches the pile at about 2.5 s, pushing
/// through the sleepers at 1 m/s; a box dropped from 8 m onto column 20, which lands at about
/// 1.2 s. 147 shapes: the resting lists' world (ShapeWorld::min_grid_shapes).
RestScene rest_scene() {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.contacts->sleep = true;
  s.contacts->sleep_time = 0.25;
  RestScene scene{WorldDef::empty(Precision::f64, s)};
  for (int i = 0; i < rest_tiles; ++i) {
    BodyDef t;
    t.type = BodyType::static_body;
    t.body.position = {i * 1.0, -0.5};
    t.shapes.push_back(make_box(0.5, 0.5));
    scene.def.add_body(t);
  }
  for (int c = 0; c < rest_columns; ++c) {
    for (int r = 0; r < 2; ++r) {
      scene.def.add_body(shape_exact::box_body(0.4, 0.25, {2.0 + 1.5 * c, 0.25 + 0.5 * r}));
    }
  }
  BodyDef sensor;
  sensor.type = BodyType::static_body;
  sensor.body.position = {4.0, 0.5};
  ShapeDef zone = make_box(3.0, 0.6);
  zone.sensor = true;
  sensor.shapes.push_back(zone);
  scene.def.add_body(sensor);
  BodyDef pusher = shape_exact::box_body(0.3, 0.3, {-1.0, 0.32});
  pusher.type = BodyType::kinematic;
  pusher.gravity.reset();
  pusher.body.velocity = {1.0, 0.0};
  scene.def.add_body(pusher);
  scene.def.add_body(shape_exact::box_body(0.4, 0.25, {2.0 + 1.5 * 20, 8.0}));
  scene.shaped = rest_tiles + 2 * rest_columns + 3;
  return scene;
}

// The reference visits every body every tick: an edit between ticks (a static tile's velocity
// set to zero, which changes nothing) makes the resting lists stale, and a stale tick gives
// every body its state and makes them again; and a restore of its own snapshot each tick
// forgets what the last lists made of each resting body (ShapeRest::Key), so that it makes
// every box and rotation afresh, where the lean world keeps those of the bodies that rested
// at its last lists and still do. At 2.5 s, as the pusher drives the first column,
// the tile under it rises 10 cm in both: a static body's edit, which the lean world's lists
// must take in (the column's lower box rises with it).
TEST(ShapeRest, ALargeWorldStepsAsOneThatVisitsEveryBodyWhileItsTicksVisitTheMovingOnes) {
  const RestScene scene = rest_scene();
  World lean(scene.def), full(scene.def);
  WorldSnapshot snapshot;
  const Entity tile = lean.defined_bodies()[0];
  const Entity under = lean.defined_bodies()[2];
  const Entity lower = lean.defined_bodies()[rest_tiles];  // the first column's
  std::size_t least_visited = scene.shaped, woken = 0, most_asleep = 0;
  for (int t = 1; t <= 360; ++t) {
    if (t == 150) {
      for (World* w : {&lean, &full}) w->set_position(under, {2.0, -0.4});
    }
    full.set_velocity(tile, {0.0, 0.0});
    full.save(snapshot), full.restore(snapshot);
    lean.step(), full.step();
    ASSERT_EQ(lean.state_hash(), full.state_hash()) << "tick " << t;
    const ContactStats& a = lean.contact_stats();
    const ContactStats& b = full.contact_stats();
    ASSERT_EQ(a.sleeping, b.sleeping) << "tick " << t;
    ASSERT_EQ(a.shape_points, b.shape_points) << "tick " << t;
    ASSERT_EQ(lean.sensor_overlaps().size(), full.sensor_overlaps().size()) << "tick " << t;
    EXPECT_EQ(b.shape_visited, scene.shaped) << "tick " << t;
    if (a.shape_visited != 0) least_visited = std::min(least_visited, a.shape_visited);
    if (t == 100) {  // every box asleep: the zone still holds the first four columns' eight
      EXPECT_EQ(lean.sensor_overlaps().size(), 8u) << "the sensor sees the sleepers in it";
    }
    if (t == 170) {
      EXPECT_NEAR(lean.body(lower).position.y, 0.35, 0.01) << "on the raised tile";
    }
    woken += a.woken, most_asleep = std::max(most_asleep, a.sleeping);
  }
  // What the run went through: every box asleep (the dropped one too), woken by the dropped
  // box and the pusher, and ticks that visited the pusher alone.
  EXPECT_EQ(most_asleep, 2u * rest_columns + 1);
  EXPECT_GT(woken, 0u);
  EXPECT_EQ(least_visited, 1u) << "the pusher alone, while every box sleeps";
}

constexpr int hinged_pairs = 34;  // of two boxes each, hinged where they meet, on the tiles

/// Static tiles under 34 pairs of boxes lying end to end, each pair hinged where its boxes
/// meet (revolute, within ±0.5 rad), that settle and fall asleep; a pendulum hinged to the
/// world at (-5, 5), released horizontal, that swings on awake; a box dropped from 8 m onto
/// pair 20, which lands at about 1.2 s. 134 shapes: the resting lists' world.
WorldDef hinged_scene() {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.contacts->sleep = true;
  s.contacts->sleep_time = 0.25;
  WorldDef def = WorldDef::empty(Precision::f64, s);
  for (int i = 0; i < rest_tiles; ++i) {
    BodyDef t;
    t.type = BodyType::static_body;
    t.body.position = {i * 1.0, -0.5};
    t.shapes.push_back(make_box(0.5, 0.5));
    def.add_body(t);
  }
  for (int p = 0; p < hinged_pairs; ++p) {
    const double x = 2.0 + 1.8 * p;
    const Entity a = def.add_body(shape_exact::box_body(0.4, 0.1, {x, 0.1}));
    const Entity b = def.add_body(shape_exact::box_body(0.4, 0.1, {x + 0.8, 0.1}));
    def.joints.push_back(
        JointDef{.body_a = a, .body_b = b, .anchor = {x + 0.4, 0.1}, .lower = -0.5, .upper = 0.5});
  }
  BodyDef bob = shape_exact::box_body(0.5, 0.1, {-4.5, 5.0});
  const Entity pendulum = def.add_body(bob);
  def.joints.push_back(JointDef{.body_b = pendulum, .anchor = {-5.0, 5.0}});
  def.add_body(shape_exact::box_body(0.4, 0.25, {2.0 + 1.8 * 20 + 0.4, 8.0}));
  return def;
}

// The reference visits every body every tick, as above. At 3 s both worlds hinge the
// pendulum's far end to the world too (a joint created between two ticks: a structural change,
// which wakes every island), which stops it; at 4 s they destroy its first hinge, the second
// taking its place in the world's list, and it swings again from the far end. Each hinge holds
// while it is there, and every pair's, asleep or woken, within its limits.
TEST(ShapeRest, JointsWhoseEndsRestAreLeftAloneWhileTheMovingOnesAreSolvedAsInAWorldVisitedWhole) {
  const WorldDef def = hinged_scene();
  World lean(def), full(def);
  WorldSnapshot snapshot;  // (as the test above: the reference forgets the keys)
  const Entity tile = lean.defined_bodies()[0];
  const Entity pendulum = lean.defined_bodies()[rest_tiles + 2 * hinged_pairs];
  std::size_t least_joints = hinged_pairs + 1, most_asleep = 0, woken = 0;
  double hinge_error = 0.0, pair_error = 0.0, past_limit = 0.0, still = 1.0;
  for (int t = 1; t <= 300; ++t) {
    if (t == 180) {
      for (World* w : {&lean, &full}) {
        const Vec2 far = w->body(pendulum).position * 2.0 - Vec2{-5.0, 5.0};
        w->create_joint(JointDef{.body_b = pendulum, .anchor = far});
      }
    }
    if (t == 240) {
      for (World* w : {&lean, &full}) w->destroy_joint(w->defined_joints()[hinged_pairs]);
    }
    full.set_velocity(tile, {0.0, 0.0});
    full.save(snapshot), full.restore(snapshot);
    lean.step(), full.step();
    ASSERT_EQ(lean.state_hash(), full.state_hash()) << "tick " << t;
    const ContactStats& a = lean.contact_stats();
    ASSERT_EQ(a.sleeping, full.contact_stats().sleeping) << "tick " << t;
    ASSERT_EQ(a.joint_visited, full.contact_stats().joint_visited) << "tick " << t;
    if (a.joint_visited != 0) least_joints = std::min(least_joints, a.joint_visited);
    for (const Joint j : lean.joints()) {
      const JointState s = lean.joint_state(j);
      const double error = std::hypot(s.anchor_a.x - s.anchor_b.x, s.anchor_a.y - s.anchor_b.y);
      const bool hinge = lean.joint(j).body_a.is_null();
      (hinge ? hinge_error : pair_error) = std::max(hinge ? hinge_error : pair_error, error);
      if (!hinge) past_limit = std::max(past_limit, std::abs(s.value) - 0.5);
    }
    if (t == 239)
      still = std::hypot(lean.body(pendulum).velocity.x, lean.body(pendulum).velocity.y);
    woken += a.woken, most_asleep = std::max(most_asleep, a.sleeping);
  }
  // What the run went through: every pair asleep (and the dropped box), woken by the box;
  // ticks that solved the pendulum's hinge alone; the pendulum asleep once it hung still from
  // both ends, woken as its first hinge went.
  EXPECT_EQ(most_asleep, 2u * hinged_pairs + 2);
  EXPECT_GT(woken, 0u);
  EXPECT_EQ(least_joints, 1u) << "the pendulum's hinge alone, while every pair sleeps";
  EXPECT_LT(hinge_error, 1e-6) << "m: a hinge to the world";
  EXPECT_LT(pair_error, 1e-3) << "m: a pair's hinge";
  EXPECT_LT(past_limit, 0.02) << "rad";
  EXPECT_LT(still, 1e-3) << "m/s: the pendulum hinged at both ends";
}

// A static body swapped for another of a new shape at the same pose (destroyed, and the new one
// created in its place, the last body both times): the same index and the same state bits as
// the one the resting lists last kept, so only the rebuild of the shapes tells the lists to
// make its box afresh (ShapeWorld::reshape). A box dropped onto it then lands on the new, taller
// top (y = 1.0), in the lean world as in one that forgets every tick.
TEST(ShapeRest, AStaticBodySwappedForAnotherShapeAtTheSamePoseIsBoxedAfresh) {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.contacts->sleep = true;
  WorldDef def = WorldDef::empty(Precision::f64, s);
  auto tile = [](double half_height) {
    BodyDef t;
    t.type = BodyType::static_body;
    t.body.position = {200.0, -0.5};
    t.shapes.push_back(make_box(0.5, half_height));
    return t;
  };
  for (int i = 0; i < 140; ++i) {  // the resting lists' world: tiles far from the drop
    BodyDef t = tile(0.5);
    t.body.position = {i * 1.0, -0.5};
    def.add_body(t);
  }
  def.add_body(tile(0.5));  // the one swapped, its top at y = 0, the last body
  World lean(def), full(def);
  WorldSnapshot snapshot;
  double top = 0.0;
  for (int t = 1; t <= 180; ++t) {
    if (t == 10) {
      for (World* w : {&lean, &full}) {
        w->destroy(w->defined_bodies().back());
        w->create_body(tile(1.5));  // the same centre: its top at y = 1.0
      }
    }
    if (t == 20) {
      for (World* w : {&lean, &full})
        w->create_body(shape_exact::box_body(0.25, 0.25, {200.0, 3.0}));
    }
    full.save(snapshot), full.restore(snapshot);
    lean.step(), full.step();
    ASSERT_EQ(lean.state_hash(), full.state_hash()) << "tick " << t;
    if (t == 180) top = lean.body(lean.bodies().back()).position.y;
  }
  EXPECT_NEAR(top, 1.25, 0.01) << "m: the dropped box's centre on the new top";
}

// Sleepers woken by input (an impulse up on one column's upper box, a torque on another's):
// the tick that wakes them makes the lists again from the bodies that woke and fell asleep
// alone (ShapeRest::flipped), and its passes give those bodies their state, which the input
// has just changed. Both move as in the reference, which makes the lists from every body.
TEST(ShapeRest, SleepersWokenByInputTakeTheirImpulseAndTorqueInALargeWorld) {
  const RestScene scene = rest_scene();
  World lean(scene.def), full(scene.def);
  WorldSnapshot snapshot;
  const Entity lifted = lean.defined_bodies()[rest_tiles + 2 * 30 + 1];
  const Entity turned = lean.defined_bodies()[rest_tiles + 2 * 35 + 1];
  double y0 = 0.0, a0 = 0.0;
  for (int t = 1; t <= 150; ++t) {
    TickInput in;
    if (t == 120) {
      ASSERT_TRUE(lean.asleep(lifted) && lean.asleep(turned)) << "asleep by 2 s";
      y0 = lean.body(lifted).position.y, a0 = lean.body(turned).angle;
      in.bodies.push_back(
          BodyInput{.body = lifted, .kind = BodyInputKind::impulse, .value = {0.0, 3.0}});
      in.bodies.push_back(
          BodyInput{.body = turned, .kind = BodyInputKind::torque, .value = {40.0, 0.0}});
    }
    full.save(snapshot), full.restore(snapshot);
    lean.step(in), full.step(in);
    ASSERT_EQ(lean.state_hash(), full.state_hash()) << "tick " << t;
    if (t == 126) {
      EXPECT_GT(lean.body(lifted).position.y - y0, 0.1) << "m: thrown up";
      EXPECT_GT(std::abs(lean.body(turned).angle - a0), 0.01) << "rad: turned";
    }
  }
}

}  // namespace
}  // namespace fixstep
