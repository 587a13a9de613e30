// Scene files: the documented schema loads; every malformed file names file, line and key.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"

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
  EXPECT_EQ(s.def.settings.dt, 0.01);
  EXPECT_EQ(s.def.settings.integrator, Integrator::semi_implicit_euler);
  EXPECT_EQ(s.def.precision, Precision::f32);
  ASSERT_EQ(s.def.bodies.size(), 1u);
  const BodyDef& b = s.def.bodies[0];
  EXPECT_EQ(b.name, "bob");
  EXPECT_EQ(b.body.position, (Vec2{1000.0, 0.0}));
  ASSERT_TRUE(b.spring.has_value());
  EXPECT_EQ(b.spring->stiffness, 15.0);
  EXPECT_EQ(b.spring->damping, 0.1);
  EXPECT_FALSE(b.gravity || b.drag || b.constant_force);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(Scene, ShippedScenesLoadCleanly) {
  for (const char* name :
       {"default", "spring_damper", "projectile", "rope", "soft_body", "cloth", "chain", "bounce",
        "ball_pit", "billiards", "newtons_cradle", "galton_board"}) {
    const Scene s = load_scene(std::string(FIXSTEP_SOURCE_DIR "/assets/scenes/") + name + ".toml");
    EXPECT_FALSE(s.def.bodies.empty()) << name;
    EXPECT_TRUE(s.warnings.empty()) << name << ": " << (s.warnings.empty() ? "" : s.warnings[0]);
  }
}

TEST(Scene, ChainSceneIsLinearWithDampingProportionalToStiffness) {
  // chain.toml promises an exact solution (exact::LinearNetwork): every spring, the anchored
  // one included, has rest length 0 and b = α k with one α, and no body has drag.
  const Scene s = load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/chain.toml");
  ASSERT_GE(s.def.bodies.size(), 5u);
  ASSERT_EQ(s.def.links.size(), s.def.bodies.size() - 1);
  ASSERT_TRUE(s.def.bodies[0].spring.has_value());
  const double alpha = s.def.bodies[0].spring->damping / s.def.bodies[0].spring->stiffness;
  EXPECT_GT(alpha, 0.0);
  EXPECT_EQ(s.def.bodies[0].spring->rest_length, 0.0);
  for (const BodyDef& b : s.def.bodies) EXPECT_FALSE(b.drag.has_value()) << b.name;
  for (const LinkDef& l : s.def.links) {
    EXPECT_EQ(l.spring.rest_length, 0.0);
    EXPECT_NEAR(l.spring.damping / l.spring.stiffness, alpha, 1e-12 * alpha);
    EXPECT_EQ(l.body_b.slot(), l.body_a.slot() + 1);  // a linear chain in body order
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
)",
                              "opt.toml");
  EXPECT_EQ(s.def.precision, Precision::f64);  // default
  EXPECT_EQ(s.def.settings.integrator, Integrator::semi_implicit_euler);
  EXPECT_EQ(s.def.bodies[0].name, "body0");
  EXPECT_EQ(s.def.bodies[0].appearance->color, (Rgba8{255, 0, 0, 128}));
  EXPECT_EQ(*s.view.width, 30.0);
  EXPECT_EQ(s.def.bodies[0].drag->coefficient, 0.5);
}

TEST(Scene, ViewAtItsBoundsLoads) {
  // The widest and narrowest views, and the narrowest view of a centre at the edge of the
  // runtime guard's range, are accepted as given.
  for (const auto& [center, width] : {std::pair{0.0, max_view_width},
                                      {0.0, min_view_width},
                                      {-max_view_center, min_view_width_ratio * max_view_center},
                                      {max_view_center, max_view_width}}) {
    const Scene s =
        parse_scene(fmt::format("[world]\ndt = 0.01\n[view]\ncenter = [{}, {}]\nwidth = {}\n"
                                "[[body]]\nmass = 1\nposition = [0, 0]\n",
                                center, -center, width),
                    "view.toml");
    EXPECT_EQ(s.view.center->x, center);
    EXPECT_EQ(s.view.center->y, -center);
    EXPECT_EQ(*s.view.width, width);
  }
}

struct Bad {
  const char* what;
  std::string text;
  std::size_t line;
  const char* key;      // expected SceneError::key()
  const char* message;  // expected to appear in what()
};

void PrintTo(const Bad& bad, std::ostream* os) {
  *os << bad.what;
}

/// Two bodies "a" (1 kg at the origin) and "b" (2 kg at [1, 0]), then one [[spring]] table
/// (line 11) with `spring_keys` from line 12.
std::string two_bodies(std::string_view spring_keys) {
  return "[world]\ndt = 0.01\n[[body]]\nname = \"a\"\nmass = 1\nposition = [0, 0]\n[[body]]\n"
         "name = \"b\"\nmass = 2\nposition = [1, 0]\n[[spring]]\n" +
         std::string(spring_keys);
}

/// [world], then a [[chain]] table (line 3) with `keys` from line 4.
std::string chain(std::string_view keys) {
  return "[world]\ndt = 0.01\n[[chain]]\n" + std::string(keys);
}

/// [world], then a columns x rows [[grid]] (line 3) of 1 kg bodies whose keys end on line 9.
std::string grid_tail(int columns, int rows) {
  return "[world]\ndt = 0.01\n[[grid]]\ncolumns = " + std::to_string(columns) +
         "\nrows = " + std::to_string(rows) +
         "\norigin = [0, 0]\nspacing = [1, -1]\nbody = { mass = 1 }\nlink = { stiffness = 1 }\n";
}

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
    const std::string where =
        bad.line ? "bad.toml:" + std::to_string(bad.line) + ":" : "bad.toml: ";
    EXPECT_EQ(what.rfind(where, 0), 0u) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Scene, MalformedScene,
    ::testing::Values(
        Bad{"syntax", "[world]\ndt = 0.01\nintegrator = \n", 3, "",
            "TOML syntax error in a `key = value` line: expected a value, found the end of the "
            "line; give a value after `integrator =`"},
        Bad{"missing world", "[[body]]\nmass = 1\nposition = [0, 0]\n", 1, "world",
            "missing [world] table (required): add [world] with dt, the fixed step in s"},
        Bad{"missing dt",
            "[world]\nintegrator = \"explicit_euler\"\n[[body]]\nmass = 1\nposition = [0,0]\n", 1,
            "world.dt", "missing (required): the fixed physics step in s, e.g. dt = 0.01"},
        Bad{"dt zero", "[world]\ndt = 0\n[[body]]\nmass = 1\nposition = [0,0]\n", 2, "world.dt",
            "> 0"},
        Bad{"dt nan", "[world]\ndt = nan\n[[body]]\nmass = 1\nposition = [0,0]\n", 2, "world.dt",
            "finite"},
        Bad{"dt string", "[world]\ndt = \"fast\"\n[[body]]\nmass = 1\nposition = [0,0]\n", 2,
            "world.dt", "expected a number, found a string (\"fast\")"},
        Bad{"unknown integrator",
            "[world]\ndt = 0.01\nintegrator = \"verlett\"\n[[body]]\nmass = 1\nposition = [0,0]\n",
            3, "world.integrator", "valid: semi_implicit_euler, explicit_euler"},
        Bad{"unknown precision",
            "[world]\ndt = 0.01\nprecision = \"f16\"\n[[body]]\nmass = 1\nposition = [0,0]\n", 3,
            "world.precision", "valid: f32, f64"},
        Bad{"no bodies", "[world]\ndt = 0.01\n", 1, "body",
            "at least one body; add one, e.g. [[body]] with mass = 1.0 and position = [0.0, 0.0]"},
        Bad{"negative mass", "[world]\ndt = 0.01\n[[body]]\nmass = -1\nposition = [0, 0]\n", 4,
            "body[0].mass", "> 0 kg"},
        Bad{"missing position", "[world]\ndt = 0.01\n[[body]]\nmass = 1\n", 3, "body[0].position",
            "missing (required): the starting position [x, y] in m, e.g. position = [0.0, 0.0]"},
        Bad{"vector length", "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0, 0]\n", 5,
            "body[0].position", "2 numbers"},
        Bad{"vector element type",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, \"y\"]\n", 5,
            "body[0].position[1]", "expected a number"},
        Bad{"negative stiffness",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n"
            "spring = { anchor = [0, 0], stiffness = -15.0 }\n",
            6, "body[0].spring.stiffness", ">= 0 N/m"},
        Bad{"spring without stiffness",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n"
            "spring = { anchor = [0, 0] }\n",
            6, "body[0].spring.stiffness", "missing"},
        Bad{"negative drag",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\ndrag = -0.1\n", 6,
            "body[0].drag", ">= 0"},
        Bad{"inf gravity",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\ngravity = [0, -inf]\n", 6,
            "body[0].gravity[1]", "finite"},
        Bad{"bad color",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\ncolor = \"red\"\n", 6,
            "body[0].color", "#rrggbb"},
        Bad{"duplicate names",
            "[world]\ndt = 0.01\n[[body]]\nname = \"a\"\nmass = 1\nposition = [0, 0]\n"
            "[[body]]\nname = \"a\"\nmass = 1\nposition = [1, 0]\n",
            8, "body[1].name", "duplicate"},
        Bad{"f32 overflow",
            "[world]\ndt = 0.01\nprecision = \"f32\"\n[[body]]\nmass = 1\nposition = [1e39, 0]\n",
            6, "body[0].position[0]",
            "1e+39 overflows precision = \"f32\" (largest float 3.40282e+38); use a smaller value, "
            "or precision = \"f64\" in [world]"},
        Bad{"body not a table", "body = 3\n[world]\ndt = 0.01\n", 1, "body",
            "expected [[body]] tables, found an integer (3)"},
        // --- the slips of a first scene file: the message says what to write instead ---
        Bad{"empty file", "", 0, "", "the scene file is empty (no tables or keys)"},
        Bad{"only comments", "# my first scene\n\n", 0, "", "the scene file is empty"},
        Bad{"[body] with single brackets",
            "[world]\ndt = 0.01\n[body]\nmass = 1\nposition = [0, 0]\n", 3, "body",
            "expected [[body]] tables, found a single [body] table; write [[body]] (double "
            "brackets) above each one"},
        Bad{"a number in quotes",
            "[world]\ndt = 0.01\n[[body]]\nmass = \"1.5\"\nposition = [0, 0]\n", 4, "body[0].mass",
            "expected a number, found a string (\"1.5\"); write the number without quotes: 1.5"},
        Bad{"arithmetic", "[world]\ndt = 1/60\n", 2, "",
            "TOML syntax error in a number: expected digit, found '/'; TOML has no arithmetic: "
            "write the number, e.g. dt = 0.016666666666666666"},
        Bad{"a bare word", "[world]\ndt = 0.01\nintegrator = rk4\n", 3, "",
            "TOML syntax error in a value: could not determine value type; text must be in "
            "quotes, e.g. \"rk4\""},
        Bad{"a vector in parentheses",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = (0, 0)\n", 5, "",
            "; write a vector in square brackets, e.g. [0.0, 1.0]"},
        Bad{"a colour without quotes",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\ncolor = #ff0000\n", 6, "",
            "; # starts a comment in TOML: put the colour in quotes, e.g. \"#ff0000\""},
        Bad{"a number without its leading zero", "[world]\ndt = .01\n", 2, "",
            "; TOML numbers need a digit before the point, e.g. 0.5"},
        Bad{"a recording given as the scene", "fixstep-recording 1\nscene x.toml\n", 0, "",
            "is a fixstep recording, not a scene file: replay it with `fixstep replay bad.toml`"},
        Bad{"integrator named in part",
            "[world]\ndt = 0.01\nintegrator = \"verlet\"\n[[body]]\nmass = 1\nposition = [0,0]\n",
            3, "world.integrator",
            "unknown integrator \"verlet\"; did you mean \"velocity_verlet\"?"},
        Bad{"binary", std::string("[world]\0dt = 1", 14), 0, "", "binary"},
        // --- springs between bodies, frequency form, generators ---
        Bad{"spring to an unknown body", two_bodies("bodies = [\"a\", \"bb\"]\nstiffness = 1\n"),
            12, "spring[0].bodies[1]", "no body named \"bb\" (did you mean \"b\"?)"},
        Bad{"spring to a body twice", two_bodies("bodies = [\"a\", \"a\"]\nstiffness = 1\n"), 12,
            "spring[0].bodies[1]", "\"a\" twice"},
        Bad{"spring bodies not two", two_bodies("bodies = [\"a\", \"b\", \"a\"]\nstiffness = 1\n"),
            12, "spring[0].bodies", "2 body names), found 3 elements"},
        Bad{"spring bodies a string", two_bodies("bodies = \"a\"\nstiffness = 1\n"), 12,
            "spring[0].bodies", "found a string"},
        Bad{"spring body not a string", two_bodies("bodies = [\"a\", 1]\nstiffness = 1\n"), 12,
            "spring[0].bodies[1]", "expected a body name (a string), found an integer"},
        Bad{"spring without bodies", two_bodies("stiffness = 1\n"), 11, "spring[0].bodies",
            "missing"},
        Bad{"spring without stiffness or frequency",
            two_bodies("bodies = [\"a\", \"b\"]\ndamping = 1\n"), 11, "spring[0].stiffness",
            "give stiffness (N/m) or frequency (Hz)"},
        Bad{"spring in both forms",
            two_bodies("bodies = [\"a\", \"b\"]\nstiffness = 1\nfrequency = 2\n"), 14,
            "spring[0].frequency", "`stiffness` and `frequency` both given"},
        Bad{"spring damping with damping_ratio",
            two_bodies("bodies = [\"a\", \"b\"]\ndamping_ratio = 0.1\ndamping = 1\n"), 13,
            "spring[0].damping_ratio", "`damping` and `damping_ratio` both given"},
        Bad{"damping_ratio without frequency",
            two_bodies("bodies = [\"a\", \"b\"]\ndamping_ratio = 0.1\n"), 11, "spring[0].frequency",
            "missing (required with damping_ratio): the natural frequency in Hz that "
            "damping_ratio ζ goes with, e.g. frequency = 2.0; or give stiffness and damping "
            "instead"},
        Bad{"frequency zero", two_bodies("bodies = [\"a\", \"b\"]\nfrequency = 0\n"), 13,
            "spring[0].frequency", "> 0 Hz"},
        Bad{"negative damping ratio",
            two_bodies("bodies = [\"a\", \"b\"]\nfrequency = 1\ndamping_ratio = -0.5\n"), 14,
            "spring[0].damping_ratio", ">= 0"},
        Bad{"nan frequency", two_bodies("bodies = [\"a\", \"b\"]\nfrequency = nan\n"), 13,
            "spring[0].frequency", "finite"},
        Bad{"negative link stiffness", two_bodies("bodies = [\"a\", \"b\"]\nstiffness = -1\n"), 13,
            "spring[0].stiffness", ">= 0 N/m"},
        Bad{"inf link damping",
            two_bodies("bodies = [\"a\", \"b\"]\nstiffness = 1\ndamping = inf\n"), 14,
            "spring[0].damping", "finite"},
        Bad{"negative link rest length",
            two_bodies("bodies = [\"a\", \"b\"]\nstiffness = 1\nrest_length = -1\n"), 14,
            "spring[0].rest_length", ">= 0 m"},
        Bad{"rest length between bodies at one point",
            "[world]\ndt = 0.01\n[[body]]\nname = \"a\"\nmass = 1\nposition = [1, 2]\n[[body]]\n"
            "name = \"b\"\nmass = 1\nposition = [1, 2]\n[[spring]]\nbodies = [\"a\", \"b\"]\n"
            "stiffness = 1\nrest_length = 0.5\n",
            14, "spring[0].rest_length", "both start at (1, 2) m"},
        Bad{"frequency overflowing a double",
            two_bodies("bodies = [\"a\", \"b\"]\nfrequency = 1e200\n"), 13, "spring[0].frequency",
            "beyond the range of a double; use a lower frequency"},
        Bad{"frequency overflowing f32",
            "[world]\ndt = 0.01\nprecision = \"f32\"\n[[body]]\nmass = 1\nposition = [0, 0]\n"
            "spring = { frequency = 1e19 }\n",
            7, "body[0].spring.frequency",
            "beyond the range of a float; use a lower frequency or precision = \"f64\" in [world]"},
        Bad{"body spring in both forms",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n"
            "spring = { stiffness = 1, damping_ratio = 0.2 }\n",
            6, "body[0].spring.damping_ratio", "`stiffness` and `damping_ratio` both given"},
        Bad{"[[spring]] not tables",
            "spring = 1\n[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n", 1, "spring",
            "expected [[spring]] tables"},
        Bad{"only springs, no bodies",
            "[world]\ndt = 0.01\n[[spring]]\nbodies = [\"a\", \"b\"]\nstiffness = 1\n", 1, "body",
            "no [[body]], [[chain]] or [[grid]] tables"},
        Bad{"chain without count", chain("start = [0, 0]\n"), 3, "chain[0].count", "missing"},
        Bad{"chain count a float", chain("count = 4.0\n"), 4, "chain[0].count",
            "expected an integer, found a float (4.0); write it without the decimal point: 4"},
        Bad{"chain count zero", chain("count = 0\n"), 4, "chain[0].count", "must be 1 .. 1000000"},
        Bad{"chain beyond the body limit",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n[[chain]]\ncount = "
            "1000000\n",
            7, "chain[0].count",
            "the scene would have 1000001 bodies; at most 1000000 are allowed"},
        Bad{"grid beyond the body limit",
            "[world]\ndt = 0.01\n[[grid]]\ncolumns = 1001\nrows = 1000\n", 5, "grid[0].rows",
            "the scene would have 1001000 bodies; at most 1000000 are allowed"},
        // A required key missing beside a misspelling of it: the error is at the misspelling
        // and names both.
        Bad{"misspelt required stiffness",
            "[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n"
            "spring = { anchor = [0, 0], stifness = 15 }\n",
            6, "body[0].spring.stiffness",
            "missing (required): give stiffness (N/m) or frequency (Hz); found `stifness` — "
            "did you mean `stiffness`?"},
        Bad{"misspelt required mass", "[world]\ndt = 0.01\n[[body]]\nmas = 1\nposition = [0, 0]\n",
            4, "body[0].mass", "missing (required); found `mas` — did you mean `mass`?"},
        Bad{"misspelt [world]", "[wrld]\ndt = 0.01\n", 1, "world",
            "missing [world] table (required); found `wrld` — did you mean `world`?"},
        Bad{"missing mass, nothing like it", "[world]\ndt = 0.01\n[[body]]\nposition = [0, 0]\n", 3,
            "body[0].mass", "missing (required)"},
        Bad{"chain without body template", chain("count = 3\nstart = [0, 0]\nspacing = [1, 0]\n"),
            3, "chain[0].body", "missing (required): the bodies' template"},
        Bad{"chain template without mass",
            chain("count = 3\nstart = [0, 0]\nspacing = [1, 0]\nbody = { radius = 1 }\n"), 7,
            "chain[0].body.mass", "missing"},
        Bad{"chain link in both forms",
            chain("count = 3\nstart = [0, 0]\nspacing = [1, 0]\nbody = { mass = 1 }\n"
                  "link = { frequency = 1, stiffness = 2 }\n"),
            8, "chain[0].link.frequency", "`stiffness` and `frequency` both given"},
        Bad{"chain pin out of range",
            chain("count = 3\nstart = [0, 0]\nspacing = [1, 0]\nbody = { mass = 1 }\n"
                  "link = { stiffness = 1 }\npin = [0, 3]\npin_spring = { stiffness = 1 }\n"),
            9, "chain[0].pin[1]",
            "must be 0 .. 2, the index of one of the chain's 3 bodies (got 3)"},
        Bad{"chain pin without pin_spring",
            chain("count = 3\nstart = [0, 0]\nspacing = [1, 0]\nbody = { mass = 1 }\n"
                  "link = { stiffness = 1 }\npin = [0]\n"),
            9, "chain[0].pin", "needs pin_spring"},
        Bad{"chain rest length with zero spacing",
            chain("count = 3\nstart = [0, 0]\nspacing = [0, 0]\nbody = { mass = 1 }\n"
                  "link = { stiffness = 1, rest_length = 1 }\n"),
            6, "chain[0].spacing", "chain0[0] and chain0[1] start at the same point"},
        Bad{"chain spacing overflowing a double",
            chain("count = 3\nstart = [0, 0]\nspacing = [1e308, 0]\nbody = { mass = 1 }\n"
                  "link = { stiffness = 1 }\n"),
            6, "chain[0].spacing", "chain0[1] would be at (1e+308, 0) m, beyond +-1e12 m"},
        Bad{"generated name taken",
            "[world]\ndt = 0.01\n[[body]]\nname = \"rope[1]\"\nmass = 1\nposition = [0, 0]\n"
            "[[chain]]\nname = \"rope\"\ncount = 3\nstart = [0, 0]\nspacing = [1, 0]\n"
            "body = { mass = 1 }\nlink = { stiffness = 1 }\n",
            8, "chain[0].name", "\"rope[1]\" is already taken by the body of line 3"},
        Bad{"grid pin not a pair",
            grid_tail(3, 2) + "pin = [[0, 0], [1]]\npin_spring = { stiffness = 1 }\n", 10,
            "grid[0].pin[1]", "expected [column, row] (2 integers), found 1 element"},
        Bad{"grid pin row out of range",
            grid_tail(3, 2) + "pin = [[2, 2]]\npin_spring = { stiffness = 1 }\n", 10,
            "grid[0].pin[0][1]", "must be 0 .. 1, one of the grid's 2 rows (got 2)"},
        Bad{"spring to a generated body out of range",
            grid_tail(3, 2) +
                "[[spring]]\nbodies = [\"grid0[0,0]\", \"grid0[3,0]\"]\nstiffness = 1\n",
            11, "spring[0].bodies[1]", "grid[0] makes grid0[0,0] .. grid0[2,1] ([column,row])"},
        // [view]: bounded so that a frame's grid lines and pixels can be placed (SceneView).
        Bad{"view center far out", "[world]\ndt = 0.01\n[view]\ncenter = [0, -1e300]\n", 4,
            "view.center[1]", "must be within ±1e+12 m, where bodies can be"},
        Bad{"view center just past the guard's range",
            "[world]\ndt = 0.01\n[view]\ncenter = [1.000001e12, 0]\n", 4, "view.center[0]",
            "(the runtime guard's limit; got 1000001000000)"},
        Bad{"view width huge", "[world]\ndt = 0.01\n[view]\nwidth = 1e300\n", 4, "view.width",
            "must be 1e-06 .. 1e+13 m (got 1e+300)"},
        Bad{"view width tiny", "[world]\ndt = 0.01\n[view]\nwidth = 1e-300\n", 4, "view.width",
            "must be 1e-06 .. 1e+13 m (got 1e-300)"},
        Bad{"view width too narrow for its center",
            "[world]\ndt = 0.01\n[view]\ncenter = [3, 1e10]\nwidth = 1\n", 5, "view.width",
            "must be >= 10 m for a center 1e+10 m out"}),
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

TEST(Scene, SpringTablesJoinNamedBodies) {
  const Scene s =
      parse_scene(two_bodies("bodies = [\"b\", \"a\"]\nstiffness = 12.5\ndamping = 0.25\n"
                             "rest_length = 0.75\n[[spring]]\nbodies = [\"a\", \"b\"]\n"
                             "stiffness = 3\n"),
                  "springs.toml");
  ASSERT_EQ(s.def.links.size(), 2u);
  ASSERT_EQ(s.source.link_lines.size(), 2u);
  EXPECT_EQ(s.def.links[0].body_a.slot(), 1u);  // "b"
  EXPECT_EQ(s.def.links[0].body_b.slot(), 0u);  // "a"
  EXPECT_EQ(s.def.links[0].spring.stiffness, 12.5);
  EXPECT_EQ(s.def.links[0].spring.damping, 0.25);
  EXPECT_EQ(s.def.links[0].spring.rest_length, 0.75);
  EXPECT_EQ(s.source.link_lines[0], 11u);
  // Defaults: damping 0, rest length 0.
  EXPECT_EQ(s.def.links[1].spring.stiffness, 3.0);
  EXPECT_EQ(s.def.links[1].spring.damping, 0.0);
  EXPECT_EQ(s.def.links[1].spring.rest_length, 0.0);
  EXPECT_EQ(s.source.link_lines[1], 16u);
  // Two links between the same bodies: both act, with a warning.
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("already joined by spring[0]"), std::string::npos) << s.warnings[0];
  const World sim = World(s.def);
  EXPECT_EQ(sim.link_count(), 2u);
}

TEST(Scene, FrequencyFormUsesTheReducedMassOfLinksAndTheMassOfAnchoredSprings) {
  // Bodies of 1 kg and 2 kg: μ = 2/3 kg. k = μ (2πf)², b = 2 μ ζ (2πf).
  const double f = 1.5, zeta = 0.3, w = 2.0 * std::numbers::pi * f;
  const Scene s = parse_scene(
      two_bodies("bodies = [\"a\", \"b\"]\nfrequency = 1.5\ndamping_ratio = 0.3\nrest_length = 2\n"
                 "[[body]]\nname = \"c\"\nmass = 4\nposition = [5, 5]\n"
                 "spring = { anchor = [1, 1], frequency = 1.5, damping_ratio = 0.3 }\n"),
      "freq.toml");
  ASSERT_EQ(s.def.links.size(), 1u);
  const double mu = 1.0 * 2.0 / 3.0;
  EXPECT_NEAR(s.def.links[0].spring.stiffness, mu * w * w, 1e-12 * mu * w * w);
  EXPECT_NEAR(s.def.links[0].spring.damping, 2.0 * mu * zeta * w, 1e-12);
  EXPECT_EQ(s.def.links[0].spring.rest_length, 2.0);
  ASSERT_EQ(s.def.bodies.size(), 3u);
  ASSERT_TRUE(s.def.bodies[2].spring.has_value());
  EXPECT_NEAR(s.def.bodies[2].spring->stiffness, 4.0 * w * w, 1e-12 * 4.0 * w * w);
  EXPECT_NEAR(s.def.bodies[2].spring->damping, 2.0 * 4.0 * zeta * w, 1e-12);
  EXPECT_EQ(s.def.bodies[2].spring->anchor, (Vec2{1.0, 1.0}));
  // damping_ratio defaults to 0.
  const Scene u = parse_scene(two_bodies("bodies = [\"a\", \"b\"]\nfrequency = 2\n"), "u.toml");
  EXPECT_EQ(u.def.links[0].spring.damping, 0.0);
  EXPECT_GT(u.def.links[0].spring.stiffness, 0.0);
}

TEST(Scene, ChainMakesNamedBodiesLinksAndPins) {
  const Scene s = parse_scene(R"([world]
dt = 0.01
[[body]]
name = "hook"
mass = 1
position = [-1, 0]
[[chain]]
name = "rope"
count = 4
start = [0.0, 1.0]
spacing = [0.5, -0.25]
body = { mass = 0.2, velocity = [1, 2], gravity = [0, -9.81], drag = 0.01, radius = 0.1, color = "#ff0000" }
link = { stiffness = 100, damping = 0.5 }
pin = [0, 3]
pin_spring = { frequency = 10, damping_ratio = 1 }
[[spring]]
bodies = ["hook", "rope[0]"]
stiffness = 7
)",
                              "chain.toml");
  ASSERT_EQ(s.def.bodies.size(), 5u);
  ASSERT_EQ(s.source.body_lines.size(), 5u);
  for (std::size_t i = 0; i < 4; ++i) {
    const BodyDef& b = s.def.bodies[1 + i];
    EXPECT_EQ(b.name, "rope[" + std::to_string(i) + "]");
    EXPECT_EQ(b.body.position, (Vec2{0.5 * double(i), 1.0 - 0.25 * double(i)}));
    EXPECT_EQ(b.body.velocity, (Vec2{1.0, 2.0}));
    EXPECT_EQ(b.body.mass, 0.2);
    EXPECT_EQ(b.gravity->acceleration, (Vec2{0.0, -9.81}));
    EXPECT_EQ(b.drag->coefficient, 0.01);
    EXPECT_EQ(b.appearance->radius, 0.1);
    EXPECT_EQ(b.appearance->color, (Rgba8{255, 0, 0, 255}));
    EXPECT_EQ(s.source.body_lines[1 + i], 7u);
    EXPECT_EQ(b.spring.has_value(), i == 0 || i == 3) << i;
  }
  // The pins: anchored at the start position, frequency form on the body's own mass.
  const double w = 2.0 * std::numbers::pi * 10.0;
  EXPECT_EQ(s.def.bodies[4].spring->anchor, s.def.bodies[4].body.position);
  EXPECT_NEAR(s.def.bodies[4].spring->stiffness, 0.2 * w * w, 1e-9);
  EXPECT_NEAR(s.def.bodies[4].spring->damping, 2.0 * 0.2 * w, 1e-12);
  EXPECT_EQ(s.def.bodies[4].spring->rest_length, 0.0);
  // Links: consecutive bodies, rest length = the spacing's length, then the [[spring]].
  ASSERT_EQ(s.def.links.size(), 4u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(s.def.links[i].body_a.slot(), 1 + i);
    EXPECT_EQ(s.def.links[i].body_b.slot(), 2 + i);
    EXPECT_EQ(s.def.links[i].spring.stiffness, 100.0);
    EXPECT_EQ(s.def.links[i].spring.damping, 0.5);
    EXPECT_NEAR(s.def.links[i].spring.rest_length, std::hypot(0.5, 0.25), 1e-15);
    EXPECT_EQ(s.source.link_lines[i], 7u);
  }
  EXPECT_EQ(s.def.links[3].body_a.slot(), 0u);
  EXPECT_EQ(s.def.links[3].body_b.slot(), 1u);
  EXPECT_EQ(s.source.link_lines[3], 16u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
  EXPECT_EQ(World(s.def).link_count(), 4u);
}

TEST(Scene, ChainLinksInTheFrequencyFormUseTheReducedMassAndAnExplicitRestLength) {
  const Scene s =
      parse_scene(chain("count = 3\nstart = [0, 0]\nspacing = [1, 0]\n"
                        "body = { mass = 0.4 }\n"
                        "link = { frequency = 2, damping_ratio = 0.5, rest_length = 0 }\n"),
                  "c.toml");
  const double mu = 0.2, w = 2.0 * std::numbers::pi * 2.0;
  ASSERT_EQ(s.def.links.size(), 2u);
  EXPECT_NEAR(s.def.links[1].spring.stiffness, mu * w * w, 1e-12 * mu * w * w);
  EXPECT_NEAR(s.def.links[1].spring.damping, 2.0 * mu * 0.5 * w, 1e-12);
  EXPECT_EQ(s.def.links[1].spring.rest_length, 0.0);
  EXPECT_EQ(s.def.bodies[2].name, "chain0[2]");  // the default name
}

TEST(Scene, GridMakesStructuralShearAndBendLinks) {
  const Scene s = parse_scene(R"([world]
dt = 0.01
[[grid]]
name = "cloth"
columns = 4
rows = 3
origin = [-1.0, 2.0]
spacing = [0.5, -0.25]
body = { mass = 0.1 }
link = { stiffness = 50 }
shear = { stiffness = 20, damping = 0.1 }
bend = { stiffness = 5, rest_length = 0.1 }
pin = [[0, 0], [3, 0]]
pin_spring = { stiffness = 1000 }
)",
                              "grid.toml");
  ASSERT_EQ(s.def.bodies.size(), 12u);
  // Row by row: cloth[i,j] is body j * columns + i at origin + [i sx, j sy].
  EXPECT_EQ(s.def.bodies[0].name, "cloth[0,0]");
  EXPECT_EQ(s.def.bodies[6].name, "cloth[2,1]");
  EXPECT_EQ(s.def.bodies[6].body.position, (Vec2{0.0, 1.75}));
  EXPECT_EQ(s.def.bodies[11].name, "cloth[3,2]");
  // Structural: 3 per row x 3 rows + 4 per column pair x 2 = 17; shear: 2 x 3 x 2 = 12;
  // bend: 2 per row x 3 + 4 x 1 = 10.
  ASSERT_EQ(s.def.links.size(), 17u + 12u + 10u);
  std::size_t structural = 0, shear = 0, bend = 0;
  for (const LinkDef& l : s.def.links) {
    const Vec2 a = s.def.bodies[l.body_a.slot()].body.position,
               b = s.def.bodies[l.body_b.slot()].body.position;
    const double d = std::hypot(a.x - b.x, a.y - b.y);
    if (l.spring.stiffness == 50.0) {
      ++structural;
      EXPECT_TRUE(d == 0.5 || d == 0.25) << d;
      EXPECT_EQ(l.spring.rest_length, d);
    } else if (l.spring.stiffness == 20.0) {
      ++shear;
      EXPECT_NEAR(d, std::hypot(0.5, 0.25), 1e-15);
      EXPECT_EQ(l.spring.rest_length, d);
      EXPECT_EQ(l.spring.damping, 0.1);
    } else {
      ++bend;
      EXPECT_EQ(l.spring.stiffness, 5.0);
      EXPECT_TRUE(d == 1.0 || d == 0.5) << d;
      EXPECT_EQ(l.spring.rest_length, 0.1);  // as given
    }
  }
  EXPECT_EQ(structural, 17u);
  EXPECT_EQ(shear, 12u);
  EXPECT_EQ(bend, 10u);
  // The first links: cloth[0,0]-cloth[1,0], then cloth[0,0]-cloth[0,1].
  EXPECT_EQ(s.def.links[0].body_a.slot(), 0u);
  EXPECT_EQ(s.def.links[0].body_b.slot(), 1u);
  EXPECT_EQ(s.def.links[1].body_b.slot(), 4u);
  for (std::size_t i = 0; i < s.def.bodies.size(); ++i) {
    EXPECT_EQ(s.def.bodies[i].spring.has_value(), i == 0 || i == 3) << i;
  }
  EXPECT_EQ(s.def.bodies[3].spring->anchor, (Vec2{0.5, 2.0}));
  EXPECT_EQ(s.def.bodies[3].spring->stiffness, 1000.0);
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(World(s.def).link_count(), 39u);
}

TEST(Scene, UnknownKeysOfTheNewTablesWarnWithASuggestion) {
  const Scene s = parse_scene(R"([world]
dt = 0.01
[[chain]]
count = 2
start = [0, 0]
spacng = [1, 0]
spacing = [1, 0]
body = { mass = 1, radus = 0.1 }
link = { stiffness = 1, dampng = 0.1 }
pin_spring = { stiffness = 1 }
[[grid]]
columns = 2
rows = 2
origin = [5, 5]
spacing = [1, 1]
body = { mass = 1 }
link = { frequncy = 1, frequency = 1 }
sheer = { stiffness = 1 }
[[spring]]
bodies = ["chain0[0]", "grid0[1,1]"]
stifness = 1
stiffness = 1
)",
                              "typo.toml");
  const char* expected[] = {
      "typo.toml:6:1: chain[0].spacng: unknown key ignored (did you mean `spacing`?)",
      "typo.toml:8:20: chain[0].body.radus: unknown key ignored (did you mean `radius`?)",
      "typo.toml:9:25: chain[0].link.dampng: unknown key ignored (did you mean `damping`?)",
      ("typo.toml:10:14: chain[0].pin_spring: ignored: there is no `pin` list of bodies for it "
       "to hold (e.g. pin = [0])"),
      "typo.toml:17:10: grid[0].link.frequncy: unknown key ignored (did you mean `frequency`?)",
      "typo.toml:18:1: grid[0].sheer: unknown key ignored (did you mean `shear`?)",
      "typo.toml:21:1: spring[0].stifness: unknown key ignored (did you mean `stiffness`?)"};
  ASSERT_EQ(s.warnings.size(), std::size(expected));
  for (std::size_t i = 0; i < std::size(expected); ++i) EXPECT_EQ(s.warnings[i], expected[i]);
}

/// The message of the SceneError load_scene(path) throws.
std::string load_error(const std::filesystem::path& path) {
  try {
    (void)load_scene(path);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST(Scene, MissingFileAndDirectory) {
  EXPECT_EQ(load_error("/nonexistent/scene.toml"),
            "/nonexistent/scene.toml: no such scene file: the directory /nonexistent does not "
            "exist");
  EXPECT_EQ(load_error(FIXSTEP_SOURCE_DIR "/assets"),
            FIXSTEP_SOURCE_DIR "/assets: is a directory, not a scene file");
  // A typo in the name: the closest file beside it. A directory: the scene files in it.
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "fixstep_scenes";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (const char* name :
       {"rope.toml", "scene.toml", "soft_body.toml", "spring.toml", "notes.txt"}) {
    std::ofstream(dir / name) << "[world]\ndt = 0.01\n";
  }
  EXPECT_EQ(load_error(dir / "scen.toml"), (dir / "scen.toml").string() +
                                               ": no such scene file; did you mean " +
                                               (dir / "scene.toml").string() + "?");
  EXPECT_EQ(load_error(dir / "nothing_like_it.toml"),
            (dir / "nothing_like_it.toml").string() + ": no such scene file");
  EXPECT_EQ(load_error(dir),
            dir.string() + ": is a directory, not a scene file; give a file in it: " +
                (dir / "rope.toml").string() + ", " + (dir / "scene.toml").string() + ", " +
                (dir / "soft_body.toml").string() + " (and 1 more)");
  std::filesystem::remove_all(dir);
}

TEST(Scene, SyntaxErrorsAreInPlainWords) {
  // toml++'s "Error while parsing SCOPE", its escapes and its C++ macro names stay out.
  std::string deep = "x = ";
  deep.append(300, '[');
  for (const std::string& text : {std::string("[world]\x01"
                                              "dt = 0.01\n"),
                                  deep, std::string("[world]\ndt = 0.01\nintegrator = \n")}) {
    try {
      (void)parse_scene(text, "s.toml");
      FAIL() << text;
    } catch (const SceneError& e) {
      const std::string what = e.what();
      // 300 brackets: refused by the nesting bound (toml_depth.hpp) before toml++'s own 256.
      EXPECT_NE(what.find(text == deep ? "TOML nested too deep" : "TOML syntax error"),
                std::string::npos)
          << what;
      for (const char* jargon : {"Error while parsing", "TOML_MAX", "saw '", "\\u", "\\n"}) {
        EXPECT_EQ(what.find(jargon), std::string::npos) << jargon << " in " << what;
      }
    }
  }
  try {
    (void)parse_scene(
        "[world]\x01"
        "dt = 0.01\n",
        "s.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "s.toml:1:8: TOML syntax error in a [table] header: expected a comment or "
              "whitespace, found the control character U+0001");
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
      EXPECT_NE(std::string(e.what()).find("expected an integer, found a float"), std::string::npos)
          << e.what();
    }
  }
}
