// Shape definitions (shape.cpp): the make_* helpers, every refusal of shape_problem naming its
// field, and where a placed shape lies (shape_aabb, shape_outline).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/core/shape.hpp"

namespace fixstep {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

/// shape_problem's message, or "" when the shape is valid.
std::string problem_of(const ShapeDef& s) {
  return shape_problem(s).value_or("");
}

ShapeDef polygon(std::vector<Vec2> pts, double rounding = 0.0) {
  return make_polygon(pts, rounding);
}

TEST(ShapeChecks, KindNames) {
  EXPECT_STREQ(shape_kind_name(ShapeKind::circle), "circle");
  EXPECT_STREQ(shape_kind_name(ShapeKind::capsule), "capsule");
  EXPECT_STREQ(shape_kind_name(ShapeKind::box), "box");
  EXPECT_STREQ(shape_kind_name(ShapeKind::polygon), "polygon");
}

TEST(ShapeChecks, MakeFillsTheDefinition) {
  const ShapeDef c = make_circle(0.25, {1, 2});
  EXPECT_EQ(c.kind, ShapeKind::circle);
  EXPECT_EQ(c.radius, 0.25);
  EXPECT_EQ(c.offset, (Vec2{1, 2}));
  const ShapeDef cap = make_capsule({0, 0}, {1, 0}, 0.1);
  EXPECT_EQ(cap.count, 2);
  EXPECT_EQ(cap.vertices[1], (Vec2{1, 0}));
  const ShapeDef b = make_box(2, 1, {3, 4}, 0.5, 0.05);
  EXPECT_EQ(b.half_extents, (Vec2{2, 1}));
  EXPECT_EQ(b.offset, (Vec2{3, 4}));
  EXPECT_EQ(b.angle, 0.5);
  EXPECT_EQ(b.radius, 0.05);
  const ShapeDef p = polygon({{0, 0}, {1, 0}, {0, 1}}, 0.1);
  EXPECT_EQ(p.kind, ShapeKind::polygon);
  EXPECT_EQ(p.count, 3);
  EXPECT_EQ(p.radius, 0.1);
}

TEST(ShapeChecks, ValidShapesPass) {
  EXPECT_EQ(problem_of(make_circle(0.5)), "");
  EXPECT_EQ(problem_of(make_capsule({0, 0}, {1, 0}, 0.2)), "");
  EXPECT_EQ(problem_of(make_box(1, 2, {3, 4}, 0.3, 0.1)), "");
  EXPECT_EQ(problem_of(polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}})), "");
  std::vector<Vec2> octagon;
  for (int i = 0; i < 8; ++i) {
    const double a = i * std::numbers::pi / 4;
    octagon.push_back({std::cos(a), std::sin(a)});
  }
  ShapeDef s = polygon(octagon, 0.05);
  s.density = 0.0;
  s.friction = 1e100;
  s.restitution = 1.0;
  EXPECT_EQ(problem_of(s), "");
}

TEST(ShapeChecks, RadiusRulesPerKind) {
  EXPECT_EQ(problem_of(make_circle(0.0)), "radius must be finite, > 0 and <= 1000000 m (got 0)");
  EXPECT_EQ(problem_of(make_circle(nan)), "radius must be finite, > 0 and <= 1000000 m (got nan)");
  EXPECT_EQ(problem_of(make_capsule({0, 0}, {1, 0}, -1)),
            "radius must be finite, > 0 and <= 1000000 m (got -1)");
  EXPECT_EQ(problem_of(make_box(1, 1, {}, 0, -0.5)),
            "radius must be finite, >= 0 and <= 1000000 m (got -0.5)");
  EXPECT_EQ(problem_of(polygon({{0, 0}, {1, 0}, {0, 1}}, 2e6)),
            "radius must be finite, >= 0 and <= 1000000 m (got 2000000)");
}

TEST(ShapeChecks, BoxHalfExtents) {
  EXPECT_EQ(problem_of(make_box(0, 1)),
            "box half extents must be finite, >= 5e-07 and <= 1000000 m (got 0, 1)");
  EXPECT_EQ(problem_of(make_box(1, inf)),
            "box half extents must be finite, >= 5e-07 and <= 1000000 m (got 1, inf)");
  EXPECT_EQ(problem_of(make_box(-1, 1)),
            "box half extents must be finite, >= 5e-07 and <= 1000000 m (got -1, 1)");
}

TEST(ShapeChecks, CapsuleGeometry) {
  EXPECT_EQ(problem_of(make_capsule({0, 0}, {0, 5e-7}, 0.1)),
            "capsule length must be at least 1e-06 m (got 5e-07)");
  EXPECT_EQ(problem_of(make_capsule({0, 0}, {nan, 0}, 0.1)),
            "capsule vertex 1 must be finite with |x|, |y| <= 1000000 m (got nan, 0)");
  ShapeDef c = make_capsule({0, 0}, {1, 0}, 0.1);
  c.count = 3;
  EXPECT_EQ(problem_of(c), "capsule count must be 2 (got 3)");
}

TEST(ShapeChecks, PolygonCount) {
  EXPECT_EQ(problem_of(polygon({{0, 0}, {1, 0}})), "polygon count must be 3 to 8 (got 2)");
  std::vector<Vec2> nine;
  for (int i = 0; i < 9; ++i) {
    const double a = i * 2 * std::numbers::pi / 9;
    nine.push_back({std::cos(a), std::sin(a)});
  }
  EXPECT_EQ(problem_of(polygon(nine)), "polygon count must be 3 to 8 (got 9)");
}

TEST(ShapeChecks, PolygonVerticesFiniteAndWithinExtent) {
  EXPECT_EQ(problem_of(polygon({{0, 0}, {1, 0}, {0, inf}})),
            "polygon vertex 2 must be finite with |x|, |y| <= 1000000 m (got 0, inf)");
  EXPECT_EQ(problem_of(polygon({{0, 0}, {2e6, 0}, {0, 1}})),
            "polygon vertex 1 must be finite with |x|, |y| <= 1000000 m (got 2000000, 0)");
}

TEST(ShapeChecks, PolygonShortEdge) {
  EXPECT_EQ(problem_of(polygon({{0, 0}, {1, 0}, {1, 1e-7}, {0, 1}})),
            "polygon edge 1 -> 2 must be at least 1e-06 m long");
}

TEST(ShapeChecks, PolygonZeroAreaClockwiseConcaveCollinear) {
  EXPECT_EQ(problem_of(polygon({{0, 0}, {1, 0}, {2, 0}})),
            "polygon has no area (its vertices are collinear)");
  EXPECT_EQ(problem_of(polygon({{0, 0}, {0, 1}, {1, 0}})),
            "polygon vertices must run counter-clockwise (they run clockwise)");
  EXPECT_EQ(problem_of(polygon({{0, 0}, {2, 0}, {1, 0.5}, {2, 2}, {0, 2}})),
            "polygon vertex 2 makes it concave");
  EXPECT_EQ(problem_of(polygon({{0, 0}, {1, 0}, {2, 0}, {1, 1}})),
            "polygon vertex 1 lies on the line through vertices 0 and 2 (no three vertices may "
            "be collinear)");
  // Nearly collinear within the relative tolerance, at any scale.
  EXPECT_NE(problem_of(polygon({{0, 0}, {1e5, 1e-6}, {2e5, 0}, {1e5, 1e5}})).find("collinear"),
            std::string::npos);
  // A pentagram winds twice: every turn is to the left, yet it is not convex.
  std::vector<Vec2> star;
  for (int i = 0; i < 5; ++i) {
    const double a = i * 4 * std::numbers::pi / 5;
    star.push_back({std::cos(a), std::sin(a)});
  }
  EXPECT_EQ(problem_of(polygon(star)),
            "polygon must go round once, convex (vertex 3 lies outside edge 0 -> 1)");
}

TEST(ShapeChecks, PoseAndMaterial) {
  ShapeDef s = make_box(1, 1, {2e6, 0});
  EXPECT_EQ(problem_of(s), "offset must be finite with |x|, |y| <= 1000000 m (got 2000000, 0)");
  s = make_box(1, 1, {}, nan);
  EXPECT_EQ(problem_of(s).rfind("angle must be finite with |angle| <= ", 0), 0U);
  s = make_circle(1);
  s.density = -1;
  EXPECT_EQ(problem_of(s), "density must be finite, >= 0 and <= 1e100 kg/m^2 (got -1)");
  s.density = nan;
  EXPECT_EQ(problem_of(s), "density must be finite, >= 0 and <= 1e100 kg/m^2 (got nan)");
  s.density = std::nullopt;
  s.friction = -0.1;
  EXPECT_EQ(problem_of(s), "friction must be in [0, 1e100] (got -0.1)");
  s.friction = inf;
  EXPECT_EQ(problem_of(s), "friction must be in [0, 1e100] (got inf)");
  s.friction = std::nullopt;
  s.restitution = 1.5;
  EXPECT_EQ(problem_of(s), "restitution must be in [0, 1] (got 1.5)");
  s.restitution = nan;
  EXPECT_EQ(problem_of(s), "restitution must be in [0, 1] (got nan)");
  s.restitution = std::nullopt;
  s.kind = static_cast<ShapeKind>(7);
  EXPECT_EQ(problem_of(s), "kind must be circle, capsule, box or polygon");
}

TEST(ShapePlacement, AabbAndOutlineFollowTheShapeAndBodyPoses) {
  // A 2 × 1 box (hx = 1, hy = 0.5) at (1, 0) in the body; the body at (10, 0) turned by π/2:
  // the box's centre goes to (10, 1) and its long side along y.
  const ShapeDef box = make_box(1.0, 0.5, {1.0, 0.0}, 0.0, 0.1);
  const Aabb a = shape_aabb(box, {10.0, 0.0}, std::numbers::pi / 2);
  EXPECT_NEAR(a.lower.x, 10.0 - 0.5 - 0.1, 1e-14);
  EXPECT_NEAR(a.upper.x, 10.0 + 0.5 + 0.1, 1e-14);
  EXPECT_NEAR(a.lower.y, 0.0 - 0.1, 1e-14);
  EXPECT_NEAR(a.upper.y, 2.0 + 0.1, 1e-14);
  const ShapeOutline o = shape_outline(box, {10.0, 0.0}, std::numbers::pi / 2);
  EXPECT_EQ(o.count, 4);
  EXPECT_EQ(o.radius, 0.1);
  // The corner (-1, -0.5) of the box frame: (0, -0.5) in the body, (10.5, 0) in the world.
  EXPECT_NEAR(o.points[0].x, 10.5, 1e-14);
  EXPECT_NEAR(o.points[0].y, 0.0, 1e-14);
  // Counter-clockwise still.
  EXPECT_GT(cross(o.points[1] - o.points[0], o.points[2] - o.points[1]), 0.0);

  const ShapeDef circle = make_circle(0.5, {1.0, 2.0});
  const Aabb c = shape_aabb(circle, {-1.0, 0.0}, 0.0);
  EXPECT_EQ(c, (Aabb{{-0.5, 1.5}, {0.5, 2.5}}));
  const ShapeOutline co = shape_outline(circle, {-1.0, 0.0}, 0.0);
  EXPECT_EQ(co.count, 1);
  EXPECT_EQ(co.points[0], (Vec2{0.0, 2.0}));
  EXPECT_EQ(co.radius, 0.5);

  // A capsule turned by its own angle π (the segment 0..2 on x flips to -2..0).
  ShapeDef cap = make_capsule({0, 0}, {2, 0}, 0.25);
  cap.angle = std::numbers::pi;
  const Aabb k = shape_aabb(cap, {0.0, 0.0}, 0.0);
  EXPECT_NEAR(k.lower.x, -2.25, 1e-14);
  EXPECT_NEAR(k.upper.x, 0.25, 1e-14);
  EXPECT_NEAR(k.lower.y, -0.25, 1e-14);
  EXPECT_NEAR(k.upper.y, 0.25, 1e-14);
  EXPECT_EQ(shape_outline(cap, {}, 0.0).count, 2);
}

}  // namespace
}  // namespace fixstep
