// Scene files: the documented schema loads; every malformed file names file, line and key.
#include <gtest/gtest.h>

#include <cctype>
#include <ostream>
#include <string>
#include <string_view>

#include "fixstep/scene.hpp"

namespace fixstep {
namespace {

constexpr const char* minimal = R"([world]
dt = 0.01                          # s, fixed physics step
integrator = "semi_implicit_euler" # or "explicit_euler"
precision = "f32"                  # or "f64"

[[body]]
name = "bob"
mass = 1.0                         # kg
position = [1000.0, 0.0]           # m
velocity = [0.0, 0.0]              # m/s
spring = { anchor = [0.0, 0.0], stiffness = 15.0, damping = 0.1 }  # N/m, N*s/m
# force = [10.0, 0.0]              # N, constant
)";

TEST(Scene, TheDocumentedSchemaLoads) {
  const Scene s = parse_scene(minimal, "minimal.toml");
  EXPECT_EQ(s.world.dt, 0.01);
  EXPECT_EQ(s.world.integrator, Integrator::semi_implicit_euler);
  EXPECT_EQ(s.precision, Precision::f32);
  ASSERT_EQ(s.bodies.size(), 1u);
  const BodyDef& b = s.bodies[0];
  EXPECT_EQ(b.name, "bob");
  EXPECT_EQ(b.body.position, (Vec2{1000.0, 0.0}));
  ASSERT_TRUE(b.spring.has_value());
  EXPECT_EQ(b.spring->stiffness, 15.0);
  EXPECT_EQ(b.spring->damping, 0.1);
  EXPECT_FALSE(b.gravity || b.drag || b.constant_force);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(Scene, ShippedScenesLoadCleanly) {
  for (const char* name : {"default", "spring_damper", "projectile"}) {
    const Scene s = load_scene(std::string(FIXSTEP_SOURCE_DIR "/assets/scenes/") + name + ".toml");
    EXPECT_FALSE(s.bodies.empty()) << name;
    EXPECT_TRUE(s.warnings.empty()) << name << ": " << (s.warnings.empty() ? "" : s.warnings[0]);
  }
}

TEST(Scene, OptionalPartsAndDefaults) {
  const Scene s = parse_scene(R"([world]
dt = 0.02
[view]
center = [1, 2]
width = 30
[[body]]
mass = 2
position = [0, 0]
gravity = [0, -9.81]
drag = 0.5
force = [1, 0]
radius = 0.25
color = "#ff000080"
)", "opt.toml");
  EXPECT_EQ(s.precision, Precision::f64);  // default
  EXPECT_EQ(s.world.integrator, Integrator::semi_implicit_euler);
  EXPECT_EQ(s.bodies[0].name, "body0");
  EXPECT_EQ(s.bodies[0].appearance->color, (Rgba8{255, 0, 0, 128}));
  EXPECT_EQ(*s.view.width, 30.0);
  EXPECT_EQ(s.bodies[0].drag->coefficient, 0.5);
}

struct Bad {
  const char* what;
  std::string_view text;
  std::size_t line;
  const char* key;      // expected SceneError::key()
  const char* message;  // expected to appear in what()
};

void PrintTo(const Bad& bad, std::ostream* os) { *os << bad.what; }


class MalformedScene : public ::testing::TestWithParam<Bad> {};

TEST_P(MalformedScene, ErrorNamesFileLineAndKey) {
  const Bad& bad = GetParam();
  try {
    (void)parse_scene(bad.text, "bad.toml");
    FAIL() << bad.what << ": accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), "bad.toml");
    EXPECT_EQ(e.line(), bad.line) << e.what();
    EXPECT_EQ(e.key(), bad.key) << e.what();
    const std::string what = e.what();
    EXPECT_NE(what.find(bad.message), std::string::npos) << what;
    const std::string where = bad.line ? "bad.toml:" + std::to_string(bad.line) + ":" : "bad.toml: ";
    EXPECT_EQ(what.rfind(where, 0), 0u) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Scene, MalformedScene,
    ::testing::Values(
        Bad{"syntax", "[world]\ndt = 0.01\nintegrator = \n", 3, "", "TOML syntax error"},
        Bad{"missing world", "[[body]]\nmass = 1\nposition = [0, 0]\n", 1, "world", "missing [world]"},
        Bad{"missing dt", "[world]\nintegrator = \"explicit_euler\"\n[[body]]\nmass = 1\nposition = [0,0]\n",
            1, "world.dt", "missing"},
        Bad{"dt zero", "[world]\ndt = 0\n[[body]]\nmass = 1\nposition = [0,0]\n", 2, "world.dt", "> 0"},
        Bad{"dt nan", "[world]\ndt = nan\n[[body]]\nmass = 1\nposition = [0,0]\n", 2, "world.dt", "finite"},
        Bad{"dt string", "[world]\ndt = \"fast\"\n[[body]]\nmass = 1\nposition = [0,0]\n", 2,
            "world.dt", "expected a number, found a string"},
        Bad{"unknown integrator", "[world]\ndt = 0.01\nintegrator = \"verlett\"\n[[body]]\nmass = 1\nposition = [0,0]\n",
            3, "world.integrator", "valid: semi_implicit_euler, explicit_euler"},
        Bad{"unknown precision", "[world]\ndt = 0.01\nprecision = \"f16\"\n[[body]]\nmass = 1\nposition = [0,0]\n",
            3, "world.precision", "valid: f32, f64"},
        Bad{"no bodies", "[world]\ndt = 0.01\n", 1, "body", "at least one body"},
        Bad{"negative mass", "[world]\ndt = 0.01\n[[body]]\nmass = -1\nposition = [0, 0]\n", 4,
            "body[0].mass", "> 0 kg"},
        Bad{"missing position", "[world]\ndt = 0.01\n[[body]]\nmass = 1\n", 3, "body[0].position", "missing"},
        Bad{"vector length", "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0, 0]\n", 5,
            "body[0].position", "2 numbers"},
        Bad{"vector element type", "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, \"y\"]\n", 5,
            "body[0].position[1]", "expected a number"},
        Bad{"negative stiffness", "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n"
            "spring = { anchor = [0, 0], stiffness = -15.0 }\n", 6, "body[0].spring.stiffness", ">= 0 N/m"},
        Bad{"spring without stiffness", "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n"
            "spring = { anchor = [0, 0] }\n", 6, "body[0].spring.stiffness", "missing"},
        Bad{"negative drag", "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\ndrag = -0.1\n", 6,
            "body[0].drag", ">= 0"},
        Bad{"inf gravity", "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\ngravity = [0, -inf]\n", 6,
            "body[0].gravity[1]", "finite"},
        Bad{"bad color", "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\ncolor = \"red\"\n", 6,
            "body[0].color", "#rrggbb"},
        Bad{"duplicate names", "[world]\ndt = 0.01\n[[body]]\nname = \"a\"\nmass = 1\nposition = [0, 0]\n"
            "[[body]]\nname = \"a\"\nmass = 1\nposition = [1, 0]\n", 8, "body[1].name", "duplicate"},
        Bad{"f32 overflow", "[world]\ndt = 0.01\nprecision = \"f32\"\n[[body]]\nmass = 1\nposition = [1e39, 0]\n",
            6, "body[0].position[0]", "overflows"},
        Bad{"body not a table", "body = 3\n[world]\ndt = 0.01\n", 1, "body", "[[body]]"},
        Bad{"binary", std::string_view("[world]\0dt = 1", 14), 0, "", "binary"}),
    [](const ::testing::TestParamInfo<Bad>& info) {
      std::string name = info.param.what;
      for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });

TEST(Scene, UnknownKeysWarnWithASuggestion) {
  const Scene s = parse_scene(
      "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n"
      "spring = { anchor = [0, 0], stiffness = 1, dampng = 0.1 }\nvelocty = [1, 0]\n",
      "typo.toml");
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_NE(s.warnings[0].find("typo.toml:6:"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("did you mean `damping`?"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[1].find("body[0].velocty"), std::string::npos) << s.warnings[1];
  EXPECT_NE(s.warnings[1].find("did you mean `velocity`?"), std::string::npos) << s.warnings[1];
}

TEST(Scene, MissingFileAndDirectory) {
  EXPECT_THROW((void)load_scene("/nonexistent/scene.toml"), SceneError);
  try {
    (void)load_scene(FIXSTEP_SOURCE_DIR "/assets");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos);
  }
}

}  // namespace
}  // namespace fixstep

// Found by tests/fuzz: `substeps` was converted to int64 before its type was checked, undefined
// behaviour for a float beyond the int64 range (clang UBSan: "1e+30 is outside the range of
// representable values of type 'long'"). Any float is now refused by type, never converted.
TEST(Scene, FloatSubstepsAreRefusedByTypeWithoutConversion) {
  for (const char* value : {"1e30", "-1e30", "1e300", "2.0", "nan"}) {
    SCOPED_TRACE(value);
    try {
      (void)fixstep::parse_scene(std::string("[world]\ndt = 1\nsubsteps = ") + value +
                                     "\n[[body]]\nmass = 1\nposition = [0, 0]\n",
                                 "substeps.toml");
      FAIL() << "accepted";
    } catch (const fixstep::SceneError& e) {
      EXPECT_EQ(e.key(), "world.substeps");
      EXPECT_EQ(e.line(), 3u);
      EXPECT_NE(std::string(e.what()).find("expected an integer, found a float"),
                std::string::npos)
          << e.what();
    }
  }
}
