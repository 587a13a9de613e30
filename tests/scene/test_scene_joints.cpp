// Joints in scene files (scene_joints.cpp): each [[joint]] type read into the JointDef fields its
// type uses (joint.hpp), bodies by the handles WorldDef::add_body gives them and the world where
// one is left out, the anchors' defaults, the warnings, and each refusal at its file:line:column
// and key. Read at the WorldDef level (parse_scene): no World steps a joint here. (The writer's
// round trip: test_scene_writer.cpp.)
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep {
namespace scene_joints_test {  // named: a unity batch shares anonymous namespaces

/// Bodies 0 .. 4: a static post, a bob, a cart, a wheel (each with a shape) and a disc without
/// shapes; the [[joint]] tables follow.
const std::string bodies = R"([world]
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

[[body]]
name = "cart"
mass = 2.0
position = [0.0, 1.0]
shape = { box = [1.0, 0.25] }

[[body]]
name = "wheel"
mass = 0.5
position = [0.75, 0.5]
shape = { circle = 0.3 }

[[body]]
name = "ball"
mass = 1.0
position = [4.0, 0.0]
radius = 0.5
)";

const Entity post = defined_entity(0), bob = defined_entity(1), cart = defined_entity(2),
             wheel = defined_entity(3);

/// The 1-based line of the first line of `text` at or after line `from` that starts with
/// `needle`; 0 when there is none.
std::size_t line_of(const std::string& text, std::string_view needle, std::size_t from = 1) {
  std::size_t line = 1;
  for (std::size_t at = 0; at < text.size(); ++line) {
    if (line >= from && std::string_view(text).substr(at).starts_with(needle)) return line;
    const std::size_t end = text.find('\n', at);
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return 0;
}

TEST(SceneJoints, EachTypeFillsTheFieldsItUses) {
  const std::string text = bodies + R"(
[[joint]]
type = "revolute"
name = "hinge"
body_a = "post"
body_b = "bob"
anchor = [0.0, 5.0]
lower = -0.5
upper = 0.75
motor_speed = 2.0
max_motor_torque = 10
frequency = 1.0
damping_ratio = 0.5
target = 0.25
break_torque = 100.0
collide_connected = true

[[joint]]
type = "prismatic"
body_b = "cart"
anchor = [0.0, 1.0]
axis = [0.0, 2.0]
lower = -1.0
upper = 2.0
motor_speed = -0.5
max_motor_force = 50.0
target = 0.5
frequency = 3.0
break_force = 1000.0

[[joint]]
type = "weld"
body_a = "bob"
body_b = "cart"
frequency = 5.0
damping_ratio = 0.7

[[joint]]
type = "distance"
body_a = "post"
body_b = "bob"
length = 2.5
lower = 1.0
upper = 3.0
frequency = 2.0

[[joint]]
type = "distance"
body_b = "bob"
anchor = [0.0, 10.0]
upper = 5.0

[[joint]]
type = "wheel"
body_a = "cart"
body_b = "wheel"
axis = [0.0, 1.0]
frequency = 4.0
damping_ratio = 0.7
target = -0.1
lower = -0.2
upper = 0.2
motor_speed = 10.0
max_motor_torque = 20.0

[[joint]]
type = "motor"
body_a = "cart"
body_b = "bob"
max_motor_force = 100.0
max_motor_torque = 5.0
)";
  const Scene s = parse_scene(text, "j.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.def.joints.size(), 7u);
  const std::vector<JointDef> expected{
      {.type = JointType::revolute,
       .body_a = post,
       .body_b = bob,
       .anchor = {0.0, 5.0},
       .lower = -0.5,
       .upper = 0.75,
       .motor_speed = 2.0,
       .max_motor_torque = 10.0,
       .frequency = 1.0,
       .damping_ratio = 0.5,
       .target = 0.25,
       .break_torque = 100.0,
       .collide_connected = true,
       .name = "hinge"},
      {.type = JointType::prismatic,
       .body_b = cart,  // body_a: the world
       .anchor = {0.0, 1.0},
       .axis = {0.0, 2.0},  // as given (World keeps it as a unit vector)
       .lower = -1.0,
       .upper = 2.0,
       .motor_speed = -0.5,
       .max_motor_force = 50.0,
       .frequency = 3.0,
       .target = 0.5,
       .break_force = 1000.0,
       .name = {}},
      // anchor: body_b's position
      {.type = JointType::weld,
       .body_a = bob,
       .body_b = cart,
       .anchor = {0.0, 1.0},
       .frequency = 5.0,
       .damping_ratio = 0.7,
       .name = {}},
      // the ends: each body's position
      {.type = JointType::distance,
       .body_a = post,
       .body_b = bob,
       .anchor = {0.0, 5.0},
       .anchor_b = Vec2{2.0, 5.0},
       .length = 2.5,
       .lower = 1.0,
       .upper = 3.0,
       .frequency = 2.0,
       .name = {}},
      // a rope from the world: the end on B is B's position
      {.type = JointType::distance,
       .body_b = bob,
       .anchor = {0.0, 10.0},
       .anchor_b = Vec2{2.0, 5.0},
       .upper = 5.0,
       .name = {}},
      // anchor (the hub): body_b's position
      {.type = JointType::wheel,
       .body_a = cart,
       .body_b = wheel,
       .anchor = {0.75, 0.5},
       .axis = {0.0, 1.0},
       .lower = -0.2,
       .upper = 0.2,
       .motor_speed = 10.0,
       .max_motor_torque = 20.0,
       .frequency = 4.0,
       .damping_ratio = 0.7,
       .target = -0.1,
       .name = {}},
      // no anchor: the motor joint drives B's centre
      {.type = JointType::motor,
       .body_a = cart,
       .body_b = bob,
       .max_motor_torque = 5.0,
       .max_motor_force = 100.0,
       .name = {}},
  };
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE(fmt::format("joint[{}] {}", i, joint_type_name(expected[i].type)));
    EXPECT_EQ(s.def.joints[i], expected[i]);
  }
  // The lines of the tables, and the handles are those WorldDef::add_body gives the bodies.
  std::vector<std::size_t> lines;
  for (std::size_t from = 1; (from = line_of(text, "[[joint]]", from)) != 0; ++from) {
    lines.push_back(from);
  }
  EXPECT_EQ(s.source.joint_lines, lines);
  WorldDef def;
  for (std::size_t i = 0; i < s.def.bodies.size(); ++i) {
    EXPECT_EQ(def.add_body(s.def.bodies[i]), defined_entity(i));
  }
}

TEST(SceneJoints, DefaultsForAnchorAxisAndAnUnsetEndOnB) {
  const Scene s = parse_scene(bodies + R"(
[[joint]]
type = "revolute"
body_a = "bob"

[[joint]]
type = "prismatic"
body_a = "post"
body_b = "cart"

[[joint]]
type = "distance"
body_a = "bob"
anchor = [1.0, 2.0]
anchor_b = [1.0, 2.0]
length = 1.0
)",
                              "d.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.def.joints.size(), 3u);
  // body_b left out (the world): the anchor is body_a's position.
  EXPECT_EQ(s.def.joints[0], (JointDef{.body_a = bob, .anchor = {2.0, 5.0}, .name = {}}));
  // body_b's position; the axis JointDef's [1, 0].
  EXPECT_EQ(s.def.joints[1], (JointDef{.type = JointType::prismatic,
                                       .body_a = post,
                                       .body_b = cart,
                                       .anchor = {0.0, 1.0},
                                       .axis = {1.0, 0.0},
                                       .name = {}}));
  // An end on B equal to the anchor is left unset, as JointDef's unset means the anchor.
  EXPECT_FALSE(s.def.joints[2].anchor_b.has_value());
  EXPECT_EQ(s.def.joints[2].anchor, (Vec2{1.0, 2.0}));
  // No [[joint]] table: no joints.
  EXPECT_TRUE(parse_scene(bodies, "n.toml").def.joints.empty());
}

TEST(SceneJoints, WarningsAtTheirKeys) {
  const std::string text = bodies + R"(
[[joint]]
type = "revolute"
body_b = "bob"
anchr = [0.0, 5.0]

[[joint]]
type = "weld"
body_a = "bob"
body_b = "cart"
damping_ratio = 0.5

[[joint]]
type = "revolute"
body_a = "post"
)";
  const Scene s = parse_scene(text, "w.toml");
  ASSERT_EQ(s.warnings.size(), 3u);
  EXPECT_EQ(s.warnings[0],
            fmt::format("w.toml:{}:1: joint[0].anchr: unknown key ignored (did you mean `anchor`?)",
                        line_of(text, "anchr")));
  EXPECT_EQ(s.warnings[1],
            fmt::format("w.toml:{}:17: joint[1].damping_ratio: does nothing without frequency > "
                        "0 (no spring)",
                        line_of(text, "damping_ratio")));
  EXPECT_EQ(s.warnings[2],
            fmt::format("w.toml:{}:10: joint[2].body_a: does nothing: \"post\" (static) and the "
                        "world are both immovable",
                        line_of(text, "body_a = \"post\"")));
  EXPECT_EQ(s.def.joints.size(), 3u);
}

/// One refusal: the joint table's text after `bodies`, the key the error names, a part of its
/// message, and the start of the line it points at (the table's header by default).
struct Refusal {
  std::string_view what;
  std::string table;
  std::string key;
  std::string message;
  std::string line_starts = "[[joint]]";
};

TEST(SceneJoints, EachRefusalNamesItsLineAndKey) {
  const std::vector<Refusal> cases{
      {"unknown body name", "type = \"revolute\"\nbody_b = \"bbo\"", "joint[0].body_b",
       "no body named \"bbo\" (did you mean \"bob\"?)", "body_b"},
      {"a body jointed to itself", "type = \"weld\"\nbody_a = \"bob\"\nbody_b = \"bob\"",
       "joint[0].body_b", "\"bob\" is also body_a: a joint joins two different bodies", "body_b"},
      {"both bodies omitted", "type = \"revolute\"\nanchor = [0.0, 0.0]", "joint[0].body_b",
       "missing (required): a joint needs a body"},
      {"a misspelt body_b with no body", "type = \"revolute\"\nbodyb = \"bob\"", "joint[0].body_b",
       "found `bodyb` — did you mean `body_b`?", "bodyb"},
      {"a body without shapes (a disc)", "type = \"revolute\"\nbody_b = \"ball\"",
       "joint[0].body_b",
       fmt::format("\"ball\" (line {}) has no shapes (a disc's radius is not one)",
                   line_of(bodies, "name = \"ball\"") - 1),
       "body_b"},
      {"a body name not a string", "type = \"revolute\"\nbody_a = 1", "joint[0].body_a",
       "expected a body name (a string), found an integer (1)", "body_a"},
      {"no type", "body_b = \"bob\"", "joint[0].type", "missing (required)"},
      {"unknown type", "type = \"revolut\"\nbody_b = \"bob\"", "joint[0].type",
       "unknown joint type \"revolut\"; did you mean \"revolute\"? (valid: revolute, prismatic, "
       "weld, distance, wheel, motor)",
       "type"},
      {"another engine's word for a type", "type = \"hinge\"\nbody_b = \"bob\"", "joint[0].type",
       "did you mean \"revolute\"?", "type"},
      {"type not a string", "type = 1\nbody_b = \"bob\"", "joint[0].type",
       "expected a string, found an integer (1)", "type"},
      {"axis on a revolute joint", "type = \"revolute\"\nbody_b = \"bob\"\naxis = [1.0, 0.0]",
       "joint[0].axis",
       "a revolute joint does not use `axis` (a key of prismatic, wheel joints); its keys are "
       "anchor, lower, upper, motor_speed, max_motor_torque, frequency, damping_ratio, target",
       "axis"},
      {"anchor on a motor joint", "type = \"motor\"\nbody_b = \"bob\"\nanchor = [0.0, 0.0]",
       "joint[0].anchor", "a motor joint does not use `anchor`", "anchor"},
      {"anchor_b on a revolute joint",
       "type = \"revolute\"\nbody_b = \"bob\"\nanchor_b = [0.0, 0.0]", "joint[0].anchor_b",
       "does not use `anchor_b` (a key of distance joints)", "anchor_b"},
      {"length on a weld joint", "type = \"weld\"\nbody_b = \"bob\"\nlength = 1.0",
       "joint[0].length", "a weld joint does not use `length`", "length"},
      {"limits on a weld joint", "type = \"weld\"\nbody_b = \"bob\"\nlower = 0.0", "joint[0].lower",
       "a weld joint does not use `lower`", "lower"},
      {"max_motor_force on a revolute joint",
       "type = \"revolute\"\nbody_b = \"bob\"\nmax_motor_force = 1.0", "joint[0].max_motor_force",
       "does not use `max_motor_force` (a key of prismatic, motor joints)", "max_motor_force"},
      {"max_motor_torque on a prismatic joint",
       "type = \"prismatic\"\nbody_b = \"bob\"\nmax_motor_torque = 1.0",
       "joint[0].max_motor_torque", "does not use `max_motor_torque`", "max_motor_torque"},
      {"target on a distance joint", "type = \"distance\"\nbody_b = \"bob\"\ntarget = 1.0",
       "joint[0].target", "a distance joint does not use `target`", "target"},
      {"frequency on a motor joint", "type = \"motor\"\nbody_b = \"bob\"\nfrequency = 1.0",
       "joint[0].frequency", "a motor joint does not use `frequency`", "frequency"},
      {"motor_speed on a distance joint",
       "type = \"distance\"\nbody_b = \"bob\"\nanchor = [0.0, 0.0]\nmotor_speed = 1.0",
       "joint[0].motor_speed", "a distance joint does not use `motor_speed`", "motor_speed"},
      {"lower > upper", "type = \"prismatic\"\nbody_b = \"cart\"\nlower = 1.0\nupper = -1.0",
       "joint[0].upper", "is below lower (1): the limits need lower <= upper (got -1)", "upper"},
      {"lower > upper, revolute", "type = \"revolute\"\nbody_b = \"bob\"\nupper = 0.1\nlower = 0.2",
       "joint[0].upper", "is below lower (0.2)", "upper"},
      {"a revolute upper limit beyond π", "type = \"revolute\"\nbody_b = \"bob\"\nupper = 3.2",
       "joint[0].upper", "must be within [-π, π] rad (the relative angle, wrapped) (got 3.2)",
       "upper"},
      {"a revolute lower limit below -π", "type = \"revolute\"\nbody_b = \"bob\"\nlower = -4",
       "joint[0].lower", "must be within [-π, π] rad", "lower"},
      {"a limit = nan", "type = \"revolute\"\nbody_b = \"bob\"\nlower = nan", "joint[0].lower",
       "must be finite (got nan)", "lower"},
      {"motor_speed = inf", "type = \"revolute\"\nbody_b = \"bob\"\nmotor_speed = inf",
       "joint[0].motor_speed", "must be finite (got inf)", "motor_speed"},
      {"an anchor of nan", "type = \"revolute\"\nbody_b = \"bob\"\nanchor = [nan, 0.0]",
       "joint[0].anchor[0]", "must be finite (got nan)", "anchor"},
      {"an anchor beyond 1e12 m", "type = \"revolute\"\nbody_b = \"bob\"\nanchor = [0.0, 2e12]",
       "joint[0].anchor[1]", "must be within +-1e+12 m", "anchor"},
      {"an anchor not [x, y]", "type = \"revolute\"\nbody_b = \"bob\"\nanchor = 1.0",
       "joint[0].anchor", "expected [x, y], found a float (1.0)", "anchor"},
      {"a number in quotes", "type = \"weld\"\nbody_b = \"bob\"\nfrequency = \"2\"",
       "joint[0].frequency", "expected a number, found a string (\"2\"); write the number",
       "frequency"},
      {"target not a number", "type = \"revolute\"\nbody_b = \"bob\"\ntarget = true",
       "joint[0].target", "expected a number, found a boolean (true)", "target"},
      {"collide_connected not a boolean",
       "type = \"revolute\"\nbody_b = \"bob\"\ncollide_connected = 1", "joint[0].collide_connected",
       "expected true or false, found an integer (1)", "collide_connected"},
      {"name not a string", "type = \"revolute\"\nbody_b = \"bob\"\nname = 3", "joint[0].name",
       "expected a string, found an integer (3)", "name"},
      {"negative max_motor_torque",
       "type = \"revolute\"\nbody_b = \"bob\"\nmax_motor_torque = -1.0",
       "joint[0].max_motor_torque", "must be >= 0 N*m (0: no motor) (got -1)", "max_motor_torque"},
      {"negative max_motor_force", "type = \"motor\"\nbody_b = \"bob\"\nmax_motor_force = -1.0",
       "joint[0].max_motor_force", "must be >= 0 N (0: no motor) (got -1)", "max_motor_force"},
      {"negative frequency", "type = \"weld\"\nbody_b = \"bob\"\nfrequency = -1.0",
       "joint[0].frequency", "must be >= 0 Hz (0: no spring) (got -1)", "frequency"},
      {"negative damping_ratio",
       "type = \"weld\"\nbody_b = \"bob\"\nfrequency = 1.0\ndamping_ratio = -0.1",
       "joint[0].damping_ratio", "must be >= 0 (got -0.1)", "damping_ratio"},
      {"negative break_force", "type = \"weld\"\nbody_b = \"bob\"\nbreak_force = -1.0",
       "joint[0].break_force", "must be >= 0 N (got -1)", "break_force"},
      {"negative break_torque", "type = \"weld\"\nbody_b = \"bob\"\nbreak_torque = -1.0",
       "joint[0].break_torque", "must be >= 0 N*m (got -1)", "break_torque"},
      {"negative length", "type = \"distance\"\nbody_b = \"bob\"\nbody_a = \"post\"\nlength = -1.0",
       "joint[0].length", "must be > 0 m (got -1)", "length"},
      {"length = 0", "type = \"distance\"\nbody_b = \"bob\"\nbody_a = \"post\"\nlength = 0.0",
       "joint[0].length", "must be > 0 m (got 0)", "length"},
      {"a negative distance limit",
       "type = \"distance\"\nbody_b = \"bob\"\nbody_a = \"post\"\nlower = -0.5", "joint[0].lower",
       "must be >= 0 m (a distance) (got -0.5)", "lower"},
      {"a rigid distance joint whose ends coincide",
       "type = \"distance\"\nbody_a = \"post\"\nbody_b = \"bob\"\nanchor = [2.0, 5.0]",
       "joint[0].anchor",
       "both ends are at (2, 5) m: a rigid distance joint would hold them at a "
       "length of 0",
       "anchor"},
      {"a distance joint's end on the world not given", "type = \"distance\"\nbody_a = \"bob\"",
       "joint[0].anchor_b",
       "missing (required where that end is the world): the joint's end on B (the world)"},
      {"a zero axis", "type = \"prismatic\"\nbody_b = \"cart\"\naxis = [0.0, -0.0]",
       "joint[0].axis", "must be a non-zero vector (got [0, -0])", "axis"},
      {"a wheel without frequency", "type = \"wheel\"\nbody_a = \"cart\"\nbody_b = \"wheel\"",
       "joint[0].frequency",
       "missing (required for a wheel joint): the suspension's frequency in Hz, > 0"},
      {"a wheel with frequency = 0",
       "type = \"wheel\"\nbody_a = \"cart\"\nbody_b = \"wheel\"\nfrequency = 0.0",
       "joint[0].frequency",
       "must be > 0 Hz for a wheel joint (its suspension is a spring) (got 0)", "frequency"},
  };
  for (const Refusal& c : cases) {
    SCOPED_TRACE(c.what);
    const std::string text = bodies + "\n[[joint]]\n" + c.table + "\n";
    const std::size_t header = line_of(text, "[[joint]]");
    try {
      (void)parse_scene(text, "r.toml");
      ADD_FAILURE() << "loaded";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), c.key) << e.what();
      EXPECT_EQ(e.line(), line_of(text, c.line_starts, header)) << e.what();
      EXPECT_GT(e.column(), 0u);
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(fmt::format("r.toml:{}:", e.line()), 0), 0u)
          << e.what();
    }
  }
}

TEST(SceneJoints, TheSecondTableIsNamedByItsIndex) {
  const std::string text = bodies + R"(
[[joint]]
type = "revolute"
body_b = "bob"

[[joint]]
type = "revolute"
body_b = "bob"
upper = 4.0
)";
  try {
    (void)parse_scene(text, "i.toml");
    ADD_FAILURE() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "joint[1].upper");
    EXPECT_EQ(e.line(), line_of(text, "upper"));
  }
}

TEST(SceneJoints, RefusesASingleTableAndMoreThanMaxJoints) {
  try {
    (void)parse_scene(bodies + "\n[joint]\ntype = \"weld\"\n", "one.toml");
    ADD_FAILURE() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "joint");
    EXPECT_NE(std::string(e.what()).find("expected [[joint]] tables, found a single [joint]"),
              std::string::npos)
        << e.what();
  }
  // 10^6 + 1 inline tables fit in a scene's 4 MiB ({} and a comma each): refused by their
  // number before any is read.
  // (A root key, so before [world].)
  std::string text = "joint = [";
  text.reserve(3 * (max_joints + 1) + 16 + bodies.size());
  for (std::size_t i = 0; i <= max_joints; ++i) text += "{},";
  text += "]\n" + bodies;
  ASSERT_LE(text.size(), max_scene_bytes);
  try {
    (void)parse_scene(text, "many.toml");
    ADD_FAILURE() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "joint");
    EXPECT_EQ(e.line(), 1u);
    EXPECT_NE(std::string(e.what()).find(
                  "the scene has 1000001 joints; at most 1000000 are allowed (max_joints)"),
              std::string::npos)
        << e.what();
  }
}

// The example of docs/SCENES.md, "Joints": a pendulum, a rope and a car's wheel.
TEST(SceneJoints, TheExampleInScenesMdLoads) {
  std::ifstream in(std::string(FIXSTEP_SOURCE_DIR) + "/docs/SCENES.md");
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string md = doc.str();
  const std::size_t section = md.find("## Joints: `[[joint]]`");
  ASSERT_NE(section, std::string::npos);
  const std::size_t begin = md.find("```toml\n", section) + 8;
  const std::size_t end = md.find("```\n", begin);
  ASSERT_LT(begin, end);
  const Scene s = parse_scene(md.substr(begin, end - begin), "SCENES.md");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.def.joints.size(), 3u);
  const JointDef &pendulum = s.def.joints[0], &rope = s.def.joints[1], &wheel = s.def.joints[2];
  EXPECT_EQ(pendulum.type, JointType::revolute);
  EXPECT_EQ(pendulum.name, "pendulum");
  EXPECT_TRUE(pendulum.body_a.is_null());
  EXPECT_EQ(rope.type, JointType::distance);
  EXPECT_EQ(rope.anchor_b, (Vec2{6.0, 2.3}));
  EXPECT_FALSE(rope.lower.has_value());
  EXPECT_EQ(rope.upper, 4.0);
  EXPECT_EQ(wheel.type, JointType::wheel);
  EXPECT_EQ(wheel.anchor, s.def.bodies[3].body.position);  // the hub: rear_wheel's position
  EXPECT_EQ(wheel.frequency, 4.0);
}

}  // namespace scene_joints_test
}  // namespace fixstep
