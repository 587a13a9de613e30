// Angular per-body input in input scripts (`torque`, `angular_impulse`, `angular_velocity`,
// `target_angle` in [[at]] tables, one number each): read into BodyInputs of their kind with
// the number in value.x and 0 in value.y, played by ScriptPlayer at their tick (a torque and an
// angular impulse for that tick only), and the located error of each bad entry, as data
// (TickInput values); and a world with shapes turned by a script, recorded, written as text,
// read back and replayed bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fixstep/core/components.hpp>
#include <fixstep/core/defined_bodies.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/core/shape.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/scene/input_script.hpp>
#include <fixstep/scene/scene.hpp>
#include <string>
#include <vector>

namespace fixstep {
namespace {

BodyDef angular_body(const char* name, BodyType type, bool shaped) {
  BodyDef b;
  b.name = name;
  b.type = type;
  if (shaped) b.shapes.push_back(ShapeDef{});  // a circle of 0.5 m
  return b;
}

// 0 wheel: dynamic with a shape; 1 flipper: kinematic with a shape; 2 ball: dynamic without
// shapes; 3 wall: static with a shape; 4 paddle: kinematic without shapes.
const std::vector<BodyDef> angular_bodies = {angular_body("wheel", BodyType::dynamic, true),
                                             angular_body("flipper", BodyType::kinematic, true),
                                             angular_body("ball", BodyType::dynamic, false),
                                             angular_body("wall", BodyType::static_body, true),
                                             angular_body("paddle", BodyType::kinematic, false)};

constexpr const char* angular_script_text = R"([[at]]
tick = 2
target_angle = { body = "flipper", value = 0.5 }
angular_velocity = { body = "flipper", value = 3 }
angular_impulse = [{ body = "wheel", value = -0.25 }, { body = "wheel", value = 1e-3 }]
torque = { body = "wheel", value = 5.0 }
impulse = { body = "ball", value = [1.0, 0.5] }
[[at]]
tick = 4
torque = { body = "wheel", value = -0.0 }
)";

TEST(ScriptAngularInput, EachKeyReadsAsItsKindWithItsNumberInX) {
  const InputScript script = parse_input_script(angular_script_text, "s.toml", angular_bodies);
  EXPECT_TRUE(script.warnings.empty());
  ASSERT_EQ(script.events.size(), 2u);
  const Entity wheel = defined_entity(0), flipper = defined_entity(1), ball = defined_entity(2);
  // In BodyInputKind order, each kind in file order.
  const std::vector<BodyInput> at2 = {{ball, BodyInputKind::impulse, {1.0, 0.5}},
                                      {wheel, BodyInputKind::torque, {5.0, 0.0}},
                                      {wheel, BodyInputKind::angular_impulse, {-0.25, 0.0}},
                                      {wheel, BodyInputKind::angular_impulse, {1e-3, 0.0}},
                                      {flipper, BodyInputKind::angular_velocity, {3.0, 0.0}},
                                      {flipper, BodyInputKind::target_angle, {0.5, 0.0}}};
  EXPECT_EQ(script.events[0].bodies, at2);
  ASSERT_EQ(script.events[1].bodies.size(), 1u);
  EXPECT_TRUE(std::signbit(script.events[1].bodies[0].value.x));  // -0.0 kept
  // Played: each at its tick only (the world keeps an angular velocity, not the sampler).
  const std::vector<TickInput> ticks = script_inputs(script, 6);
  for (std::uint64_t t : {0, 1, 3, 5}) EXPECT_TRUE(ticks[t].bodies.empty()) << t;
  ASSERT_EQ(ticks[2].bodies.size(), at2.size());
  for (const BodyInput& b : at2) {
    EXPECT_NE(std::find(ticks[2].bodies.begin(), ticks[2].bodies.end(), b), ticks[2].bodies.end())
        << body_input_kind_name(b.kind) << " " << b.value.x;
  }
  ASSERT_EQ(ticks[4].bodies.size(), 1u);
  EXPECT_EQ(ticks[4].bodies[0].kind, BodyInputKind::torque);
  EXPECT_TRUE(std::signbit(ticks[4].bodies[0].value.x));
}

std::string angular_error_of(const std::string& script) {
  try {
    (void)parse_input_script(script, "s.toml", angular_bodies);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(parsed)";
}

TEST(ScriptAngularInput, BadEntriesAreLocatedErrors) {
  const std::string at = "[[at]]\ntick = 3\n";
  EXPECT_EQ(angular_error_of(at + "torque = { body = \"flipper\", value = 1.0 }\n"),
            "s.toml:3:19: at[0].torque.body: \"flipper\" is a kinematic body: torque acts on "
            "dynamic bodies only (turn a kinematic one with angular_velocity or target_angle)");
  EXPECT_EQ(angular_error_of(at + "angular_impulse = { body = \"wall\", value = 1.0 }\n"),
            "s.toml:3:28: at[0].angular_impulse.body: \"wall\" is a static body: angular_impulse "
            "acts on dynamic bodies only");
  EXPECT_EQ(angular_error_of(at + "angular_velocity = { body = \"wheel\", value = 1.0 }\n"),
            "s.toml:3:29: at[0].angular_velocity.body: \"wheel\" is a dynamic body: "
            "angular_velocity is for kinematic bodies only (turn a dynamic one with "
            "angular_impulse or torque)");
  EXPECT_EQ(angular_error_of(at + "target_angle = { body = \"wall\", value = 1.0 }\n"),
            "s.toml:3:25: at[0].target_angle.body: \"wall\" is a static body: target_angle is for "
            "kinematic bodies only");
  EXPECT_EQ(angular_error_of(at + "torque = { body = \"ball\", value = 1.0 }\n"),
            "s.toml:3:19: at[0].torque.body: \"ball\" has no shapes: torque turns bodies with "
            "shapes only");
  EXPECT_EQ(angular_error_of(at + "target_angle = { body = \"paddle\", value = 1.0 }\n"),
            "s.toml:3:25: at[0].target_angle.body: \"paddle\" has no shapes: target_angle turns "
            "bodies with shapes only");
  EXPECT_EQ(angular_error_of(at + "torque = { body = \"wheel\", value = [1.0, 0.0] }\n"),
            "s.toml:3:36: at[0].torque.value: expected one number, not [x, y]: the torque in N*m "
            "(counter-clockwise positive), e.g. value = 5.0 (found an array of 2 elements)");
  EXPECT_EQ(angular_error_of(at + "angular_velocity = { body = \"flipper\", value = \"3\" }\n"),
            "s.toml:3:48: at[0].angular_velocity.value: expected a number, found a string "
            "(\"3\"); write the number without quotes: 3");
  EXPECT_EQ(angular_error_of(at + "angular_impulse = { body = \"wheel\", value = inf }\n"),
            "s.toml:3:45: at[0].angular_impulse.value: must be finite (got inf)");
  EXPECT_EQ(angular_error_of(at + "target_angle = [{ body = \"flipper\" }]\n"),
            "s.toml:3:17: at[0].target_angle[0].value: missing (required): the angle in rad "
            "reached at the tick's end, e.g. value = 0.5");
  EXPECT_EQ(angular_error_of(at + "torque = 5.0\n"),
            "s.toml:3:10: at[0].torque: expected { body = \"NAME\", value = NUMBER } or an array "
            "of them, found a float (5.0)");
  // A misspelt key is a warning naming the key meant, as elsewhere in scripts.
  const InputScript warned = parse_input_script(at + "torq = { body = \"wheel\", value = 1.0 }\n",
                                                "s.toml", angular_bodies);
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_EQ(warned.warnings[0],
            "s.toml:3:1: at[0].torq: unknown key ignored (did you mean "
            "`torque`?)");
}

// A wheel (dynamic, I = 2 kg·m²) and a flipper (kinematic), apart, no gravity: each turns by its
// script input only. dt = 0.01 s, semi-implicit Euler.
TEST(ScriptAngularInput, AScriptTurnsAWorldWithShapesAndItsRecordingReplaysBitForBit) {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef wheel = angular_body("wheel", BodyType::dynamic, true);
  wheel.body = {1.0, {0.0, 0.0}, {0.0, 0.0}};
  wheel.inertia = 2.0;
  BodyDef flipper = angular_body("flipper", BodyType::kinematic, true);
  flipper.body.position = {10.0, 0.0};
  def.bodies = {wheel, flipper};
  constexpr const char* turning = R"([[at]]
tick = 2
angular_impulse = { body = "wheel", value = 1.0 }
angular_velocity = { body = "flipper", value = 3.0 }
[[at]]
tick = 5
torque = { body = "wheel", value = 2.0 }
target_angle = { body = "flipper", value = 0.0 }
)";
  const InputScript script = parse_input_script(turning, "turn.toml", def.bodies);
  World sim = World(def);
  Recorder recorder(def, "code-built", 1);
  const Entity w = sim.defined_bodies()[0], f = sim.defined_bodies()[1];
  double flipper_at_5 = 1.0, flipper_before_5 = 0.0;
  for (const TickInput& in : script_inputs(script, 10)) {
    sim.check_input(in);  // nothing World::step would ignore
    if (in.tick == 5) flipper_before_5 = sim.body(f).angle;
    sim.step(in);
    recorder.record(in, sim);
    if (in.tick == 5) flipper_at_5 = sim.body(f).angle;
  }
  // The angular impulse L = 1 N·m·s on I = 2: Δω = 0.5 rad/s at tick 2; the torque 2 N·m for
  // tick 5 only: Δω = τ dt / I = 0.01 rad/s.
  EXPECT_NEAR(sim.body(w).angular_velocity, 0.51, 1e-12);
  // The flipper turns at 3 rad/s over ticks 2..4 (0.09 rad), reaches angle 0 at tick 5's end
  // and keeps the angular velocity that took it there.
  EXPECT_NEAR(flipper_before_5, 0.09, 1e-12);
  EXPECT_NEAR(flipper_at_5, 0.0, 1e-12);
  EXPECT_NEAR(sim.body(f).angular_velocity, -9.0, 1e-9);
  const Recording rec = recorder.finish(sim);
  const std::string text = format_recording(rec);
  EXPECT_NE(text.find("angular_impulse=1:1,1,0 angular_velocity=2:1,3,0\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("torque=1:1,2,0 target_angle=2:1,0,0\n"), std::string::npos) << text;
  const Recording back = parse_recording(text, "turn.rec");
  EXPECT_EQ(back, rec);
  EXPECT_TRUE(replay(def, back).ok());
  // Without the angular inputs the replay diverges at the first tick they act in.
  Recording still = back;
  for (TickInput& in : still.inputs) in.bodies.clear();
  const ReplayReport r = replay(def, still);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.mismatch->tick, 3u);
}

}  // namespace
}  // namespace fixstep
