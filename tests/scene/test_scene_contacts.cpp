// Scene files, bodies that touch: [contacts], body types, the disc keys, the generators' discs,
// and the discs that overlap where they start (the loader's definitions, not the motion).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/disc_overlap.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_stability.hpp"
#include "fixstep/scene/scene_writer.hpp"
#include "scene_guard.hpp"

namespace fixstep {
namespace {
using test::enforce_stability;
using test::located_world;

/// [world] (lines 1-2), then `rest` from line 3.
std::string scene(std::string_view rest) {
  return "[world]\ndt = 0.01\n" + std::string(rest);
}

/// The SceneError parse_scene throws for text; fails the test when it loads.
SceneError error_of(const std::string& text) {
  try {
    (void)parse_scene(text, "c.toml");
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return SceneError("", 0, 0, "", "");
}

void expect_error(const std::string& text, std::size_t line, std::string_view key,
                  std::string_view message) {
  const SceneError e = error_of(text);
  EXPECT_EQ(e.line(), line) << e.what();
  EXPECT_EQ(e.key(), key) << e.what();
  EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
}

/// The warning of s that contains `part` (and "c.toml:LINE:"); fails when there is none.
std::string warning(const Scene& s, std::size_t line, std::string_view part) {
  for (const std::string& w : s.warnings) {
    if (w.find(part) != std::string::npos &&
        w.rfind("c.toml:" + std::to_string(line) + ":", 0) == 0) {
      return w;
    }
  }
  std::string all;
  for (const std::string& w : s.warnings) all += "\n  " + w;
  ADD_FAILURE() << "no warning at line " << line << " with \"" << part << "\" in:" << all;
  return {};
}

TEST(SceneContacts, ContactsTableFillsTheWorldSettings) {
  const std::string disc = "[[body]]\nmass = 1\nposition = [0, 0]\nradius = 0.5\n";
  const Scene on =
      parse_scene(scene("[contacts]\nrestitution = 0.5\nfriction = 0.3\n" + disc), "c.toml");
  ASSERT_TRUE(on.def.settings.contacts.has_value());
  EXPECT_EQ(on.def.settings.contacts->restitution, 0.5);
  EXPECT_EQ(on.def.settings.contacts->friction, 0.3);
  EXPECT_TRUE(on.warnings.empty()) << on.warnings[0];
  EXPECT_TRUE(on.def.settings.contacts.has_value());  // what Session and the CLI build
  const Scene defaults = parse_scene(scene("[contacts]\n" + disc), "c.toml");
  ASSERT_TRUE(defaults.def.settings.contacts.has_value());
  EXPECT_EQ(defaults.def.settings.contacts->restitution, 0.0);
  EXPECT_EQ(defaults.def.settings.contacts->friction, 0.0);
  EXPECT_FALSE(parse_scene(scene(disc), "c.toml").def.settings.contacts.has_value());
  EXPECT_EQ(defaults.def.settings.contacts->velocity_iterations,
            ContactSettings::default_velocity_iterations);
  EXPECT_EQ(defaults.def.settings.contacts->position_iterations,
            ContactSettings::default_position_iterations);
  // The resting solver's iteration counts; format_scene writes them back (it checks that the
  // text loads to the same definition hash, which includes them when not the defaults).
  const Scene fast = parse_scene(
      scene("[contacts]\nvelocity_iterations = 8\nposition_iterations = 0\n" + disc), "c.toml");
  EXPECT_EQ(fast.def.settings.contacts->velocity_iterations, 8);
  EXPECT_EQ(fast.def.settings.contacts->position_iterations, 0);
  const std::string text = format_scene(fast.def);
  EXPECT_NE(text.find("velocity_iterations = 8\nposition_iterations = 0\n"), std::string::npos)
      << text;
  EXPECT_EQ(format_scene(defaults.def).find("iterations"), std::string::npos);
}

TEST(SceneContacts, RestitutionThresholdFillsTheSettingsAndWritesBackWhenNotTheDefault) {
  const std::string disc = "[[body]]\nmass = 1\nposition = [0, 0]\nradius = 0.5\n";
  const Scene defaults = parse_scene(scene("[contacts]\n" + disc), "c.toml");
  EXPECT_EQ(defaults.def.settings.contacts->restitution_threshold, 1.0);  // Box2D's
  EXPECT_EQ(format_scene(defaults.def).find("restitution_threshold"), std::string::npos);
  const Scene gas = parse_scene(scene("[contacts]\nrestitution_threshold = 0\n" + disc), "c.toml");
  EXPECT_TRUE(gas.warnings.empty()) << gas.warnings[0];
  EXPECT_EQ(gas.def.settings.contacts->restitution_threshold, 0.0);
  const std::string text = format_scene(gas.def);  // checks the hash of what it wrote
  EXPECT_NE(text.find("restitution_threshold = 0.0\n"), std::string::npos) << text;
  EXPECT_NE(definition_hash(gas.def), definition_hash(defaults.def));
  EXPECT_EQ(definition_hash(parse_scene(text, "again.toml").def), definition_hash(gas.def));
}

TEST(SceneContacts, SleepKeysFillTheContactSettingsAndWriteBack) {
  const std::string disc = "[[body]]\nmass = 1\nposition = [0, 0]\nradius = 0.5\n";
  const Scene off = parse_scene(scene("[contacts]\n" + disc), "c.toml");
  EXPECT_FALSE(off.def.settings.contacts->sleep);
  EXPECT_EQ(off.def.settings.contacts->sleep_speed, ContactSettings::default_sleep_speed);
  EXPECT_EQ(off.def.settings.contacts->sleep_time, ContactSettings::default_sleep_time);
  EXPECT_EQ(format_scene(off.def).find("sleep"), std::string::npos);

  const Scene on = parse_scene(
      scene("[contacts]\nsleep = true\nsleep_speed = 0.02\nsleep_time = 1.25\n" + disc), "c.toml");
  EXPECT_TRUE(on.warnings.empty()) << on.warnings[0];  // known keys, no unknown-key warning
  const ContactSettings& c = *on.def.settings.contacts;
  EXPECT_TRUE(c.sleep);
  EXPECT_EQ(c.sleep_speed, 0.02);
  EXPECT_EQ(c.sleep_time, 1.25);
  EXPECT_NO_THROW((void)located_world(on));
  // Written and read back: the same settings and definition hash (format_scene checks the hash,
  // which holds the three keys with sleep on, so a key left out would throw there).
  const std::string text = format_scene(on.def);
  EXPECT_NE(text.find("sleep = true\nsleep_speed = 0.02\nsleep_time = 1.25\n"), std::string::npos)
      << text;
  const Scene again = parse_scene(text, "again.toml");
  EXPECT_TRUE(again.warnings.empty()) << again.warnings[0];
  EXPECT_TRUE(again.def.settings.contacts->sleep);
  EXPECT_EQ(again.def.settings.contacts->sleep_speed, 0.02);
  EXPECT_EQ(again.def.settings.contacts->sleep_time, 1.25);
  EXPECT_EQ(definition_hash(again.def), definition_hash(on.def));
  EXPECT_NE(definition_hash(again.def), definition_hash(off.def));

  // sleep = true with the default speed and time: only `sleep = true` is written.
  const Scene plain = parse_scene(scene("[contacts]\nsleep = true\n" + disc), "c.toml");
  EXPECT_TRUE(plain.def.settings.contacts->sleep);
  const std::string plain_text = format_scene(plain.def);
  EXPECT_NE(plain_text.find("sleep = true\n"), std::string::npos) << plain_text;
  EXPECT_EQ(plain_text.find("sleep_"), std::string::npos) << plain_text;
  EXPECT_TRUE(parse_scene(plain_text, "again.toml").def.settings.contacts->sleep);

  // sleep_time = 0 (asleep after one tick) is allowed.
  const Scene zero =
      parse_scene(scene("[contacts]\nsleep = true\nsleep_time = 0\n" + disc), "c.toml");
  EXPECT_EQ(zero.def.settings.contacts->sleep_time, 0.0);
  EXPECT_NE(format_scene(zero.def).find("sleep_time = 0.0\n"), std::string::npos);
}

TEST(SceneContacts, SleepTimeIsRefusedWhereTheWorldRefusesIt) {
  // dt = 0.5 s: 499999999.5 s is 999999999 ticks, the most the World takes; a quarter second
  // more rounds up to 1e9 ticks.
  auto text = [](std::string_view time) {
    return "[world]\ndt = 0.5\n[contacts]\nsleep = true\nsleep_time = " + std::string(time) +
           "\n[[body]]\nmass = 1\nposition = [0, 0]\nradius = 0.5\n";
  };
  const Scene most = parse_scene(text("499999999.5"), "c.toml");
  EXPECT_EQ(most.def.settings.contacts->sleep_time, 499999999.5);
  EXPECT_NO_THROW((void)located_world(most));
  expect_error(text("499999999.75"), 5, "contacts.sleep_time",
               "must be under 1e9 ticks of dt = 0.5 s (got 5e+08 s, 1e+09 ticks)");
  WorldDef over = most.def;
  over.settings.contacts->sleep_time = 499999999.75;
  EXPECT_THROW((void)World(over), std::invalid_argument);  // what the loader keeps out
}

TEST(SceneContacts, SleepSpeedAndTimeWithoutSleepWarnAtTheirKeys) {
  const std::string disc = "[[body]]\nmass = 1\nposition = [0, 0]\nradius = 0.5\n";
  for (const std::string_view sleep : {"", "sleep = false\n"}) {
    SCOPED_TRACE(sleep);
    const std::string keys = "sleep_speed = 0.1\nsleep_time = 2\n";
    const std::size_t first = sleep.empty() ? 4 : 5;
    const Scene s = parse_scene(scene("[contacts]\n" + std::string(sleep) + keys + disc), "c.toml");
    ASSERT_EQ(s.warnings.size(), 2u);
    const std::string w =
        warning(s, first,
                "contacts.sleep_speed: ignored: islands fall asleep only with sleep on; add "
                "sleep = true to [contacts], or remove it");
    EXPECT_EQ(w.rfind(fmt::format("c.toml:{}:15: ", first), 0), 0u) << w;  // at the value
    warning(s, first + 1, "contacts.sleep_time: ignored: islands fall asleep only with sleep on");
    // Still read and checked, as the rolling keys are without rolling.
    EXPECT_FALSE(s.def.settings.contacts->sleep);
    EXPECT_EQ(s.def.settings.contacts->sleep_speed, 0.1);
    EXPECT_EQ(s.def.settings.contacts->sleep_time, 2.0);
  }
  // With sleep = true they act, and nothing is said.
  EXPECT_TRUE(
      parse_scene(scene("[contacts]\nsleep = true\nsleep_speed = 0.1\nsleep_time = 2\n" + disc),
                  "c.toml")
          .warnings.empty());
}

TEST(SceneContacts, BodyTypesAndDiscKeysFillBodyDefAndCollider) {
  const Scene s = parse_scene(scene(R"([contacts]
[[body]]
name = "ball"
mass = 2
position = [0, 5]
radius = 0.5
restitution = 0.9
friction = 0.1
[[body]]
name = "peg"
type = "static"
position = [0, 0]
radius = 0.2
collide = false
[[body]]
name = "paddle"
type = "kinematic"
position = [3, 0]
velocity = [1, 0]
radius = 1
[[body]]
name = "plain"
type = "dynamic"
mass = 1
position = [9, 9]
radius = 0.5
)"),
                              "c.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
  ASSERT_EQ(s.def.bodies.size(), 4u);
  const BodyDef &ball = s.def.bodies[0], &peg = s.def.bodies[1], &paddle = s.def.bodies[2];
  EXPECT_EQ(ball.type, BodyType::dynamic);
  EXPECT_EQ(ball.collider->radius, 0.5);
  EXPECT_EQ(ball.collider->restitution, std::optional<double>(0.9));
  EXPECT_EQ(ball.collider->friction, std::optional<double>(0.1));
  EXPECT_TRUE(ball.collider->collide);
  EXPECT_EQ(peg.type, BodyType::static_body);
  EXPECT_FALSE(peg.collider->collide);
  EXPECT_FALSE(peg.collider->restitution || peg.collider->friction);  // the [contacts] default
  EXPECT_EQ(paddle.type, BodyType::kinematic);
  EXPECT_EQ(paddle.body.velocity, (Vec2{1.0, 0.0}));  // a kinematic body keeps its velocity
  EXPECT_EQ(s.def.bodies[3].type, BodyType::dynamic);
}

TEST(SceneContacts, StaticAndKinematicBodiesDropWhatWouldMoveThemWithAWarning) {
  const Scene s = parse_scene(scene(R"([[body]]
name = "wall"
type = "static"
mass = 5
position = [0, 0]
velocity = [1, 2]
spring = { anchor = [0, 0], stiffness = 10 }
gravity = [0, -9.81]
force = [1, 0]
drag = 0.5
[[body]]
name = "lift"
type = "kinematic"
mass = 3
position = [1, 0]
velocity = [0, 1]
gravity = [0, -9.81]
spring = { frequency = 2 }
)"),
                              "c.toml");
  const BodyDef &wall = s.def.bodies[0], &lift = s.def.bodies[1];
  EXPECT_FALSE(wall.spring || wall.gravity || wall.constant_force || wall.drag);
  EXPECT_EQ(wall.body.velocity, (Vec2{}));
  EXPECT_EQ(wall.body.mass, 1.0);  // the default: the mass given is ignored
  EXPECT_FALSE(lift.spring || lift.gravity);
  EXPECT_EQ(lift.body.velocity, (Vec2{0.0, 1.0}));
  EXPECT_EQ(s.warnings.size(), 9u);
  warning(s, 6, "body[0].mass: ignored: a static body has no mass (a static body never moves");
  warning(s, 8, "body[0].velocity: set to [0, 0]: a static body never moves (got [1, 2] m/s");
  warning(s, 9, "body[0].spring: ignored: a static body never moves");
  warning(s, 10, "body[0].gravity: ignored: a static body never moves");
  warning(s, 11, "body[0].force: ignored");
  warning(s, 12, "body[0].drag: ignored");
  warning(s, 16,
          "body[1].mass: ignored: a kinematic body has no mass (a kinematic body moves "
          "only at its velocity");
  warning(s, 19, "body[1].gravity: ignored: a kinematic body moves only at its velocity");
  warning(s, 20, "body[1].spring: ignored");
}

TEST(SceneContacts, ContactsWithoutDiscsAndSpringsBetweenAnchorsWarn) {
  const Scene s = parse_scene(scene(R"([contacts]
restitution = 0.5
[[body]]
name = "a"
type = "static"
position = [0, 0]
[[body]]
name = "b"
type = "kinematic"
position = [1, 0]
[[spring]]
bodies = ["a", "b"]
stiffness = 1
)"),
                              "c.toml");
  ASSERT_EQ(s.warnings.size(), 2u);
  warning(s, 3, "contacts: no body has a radius, so there are no discs to collide");
  warning(s, 14,
          "spring[0].bodies: does nothing: \"a\" (static) and \"b\" (kinematic) are both "
          "immovable");
  EXPECT_TRUE(s.def.settings.contacts.has_value());  // still on: code may add discs
}

TEST(SceneContacts, DiscCoefficientsWithoutContactsWarnAtTheirKeys) {
  const std::string bodies = R"([[body]]
mass = 1.0
position = [0, 0]
radius = 0.5
restitution = 0.9
[[body]]
mass = 1.0
position = [2, 0]
radius = 0.5
friction = 0.2
[[grid]]
columns = 2
rows = 1
origin = [0, 3]
spacing = [2, 0]
body = { mass = 1.0, radius = 0.5, restitution = 0.4, friction = 0.1 }
)";
  const Scene s = parse_scene(scene(bodies), "c.toml");
  ASSERT_EQ(s.warnings.size(), 4u);  // one per key written, not per generated body
  const std::string w = warning(s, 7, "body[0].restitution: ignored: it acts only in disc-disc");
  EXPECT_EQ(w.rfind("c.toml:7:15: ", 0), 0u) << w;  // line and column of the value
  EXPECT_NE(w.find("add [contacts]"), std::string::npos) << w;
  warning(s, 12, "body[1].friction: ignored");
  warning(s, 18, "grid[0].body.restitution: ignored");
  warning(s, 18, "grid[0].body.friction: ignored");
  // Still read: code that adds WorldSettings::contacts gets them.
  EXPECT_EQ(s.def.bodies[0].collider->restitution, 0.9);
  // With [contacts] they act, and nothing is said.
  EXPECT_TRUE(parse_scene(scene("[contacts]\n" + bodies), "c.toml").warnings.empty());
}

TEST(SceneContacts, FrequencyFormOfALinkToAnAnchorUsesTheDynamicMassAlone) {
  const Scene s = parse_scene(scene(R"([[body]]
name = "hook"
type = "static"
position = [0, 0]
[[body]]
name = "bob"
mass = 2
position = [0, -1]
[[spring]]
bodies = ["hook", "bob"]
frequency = 1.5
)"),
                              "c.toml");
  const double w = 2.0 * std::numbers::pi * 1.5;
  ASSERT_EQ(s.def.links.size(), 1u);
  EXPECT_DOUBLE_EQ(s.def.links[0].spring.stiffness, 2.0 * w * w);  // not the reduced mass 2/3
}

TEST(SceneContacts, TheStabilityGuardTakesAStaticEndAsAnAnchor) {
  // bob (1 kg) on k = 225 N/m to a static hook: ω·h = 15 · 0.1 = 1.5 < 2 (symplectic Euler).
  // Were the hook a free 1 kg body, ω = sqrt(k/μ) = 21.2 rad/s and ω·h = 2.12: refused.
  const std::string text = R"([world]
dt = 0.1
[[body]]
name = "hook"
type = "static"
position = [0, 0]
[[body]]
name = "bob"
mass = 1
position = [0, -1]
[[spring]]
bodies = ["hook", "bob"]
stiffness = 225
)";
  EXPECT_TRUE(enforce_stability(parse_scene(text, "c.toml")).empty());
  std::string free = text;
  free.replace(free.find("type = \"static\""), 15, "mass = 1");
  EXPECT_THROW((void)enforce_stability(parse_scene(free, "c.toml")), SceneError) << free;
}

TEST(SceneContacts, SensorAndFilterKeysFillTheColliderAndWriteBack) {
  const Scene s = parse_scene(scene(R"([contacts]
[[body]]
name = "bucket"
type = "kinematic"
position = [0, 0]
radius = 1
sensor = true
mask = 0x2
[[body]]
name = "ball"
mass = 1
position = [0, 5]
radius = 0.1
category = 0x2
mask = -1
group = -3
[[body]]
name = "marker"
type = "static"
position = [4, 0]
radius = 0.1
category = -9223372036854775808
visible = false
trail = false
trail_time = 2.5
)"),
                              "c.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
  const Collider &bucket = *s.def.bodies[0].collider, &ball = *s.def.bodies[1].collider;
  EXPECT_TRUE(bucket.sensor);
  EXPECT_EQ(bucket.filter.category, default_category);
  EXPECT_EQ(bucket.filter.mask, 2u);
  EXPECT_FALSE(ball.sensor);
  EXPECT_EQ(ball.filter.category, 2u);
  EXPECT_EQ(ball.filter.mask, all_categories);  // -1: every bit
  EXPECT_EQ(ball.filter.group, -3);
  EXPECT_EQ(s.def.bodies[2].collider->filter.category, std::uint64_t{1} << 63);
  const Appearance& marker = *s.def.bodies[2].appearance;
  EXPECT_FALSE(marker.visible);
  EXPECT_FALSE(marker.trail);
  EXPECT_EQ(marker.trail_time, 2.5);
  // Written and read back: the same definition (its hash holds the new keys).
  const Scene again = parse_scene(format_scene(s.def), "again.toml");
  EXPECT_EQ(definition_hash(again.def), definition_hash(s.def));
  EXPECT_EQ(again.def.bodies[2].collider->filter, s.def.bodies[2].collider->filter);
  EXPECT_FALSE(again.def.bodies[2].appearance->visible);
  EXPECT_EQ(again.def.bodies[2].appearance->trail_time, 2.5);
  // The hash tells a sensor from a disc and one filter from another.
  WorldDef other = s.def;
  other.bodies[0].collider->sensor = false;
  EXPECT_NE(definition_hash(other), definition_hash(s.def));
  other = s.def;
  other.bodies[1].collider->filter.group = 3;
  EXPECT_NE(definition_hash(other), definition_hash(s.def));
}

TEST(SceneContacts, FilterKeysWithoutContactsWarnAndASensorIsRefused) {
  const std::string disc = "[[body]]\nmass = 1\nposition = [0, 0]\nradius = 1\n";  // lines 3-6
  const Scene s = parse_scene(scene(disc + "category = 2\n"), "c.toml");
  warning(s, 7, "body[0].category: ignored: it acts only in disc-disc contacts");
  expect_error(scene(disc + "sensor = true\n"), 7, "body[0].sensor", "needs a [contacts] table");
}

struct BadKey {
  const char* what;
  std::string text;
  std::size_t line;
  const char* key;
  const char* message;
};

void PrintTo(const BadKey& b, std::ostream* os) {
  *os << b.what;
}

class MalformedContacts : public ::testing::TestWithParam<BadKey> {};

TEST_P(MalformedContacts, ErrorNamesLineKeyAndWhatIsAllowed) {
  expect_error(GetParam().text, GetParam().line, GetParam().key, GetParam().message);
}

const std::string body = "[[body]]\nmass = 1\nposition = [0, 0]\n";  // lines 3-5

INSTANTIATE_TEST_SUITE_P(
    SceneContacts, MalformedContacts,
    ::testing::Values(
        BadKey{"contacts restitution above 1", scene("[contacts]\nrestitution = 1.5\n" + body), 4,
               "contacts.restitution", "must be in [0, 1] (got 1.5)"},
        BadKey{"contacts restitution negative", scene("[contacts]\nrestitution = -0.1\n" + body), 4,
               "contacts.restitution", "must be in [0, 1] (got -0.1)"},
        BadKey{"contacts friction negative", scene("[contacts]\nfriction = -0.2\n" + body), 4,
               "contacts.friction", "must be >= 0 (got -0.2)"},
        BadKey{"contacts restitution_threshold negative",
               scene("[contacts]\nrestitution_threshold = -1\n" + body), 4,
               "contacts.restitution_threshold", "must be >= 0 m/s (got -1)"},
        BadKey{"contacts restitution_threshold nan",
               scene("[contacts]\nrestitution_threshold = nan\n" + body), 4,
               "contacts.restitution_threshold", "finite"},
        BadKey{"contacts velocity_iterations zero",
               scene("[contacts]\nvelocity_iterations = 0\n" + body), 4,
               "contacts.velocity_iterations", "must be 1 .. 1000 (got 0)"},
        BadKey{"contacts position_iterations a float",
               scene("[contacts]\nposition_iterations = 2.5\n" + body), 4,
               "contacts.position_iterations", "expected an integer, found a float"},
        BadKey{"contacts sleep not a boolean", scene("[contacts]\nsleep = 1\n" + body), 4,
               "contacts.sleep", "expected true or false, found an integer (1)"},
        BadKey{"contacts sleep a string", scene("[contacts]\nsleep = \"yes\"\n" + body), 4,
               "contacts.sleep", "expected true or false, found a string (\"yes\")"},
        BadKey{"contacts sleep_speed zero",
               scene("[contacts]\nsleep = true\nsleep_speed = 0\n" + body), 5,
               "contacts.sleep_speed", "must be > 0 m/s (got 0)"},
        BadKey{"contacts sleep_speed negative",
               scene("[contacts]\nsleep = true\nsleep_speed = -0.1\n" + body), 5,
               "contacts.sleep_speed", "must be > 0 m/s (got -0.1)"},
        BadKey{"contacts sleep_speed nan",
               scene("[contacts]\nsleep = true\nsleep_speed = nan\n" + body), 5,
               "contacts.sleep_speed", "must be finite (got nan)"},
        BadKey{"contacts sleep_speed inf",
               scene("[contacts]\nsleep = true\nsleep_speed = inf\n" + body), 5,
               "contacts.sleep_speed", "must be finite (got inf)"},
        BadKey{"contacts sleep_speed a string",
               scene("[contacts]\nsleep = true\nsleep_speed = \"0.1\"\n" + body), 5,
               "contacts.sleep_speed",
               "expected a number, found a string (\"0.1\"); write the number without quotes"},
        BadKey{"contacts sleep_speed zero without sleep",
               scene("[contacts]\nsleep_speed = 0\n" + body), 4, "contacts.sleep_speed",
               "must be > 0 m/s (got 0)"},
        BadKey{"contacts sleep_time negative",
               scene("[contacts]\nsleep = true\nsleep_time = -1\n" + body), 5,
               "contacts.sleep_time", "must be >= 0 s (got -1)"},
        BadKey{"contacts sleep_time nan",
               scene("[contacts]\nsleep = true\nsleep_time = nan\n" + body), 5,
               "contacts.sleep_time", "must be finite (got nan)"},
        BadKey{"contacts sleep_time inf",
               scene("[contacts]\nsleep = true\nsleep_time = inf\n" + body), 5,
               "contacts.sleep_time", "must be finite (got inf)"},
        BadKey{"contacts sleep_time a boolean",
               scene("[contacts]\nsleep = true\nsleep_time = true\n" + body), 5,
               "contacts.sleep_time", "expected a number, found a boolean (true)"},
        BadKey{"contacts sleep_time beyond 1e9 ticks",
               scene("[contacts]\nsleep = true\nsleep_time = 1e8\n" + body), 5,
               "contacts.sleep_time",
               "must be under 1e9 ticks of dt = 0.01 s (got 1e+08 s, 1e+10 ticks); give a "
               "shorter sleep_time"},
        BadKey{"contacts sleep_time beyond 1e9 ticks without sleep",
               scene("[contacts]\nsleep_time = 1e300\n" + body), 4, "contacts.sleep_time",
               "must be under 1e9 ticks of dt = 0.01 s (got 1e+300 s, 1e+302 ticks)"},
        BadKey{"contacts not a table", "contacts = 1\n" + scene(body), 1, "contacts",
               "expected a table, found an integer (1)"},
        BadKey{"body restitution above 1", scene(body + "radius = 1\nrestitution = 2\n"), 7,
               "body[0].restitution", "must be in [0, 1] (got 2)"},
        BadKey{"body friction negative", scene(body + "radius = 1\nfriction = -1\n"), 7,
               "body[0].friction", "must be >= 0 (got -1)"},
        BadKey{"body restitution nan", scene(body + "radius = 1\nrestitution = nan\n"), 7,
               "body[0].restitution", "must be finite"},
        BadKey{"restitution without radius", scene(body + "restitution = 0.5\n"), 6,
               "body[0].restitution", "needs a radius: only a disc"},
        BadKey{"friction without radius", scene(body + "friction = 0.5\n"), 6, "body[0].friction",
               "needs a radius"},
        BadKey{"collide without radius", scene(body + "collide = false\n"), 6, "body[0].collide",
               "needs a radius"},
        BadKey{"collide not a boolean", scene(body + "radius = 1\ncollide = \"no\"\n"), 7,
               "body[0].collide", "expected true or false, found a string (\"no\")"},
        BadKey{"radius zero", scene(body + "radius = 0\n"), 6, "body[0].radius",
               "must be > 0 m and <= 1e12 m (got 0)"},
        BadKey{"radius negative", scene(body + "radius = -1\n"), 6, "body[0].radius",
               "must be > 0 m and <= 1e12 m (got -1)"},
        BadKey{"radius beyond the state range", scene(body + "radius = 9e307\n"), 6,
               "body[0].radius", "must be > 0 m and <= 1e12 m (got 9e+307)"},
        BadKey{"radius inf", scene(body + "radius = inf\n"), 6, "body[0].radius", "must be finite"},
        BadKey{"unknown type", scene(body + "type = \"statc\"\n"), 6, "body[0].type",
               "unknown body type \"statc\"; did you mean \"static\"? (valid: dynamic, static, "
               "kinematic)"},
        BadKey{"unknown type, nothing close", scene(body + "type = \"ghost\"\n"), 6, "body[0].type",
               "unknown body type \"ghost\" (valid: dynamic, static, kinematic)"},
        BadKey{"type not a string", scene(body + "type = 1\n"), 6, "body[0].type",
               "expected a string, found an integer (1)"},
        BadKey{"dynamic body without mass",
               scene("[[body]]\ntype = \"dynamic\"\nposition = [0, 0]\n"), 3, "body[0].mass",
               "missing (required)"},
        BadKey{"template type misspelt",
               scene("[[grid]]\ncolumns = 2\nrows = 2\norigin = [0, 0]\nspacing = [1, 1]\n"
                     "body = { type = \"kinematik\", radius = 0.1 }\n"),
               8, "grid[0].body.type", "did you mean \"kinematic\"?"},
        BadKey{"sensor without radius", scene("[contacts]\n" + body + "sensor = true\n"), 7,
               "body[0].sensor", "needs a radius"},
        BadKey{"sensor not a boolean", scene("[contacts]\n" + body + "radius = 1\nsensor = 1\n"), 8,
               "body[0].sensor", "expected true or false, found an integer (1)"},
        BadKey{"category a float", scene("[contacts]\n" + body + "radius = 1\ncategory = 2.0\n"), 8,
               "body[0].category", "expected an integer, found a float"},
        BadKey{"mask a string", scene("[contacts]\n" + body + "radius = 1\nmask = \"all\"\n"), 8,
               "body[0].mask", "expected an integer, found a string"},
        BadKey{"group beyond int32",
               scene("[contacts]\n" + body + "radius = 1\ngroup = 3000000000\n"), 8,
               "body[0].group", "must be -2147483648 .. 2147483647"},
        BadKey{"trail_time zero", scene(body + "radius = 1\ntrail_time = 0\n"), 7,
               "body[0].trail_time", "must be > 0 and <= 10 s (got 0)"},
        BadKey{"trail_time too long", scene(body + "radius = 1\ntrail_time = 11\n"), 7,
               "body[0].trail_time", "must be > 0 and <= 10 s (got 11)"},
        BadKey{"visible not a boolean", scene(body + "visible = \"no\"\n"), 6, "body[0].visible",
               "expected true or false, found a string"},
        BadKey{"template restitution without radius",
               scene("[[chain]]\ncount = 2\nstart = [0, 0]\nspacing = [1, 0]\n"
                     "body = { mass = 1, restitution = 0.5 }\n"),
               7, "chain[0].body.restitution", "needs a radius"}),
    [](const ::testing::TestParamInfo<BadKey>& info) {
      std::string name = info.param.what;
      for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });

TEST(SceneContacts, UnknownKeysOfContactsWarnWithASuggestion) {
  const Scene s =
      parse_scene(scene("[contacts]\nrestitutoin = 0.5\n" + body + "radius = 1\n"), "c.toml");
  warning(s, 4, "contacts.restitutoin: unknown key ignored (did you mean `restitution`?)");
  const Scene u = parse_scene(
      scene("[contacts]\nslep = true\nsleep_sped = 0.1\n" + body + "radius = 1\n"), "c.toml");
  warning(u, 4, "contacts.slep: unknown key ignored (did you mean `sleep`?)");
  warning(u, 5, "contacts.sleep_sped: unknown key ignored (did you mean `sleep_speed`?)");
  const Scene t = parse_scene(scene(body + "radius = 1\ncolide = false\n"), "c.toml");
  warning(t, 7, "body[0].colide: unknown key ignored (did you mean `collide`?)");
}

}  // namespace
}  // namespace fixstep
