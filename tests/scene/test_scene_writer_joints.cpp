// The scene writer's joints (scene_joints.cpp, joints_text): every JointDef a [[joint]] table that
// loads back with the same fields bit for bit (read–write–read of a scene file, and a world of
// awkward values built in code, in both precisions); the one normalisation (a distance joint's
// anchor_b equal to its anchor reloads unset, as unset means the anchor); and the refusals (a
// body handle not of the definition, a field the type does not use, in the loader's words).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_writer.hpp"
#include "scene_writer_check.hpp"

namespace fixstep {
namespace scene_writer_joints_test {  // named: a unity batch shares anonymous namespaces

WorldDef reload(const WorldDef& def) {
  const Scene back = parse_scene(format_scene(def), "written.toml");
  EXPECT_TRUE(back.warnings.empty()) << back.warnings.front();
  return back.def;
}

/// A body with one shape.
BodyDef shaped(const char* name, BodyType type, Vec2 position, double mass = 1.0) {
  BodyDef b;
  b.name = name;
  b.type = type;
  b.body.position = position;
  if (type == BodyType::dynamic) b.body.mass = mass;
  b.shapes = {make_box(0.5, 0.25)};
  return b;
}

/// Every joint type, the world at either end, names that need escaping, numbers that need all
/// 17 digits or a sign on zero, limits at ±π, a break force of 0, an unset and a set end on B.
WorldDef joint_world(Precision precision) {
  const double third = 1.0 / 3.0, tiny = 1e-100;
  const double huge = precision == Precision::f32 ? 3.0e38 : 1e100;
  WorldDef def;
  def.precision = precision;
  def.settings.dt = 0.01;
  def.settings.track_dissipation = true;  // a scene's, always
  const Entity frame = def.add_body(shaped("frame", BodyType::static_body, {0.0, 5.0}));
  const Entity arm = def.add_body(shaped("arm \"q\"\n", BodyType::dynamic, {2.0, 5.0}, third));
  const Entity car = def.add_body(shaped("car", BodyType::dynamic, {0.0, 1.0}, 2.0));
  const Entity tyre = def.add_body(shaped("", BodyType::dynamic, {1.0, 0.5}));  // body3
  const Entity lift = def.add_body(shaped("lift", BodyType::kinematic, {5.0, 0.0}));
  def.joints = {
      {.type = JointType::revolute,
       .body_a = frame,
       .body_b = arm,
       .anchor = {third, -0.0},
       .lower = -std::numbers::pi,
       .upper = std::numbers::pi,
       .motor_speed = -0.0,
       .max_motor_torque = tiny,
       .frequency = third,
       .target = -third,
       .break_torque = huge,
       .collide_connected = true,
       .name = "hinge \"1\"\\"},
      {.type = JointType::prismatic,
       .body_b = car,
       .anchor = {-1e11, 1e11},
       .axis = {-0.0, third},
       .lower = -1e11,
       .upper = 0.0,
       .motor_speed = 1e100 > huge ? huge : 1e100,
       .max_motor_force = 0.1 + 0.2,
       .name = {}},
      {.type = JointType::weld, .body_a = arm, .body_b = car, .name = "weld"},  // anchor [0, 0]
      {.type = JointType::distance,
       .body_a = frame,
       .body_b = arm,
       .anchor = {1.0, 2.0},  // anchor_b unset: the same point
       .length = third,
       .name = {}},
      {.type = JointType::distance,
       .body_b = arm,
       .anchor = {0.0, 10.0},
       .anchor_b = Vec2{third, 5.0},
       .lower = -0.0,
       .upper = 7.0,
       .frequency = 2.0,
       .damping_ratio = 1.0,
       .name = {}},
      {.type = JointType::wheel,
       .body_a = car,
       .body_b = tyre,
       .anchor = {1.0, 0.5},
       .axis = {0.0, 1.0},
       .lower = -0.25,
       .upper = 0.25,
       .motor_speed = 10.0,
       .max_motor_torque = 20.0,
       .frequency = 4.0,
       .damping_ratio = 0.7,
       .target = -0.1,
       .break_force = 0.0,
       .name = {}},
      {.type = JointType::motor,
       .body_a = lift,
       .body_b = car,
       .max_motor_torque = 5.0,
       .max_motor_force = 100.0,
       .break_force = std::nextafter(1.0, 2.0),
       .name = {}},
  };
  return def;
}

TEST(SceneWriterJoints, EveryTypeRoundTripsBitForBitInBothPrecisions) {
  for (const Precision precision : {Precision::f32, Precision::f64}) {
    SCOPED_TRACE(precision_name(precision));
    const WorldDef def = joint_world(precision);
    const WorldDef back = reload(def);
    WorldDef expected = def;
    expected.bodies[3].name = "body3";  // the name the writer gives an unnamed body
    test::expect_same_world(expected, back);
    EXPECT_EQ(back.joints, def.joints);
    EXPECT_EQ(definition_hash(back), definition_hash(def));
    EXPECT_EQ(format_scene(back), format_scene(def));  // a written scene writes itself again
  }
  const std::string text = format_scene(joint_world(Precision::f64));
  // The world's end is no key; bodies go by the writer's names; -0.0 keeps its sign.
  EXPECT_NE(text.find("[[joint]]\ntype = \"prismatic\"\nbody_b = \"car\"\nanchor = "),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("body_b = \"arm \\\"q\\\"\\n\"\nname = \"hinge \\\"1\\\"\\\\\"\n"
                      "anchor = [0.3333333333333333, -0.0]\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("body_b = \"body3\"\n"), std::string::npos) << text;
  EXPECT_NE(text.find("motor_speed = -0.0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("break_force = 0.0\n"), std::string::npos) << text;
  // The weld's anchor at the origin is written (the loader's default is body_b's position).
  EXPECT_NE(text.find("type = \"weld\"\nbody_a = \"arm \\\"q\\\"\\n\"\nbody_b = \"car\"\nname = "
                      "\"weld\"\nanchor = [0.0, 0.0]\n"),
            std::string::npos)
      << text;
}

TEST(SceneWriterJoints, ASceneFileReadWrittenAndReadAgainIsTheSame) {
  const Scene first = parse_scene(R"([world]
dt = 0.01
[[body]]
name = "post"
type = "static"
position = [0.0, 5.0]
shape = { box = [0.1, 0.1] }
[[body]]
name = "bob"
mass = 1.0
position = [2.0, 5.0]
shape = { circle = 0.25 }
[[joint]]
type = "revolute"
body_a = "post"
body_b = "bob"
lower = -1.0
[[joint]]
type = "distance"
body_b = "bob"
anchor = [0.0, 8.0]
upper = 4.0
collide_connected = true
[[joint]]
type = "prismatic"
body_b = "bob"
axis = [1.0, 1.0]
break_force = 5.0
)",
                                  "first.toml");
  ASSERT_EQ(first.def.joints.size(), 3u);
  const WorldDef second = reload(first.def);
  test::expect_same_world(first.def, second);
  EXPECT_EQ(second.joints, first.def.joints);
}

TEST(SceneWriterJoints, AnEndOnBEqualToTheAnchorReloadsUnset) {
  WorldDef def = joint_world(Precision::f64);
  def.joints[4].anchor_b = def.joints[4].anchor;  // the same point as unset, written once
  const WorldDef back = reload(def);
  EXPECT_FALSE(back.joints[4].anchor_b.has_value());
  def.joints[4].anchor_b.reset();
  EXPECT_EQ(back.joints, def.joints);
  // -0.0 is not 0.0: kept.
  def.joints[4].anchor_b = Vec2{-0.0, 10.0};
  def.joints[4].anchor = Vec2{0.0, 10.0};
  EXPECT_EQ(reload(def).joints[4].anchor_b, def.joints[4].anchor_b);
}

std::string refusal(const WorldDef& def) {
  try {
    (void)format_scene(def);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "format_scene wrote it";
  return {};
}

TEST(SceneWriterJoints, RefusesWhatWouldNotLoadBack) {
  WorldDef stray = joint_world(Precision::f64);
  stray.joints[1].body_b = defined_entity(7);
  EXPECT_EQ(refusal(stray),
            "format_scene: joint[1]: body_b is body 8:1: it must be null (the world) or one of "
            "the 5 bodies (a handle WorldDef::add_body returned)");
  WorldDef stale = joint_world(Precision::f64);
  stale.joints[0].body_a = Entity{1, 2};  // slot 0, a later generation
  EXPECT_NE(refusal(stale).find("joint[0]: body_a is body 1:2"), std::string::npos);
  // A field the type does not use: written, and refused by the loader at its key.
  WorldDef axis = joint_world(Precision::f64);
  axis.joints[0].axis = {0.0, 1.0};
  EXPECT_NE(refusal(axis).find("joint[0].axis: a revolute joint does not use `axis`"),
            std::string::npos);
  WorldDef anchor = joint_world(Precision::f64);
  anchor.joints[6].anchor = {1.0, 0.0};
  EXPECT_NE(refusal(anchor).find("joint[6].anchor: a motor joint does not use `anchor`"),
            std::string::npos);
  WorldDef limit = joint_world(Precision::f64);
  limit.joints[2].upper = 1.0;
  EXPECT_NE(refusal(limit).find("joint[2].upper: a weld joint does not use `upper`"),
            std::string::npos);
  // Both ends the world, and values the loader refuses, in its words.
  WorldDef world = joint_world(Precision::f64);
  world.joints[2].body_a = world.joints[2].body_b = Entity{};
  EXPECT_NE(refusal(world).find("joint[2].body_b: missing (required): a joint needs a body"),
            std::string::npos);
  WorldDef negative = joint_world(Precision::f64);
  negative.joints[5].max_motor_torque = -1.0;
  EXPECT_NE(refusal(negative).find("joint[5].max_motor_torque: must be >= 0 N*m"),
            std::string::npos);
  WorldDef nan = joint_world(Precision::f64);
  nan.joints[3].length = std::nan("");
  EXPECT_NE(refusal(nan).find("joint[3].length: must be finite (got nan)"), std::string::npos);
}

}  // namespace scene_writer_joints_test
}  // namespace fixstep
