// Shapes in scene files (scene_shapes.cpp): each form of `shape` read into BodyDef::shapes,
// compound bodies, the body keys a body with shapes takes, the writer's exact round trip, and
// each refusal at its file:line:column and key. Read at the WorldDef level (parse_scene): the
// World steps no shape here.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_writer.hpp"
#include "scene_writer_check.hpp"

namespace fixstep {
namespace {

/// [world] (lines 1-2), then a [[body]] (line 3) with mass and position (lines 4-5), then
/// `body` from line 6.
std::string shape_scene(const std::string& body) {
  return "[world]\ndt = 0.01\n[[body]]\nmass = 2.0\nposition = [1.0, 2.0]\n" + body + "\n";
}

/// The loader's message for text, "" when it loads.
std::string shape_error(const std::string& text) {
  try {
    (void)parse_scene(text, "s.toml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneShapes, EachFormIsRead) {
  const Scene s = parse_scene(
      "[world]\ndt = 0.01\n"
      "[[body]]\nname = \"crate\"\nmass = 2.0\nposition = [0.0, 0.0]\n"
      "shape = { box = [0.5, 0.25], radius = 0.01, offset = [0.1, -0.2], angle = 0.3, "
      "density = 3.0, friction = 0.6, restitution = 0.2, rolling_resistance = 0.1, sensor = true, "
      "category = 0x2, mask = 0x5, group = -3 }\n"
      "[[body]]\nname = \"ball\"\nmass = 1.0\nposition = [3.0, 0.0]\nshape = { circle = 0.5 }\n"
      "[[body]]\nname = \"pill\"\nmass = 1.0\nposition = [6.0, 0.0]\n"
      "shape = { capsule = [[-0.5, 0.0], [0.5, 0.0]], radius = 0.2 }\n"
      "[[body]]\nname = \"gem\"\nmass = 1.0\nposition = [9.0, 0.0]\n"
      "shape = { polygon = [[0, 0], [1, 0], [1.5, 1], [0, 1]], radius = 0.05 }\n",
      "forms.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.def.bodies.size(), 4u);
  ShapeDef box = make_box(0.5, 0.25, {0.1, -0.2}, 0.3, 0.01);
  box.density = 3.0;
  box.friction = 0.6;
  box.restitution = 0.2;
  box.rolling_resistance = 0.1;
  box.sensor = true;
  box.filter = {.category = 2, .mask = 5, .group = -3};
  EXPECT_EQ(s.def.bodies[0].shapes, std::vector<ShapeDef>{box});
  EXPECT_FALSE(s.def.bodies[0].collider.has_value());
  EXPECT_EQ(s.def.bodies[1].shapes, std::vector<ShapeDef>{make_circle(0.5)});
  EXPECT_EQ(s.def.bodies[2].shapes,
            std::vector<ShapeDef>{make_capsule({-0.5, 0.0}, {0.5, 0.0}, 0.2)});
  const std::vector<Vec2> gem{{0, 0}, {1, 0}, {1.5, 1}, {0, 1}};
  EXPECT_EQ(s.def.bodies[3].shapes, std::vector<ShapeDef>{make_polygon(gem, 0.05)});
}

TEST(SceneShapes, CompoundBodyWithBodyKeys) {
  // [[body.shape]] tables, the body's density for the shapes that give none, and the body's
  // angle, angular_velocity and inertia without [contacts] rolling (no warning).
  const Scene s = parse_scene(shape_scene("angle = 0.5\nangular_velocity = -2.0\ninertia = 0.75\n"
                                          "density = 4.0\n"
                                          "[[body.shape]]\nbox = [1.5, 0.5]\noffset = [1.5, 0.5]\n"
                                          "[[body.shape]]\nbox = [0.5, 1.0]\noffset = [0.5, 2.0]\n"
                                          "density = 1.0\n"),
                              "l.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const BodyDef& b = s.def.bodies.at(0);
  EXPECT_EQ(b.body.angle, 0.5);
  EXPECT_EQ(b.body.angular_velocity, -2.0);
  EXPECT_EQ(b.inertia, 0.75);
  ASSERT_EQ(b.shapes.size(), 2u);
  EXPECT_EQ(b.shapes[0].density, 4.0);
  EXPECT_EQ(b.shapes[0].offset, (Vec2{1.5, 0.5}));
  EXPECT_EQ(b.shapes[1].density, 1.0);
  EXPECT_EQ(b.shapes[1].half_extents, (Vec2{0.5, 1.0}));
}

TEST(SceneShapes, InlineArrayAndGeneratorTemplates) {
  const Scene s = parse_scene(
      "[world]\ndt = 0.01\n"
      "[[body]]\nmass = 1.0\nposition = [0.0, 0.0]\n"
      "shape = [{ circle = 0.25 }, { box = [0.5, 0.1], offset = [0.0, 0.5] }]\n"
      "[[chain]]\nname = \"planks\"\ncount = 3\nstart = [0.0, 5.0]\nspacing = [1.0, 0.0]\n"
      "body = { mass = 0.5, shape = { box = [0.45, 0.05] }, angle = 0.25 }\n",
      "gen.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.def.bodies.size(), 4u);
  EXPECT_EQ(s.def.bodies[0].shapes,
            (std::vector<ShapeDef>{make_circle(0.25), make_box(0.5, 0.1, {0.0, 0.5})}));
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_EQ(s.def.bodies[i].shapes, std::vector<ShapeDef>{make_box(0.45, 0.05)});
    EXPECT_EQ(s.def.bodies[i].body.angle, 0.25);
  }
}

TEST(SceneShapes, ADynamicBodyWithDensitiesNeedsNoMass) {
  const Scene s = parse_scene(
      "[world]\ndt = 0.01\n[[body]]\nposition = [0.0, 0.0]\nshape = { circle = 1.0, density = 2.0 "
      "}\n",
      "d.toml");
  EXPECT_EQ(s.def.bodies.at(0).shapes.at(0).density, 2.0);
  EXPECT_NE(shape_error("[world]\ndt = 0.01\n[[body]]\nposition = [0.0, 0.0]\n"
                        "shape = { circle = 1.0 }\n")
                .find("body[0].mass: missing (required)"),
            std::string::npos);
}

WorldDef shape_world() {
  WorldDef def;
  def.settings.dt = 1.0 / 3.0;
  def.settings.track_dissipation = true;  // a scene's, always
  BodyDef a;
  a.name = "compound";
  a.body = Body{.mass = 0.1 + 0.2, .position = {1.0 / 3.0, -0.0}};
  a.body.angle = 2.0 / 3.0;
  a.body.angular_velocity = -1.0 / 7.0;
  a.inertia = 1.0 / 9.0;
  ShapeDef box = make_box(1.0 / 3.0, 0.1 + 0.2, {-0.0, 1e-7}, 1.0 / 7.0, 1.0 / 11.0);
  box.density = 1.0 / 3.0;
  box.friction = 0.7;
  box.restitution = 1.0 / 3.0;
  box.sensor = true;
  box.filter = {.category = 0x8000000000000001ULL, .mask = 6, .group = -7};
  const std::vector<Vec2> tri{{-0.0, -0.0}, {1.0 / 3.0, 0.0}, {0.0, 2.0 / 3.0}};
  ShapeDef poly = make_polygon(tri, 0.0);
  poly.offset = {0.1, 0.2};
  ShapeDef cap = make_capsule({-1.0 / 3.0, 0.0}, {1.0 / 3.0, 1e-3}, 0.1 + 0.2);
  cap.rolling_resistance = 1.0 / 7.0;
  cap.one_way = true;
  cap.angle = -0.0;  // written, so that it reads back as -0.0
  a.shapes = {box, poly, cap, make_circle(1.0 / 3.0, {2.0, 0.0})};
  BodyDef wall;
  wall.name = "wall";
  wall.type = BodyType::static_body;
  wall.shapes = {make_box(5.0, 0.5)};
  def.bodies = {a, wall};
  return def;
}

TEST(SceneShapes, WriteSceneRoundTripsShapesBitForBit) {
  const WorldDef def = shape_world();
  const std::string text = format_scene(def);
  const Scene back = parse_scene(text, "written.toml");
  EXPECT_TRUE(back.warnings.empty()) << back.warnings.front();
  test::expect_same_world(def, back.def);
  EXPECT_EQ(format_scene(back.def), text);  // a written scene writes itself again
  EXPECT_NE(text.find("[[body.shape]]\nbox = "), std::string::npos) << text;
}

TEST(SceneShapes, RefusedWithFileLineColumnAndKey) {
  struct Case {
    std::string body, error;
  };
  const std::vector<Case> cases{
      {"radius = 0.5\nshape = { circle = 0.5 }",
       "s.toml:7:9: body[0].shape: a body has a radius (a disc) or shapes, not both; remove "
       "radius, or make the disc a shape: { circle = r }"},
      {"shape = { polygon = [[0, 0], [2, 0], [1, 0.5], [2, 2], [0, 2]] }",
       "s.toml:6:21: body[0].shape.polygon: polygon vertex 2 makes it concave"},
      {"shape = { polygon = [[0, 0], [1, 0], [2, 0]] }",
       "s.toml:6:21: body[0].shape.polygon: polygon has no area (its vertices are collinear)"},
      {"shape = { polygon = [[0,0],[1,0],[2,1],[2,2],[1,3],[0,3],[-1,2],[-1,1],[-0.5,0.2]] }",
       "s.toml:6:21: body[0].shape.polygon: polygon count must be 3 to 8 (got 9)"},
      {"shape = { box = [nan, 1.0] }",
       "s.toml:6:18: body[0].shape.box[0]: must be finite (got nan)"},
      {"shape = { box = [1.0, 1.0], friction = -1.0 }",
       "s.toml:6:40: body[0].shape.friction: friction must be in [0, 1e100] (got -1)"},
      {"shape = { circle = 0.5, rolling_resistance = -0.1 }",
       "s.toml:6:46: body[0].shape.rolling_resistance: rolling_resistance must be in [0, 1e100] "
       "(got -0.1)"},
      {"shape = { circle = 0.5, offset = [2e6, 0.0] }",
       "s.toml:6:34: body[0].shape.offset: offset must be finite with |x|, |y| <= 1000000 m (got "
       "2000000, 0)"},
      {"shape = { capsule = [[0, 0], [1, 0]] }",
       "s.toml:6:9: body[0].shape.radius: missing (required): a capsule's radius in m, e.g. radius "
       "= 0.25"},
      {"shape = { box = [1.0, 1.0], circle = 0.5 }",
       "s.toml:6:29: body[0].shape.circle: a shape is one circle, capsule, box or polygon; this "
       "one gives both box and circle: write each as a shape of its own ([[body.shape]] tables)"},
      {"shape = { offset = [0.0, 0.0] }",
       "s.toml:6:9: body[0].shape.circle: missing (required): a shape needs one of circle = r, "
       "box = [hx, hy], capsule = [[x1, y1], [x2, y2]] with radius = r, or polygon = [[x, y], "
       "...] (m)"},
      {"shape = { circle = 0.5, radius = 0.5 }",
       "s.toml:6:34: body[0].shape.radius: a circle's radius is its `circle` key (circle = r); "
       "remove radius"},
      {"shape = { box = [1.0, 1.0], one_way = 1 }",
       "s.toml:6:39: body[0].shape.one_way: expected true or false, found an integer (1)"},
      {"shape = 3",
       "s.toml:6:9: body[0].shape: expected a shape table (shape = { box = [hx, hy] "
       "}) or an array of them ([[body.shape]] tables), found an integer (3)"},
      {"density = 2.0",
       "s.toml:6:11: body[0].density: needs a shape: a body's density (kg/m^2) is that of its "
       "shapes without their own; add shape = { ... }, or give the mass alone"},
      {"density = -2.0\nshape = { circle = 0.5 }",
       "s.toml:6:11: body[0].density: density must be finite, >= 0 and <= 1e100 kg/m^2 (got -2)"},
      {"friction = 0.5\nshape = { circle = 0.5 }",
       "s.toml:6:12: body[0].friction: a body with shapes gives it in each shape table; move it "
       "into shape = { ..., friction = ... }"},
      {"[[body.shape]]\nbox = [1.0, 1.0]\nangle = 1e300",
       "s.toml:8:9: body[0].shape[0].angle: angle must be finite with |angle| <= "
       "823549.6645826427 rad (got 1e+300)"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(shape_error(shape_scene(c.body)), c.error) << c.body;
  }
}

}  // namespace
}  // namespace fixstep
