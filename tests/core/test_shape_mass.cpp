// Mass properties of shapes (shape_mass.cpp): each kind against its closed form, rounded shapes
// against an independent numeric integration, poses, and compound bodies (body_mass).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "fixstep/core/shape.hpp"

namespace fixstep {
namespace {

constexpr double pi = std::numbers::pi;

/// Relative closeness: |a - b| <= tol · max(|a|, |b|, 1e-300).
::testing::AssertionResult near_rel(double a, double b, double tol) {
  const double scale = std::max({std::fabs(a), std::fabs(b), 1e-300});
  if (std::fabs(a - b) <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " and " << b << " differ by "
                                       << std::fabs(a - b) / scale << " (relative), over " << tol;
}

TEST(ShapeMass, CircleIsHalfMrSquared) {
  const double r = 0.75, rho = 3.0;
  const MassProperties m = shape_mass(make_circle(r, {2.0, -1.0}), rho);
  EXPECT_TRUE(near_rel(m.area, pi * r * r, 1e-15));
  EXPECT_TRUE(near_rel(m.mass, rho * pi * r * r, 1e-15));
  EXPECT_EQ(m.center, (Vec2{2.0, -1.0}));
  EXPECT_TRUE(near_rel(m.inertia, 0.5 * m.mass * r * r, 1e-15));
}

TEST(ShapeMass, BoxIsMassTimesWidthSquaredPlusHeightSquaredOverTwelve) {
  const double hx = 1.5, hy = 0.25, rho = 2.0;
  const MassProperties m = shape_mass(make_box(hx, hy), rho);
  const double w = 2 * hx, h = 2 * hy;
  EXPECT_TRUE(near_rel(m.mass, rho * w * h, 1e-15));
  EXPECT_NEAR(m.center.x, 0.0, 1e-15);
  EXPECT_NEAR(m.center.y, 0.0, 1e-15);
  EXPECT_TRUE(near_rel(m.inertia, m.mass * (w * w + h * h) / 12.0, 1e-14));
}

TEST(ShapeMass, RightTriangleKnownValues) {
  // Legs a along x and b along y: area ab/2, centroid (a/3, b/3), J = m (a² + b²) / 18
  // (a triangle's polar moment about its centroid is m (a² + b² + c²) / 36 for sides a, b, c).
  const double a = 3.0, b = 2.0;
  const std::array<Vec2, 3> pts{Vec2{0, 0}, Vec2{a, 0}, Vec2{0, b}};
  const MassProperties m = shape_mass(make_polygon(pts), 1.0);
  EXPECT_TRUE(near_rel(m.area, a * b / 2, 1e-15));
  EXPECT_TRUE(near_rel(m.center.x, a / 3, 1e-15));
  EXPECT_TRUE(near_rel(m.center.y, b / 3, 1e-15));
  EXPECT_TRUE(near_rel(m.inertia, m.mass * (a * a + b * b) / 18.0, 1e-14));
}

TEST(ShapeMass, GeneralTriangleBySideLengths) {
  const std::array<Vec2, 3> p{Vec2{-1.0, 0.5}, Vec2{2.5, -0.25}, Vec2{0.75, 3.0}};
  const MassProperties m = shape_mass(make_polygon(p), 0.5);
  const auto sq = [](Vec2 d) { return d.x * d.x + d.y * d.y; };
  const double area = 0.5 * cross(p[1] - p[0], p[2] - p[0]);
  EXPECT_TRUE(near_rel(m.mass, 0.5 * area, 1e-15));
  EXPECT_TRUE(near_rel(m.center.x, (p[0].x + p[1].x + p[2].x) / 3, 1e-15));
  EXPECT_TRUE(near_rel(m.center.y, (p[0].y + p[1].y + p[2].y) / 3, 1e-15));
  const double sides = sq(p[1] - p[0]) + sq(p[2] - p[1]) + sq(p[0] - p[2]);
  EXPECT_TRUE(near_rel(m.inertia, m.mass * sides / 36.0, 1e-14));
}

TEST(ShapeMass, CapsuleClosedForm) {
  // Rectangle 2r × L plus a disc, the disc's halves at L/2 + 4r/(3π) from the midpoint:
  // J = L³r/6 + 2Lr³ + π r⁴/2 + π r² L²/4 per unit density.
  const double r = 0.4, len = 2.0, rho = 1.5;
  const MassProperties m = shape_mass(make_capsule({-1.0, 1.0}, {1.0, 1.0}, r), rho);
  EXPECT_TRUE(near_rel(m.area, 2 * r * len + pi * r * r, 1e-15));
  EXPECT_TRUE(near_rel(m.mass, rho * m.area, 1e-15));
  EXPECT_EQ(m.center, (Vec2{0.0, 1.0}));
  const double j = len * len * len * r / 6 + 2 * len * r * r * r + pi * r * r * r * r / 2 +
                   pi * r * r * len * len / 4;
  EXPECT_TRUE(near_rel(m.inertia, rho * j, 1e-14));
}

/// Area, centroid and polar moment of the region `inside` within [lo, hi] by the midpoint rule
/// on an n × n grid: an integration independent of the closed forms.
MassProperties integrate(const std::function<bool(double, double)>& inside, Vec2 lo, Vec2 hi,
                         int n) {
  const double dx = (hi.x - lo.x) / n, dy = (hi.y - lo.y) / n, cell = dx * dy;
  double area = 0, mx = 0, my = 0, jx = 0;
  for (int i = 0; i < n; ++i) {
    const double x = lo.x + (i + 0.5) * dx;
    for (int j = 0; j < n; ++j) {
      const double y = lo.y + (j + 0.5) * dy;
      if (!inside(x, y)) continue;
      area += cell;
      mx += x * cell;
      my += y * cell;
      jx += (x * x + y * y) * cell;
    }
  }
  const Vec2 c{mx / area, my / area};
  return {area, c, jx - area * (c.x * c.x + c.y * c.y), area};
}

/// The distance from (x, y) to the segment a..b.
double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  const double t = std::clamp(dot(p - a, e) / dot(e, e), 0.0, 1.0);
  const Vec2 d = p - (a + t * e);
  return std::sqrt(dot(d, d));
}

// The grid's boundary cells make errors of about h · perimeter / area, with h = size / 2000,
// mostly cancelling along a smooth boundary: 1e-4 relative is the stated tolerance (the errors
// measured are below 3.1e-5).
constexpr int grid = 2000;
constexpr double grid_tolerance = 1e-4;

TEST(ShapeMass, RoundedBoxAgainstNumericIntegration) {
  const double hx = 1.0, hy = 0.5, r = 0.3;
  const MassProperties m = shape_mass(make_box(hx, hy, {}, 0.0, r), 1.0);
  const MassProperties ref = integrate(
      [&](double x, double y) {
        const double dx = std::max(std::fabs(x) - hx, 0.0), dy = std::max(std::fabs(y) - hy, 0.0);
        return dx * dx + dy * dy <= r * r;
      },
      {-hx - r, -hy - r}, {hx + r, hy + r}, grid);
  // Steiner's formula for the area: the box, r times the perimeter, π r².
  EXPECT_TRUE(near_rel(m.area, 4 * hx * hy + r * 4 * (hx + hy) + pi * r * r, 1e-15));
  EXPECT_TRUE(near_rel(m.area, ref.area, grid_tolerance));
  EXPECT_NEAR(m.center.x, 0.0, 1e-15);
  EXPECT_NEAR(m.center.y, 0.0, 1e-15);
  EXPECT_TRUE(near_rel(m.inertia, ref.inertia, grid_tolerance));
}

TEST(ShapeMass, RoundedTriangleAgainstNumericIntegration) {
  // No symmetry: the corner sectors' first moments move the centre.
  const std::array<Vec2, 3> p{Vec2{0, 0}, Vec2{2, 0}, Vec2{0.5, 1.5}};
  const double r = 0.25;
  const MassProperties m = shape_mass(make_polygon(p, r), 1.0);
  const MassProperties ref = integrate(
      [&](double x, double y) {
        const Vec2 q{x, y};
        bool in = true;
        for (int i = 0; i < 3; ++i) in = in && cross(p[(i + 1) % 3] - p[i], q - p[i]) >= 0;
        if (in) return true;
        for (int i = 0; i < 3; ++i) {
          if (segment_distance(q, p[i], p[(i + 1) % 3]) <= r) return true;
        }
        return false;
      },
      {-r, -r}, {2 + r, 1.5 + r}, grid);
  const double perimeter = 2 + std::hypot(1.5, 1.5) + std::hypot(0.5, 1.5);
  EXPECT_TRUE(near_rel(m.area, 1.5 + r * perimeter + pi * r * r, 1e-15));
  EXPECT_TRUE(near_rel(m.area, ref.area, grid_tolerance));
  EXPECT_TRUE(near_rel(m.center.x, ref.center.x, grid_tolerance));
  EXPECT_TRUE(near_rel(m.center.y, ref.center.y, grid_tolerance));
  EXPECT_TRUE(near_rel(m.inertia, ref.inertia, grid_tolerance));
}

TEST(ShapeMass, CapsuleAgainstNumericIntegration) {
  const Vec2 a{-0.5, 0.2}, b{1.0, 0.8};
  const double r = 0.35;
  const MassProperties m = shape_mass(make_capsule(a, b, r), 1.0);
  const MassProperties ref = integrate(
      [&](double x, double y) {
        return segment_distance({x, y}, a, b) <= r;
      },
      {-0.5 - r, 0.2 - r}, {1.0 + r, 0.8 + r}, grid);
  EXPECT_TRUE(near_rel(m.area, ref.area, grid_tolerance));
  EXPECT_TRUE(near_rel(m.inertia, ref.inertia, grid_tolerance));
}

TEST(ShapeMass, RoundedPolygonOfZeroRoundingIsThePolygon) {
  const std::array<Vec2, 5> p{Vec2{0, 0}, Vec2{2, -0.5}, Vec2{3, 1}, Vec2{1.5, 2.5},
                              Vec2{-0.5, 1.5}};
  const MassProperties sharp = shape_mass(make_polygon(p), 2.0);
  const MassProperties tiny = shape_mass(make_polygon(p, 1e-9), 2.0);
  EXPECT_TRUE(near_rel(tiny.mass, sharp.mass, 1e-8));
  EXPECT_TRUE(near_rel(tiny.inertia, sharp.inertia, 1e-8));
  EXPECT_NEAR(tiny.center.x, sharp.center.x, 1e-9);
  EXPECT_NEAR(tiny.center.y, sharp.center.y, 1e-9);
}

TEST(ShapeMass, PoseMovesTheCentreAndKeepsTheInertia) {
  const std::array<Vec2, 3> p{Vec2{0, 0}, Vec2{3, 0}, Vec2{0, 2}};
  ShapeDef tri = make_polygon(p);
  const MassProperties at_origin = shape_mass(tri, 1.0);
  tri.offset = {5.0, -2.0};
  tri.angle = pi / 2;  // (1, 2/3) turns to about (-2/3, 1)
  const MassProperties posed = shape_mass(tri, 1.0);
  EXPECT_NEAR(posed.center.x, 5.0 - 2.0 / 3.0, 1e-14);
  EXPECT_NEAR(posed.center.y, -2.0 + 1.0, 1e-14);
  EXPECT_EQ(posed.inertia, at_origin.inertia);
  EXPECT_EQ(posed.mass, at_origin.mass);

  const MassProperties box = shape_mass(make_box(1.0, 0.5, {2.0, 3.0}, 0.7), 1.0);
  EXPECT_NEAR(box.center.x, 2.0, 1e-15);
  EXPECT_NEAR(box.center.y, 3.0, 1e-15);
  EXPECT_TRUE(near_rel(box.inertia, 2.0 * (4.0 + 1.0) / 12.0, 1e-14));

  ShapeDef cap = make_capsule({0, 0}, {2, 0}, 0.5);
  cap.offset = {0.0, 1.0};
  cap.angle = pi;  // the midpoint (1, 0) turns to (-1, 0), then moves up by 1
  const MassProperties c = shape_mass(cap, 1.0);
  EXPECT_NEAR(c.center.x, -1.0, 1e-15);
  EXPECT_NEAR(c.center.y, 1.0, 1e-15);
}

// An L of two boxes: the bar [0, 3] × [0, 1] (area 3) and the post [0, 1] × [1, 3] (area 2).
// At density 2: masses 6 and 4, centre (6 (1.5, 0.5) + 4 (0.5, 2)) / 10 = (1.1, 1.1);
// own inertias 6 (9 + 1)/12 = 5 and 4 (1 + 4)/12 = 5/3; offsets (0.4, -0.6) and (-0.6, 0.9)
// add 6 · 0.52 = 3.12 and 4 · 1.17 = 4.68: I = 14.8 - 0.4 + 5/3 = 12.8 + 5/3.
std::vector<ShapeDef> l_shape() {
  return {make_box(1.5, 0.5, {1.5, 0.5}), make_box(0.5, 1.0, {0.5, 2.0})};
}
constexpr double l_inertia = 12.8 + 5.0 / 3.0;

TEST(BodyMass, AnLOfTwoBoxesByHand) {
  std::vector<ShapeDef> shapes = l_shape();
  for (ShapeDef& s : shapes) s.density = 2.0;
  const MassProperties m = body_mass(shapes, 123.0);  // densities given: the mass is ignored
  EXPECT_TRUE(near_rel(m.mass, 10.0, 1e-15));
  EXPECT_TRUE(near_rel(m.area, 5.0, 1e-15));
  EXPECT_TRUE(near_rel(m.center.x, 1.1, 1e-15));
  EXPECT_TRUE(near_rel(m.center.y, 1.1, 1e-15));
  EXPECT_TRUE(near_rel(m.inertia, l_inertia, 1e-14));
}

TEST(BodyMass, WithoutDensitiesTheMassIsSpreadOverTheArea) {
  const std::vector<ShapeDef> shapes = l_shape();
  const MassProperties m = body_mass(shapes, 10.0);
  EXPECT_EQ(m.mass, 10.0);
  EXPECT_TRUE(near_rel(m.center.x, 1.1, 1e-15));
  EXPECT_TRUE(near_rel(m.center.y, 1.1, 1e-15));
  EXPECT_TRUE(near_rel(m.inertia, l_inertia, 1e-14));
}

TEST(BodyMass, AShapeWithoutDensityWeighsNothingBesideOneWithIt) {
  std::vector<ShapeDef> shapes = l_shape();
  shapes[0].density = 2.0;
  const MassProperties m = body_mass(shapes, 10.0);
  EXPECT_TRUE(near_rel(m.mass, 6.0, 1e-15));
  EXPECT_TRUE(near_rel(m.area, 5.0, 1e-15));
  EXPECT_TRUE(near_rel(m.center.x, 1.5, 1e-15));
  EXPECT_TRUE(near_rel(m.inertia, 5.0, 1e-14));
}

TEST(BodyMass, NoMassOrNoAreaThrows) {
  try {
    (void)body_mass({}, 1.0);
    ADD_FAILURE() << "body_mass of no shapes returned";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "body_mass: the shapes have no area");
  }
  std::vector<ShapeDef> shapes = l_shape();
  EXPECT_THROW((void)body_mass(shapes, 0.0), std::invalid_argument);
  for (ShapeDef& s : shapes) s.density = 0.0;
  EXPECT_THROW((void)body_mass(shapes, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace fixstep
