// Scene files, segments carried by kinematic bodies: `body = "name"` in [[segment]] and
// [[polyline]] sets SegmentDef::body of the table's segments (every segment of a polyline) to
// the handle WorldDef::add_body gives the named body ([[body]] or generated); a world built
// from the scene moves them with their body; a body key that is not a string, names no body or
// names one that is not kinematic is refused at the key. (The writer's side:
// test_scene_writer.cpp.)
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "carried_segments_scene.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_writer.hpp"

namespace fixstep {
namespace scene_segments_test {  // named: a unity batch shares anonymous namespaces

using test::carried_bodies;  // carried_segments_scene.hpp
const std::string& level = test::carried_level;

/// The handles WorldDef::add_body returns for the scene's bodies, in order.
std::vector<Entity> handles(const Scene& s) {
  WorldDef def;
  std::vector<Entity> out;
  for (const BodyDef& b : s.def.bodies) out.push_back(def.add_body(b));
  return out;
}

/// The index of the body named `name`.
std::size_t index_of(const Scene& s, std::string_view name) {
  for (std::size_t i = 0; i < s.def.bodies.size(); ++i) {
    if (s.def.bodies[i].name == name) return i;
  }
  ADD_FAILURE() << "no body " << name;
  return 0;
}

TEST(SceneSegments, BodyKeySetsTheCarrierOfASegmentAndOfEveryPolylineSegment) {
  const Scene s = parse_scene(level, "k.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const std::vector<Entity> h = handles(s);
  const Entity lift = h[index_of(s, "lift")], deck = h[index_of(s, "deck[1,0]")];
  ASSERT_FALSE(lift.is_null());
  ASSERT_NE(lift, deck);
  ASSERT_EQ(s.def.segments.size(), 8u);
  EXPECT_EQ(s.def.segments[0].body, lift);
  EXPECT_EQ(s.def.segments[0].friction, 0.5);
  EXPECT_TRUE(s.def.segments[1].body.is_null());  // no key: static, as before
  for (const std::size_t i : {2u, 3u}) {
    SCOPED_TRACE(i);
    EXPECT_EQ(s.def.segments[i].body, lift);
    EXPECT_EQ(s.def.segments[i].friction, 0.3);
  }
  for (const std::size_t i : {4u, 5u, 6u}) {
    SCOPED_TRACE(i);
    EXPECT_EQ(s.def.segments[i].body, deck);
  }
  EXPECT_TRUE(s.def.segments[7].body.is_null());
  // The geometry is what the static forms give: the same table without `body`, the same
  // polyline_segments with body set.
  EXPECT_EQ(s.def.segments[0],
            (SegmentDef{.a = {-1.0, 0.0}, .b = {1.0, 0.0}, .friction = 0.5, .body = lift}));
  const std::vector<Vec2> points{{-1.0, 1.0}, {0.0, 1.5}, {1.0, 1.0}};
  WorldDef def;
  def.add_polyline(points, 0.0, 0.3, false, lift);
  ASSERT_EQ(def.segments.size(), 2u);
  EXPECT_EQ(s.def.segments[2], def.segments[0]);
  EXPECT_EQ(s.def.segments[3], def.segments[1]);
  EXPECT_EQ(s.source.segment_lines, (std::vector<std::size_t>{28, 33, 36, 36, 40, 40, 40, 44}));
  // The same level without any body key loads as the static level it was.
  std::string unkeyed = level;
  for (std::size_t at; (at = unkeyed.find("body = \"")) != std::string::npos;) {
    unkeyed.erase(at, unkeyed.find('\n', at) - at + 1);
  }
  const Scene still = parse_scene(unkeyed, "k.toml");
  ASSERT_EQ(still.def.segments.size(), s.def.segments.size());
  for (std::size_t i = 0; i < s.def.segments.size(); ++i) {
    SegmentDef expected = s.def.segments[i];
    expected.body = Entity{};
    EXPECT_EQ(still.def.segments[i], expected) << i;
  }
}

TEST(SceneSegments, CarriedSegmentsMoveWithTheirBody) {
  const Scene s = parse_scene(level, "k.toml");
  World w = World(s.def);
  const Entity lift = w.defined_bodies()[index_of(s, "lift")];
  const Entity deck = w.defined_bodies()[index_of(s, "deck[1,0]")];
  const Vec2 lift0 = w.body(lift).position, deck0 = w.body(deck).position;
  const int ticks = 100;  // 1 s
  for (int t = 0; t < ticks; ++t) w.step();
  const double time = ticks * s.def.settings.dt;
  ASSERT_EQ(w.segments().size(), 8u);
  // Each carried segment is displaced by its body's velocity × time, as its body is.
  auto expect_moved = [&](std::size_t i, Vec2 v, Vec2 body_moved) {
    SCOPED_TRACE(i);
    const SegmentDef &now = w.segments()[i], &then = s.def.segments[i];
    for (const auto& [p, p0] : {std::pair{now.a, then.a}, std::pair{now.b, then.b}}) {
      EXPECT_NEAR(p.x - p0.x, v.x * time, 1e-9);
      EXPECT_NEAR(p.y - p0.y, v.y * time, 1e-9);
      EXPECT_NEAR(p.x - p0.x, body_moved.x, 1e-12);
      EXPECT_NEAR(p.y - p0.y, body_moved.y, 1e-12);
    }
    // The ghost vertices move with it.
    for (const auto& [p, p0] : {std::pair{now.prev, then.prev}, std::pair{now.next, then.next}}) {
      ASSERT_EQ(p.has_value(), p0.has_value());
      if (!p) continue;
      EXPECT_NEAR(p->x - p0->x, v.x * time, 1e-9);
      EXPECT_NEAR(p->y - p0->y, v.y * time, 1e-9);
    }
  };
  const Vec2 lift_moved{w.body(lift).position.x - lift0.x, w.body(lift).position.y - lift0.y};
  const Vec2 deck_moved{w.body(deck).position.x - deck0.x, w.body(deck).position.y - deck0.y};
  for (const std::size_t i : {0u, 2u, 3u}) expect_moved(i, {0.5, 2.0}, lift_moved);
  for (const std::size_t i : {4u, 5u, 6u}) expect_moved(i, {-1.0, 0.0}, deck_moved);
  for (const std::size_t i : {1u, 7u}) EXPECT_EQ(w.segments()[i], s.def.segments[i]) << i;
}

// A disc at rest on a platform that moves right at 1 m/s (friction 0.2, gravity 9.81 m/s²) is
// brought to the platform's speed by friction after u/(μ g) = 0.51 s and rides it, resting on
// it (it slides back over the polyline's joint at x = -0.1 m on the way, without a bump): the
// scene's platform acts as the one built in code (tests/core/test_kinematic_segments.cpp).
TEST(SceneSegments, ADiscRestingOnACarriedPolylineIsCarried) {
  const Scene s = parse_scene(R"([world]
dt = 0.016666666666666666
[[body]]
name = "disc"
mass = 2.0
position = [0.0, 0.25]
gravity = [0.0, -9.81]
radius = 0.25
[[body]]
name = "platform"
type = "kinematic"
position = [0.0, 0.0]
velocity = [1.0, 0.0]
[[polyline]]
points = [[-20.0, 0.0], [-0.1, 0.0], [20.0, 0.0]]
friction = 0.2
body = "platform"
)",
                              "p.toml");
  World w = World(s.def);
  const Entity disc = w.defined_bodies()[0];
  for (int t = 0; t < 60; ++t) w.step();
  EXPECT_NEAR(w.body(disc).velocity.x, 1.0, 1e-9);
  EXPECT_NEAR(w.body(disc).position.y, 0.25, 1e-9);
  EXPECT_NEAR(w.segments()[0].a.x, -19.0, 1e-9);
  EXPECT_GT(w.external_work(), 0.0);  // the platform's work on the disc
}

/// The SceneError parse_scene throws for text; fails the test when it loads.
SceneError error_of(const std::string& text) {
  try {
    (void)parse_scene(text, "k.toml");
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return SceneError("", 0, 0, "", "");
}

struct BadCarrier {
  std::string table;  ///< appended at line 28
  std::size_t line, column;
  std::string key, message;
};

TEST(SceneSegments, ABadBodyKeyIsRefusedAtItsKey) {
  const std::string segment = "[[segment]]\na = [0.0, 0.0]\nb = [1.0, 0.0]\n";       // lines 28-30
  const std::string polyline = "[[polyline]]\npoints = [[0.0, 0.0], [1.0, 0.0]]\n";  // 28-29
  const std::vector<BadCarrier> cases{
      {segment + "body = 3\n", 31, 8, "segment[0].body",
       "expected a body name (a string), found an integer (3)"},
      {polyline + "body = [\"lift\"]\n", 30, 8, "polyline[0].body",
       "expected a body name (a string), found an array of 1 element"},
      {segment + "body = \"lfit\"\n", 31, 8, "segment[0].body",
       "no body named \"lfit\" (did you mean \"lift\"?)"},
      {polyline + "body = \"platform\"\n", 30, 8, "polyline[0].body", "no body named \"platform\""},
      {segment + "body = \"deck[1,1]\"\n", 31, 8, "segment[0].body",
       "no body named \"deck[1,1]\" (did you mean \"deck[1,0]\"? grid"},
      {segment + "body = \"ball\"\n", 31, 8, "segment[0].body",
       "\"ball\" (line 3) is a dynamic body: only a kinematic body can carry segments; give it "
       "type = \"kinematic\", or leave `body` out for a static segment"},
      {polyline + "body = \"floor\"\n", 30, 8, "polyline[0].body",
       "\"floor\" (line 13) is a static body: only a kinematic body can carry segments; give it "
       "type = \"kinematic\", or leave `body` out for a static polyline"},
      // The second table of each kind: its own index in the key.
      {segment + segment + "body = \"ball\"\n", 34, 8, "segment[1].body", "is a dynamic body"},
  };
  for (const BadCarrier& c : cases) {
    SCOPED_TRACE(c.table);
    const SceneError e = error_of(std::string(carried_bodies) + c.table);
    EXPECT_EQ(e.line(), c.line) << e.what();
    EXPECT_EQ(e.column(), c.column) << e.what();
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    EXPECT_EQ(
        std::string(e.what()).rfind(fmt::format("k.toml:{}:{}: {}: ", c.line, c.column, c.key), 0),
        0u)
        << e.what();
  }
  // A misspelt key is an unknown key, with the suggestion, and the segment stays static.
  const Scene s = parse_scene(std::string(carried_bodies) + segment + "bdy = \"lift\"\n", "k.toml");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("k.toml:31:1: segment[0].bdy: unknown key ignored (did you mean "
                               "`body`?)"),
            std::string::npos)
      << s.warnings[0];
  EXPECT_TRUE(s.def.segments[0].body.is_null());
}

// `one_way = true` on a [[segment]] and a [[polyline]] makes the segment, and every segment of
// the polyline, one-way; the writer writes it back (the same definition hash, the same flags);
// a value that is not a boolean is refused at its key. Deliberate bug checked: the writer
// leaving one_way out (the hash of the written scene differs).
TEST(SceneSegments, OneWayIsReadForSegmentsAndPolylinesAndWrittenBack) {
  const std::string tables =
      "[[segment]]\na = [0.0, 0.0]\nb = [1.0, 0.0]\none_way = true\n"
      "[[segment]]\na = [0.0, 1.0]\nb = [1.0, 1.0]\none_way = false\n"
      "[[polyline]]\npoints = [[0.0, 2.0], [1.0, 2.0], [2.0, 2.5]]\none_way = true\n"
      "[[polyline]]\npoints = [[0.0, 3.0], [1.0, 3.0]]\n";
  const Scene s = parse_scene(std::string(carried_bodies) + tables, "k.toml");
  ASSERT_EQ(s.def.segments.size(), 5u);
  const std::vector<bool> want{true, false, true, true, false};
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(s.def.segments[i].one_way, want[i]) << i;
  const Scene back = parse_scene(format_scene(s.def), "written.toml");
  EXPECT_EQ(definition_hash(back.def), definition_hash(s.def));
  ASSERT_EQ(back.def.segments.size(), 5u);
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(back.def.segments[i].one_way, want[i]);
  const std::string segment = "[[segment]]\na = [0.0, 0.0]\nb = [1.0, 0.0]\n";       // lines 28-30
  const std::string polyline = "[[polyline]]\npoints = [[0.0, 0.0], [1.0, 0.0]]\n";  // 28-29
  const std::vector<BadCarrier> cases{
      {segment + "one_way = 1\n", 31, 11, "segment[0].one_way",
       "expected true or false, found an integer (1)"},
      {polyline + "one_way = \"yes\"\n", 30, 11, "polyline[0].one_way",
       "expected true or false, found a string"},
  };
  for (const BadCarrier& c : cases) {
    SCOPED_TRACE(c.table);
    const SceneError e = error_of(std::string(carried_bodies) + c.table);
    EXPECT_EQ(e.line(), c.line) << e.what();
    EXPECT_EQ(e.column(), c.column) << e.what();
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
  }
}

}  // namespace scene_segments_test
}  // namespace fixstep
