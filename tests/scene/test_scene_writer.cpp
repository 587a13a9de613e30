// The scene writer (scene_writer.hpp): every shipped scene and a world of awkward values built in
// code load back from their written text with the same definition hash and the same fields,
// bit for bit; what the format cannot hold is normalised as documented or refused; the file is
// written atomically.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "carried_segments_scene.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/value_ranges.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_writer.hpp"
#include "link_between.hpp"
#include "scene_writer_check.hpp"

namespace fixstep {
namespace {

namespace fs = std::filesystem;

WorldDef reload(const WorldDef& def) {
  const Scene back = parse_scene(format_scene(def), "written.toml");
  EXPECT_TRUE(back.warnings.empty()) << back.warnings.front();
  return back.def;
}

TEST(SceneWriter, EveryShippedSceneRoundTrips) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(FIXSTEP_SOURCE_DIR) / "assets/scenes")) {
    if (e.path().extension() == ".toml") files.push_back(e.path());
  }
  ASSERT_GE(files.size(), 12u);
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    const WorldDef def = load_scene(file).def;
    const WorldDef back = reload(def);
    EXPECT_EQ(definition_hash(back), definition_hash(def));
    test::expect_same_world(def, back);
    EXPECT_EQ(format_scene(back), format_scene(def));  // a written scene writes itself again
  }
}

/// n/|n|, as the loader normalises a plane's normal.
Vec2 unit(Vec2 n) {
  const double len = std::hypot(n.x, n.y);
  return {n.x / len, n.y / len};
}

/// Bodies of every type, with every component, names that need escaping and numbers that need
/// all 17 digits, a sign on zero, and the ends of the ranges a world takes (value_ranges.hpp:
/// states within 1e12, coefficients within [1e-100, 1e100], and the precision's own range).
WorldDef awkward_world(Precision precision, Integrator integrator) {
  const double huge = precision == Precision::f32 ? 3.0e38 : max_coefficient;
  const double far = std::nextafter(max_state_magnitude, 0.0);  // 17 digits
  const double third = 1.0 / 3.0, tiny = min_coefficient,
               sub = std::nextafter(min_coefficient, 1.0);
  WorldDef def;
  def.precision = precision;
  def.settings.dt = third;
  def.settings.integrator = integrator;
  def.settings.substeps = 7;
  def.settings.flush_denormals = false;
  def.settings.track_dissipation = true;  // a scene's, always
  def.settings.contacts = ContactSettings{.restitution = third,
                                          .friction = tiny,
                                          .velocity_iterations = 3,
                                          .sleep = true,
                                          .sleep_speed = third,
                                          .sleep_time = tiny};

  BodyDef a;
  a.name = "quote\" back\\slash\nnew line\ttab \x01 \x7f ünïcødé ☃ 𝄞";
  a.body = Body{.mass = third, .position = {third, -0.0}, .velocity = {tiny, -far}};
  a.spring = SpringDamper{
      .anchor = {-0.0, 2.0 / 3.0}, .stiffness = 15.0, .damping = sub, .rest_length = 0.1};
  a.constant_force = ConstantForce{{-huge, 1e-99}};
  a.gravity = Gravity{{0.0, -9.81}};
  a.drag = LinearDrag{0.1 + 0.2};
  a.collider = Collider{.radius = 0.25, .restitution = 0.125, .friction = third, .collide = false};
  a.appearance = Appearance{.radius = 0.7, .color = {1, 2, 3, 4}};  // drawn larger than its disc
  BodyDef wall;
  wall.name = "wall";
  wall.type = BodyType::static_body;
  wall.body.position = {10.0, -0.0};
  wall.body.velocity = {-0.0, 0.0};
  wall.collider = Collider{.radius = 0.5};
  wall.appearance = Appearance{.radius = 0.5, .color = {255, 255, 255, 255}};
  BodyDef paddle;
  paddle.name = "paddle";
  paddle.type = BodyType::kinematic;
  paddle.body.position = {far, far};
  paddle.body.velocity = {-0.0, 3.5};
  paddle.appearance = Appearance{.radius = 2.0, .color = {0, 0, 0, 0}};  // drawn, not a disc
  BodyDef bare;
  bare.name = "body0";  // the loader's default name of body 0, given to body 3
  bare.body = Body{.mass = huge, .position = {-third, 1e-100}, .velocity = {}};
  BodyDef dot;
  dot.name = "dot";
  dot.body = Body{.mass = sub, .position = {5.0, 5.0}};
  dot.appearance = Appearance{.radius = 0.5, .color = {9, 8, 7, 255}};  // colour alone
  def.bodies = {a, wall, paddle, bare, dot};
  def.links = {fixstep::test::link_between(0, 3, LinkSpring{third, 0.0, 1e-100}),
               fixstep::test::link_between(4, 1, LinkSpring{huge, tiny, 0.0}),
               fixstep::test::link_between(
                   2, 1, LinkSpring{1.0, 1.0, 0.5})};  // two immovable ends: a warning
  def.planes = {PlaneDef{.normal = {0.0, 1.0}, .offset = -0.0, .restitution = third},
                PlaneDef{.normal = {-1.0, -0.0}, .offset = -far, .friction = 0.7},
                PlaneDef{.normal = {0.6, 0.8}, .offset = tiny, .restitution = 1.0},
                // n/|n| of these is not n/|n| again: the writer finds a normal that gives it
                PlaneDef{.normal = unit({1.0, 1.0}), .offset = -1.0},
                PlaneDef{.normal = unit({-1.0, 7.0}), .offset = -2.0}};
  return def;
}

TEST(SceneWriter, AwkwardWorldRoundTripsForEveryIntegratorAndPrecision) {
  for (const Precision precision : {Precision::f32, Precision::f64}) {
    for (const Integrator integrator : all_integrators) {
      SCOPED_TRACE(fmt::format("{} {}", precision_name(precision), integrator_name(integrator)));
      const WorldDef def = awkward_world(precision, integrator);
      const Scene back = parse_scene(format_scene(def), "written.toml");
      ASSERT_EQ(back.warnings.size(), 1u);  // the link between two immovable bodies
      EXPECT_NE(back.warnings[0].find("spring[2].bodies: does nothing"), std::string::npos);
      EXPECT_EQ(definition_hash(back.def), definition_hash(def));
      test::expect_same_world(def, back.def);
    }
  }
}

TEST(SceneWriter, NumbersAreFloatsThatKeepTheirSign) {
  const std::string text = format_scene(awkward_world(Precision::f64, Integrator::rk4));
  EXPECT_NE(text.find("position = [0.3333333333333333, -0.0]"), std::string::npos) << text;
  EXPECT_NE(text.find("substeps = 7\n"), std::string::npos);  // the one integer key
  EXPECT_NE(text.find("flush_denormals = false\n"), std::string::npos);
  EXPECT_NE(text.find("draw_radius = 0.7\n"), std::string::npos);
  EXPECT_NE(text.find("sleep = true\nsleep_speed = 0.3333333333333333\nsleep_time = 1e-100\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("bodies = [\"quote\\\" back\\\\slash\\nnew line\\u0009tab"),
            std::string::npos);
}

TEST(SceneWriter, NamesAndLooksTheFormatCannotHoldAreNormalisedAsDocumented) {
  WorldDef def;
  def.settings.threads = 2;                // not written: reloads as 0
  def.settings.track_dissipation = false;  // a scene's is always on
  BodyDef body;
  body.body.position = {0.0, 0.0};
  def.bodies.assign(5, body);
  def.bodies[0].name = "";       // -> body0
  def.bodies[1].name = "body0";  // kept: taken before generated names
  def.bodies[2].name = "twin";
  def.bodies[3].name = "twin";                       // -> twin~2
  def.bodies[4].name = "";                           // -> body4
  def.bodies[4].collider = Collider{.radius = 0.3};  // no Appearance: reloads with one
  for (std::size_t i = 0; i < 5; ++i) def.bodies[i].body.position = {double(i), 0.0};
  def.links = {fixstep::test::link_between(0, 3, {}), fixstep::test::link_between(1, 4, {})};
  // Sleep off: sleep_speed and sleep_time do nothing and are not hashed, so not written (a
  // scene with them and no `sleep = true` warns); they reload as the defaults.
  def.settings.contacts = ContactSettings{.sleep_speed = 0.2, .sleep_time = 3.0};
  const WorldDef back = reload(def);
  EXPECT_EQ(definition_hash(back), definition_hash(def));
  WorldDef expected = def;
  expected.settings.threads = 0;
  expected.settings.track_dissipation = true;
  expected.bodies[0].name = "body0~2";
  expected.bodies[3].name = "twin~2";
  expected.bodies[4].name = "body4";
  expected.bodies[4].appearance = Appearance{.radius = 0.3};
  expected.settings.contacts->sleep_speed = ContactSettings::default_sleep_speed;
  expected.settings.contacts->sleep_time = ContactSettings::default_sleep_time;
  test::expect_same_world(expected, back);
}

// The two keys the writer needs, in scene files too.
TEST(SceneWriter, LoaderReadsDrawRadiusAndFlushDenormals) {
  const Scene s = parse_scene(R"([world]
dt = 0.01
flush_denormals = false
[[body]]
mass = 1.0
position = [0.0, 0.0]
draw_radius = 2.0
[[body]]
mass = 1.0
position = [5.0, 0.0]
radius = 0.5
draw_radius = 0.25
color = "#102030"
[[chain]]
count = 2
start = [0.0, 9.0]
spacing = [1.0, 0.0]
body = { mass = 1.0, draw_radius = 3.0 }
)",
                              "keys.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_FALSE(s.def.settings.flush_denormals);
  ASSERT_EQ(s.def.bodies.size(), 4u);
  EXPECT_FALSE(s.def.bodies[0].collider);  // drawn, not a disc
  EXPECT_EQ(s.def.bodies[0].appearance->radius, 2.0);
  EXPECT_EQ(s.def.bodies[1].collider->radius, 0.5);
  EXPECT_EQ(s.def.bodies[1].appearance->radius, 0.25);
  EXPECT_EQ(s.def.bodies[1].appearance->color, (Rgba8{16, 32, 48, 255}));
  EXPECT_EQ(s.def.bodies[3].appearance->radius, 3.0);
  EXPECT_TRUE(parse_scene("[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, 0.0]\n",
                          "default.toml")
                  .def.settings.flush_denormals);
  EXPECT_THROW((void)parse_scene("[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, "
                                 "0.0]\ndraw_radius = 0.0\n",
                                 "zero.toml"),
               SceneError);
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

TEST(SceneWriter, RefusesWhatWouldNotLoadBackExactly) {
  WorldDef ok;
  ok.bodies.resize(2);
  ok.bodies[1].body.position = {1.0, 0.0};
  auto with = [&](auto change) {
    WorldDef d = ok;
    change(d);
    return refusal(d);
  };
  EXPECT_EQ(with([](WorldDef& d) {
              d.bodies[1].type = BodyType::static_body;
              d.bodies[1].body.mass = 5.0;
            }),
            "format_scene: body[1] \"body1\": the mass of a static body (5 kg) cannot be written: "
            "a scene gives static bodies no mass (they keep the default 1 kg), and the mass "
            "enters the definition hash; leave body.mass at 1");
  EXPECT_NE(with([](WorldDef& d) {
              d.bodies[0].type = BodyType::kinematic;
              d.bodies[0].gravity = Gravity{};
            }).find("body[0] \"body0\": a kinematic body's gravity cannot be written"),
            std::string::npos);
  EXPECT_NE(with([](WorldDef& d) {
              d.bodies[0].type = BodyType::static_body;
              d.bodies[0].body.velocity = {1.0, 0.0};
            }).find("a static body's velocity (1, 0) m/s cannot be written"),
            std::string::npos);
  EXPECT_EQ(with([](WorldDef& d) { d.links = {fixstep::test::link_between(0, 2, {})}; }),
            "format_scene: link[0]: joins body[0] and body[2]: each must be one of the 2 bodies (a "
            "handle WorldDef::add_body returned), and they must differ");
  EXPECT_NE(
      with([](WorldDef& d) { d.links = {fixstep::test::link_between(1, 1, {})}; }).find("link[0]"),
      std::string::npos);
  EXPECT_NE(with([](WorldDef& d) {
              d.planes = {PlaneDef{.normal = {0.0, 2.0}}};
            })
                .find("plane[0].normal: (0, 2) cannot be written: a scene's normals are "
                      "normalised when read (n/|n| = (0, 1))"),
            std::string::npos);
  // What the loader refuses, in its words.
  EXPECT_NE(with([](WorldDef& d) {
              d.bodies[1].body.mass = std::nan("");
            }).find("does not load back from its scene text: <scene text>:"),
            std::string::npos);
  EXPECT_NE(with([](WorldDef& d) {
              d.bodies[1].body.mass = std::nan("");
            }).find("body[1].mass: must be finite (got nan)"),
            std::string::npos);
  EXPECT_NE(with([](WorldDef& d) {
              d.settings.contacts = ContactSettings{.sleep = true, .sleep_speed = 0.0};
            }).find("contacts.sleep_speed: must be > 0 m/s (got 0)"),
            std::string::npos);
  EXPECT_NE(
      with([](WorldDef& d) {
        d.settings.contacts = ContactSettings{.sleep = true, .sleep_time = 1e8};
      }).find("contacts.sleep_time: must be under 1e9 ticks of dt = 0.0166667 s (got 1e+08 s"),
      std::string::npos);
  EXPECT_NE(with([](WorldDef& d) { d.bodies[0].name = "bad \xff utf-8"; }).find("<scene text>"),
            std::string::npos);
  EXPECT_NE(with([](WorldDef& d) { d.bodies.clear(); }).find("a scene needs at least one body"),
            std::string::npos);
  EXPECT_NE(
      with([](WorldDef& d) { d.bodies.resize(100'000); }).find("the world: its scene would be "),
      std::string::npos);
}

/// How many times `part` occurs in `text`.
std::size_t count(const std::string& text, std::string_view part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
    ++n;
  }
  return n;
}

// Segments a kinematic body carries (SegmentDef::body) are written with `body` = its name, on
// each segment of a carried polyline, and load back to the same segments (carriers included)
// and the same hash; a carrier with no name, or a repeated one, goes by the name the writer
// gives it (as links do). A carrier that is not one of the bodies, or not kinematic, is refused.
TEST(SceneWriter, CarriedSegmentsRoundTripByTheirBodysName) {
  const Scene scene = parse_scene(test::carried_level, "carried.toml");
  const WorldDef def = scene.def;
  ASSERT_EQ(def.segments.size(), 8u);
  const std::string text = format_scene(def);
  EXPECT_EQ(count(text, "\nbody = \"lift\"\n"), 3u) << text;
  EXPECT_EQ(count(text, "\nbody = \"deck[1,0]\"\n"), 3u) << text;
  EXPECT_EQ(count(text, "\nbody = "), 6u) << text;  // not on the static segment
  const WorldDef back = reload(def);
  EXPECT_EQ(definition_hash(back), definition_hash(def));
  test::expect_same_world(def, back);
  EXPECT_EQ(back.segments, def.segments);
  EXPECT_EQ(format_scene(back), text);  // a written scene writes itself again

  // Built in code: a carrier without a name, and one whose name repeats.
  WorldDef code;
  BodyDef carrier;
  carrier.type = BodyType::kinematic;
  carrier.body.velocity = {1.0, 0.0};
  const Entity unnamed = code.add_body(carrier);  // written as body0
  carrier.name = "twin";
  carrier.body.position = {0.0, 3.0};
  (void)code.add_body(carrier);
  carrier.body.position = {0.0, 6.0};
  const Entity twin2 = code.add_body(carrier);  // written as twin~2
  code.segments.push_back(SegmentDef{.a = {-1.0, 0.0}, .b = {1.0, 0.0}, .body = unnamed});
  const std::vector<Vec2> points{{-1.0, 6.0}, {0.0, 7.0}, {1.0, 6.0}};
  code.add_polyline(points, 0.5, 0.25, true, twin2);
  const std::string code_text = format_scene(code);
  EXPECT_EQ(count(code_text, "\nbody = \"body0\"\n"), 1u) << code_text;
  EXPECT_EQ(count(code_text, "\nbody = \"twin~2\"\n"), 3u) << code_text;
  const WorldDef code_back = reload(code);
  EXPECT_EQ(definition_hash(code_back), definition_hash(code));
  EXPECT_EQ(code_back.segments, code.segments);
  EXPECT_EQ(code_back.bodies[2].name, "twin~2");

  WorldDef stray = code;
  stray.segments[0].body = fixstep::defined_entity(7);
  EXPECT_EQ(refusal(stray),
            "format_scene: segment[0]: is carried by body[7]: it must be one of the 3 bodies (a "
            "handle WorldDef::add_body returned)");
  WorldDef dynamic = code;
  dynamic.bodies[0].type = BodyType::dynamic;
  EXPECT_EQ(refusal(dynamic),
            "format_scene: segment[0]: is carried by body[0] \"body0\", a dynamic body: only a "
            "kinematic body can carry segments");
}

TEST(SceneWriter, WritesTheFileWhole) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("scene_writer_{}", ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const WorldDef def = awkward_world(Precision::f64, Integrator::velocity_verlet);
  write_scene(dir / "world.toml", def);
  test::expect_same_world(def, load_scene(dir / "world.toml").def);

  // A refused world writes nothing: the file keeps what it had.
  WorldDef bad = def;
  bad.bodies[0].body.mass = -1.0;
  EXPECT_THROW(write_scene(dir / "world.toml", bad), std::invalid_argument);
  EXPECT_EQ(definition_hash(load_scene(dir / "world.toml").def), definition_hash(def));

  // The target is a directory: refused before a temporary file is made.
  fs::create_directory(dir / "taken.toml");
  try {
    write_scene(dir / "taken.toml", def);
    ADD_FAILURE() << "wrote over a directory";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              fmt::format("cannot write {}: is a directory (an output is a regular file, a new "
                          "name, a FIFO, a character device or standard output)",
                          (dir / "taken.toml").string()));
  }
  // A directory that does not exist.
  const fs::path missing = dir / "no_such_dir" / "w.toml";
  try {
    write_scene(missing, def);
    ADD_FAILURE() << "wrote into a missing directory";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), fmt::format("cannot write {}: the directory {} does not exist",
                                                 missing.string(), (dir / "no_such_dir").string()));
  }
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"taken.toml", "world.toml"}));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fixstep
