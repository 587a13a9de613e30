// A body's `mover = { ... }` (scene_mover.cpp): read from a scene file with its defaults, written
// back with every field bit for bit (read–write–read, and awkward values built in code, in both
// precisions), and refused at its key with the loader's words.
#include <gtest/gtest.h>

#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/mover.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_writer.hpp"
#include "scene_writer_check.hpp"

namespace fixstep {
namespace scene_writer_mover_test {  // named: a unity batch shares anonymous namespaces

constexpr const char* hero_scene = R"([world]
dt = 0.01
[[body]]
name = "hero"
type = "kinematic"
position = [0.0, 1.0]
mover = { step_height = 0.25, push_force = 150.0 }
shape = { capsule = [[0.0, -0.5], [0.0, 0.5]], radius = 0.3 }
)";

TEST(SceneWriterMover, ASceneFileReadWrittenAndReadAgainIsTheSame) {
  const Scene first = parse_scene(hero_scene, "hero.toml");
  ASSERT_TRUE(first.def.bodies[0].mover);
  const MoverDef& m = *first.def.bodies[0].mover;
  EXPECT_EQ(m.step_height, 0.25);
  EXPECT_EQ(m.push_force, 150.0);
  EXPECT_EQ(m.max_floor_angle, MoverDef{}.max_floor_angle);
  EXPECT_EQ(m.skin, MoverDef{}.skin);
  const std::string text = format_scene(first.def);
  const Scene second = parse_scene(text, "written.toml");
  test::expect_same_world(first.def, second.def);
  EXPECT_EQ(definition_hash(second.def), definition_hash(first.def));
  EXPECT_EQ(format_scene(second.def), text);
}

TEST(SceneWriterMover, AwkwardValuesRoundTripBitForBitInBothPrecisions) {
  for (const Precision precision : {Precision::f64, Precision::f32}) {
    WorldDef def;
    def.precision = precision;
    def.settings.dt = 0.01;
    def.settings.track_dissipation = true;  // a scene's, always
    BodyDef b;
    b.name = "hero";
    b.type = BodyType::kinematic;
    b.shapes = {make_capsule({0.0, -1.0 / 3.0}, {0.0, 1.0 / 3.0}, 0.1)};
    b.mover = MoverDef{.max_floor_angle = 1.0 / 7.0,
                       .step_height = 0.0,
                       .snap_distance = 1e-100,
                       .push_force = 1e30,
                       .skin = 1.0 / 30.0};
    (void)def.add_body(b);
    const Scene back = parse_scene(format_scene(def), "written.toml");
    test::expect_same_world(def, back.def);
    EXPECT_EQ(definition_hash(back.def), definition_hash(def));
  }
}

/// The loader's message for `mover` (an inline table's text) on the hero, or "".
std::string refusal(const std::string& mover, const std::string& type = "kinematic") {
  const std::string text = "[world]\ndt = 0.01\n[[body]]\ntype = \"" + type +
                           "\"\nmass = 1.0\nposition = [0.0, 1.0]\nmover = " + mover +
                           "\nshape = { capsule = [[0.0, -0.5], [0.0, 0.5]], radius = 0.3 }\n";
  try {
    (void)parse_scene(text, "bad.toml");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(SceneWriterMover, BadValuesAreRefusedAtTheirKeys) {
  EXPECT_NE(refusal("{ step_height = 0.3 }").find("body[0].mover.step_height"), std::string::npos);
  EXPECT_NE(refusal("{ skin = -1.0 }").find("body[0].mover.skin"), std::string::npos);
  EXPECT_NE(refusal("{ max_floor_angle = 2.0 }").find("body[0].mover.max_floor_angle"),
            std::string::npos);
  EXPECT_NE(refusal("{ push_force = nan }").find("body[0].mover.push_force"), std::string::npos);
  EXPECT_NE(refusal("{ snap_distance = -0.1 }").find("body[0].mover.snap_distance"),
            std::string::npos);
  const Scene unknown = parse_scene(
      "[world]\ndt = 0.01\n[[body]]\ntype = \"kinematic\"\nposition = [0.0, 1.0]\nmover = { "
      "jump = 1.0 }\nshape = { capsule = [[0.0, -0.5], [0.0, 0.5]], radius = 0.3 }\n",
      "unknown.toml");
  ASSERT_EQ(unknown.warnings.size(), 1u);  // an unknown key is a warning, as everywhere
  EXPECT_NE(unknown.warnings[0].find("body[0].mover.jump"), std::string::npos);
  EXPECT_NE(refusal("{}", "dynamic").find("kinematic"), std::string::npos);
  EXPECT_NE(refusal("1.0").find("body[0].mover"), std::string::npos);
  EXPECT_EQ(refusal("{}"), "");
}

}  // namespace scene_writer_mover_test
}  // namespace fixstep
