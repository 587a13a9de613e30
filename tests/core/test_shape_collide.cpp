// Manifolds between shapes (collide, collide_plane, collide_segment), their distances and
// times of impact (engine/core/src/shape_geom.hpp), against hand-computed values. Each check
// states its tolerance; exact geometry (axis-aligned boxes) is checked to 1e-12 m.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "../../engine/core/src/shape_geom.hpp"

namespace {

using fixstep::ShapeDef;
using fixstep::ShapeKind;
using fixstep::Vec2;
using namespace fixstep::detail;

constexpr double sc_exact = 1e-12;  // m: sums and products of short decimals

Convex sc_box(double hx, double hy, double rounding = 0.0) {
  ShapeDef d;
  d.kind = ShapeKind::box;
  d.half_extents = {hx, hy};
  d.radius = rounding;
  return to_convex(d, {});
}
Convex sc_circle(double r) {
  ShapeDef d;
  d.kind = ShapeKind::circle;
  d.radius = r;
  return to_convex(d, {});
}
Convex sc_capsule(Vec2 a, Vec2 b, double r) {
  ShapeDef d;
  d.kind = ShapeKind::capsule;
  d.vertices[0] = a;
  d.vertices[1] = b;
  d.count = 2;
  d.radius = r;
  return to_convex(d, {});
}
Pose sc_at(double x, double y, double angle = 0.0) {
  return {{x, y}, rot_of(angle)};
}

/// The manifold's points sorted by x, for checks that do not depend on their order.
std::vector<ManifoldPoint> sc_by_x(const Manifold& m) {
  std::vector<ManifoldPoint> p(m.points.begin(), m.points.begin() + m.count);
  if (p.size() == 2 && p[1].point.x < p[0].point.x) std::swap(p[0], p[1]);
  return p;
}

void sc_expect_vec(Vec2 got, Vec2 want, double tol) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
}

TEST(ShapeCollide, ConvexFormOfEachKind) {
  // A box 1 × 0.5 (half) at offset (2, 1) turned 90° in the body, the body's centre of mass at
  // (0.5, 0.5): counter-clockwise corners (2.5, 0), (2.5, 2), (1.5, 2), (1.5, 0) shifted by
  // -(0.5, 0.5), outward unit normals.
  ShapeDef d;
  d.kind = ShapeKind::box;
  d.half_extents = {1, 0.5};
  d.offset = {2, 1};
  d.angle = 1.5707963267948966;
  d.radius = 0.1;
  const Convex c = to_convex(d, {0.5, 0.5});
  ASSERT_EQ(c.count, 4);
  EXPECT_EQ(c.radius, 0.1);
  const Vec2 want[4] = {{2.0, -0.5}, {2.0, 1.5}, {1.0, 1.5}, {1.0, -0.5}};
  const Vec2 normal[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  for (int i = 0; i < 4; ++i) {
    sc_expect_vec(c.vertices[i], want[i], 1e-15);
    sc_expect_vec(c.normals[i], normal[i], 1e-15);
  }
  EXPECT_NEAR(extent(c), std::sqrt(4.0 + 2.25) + 0.1, 1e-15);
  const fixstep::Aabb box = convex_aabb(c, sc_at(10, 20), 0.05);
  sc_expect_vec(box.lower, {10.85, 19.35}, 1e-12);
  sc_expect_vec(box.upper, {12.15, 21.65}, 1e-12);
  // A capsule: two vertices, the two sides' normals; a circle: its centre at the offset.
  const Convex cap = sc_capsule({0, 0}, {3, 4}, 0.25);
  ASSERT_EQ(cap.count, 2);
  sc_expect_vec(cap.normals[0], {0.8, -0.6}, 1e-15);
  sc_expect_vec(cap.normals[1], {-0.8, 0.6}, 1e-15);
  EXPECT_NEAR(extent(cap), 5.25, 1e-15);
  ShapeDef circle;
  circle.radius = 0.3;
  circle.offset = {1, -2};
  const Convex dot1 = to_convex(circle, {1, 1});
  ASSERT_EQ(dot1.count, 1);
  sc_expect_vec(dot1.vertices[0], {0, -3}, 0.0);
  EXPECT_NEAR(extent(dot1), 3.3, 1e-15);
  // segment_convex: a..b as it is, radius 0.
  const Convex seg = segment_convex({1, 1}, {1, 3});
  sc_expect_vec(seg.normals[0], {1, 0}, 0.0);
  EXPECT_EQ(seg.radius, 0.0);
}

TEST(ShapeCollide, BoxesFaceToFaceGiveTwoPointsMidway) {
  // Unit boxes, B 0.9 above A: faces at y = 0.5 and 0.4 overlap by 0.1; points midway at 0.45.
  const Pose ta = sc_at(0, 0), tb = sc_at(0, 0.9);
  const Manifold m = collide(sc_box(0.5, 0.5), ta, sc_box(0.5, 0.5), tb, 0.01);
  ASSERT_EQ(m.count, 2);
  sc_expect_vec(m.normal, {0, 1}, sc_exact);
  const auto p = sc_by_x(m);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(p[i].separation, -0.1, sc_exact);
    sc_expect_vec(p[i].point, {i == 0 ? -0.5 : 0.5, 0.45}, sc_exact);
    sc_expect_vec(p[i].anchor_a, p[i].point - ta.p, 0.0);
    sc_expect_vec(p[i].anchor_b, p[i].point - tb.p, 0.0);
  }
}

TEST(ShapeCollide, SwappingTheShapesReversesTheNormal) {
  const Manifold ab =
      collide(sc_box(0.5, 0.5), sc_at(0, 0), sc_box(0.5, 0.5), sc_at(0.2, 0.9), 0.01);
  const Manifold ba =
      collide(sc_box(0.5, 0.5), sc_at(0.2, 0.9), sc_box(0.5, 0.5), sc_at(0, 0), 0.01);
  ASSERT_EQ(ab.count, 2);
  ASSERT_EQ(ba.count, 2);
  sc_expect_vec(ba.normal, -ab.normal, sc_exact);
  const auto p = sc_by_x(ab), q = sc_by_x(ba);
  for (int i = 0; i < 2; ++i) {
    sc_expect_vec(p[i].point, q[i].point, sc_exact);
    EXPECT_NEAR(p[i].separation, q[i].separation, sc_exact);
  }  // A turned box's corner into B's top face: B holds the reference face, the normal is -y.
  const double h = 0.5 * std::sqrt(2.0);
  const Manifold c = collide(sc_box(0.5, 0.5), sc_at(0.2, 0.95 + h, 0.785398163397448),
                             sc_box(1, 1), sc_at(0, 0), 0.01);
  ASSERT_EQ(c.count, 1);
  sc_expect_vec(c.normal, {0, -1}, sc_exact);
  EXPECT_NEAR(c.points[0].separation, -0.05, 1e-9);
  sc_expect_vec(c.points[0].point, {0.2, 0.975}, 1e-9);
}

TEST(ShapeCollide, BoxOnPlaneGivesItsBottomCorners) {
  const Manifold m = collide_plane({0, 1}, 0.0, sc_box(0.5, 0.5), sc_at(1, 0.49), 0.01);
  ASSERT_EQ(m.count, 2);
  sc_expect_vec(m.normal, {0, 1}, 0.0);
  const auto p = sc_by_x(m);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(p[i].separation, -0.01, sc_exact);
    sc_expect_vec(p[i].point, {i == 0 ? 0.5 : 1.5, -0.005}, sc_exact);
    sc_expect_vec(p[i].anchor_b, p[i].point - Vec2{1, 0.49}, 0.0);
  }
  // Corner down (45°): one corner 0.02 deep, the next ones far above the speculative margin.
  const double h = 0.5 * std::sqrt(2.0);
  const Manifold c =
      collide_plane({0, 1}, 0.0, sc_box(0.5, 0.5), sc_at(0, h - 0.02, 0.785398163397448), 0.01);
  ASSERT_EQ(c.count, 1);
  EXPECT_NEAR(c.points[0].separation, -0.02, 1e-9);
  sc_expect_vec(c.points[0].point, {0, -0.01}, 1e-9);
}

TEST(ShapeCollide, RotatedBoxCornerIntoABoxFace) {
  // B turned 45°, its lowest corner at (0.2, 0.95): 0.05 into A's top face y = 1.
  const double h = 0.5 * std::sqrt(2.0);
  const Manifold m = collide(sc_box(1, 1), sc_at(0, 0), sc_box(0.5, 0.5),
                             sc_at(0.2, 0.95 + h, 0.785398163397448), 0.01);
  ASSERT_EQ(m.count, 1);
  sc_expect_vec(m.normal, {0, 1}, sc_exact);
  EXPECT_NEAR(m.points[0].separation, -0.05, 1e-9);
  sc_expect_vec(m.points[0].point, {0.2, 0.975}, 1e-9);
}

TEST(ShapeCollide, CircleAgainstPolygonEdgeAndVertexRegions) {
  // Edge region: the circle's bottom at 0.9, the box's top at 1.
  Manifold m = collide(sc_box(1, 1), sc_at(0, 0), sc_circle(0.5), sc_at(0.3, 1.4), 0.01);
  ASSERT_EQ(m.count, 1);
  sc_expect_vec(m.normal, {0, 1}, sc_exact);
  EXPECT_NEAR(m.points[0].separation, -0.1, sc_exact);
  sc_expect_vec(m.points[0].point, {0.3, 0.95}, sc_exact);
  // Vertex region: centre (1.3, 1.3), 0.3·√2 from the corner (1, 1).
  m = collide(sc_box(1, 1), sc_at(0, 0), sc_circle(0.5), sc_at(1.3, 1.3), 0.01);
  ASSERT_EQ(m.count, 1);
  const double k = std::sqrt(0.5), d = 0.3 * std::sqrt(2.0);
  sc_expect_vec(m.normal, {k, k}, 1e-12);
  EXPECT_NEAR(m.points[0].separation, d - 0.5, 1e-12);
  const double mid = 1.0 + 0.5 * (d - 0.5) * k;  // halfway from the corner to the circle
  sc_expect_vec(m.points[0].point, {mid, mid}, 1e-12);
  // The circle as A: the opposite normal, the same point.
  const Manifold r = collide(sc_circle(0.5), sc_at(1.3, 1.3), sc_box(1, 1), sc_at(0, 0), 0.01);
  ASSERT_EQ(r.count, 1);
  sc_expect_vec(r.normal, {-k, -k}, 1e-12);
  sc_expect_vec(r.points[0].point, m.points[0].point, 1e-12);
}

TEST(ShapeCollide, CirclesAndCapsules) {
  Manifold m = collide(sc_circle(0.5), sc_at(0, 0), sc_circle(0.3), sc_at(0.7, 0), 0.01);
  ASSERT_EQ(m.count, 1);
  sc_expect_vec(m.normal, {1, 0}, 0.0);
  EXPECT_NEAR(m.points[0].separation, -0.1, sc_exact);
  sc_expect_vec(m.points[0].point, {0.45, 0}, sc_exact);
  // A circle over a capsule's side and beyond its end.
  const Convex cap = sc_capsule({-1, 0}, {1, 0}, 0.2);
  m = collide(cap, sc_at(0, 0), sc_circle(0.3), sc_at(0.5, 0.45), 0.01);
  ASSERT_EQ(m.count, 1);
  sc_expect_vec(m.normal, {0, 1}, sc_exact);
  EXPECT_NEAR(m.points[0].separation, -0.05, sc_exact);
  sc_expect_vec(m.points[0].point, {0.5, 0.175}, sc_exact);
  m = collide(cap, sc_at(0, 0), sc_circle(0.3), sc_at(1.4, 0), 0.01);
  ASSERT_EQ(m.count, 1);
  sc_expect_vec(m.normal, {1, 0}, sc_exact);
  EXPECT_NEAR(m.points[0].separation, -0.1, sc_exact);
}

TEST(ShapeCollide, CapsulesParallelGiveTwoPointsCrossedOne) {
  const Convex a = sc_capsule({-1, 0}, {1, 0}, 0.2);
  Manifold m = collide(a, sc_at(0, 0), sc_capsule({-1, 0}, {1, 0}, 0.2), sc_at(0.5, 0.3), 0.01);
  ASSERT_EQ(m.count, 2);
  sc_expect_vec(m.normal, {0, 1}, sc_exact);
  const auto p = sc_by_x(m);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(p[i].separation, -0.1, sc_exact);
    sc_expect_vec(p[i].point, {i == 0 ? -0.5 : 1.0, 0.15}, sc_exact);
  }
  // Upright B standing on A's side: one point at its lower end.
  m = collide(a, sc_at(0, 0), sc_capsule({0, 0.3}, {0, 2}, 0.2), sc_at(0.4, 0), 0.01);
  ASSERT_EQ(m.count, 1);
  sc_expect_vec(m.normal, {0, 1}, sc_exact);
  EXPECT_NEAR(m.points[0].separation, -0.1, sc_exact);
  sc_expect_vec(m.points[0].point, {0.4, 0.15}, sc_exact);
  // B leaning back from beyond A's end: clipping would give (0.95, 0) 0.335 off, but the ends
  // (1, 0) and (1.1, 0.3) are closer, √0.1: the one point between them.
  m = collide(a, sc_at(0, 0), sc_capsule({1.1, 0.3}, {-0.9, 1.3}, 0.2), sc_at(0, 0), 0.01);
  ASSERT_EQ(m.count, 1);
  const double d = std::sqrt(0.1);
  sc_expect_vec(m.normal, {0.1 / d, 0.3 / d}, 1e-12);
  EXPECT_NEAR(m.points[0].separation, d - 0.4, 1e-12);
  sc_expect_vec(m.points[0].point, Vec2{1.05, 0.15}, 1e-12);
  // Crossed cores (B upright at x = 0.3 from y = -0.9 to 1.1): the shallowest way out is B
  // along +x by A's end 0.7 away (SAT; up would be 0.9), one point at A's end.
  m = collide(a, sc_at(0, 0), sc_capsule({0, -1}, {0, 1}, 0.2), sc_at(0.3, 0.1), 0.01);
  ASSERT_EQ(m.count, 1);
  sc_expect_vec(m.normal, {1, 0}, sc_exact);
  EXPECT_NEAR(m.points[0].separation, -0.7 - 0.4, sc_exact);
  sc_expect_vec(m.points[0].point, {0.65, 0}, sc_exact);
}

TEST(ShapeCollide, RoundedBoxes) {
  // Cores of half 0.4 rounded by 0.1: the surfaces of unit boxes, 0.1 overlap.
  const Convex r = sc_box(0.4, 0.4, 0.1);
  Manifold m = collide(r, sc_at(0, 0), r, sc_at(0, 0.9), 0.01);
  ASSERT_EQ(m.count, 2);
  sc_expect_vec(m.normal, {0, 1}, sc_exact);
  const auto p = sc_by_x(m);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(p[i].separation, -0.1, sc_exact);
    sc_expect_vec(p[i].point, {i == 0 ? -0.4 : 0.4, 0.45}, sc_exact);
  }
  // Corner to corner: the cores' corners (0.4, 0.4) and (0.6, 0.6), one point on the diagonal.
  m = collide(r, sc_at(0, 0), r, sc_at(1, 1), 0.1);
  ASSERT_EQ(m.count, 1);
  const double k = std::sqrt(0.5);
  sc_expect_vec(m.normal, {k, k}, 1e-12);
  EXPECT_NEAR(m.points[0].separation, 0.2 * std::sqrt(2.0) - 0.2, 1e-12);
  sc_expect_vec(m.points[0].point, {0.5, 0.5}, 1e-12);
}

TEST(ShapeCollide, SpeculativePointsHaveTheirPositiveSeparation) {
  Manifold m = collide(sc_box(0.5, 0.5), sc_at(0, 0), sc_box(0.5, 0.5), sc_at(0, 1.05), 0.1);
  ASSERT_EQ(m.count, 2);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, 0.05, sc_exact);
  m = collide(sc_box(0.5, 0.5), sc_at(0, 0), sc_box(0.5, 0.5), sc_at(0, 1.05), 0.01);
  EXPECT_EQ(m.count, 0);
  m = collide_plane({0, 1}, 0.0, sc_circle(0.5), sc_at(0, 0.53), 0.05);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, 0.03, sc_exact);
}

TEST(ShapeCollide, FeatureIdsStayUnderSmallMotion) {
  const Convex box = sc_box(0.5, 0.5);
  const Manifold m0 = collide(box, sc_at(0, 0), box, sc_at(0.1, 0.95, 0.002), 0.01);
  ASSERT_EQ(m0.count, 2);
  EXPECT_NE(m0.points[0].id, m0.points[1].id);
  for (const double dx : {-0.25, -0.05, 0.02, 0.2}) {
    // Turning more, or the other way (beyond a hair: clip_axis_tolerance), makes B's face the
    // reference: other features, other ids.
    for (const double da : {-1e-5, 0.0005, 0.001, 0.002}) {
      const Manifold m = collide(box, sc_at(0, 0), box, sc_at(0.1 + dx, 0.96, da), 0.01);
      ASSERT_EQ(m.count, 2) << dx << " " << da;
      const auto p = sc_by_x(m), q = sc_by_x(m0);
      EXPECT_EQ(p[0].id, q[0].id) << dx << " " << da;
      EXPECT_EQ(p[1].id, q[1].id) << dx << " " << da;
    }
  }
}

fixstep::SegmentDef sc_segment(Vec2 a, Vec2 b, std::optional<Vec2> prev, std::optional<Vec2> next) {
  fixstep::SegmentDef s;
  s.a = a;
  s.b = b;
  s.prev = prev;
  s.next = next;
  return s;
}

TEST(ShapeCollideSegment, BoxSlidingAcrossAFlatJointSeesOnlyTheFloor) {
  // The polyline (-3, 0) (0, 0) (3, 0): a unit box 0.01 deep slides across the joint, a little
  // tilted either way; every contact of either segment pushes straight up.
  const auto left = sc_segment({-3, 0}, {0, 0}, std::nullopt, Vec2{3, 0});
  const auto right = sc_segment({0, 0}, {3, 0}, Vec2{-3, 0}, std::nullopt);
  const Convex box = sc_box(0.5, 0.5);
  int contacts = 0;
  for (int i = 0; i <= 400; ++i) {
    const double x = -2.0 + 0.01 * i;
    for (const double angle : {-0.01, 0.0, 0.01}) {
      const Pose at = sc_at(x, 0.49, angle);
      int here = 0;
      for (const auto& seg : {left, right}) {
        const Manifold m = collide_segment(seg, box, at, 0.01);
        here += m.count;
        if (m.count == 0) continue;
        EXPECT_NEAR(m.normal.x, 0.0, 1e-12) << x << " " << angle;
        EXPECT_NEAR(m.normal.y, 1.0, 1e-12) << x << " " << angle;
        for (int k = 0; k < m.count; ++k) {
          EXPECT_GE(m.points[k].point.x, std::min(seg.a.x, seg.b.x) - 1e-12);
          EXPECT_LE(m.points[k].point.x, std::max(seg.a.x, seg.b.x) + 1e-12);
        }
      }
      EXPECT_GE(here, 1) << x << " " << angle;
      contacts += here;
    }
  }
  EXPECT_GT(contacts, 1000);
  // Without the ghost vertices the box just past the joint catches on the left segment's end:
  // its left face is the separating axis, the normal horizontal.
  const Manifold snag = collide_segment(sc_segment({-3, 0}, {0, 0}, std::nullopt, std::nullopt),
                                        box, sc_at(0.501, 0.49), 0.01);
  ASSERT_EQ(snag.count, 1);
  sc_expect_vec(snag.normal, {1, 0}, sc_exact);
  EXPECT_EQ(collide_segment(left, box, sc_at(0.501, 0.49), 0.01).count, 0);
}

TEST(ShapeCollideSegment, BoxAcrossBentJointsPushesAlongTheFacesOnly) {
  // A hilltop (the floor then 10° down) and a valley (the floor then 10° up): every normal of
  // either segment lies between the two faces' normals (within the 0.01 wedge tolerance), never
  // the horizontal push of a box's side caught on the joint.
  const double pi = 3.14159265358979323846, k = 10.0 * pi / 180.0;
  for (const double bend : {-k, k}) {
    const Vec2 far{3 * std::cos(bend), 3 * std::sin(bend)};
    const auto left = sc_segment({-3, 0}, {0, 0}, std::nullopt, far);
    const auto right = sc_segment({0, 0}, far, Vec2{-3, 0}, std::nullopt);
    const double lo = std::min(0.0, bend) - 0.011, hi = std::max(0.0, bend) + 0.011;
    int contacts = 0;
    for (int i = 0; i <= 200; ++i) {
      const double x = -1.0 + 0.01 * i * (bend < 0 ? 1.0 : 0.5);  // up a ramp: until 0.02 deep
      for (const double angle : {-0.01, 0.0, 0.01}) {
        for (const auto& seg : {left, right}) {
          const Manifold m = collide_segment(seg, sc_box(0.5, 0.5), sc_at(x, 0.49, angle), 0.01);
          contacts += m.count;
          if (m.count == 0) continue;
          const double tilt = std::atan2(-m.normal.x, m.normal.y);  // 0: straight up
          EXPECT_GE(tilt, lo) << bend << " " << x << " " << angle;
          EXPECT_LE(tilt, hi) << bend << " " << x << " " << angle;
        }
      }
    }
    EXPECT_GT(contacts, 300) << bend;
  }
}

TEST(ShapeCollideSegment, ConvexJointVertexBelongsToTheSegmentStartingThere) {
  // A roof (-1, -1) (0, 0) (1, -1); a circle on its ridge touches the joint vertex only, with the
  // upward normal inside the joint's wedge: reported once, by the segment that starts there.
  const auto up = sc_segment({-1, -1}, {0, 0}, std::nullopt, Vec2{1, -1});
  const auto down = sc_segment({0, 0}, {1, -1}, Vec2{-1, -1}, std::nullopt);
  const Pose at = sc_at(0, 0.45);
  EXPECT_EQ(collide_segment(up, sc_circle(0.5), at, 0.01).count, 0);
  const Manifold m = collide_segment(down, sc_circle(0.5), at, 0.01);
  ASSERT_EQ(m.count, 1);
  sc_expect_vec(m.normal, {0, 1}, sc_exact);
  EXPECT_NEAR(m.points[0].separation, -0.05, sc_exact);
  sc_expect_vec(m.points[0].anchor_a, m.points[0].point, 0.0);
  // A hilltop of 10°: a circle over the floor near the top touches the falling segment's
  // start along (-0.6, 0.8), beyond the joint's wedge ((0, 1) to (sin 10°, cos 10°)): dropped,
  // the floor's face contact (0, 1) holds it.
  const double k = 10.0 * 3.14159265358979323846 / 180.0;
  const auto floor = sc_segment({-3, 0}, {0, 0}, std::nullopt, Vec2{std::cos(k), -std::sin(k)});
  const auto fall = sc_segment({0, 0}, {std::cos(k), -std::sin(k)}, Vec2{-3, 0}, std::nullopt);
  const Pose beside = sc_at(-0.24, 0.32);
  EXPECT_EQ(collide_segment(fall, sc_circle(0.5), beside, 0.01).count, 0);
  const Manifold face = collide_segment(floor, sc_circle(0.5), beside, 0.01);
  ASSERT_EQ(face.count, 1);
  sc_expect_vec(face.normal, {0, 1}, sc_exact);
  EXPECT_NEAR(face.points[0].separation, -0.18, sc_exact);
  // A box resting on a short segment before a hilltop, turned a little so that its own face
  // is the reference and the normal leans towards the joint (within its wedge): kept, with the
  // point at the joint left to the segment that starts there.
  const auto shelf = sc_segment({-0.4, 0}, {0, 0}, std::nullopt, Vec2{3, -0.3});
  const auto slope = sc_segment({0, 0}, {3, -0.3}, Vec2{-0.4, 0}, std::nullopt);
  const Pose tilted = sc_at(-0.2, 0.49, -0.005);
  const Manifold s1 = collide_segment(shelf, sc_box(0.5, 0.5), tilted, 0.01);
  const Manifold s2 = collide_segment(slope, sc_box(0.5, 0.5), tilted, 0.01);
  ASSERT_EQ(s1.count, 1);
  ASSERT_EQ(s2.count, 1);
  EXPECT_GT(s1.normal.x, 0.0);  // leaning towards the joint: B's face is the reference
  EXPECT_NEAR(s1.points[0].point.x, -0.4, 1e-3);
  EXPECT_NEAR(s2.points[0].point.x, 0.0, 1e-3);
  // Both faces: a circle under a free segment is pushed down.
  const Manifold below = collide_segment(sc_segment({-1, 0}, {1, 0}, std::nullopt, std::nullopt),
                                         sc_circle(0.5), sc_at(0.2, -0.4), 0.01);
  ASSERT_EQ(below.count, 1);
  sc_expect_vec(below.normal, {0, -1}, sc_exact);
  EXPECT_NEAR(below.points[0].separation, -0.1, sc_exact);
}

TEST(ShapeDistance, AgainstAnalyticValues) {
  Distance d = distance(sc_circle(0.5), sc_at(0, 0), sc_circle(0.3), sc_at(2, 0));
  EXPECT_FALSE(d.overlap);
  EXPECT_NEAR(d.distance, 1.2, sc_exact);
  sc_expect_vec(d.normal, {1, 0}, sc_exact);
  sc_expect_vec(d.point_a, {0.5, 0}, sc_exact);
  sc_expect_vec(d.point_b, {1.7, 0}, sc_exact);
  // A box turned 45° at (2, 0.3): its corner 0.5·√2 left of its centre faces A's side x = 0.5.
  const double h = 0.5 * std::sqrt(2.0);
  d = distance(sc_box(0.5, 0.5), sc_at(0, 0), sc_box(0.5, 0.5), sc_at(2, 0.3, 0.785398163397448));
  EXPECT_NEAR(d.distance, 1.5 - h, 1e-12);
  sc_expect_vec(d.normal, {1, 0}, 1e-12);
  sc_expect_vec(d.point_a, {0.5, 0.3}, 1e-12);
  sc_expect_vec(d.point_b, {2 - h, 0.3}, 1e-12);
  // Corner to corner, rounded: √2 between the cores' corners, less 2 × 0.1.
  d = distance(sc_box(0.4, 0.4, 0.1), sc_at(0, 0), sc_box(0.4, 0.4, 0.1), sc_at(1.8, 1.8));
  EXPECT_NEAR(d.distance, std::sqrt(2.0) - 0.2, 1e-12);
  const double k = std::sqrt(0.5);
  sc_expect_vec(d.point_a, {0.4 + 0.1 * k, 0.4 + 0.1 * k}, 1e-12);
  // A capsule over a turned box's corner, and overlapping cores.
  d = distance(sc_box(0.5, 0.5), sc_at(0, 0, 0.785398163397448), sc_capsule({-1, 0}, {1, 0}, 0.1),
               sc_at(0.2, 1.5));
  EXPECT_NEAR(d.distance, 1.5 - h - 0.1, 1e-12);
  // Capsules end to end on one line and side by side: the simplex's points line up.
  const Convex cap = sc_capsule({-1, 0}, {1, 0}, 0.1);
  d = distance(cap, sc_at(0, 0), cap, sc_at(3, 0));
  EXPECT_NEAR(d.distance, 0.8, sc_exact);
  sc_expect_vec(d.normal, {1, 0}, sc_exact);
  d = distance(cap, sc_at(0, 0), cap, sc_at(0.5, 1));
  EXPECT_NEAR(d.distance, 0.8, sc_exact);
  sc_expect_vec(d.normal, {0, 1}, sc_exact);
  const Manifold ends = collide(cap, sc_at(0, 0), cap, sc_at(2.1, 0), 0.01);
  ASSERT_EQ(ends.count, 1);
  sc_expect_vec(ends.normal, {1, 0}, sc_exact);
  EXPECT_NEAR(ends.points[0].separation, -0.1, sc_exact);
  sc_expect_vec(ends.points[0].point, {1.05, 0}, sc_exact);
  d = distance(sc_box(0.5, 0.5), sc_at(0, 0), sc_box(0.5, 0.5), sc_at(0.7, 0.2));
  EXPECT_TRUE(d.overlap);
  EXPECT_EQ(d.distance, 0.0);
}

/// A reproducible uniform number in [lo, hi) (a 64-bit LCG, Knuth's MMIX constants).
double sc_uniform(std::uint64_t& state, double lo, double hi) {
  state = state * 6364136223846793005ULL + 1442695040888963407ULL;
  return lo + (hi - lo) * static_cast<double>(state >> 11U) * 0x1.0p-53;
}

/// The distance from p to the segment a..b.
double sc_point_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  double f = dot(p - a, e) / dot(e, e);
  f = f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
  const Vec2 d = p - (a + f * e);
  return std::sqrt(dot(d, d));
}

/// Whether p lies inside the counter-clockwise polygon c placed at t.
bool sc_inside(Vec2 p, const Convex& c, const Pose& t) {
  for (int i = 0; i < c.count; ++i) {
    if (dot(p - transform(t, c.vertices[i]), fixstep::detail::rotate(t.q, c.normals[i])) > 0.0) {
      return false;
    }
  }
  return true;
}

TEST(ShapeDistance, RandomBoxesAgreeWithBruteForceAndWithCollide) {
  // 3000 pairs of turned boxes: GJK against the least distance over all pairs of edges (when no
  // edges cross and neither holds the other's vertex), and collide's deepest point against it.
  std::uint64_t state = 12345;
  int apart = 0, overlapping = 0;
  for (int n = 0; n < 3000; ++n) {
    const Convex a = sc_box(sc_uniform(state, 0.1, 1), sc_uniform(state, 0.1, 1));
    const Convex b = sc_box(sc_uniform(state, 0.1, 1), sc_uniform(state, 0.1, 1));
    const Pose ta = sc_at(0, 0, sc_uniform(state, -3, 3));
    const Pose tb =
        sc_at(sc_uniform(state, -2.5, 2.5), sc_uniform(state, -2.5, 2.5), sc_uniform(state, -3, 3));
    double brute = 1e300;
    bool inside = false;
    for (int i = 0; i < 4; ++i) {
      const Vec2 a1 = transform(ta, a.vertices[i]), a2 = transform(ta, a.vertices[(i + 1) % 4]);
      const Vec2 b1 = transform(tb, b.vertices[i]), b2 = transform(tb, b.vertices[(i + 1) % 4]);
      inside = inside || sc_inside(a1, b, tb) || sc_inside(b1, a, ta);
      for (int j = 0; j < 4; ++j) {
        const Vec2 c1 = transform(tb, b.vertices[j]), c2 = transform(tb, b.vertices[(j + 1) % 4]);
        const bool cross_a = cross(a2 - a1, c1 - a1) * cross(a2 - a1, c2 - a1) <= 0.0;
        const bool cross_c = cross(c2 - c1, a1 - c1) * cross(c2 - c1, a2 - c1) <= 0.0;
        if (cross_a && cross_c) brute = 0.0;  // the edges cross
        brute = std::min({brute, sc_point_segment(a1, c1, c2), sc_point_segment(a2, c1, c2),
                          sc_point_segment(c1, a1, a2), sc_point_segment(c2, a1, a2)});
      }
      (void)b2;
    }
    const Distance d = distance(a, ta, b, tb);
    const Manifold m = collide(a, ta, b, tb, 1.0);
    double deepest = 1e300;
    for (int k = 0; k < m.count; ++k) deepest = std::min(deepest, m.points[k].separation);
    if (!inside && brute > 1e-6) {
      ++apart;
      ASSERT_FALSE(d.overlap) << n;
      ASSERT_NEAR(d.distance, brute, 1e-12) << n;
      if (brute < 0.9) {
        ASSERT_GE(m.count, 1) << n;
        EXPECT_GE(deepest, brute - 1e-12) << n;
        EXPECT_LE(deepest, brute + 5e-4) << n;  // clip_vertex_tolerance
      }
    } else if (inside) {
      ++overlapping;
      ASSERT_TRUE(d.overlap) << n;
      ASSERT_GE(m.count, 1) << n;
      EXPECT_LT(deepest, 0.0) << n;
    }
  }
  EXPECT_GT(apart, 1000);
  EXPECT_GT(overlapping, 300);
}

/// A random shape: circle, capsule, box, rounded box or triangle.
Convex sc_random_shape(std::uint64_t& state) {
  const int kind = static_cast<int>(sc_uniform(state, 0, 5));
  const double r = sc_uniform(state, 0.05, 0.4);
  if (kind == 0) return sc_circle(r);
  if (kind == 1)
    return sc_capsule({-sc_uniform(state, 0.1, 1), 0}, {sc_uniform(state, 0.1, 1), 0}, r);
  if (kind == 2) return sc_box(sc_uniform(state, 0.1, 1), sc_uniform(state, 0.1, 1));
  if (kind == 3) return sc_box(sc_uniform(state, 0.1, 1), sc_uniform(state, 0.1, 1), r);
  ShapeDef d;
  d.kind = ShapeKind::polygon;
  d.count = 3;
  d.vertices[0] = {-sc_uniform(state, 0.2, 1), -sc_uniform(state, 0.2, 1)};
  d.vertices[1] = {sc_uniform(state, 0.2, 1), -sc_uniform(state, 0.2, 1)};
  d.vertices[2] = {sc_uniform(state, -0.5, 0.5), sc_uniform(state, 0.2, 1)};
  d.radius = kind == 4 ? 0.0 : r;
  return to_convex(d, {});
}

TEST(ShapeCollide, RandomShapesAgreeWithTheDistance) {
  // Every pair of kinds, 5000 placements: apart by d < 0.9 (GJK), collide's deepest point is d
  // (up to the vertex tolerance, 5e-4 m); cores overlapping, it is below 0; either way the
  // normal is a unit vector and swapping A and B keeps the count and negates the normal.
  std::uint64_t state = 777;
  int apart = 0, overlapping = 0;
  for (int n = 0; n < 5000; ++n) {
    const Convex a = sc_random_shape(state), b = sc_random_shape(state);
    const Pose ta = sc_at(sc_uniform(state, -1, 1), 0, sc_uniform(state, -3, 3));
    const Pose tb =
        sc_at(sc_uniform(state, -2.5, 2.5), sc_uniform(state, -2.5, 2.5), sc_uniform(state, -3, 3));
    const Distance d = distance(a, ta, b, tb);
    const Manifold m = collide(a, ta, b, tb, 1.0);
    double deepest = 1e300;
    for (int k = 0; k < m.count; ++k) deepest = std::min(deepest, m.points[k].separation);
    if (m.count > 0) {
      EXPECT_NEAR(dot(m.normal, m.normal), 1.0, 1e-12) << n;
    }
    if (d.overlap) {
      ++overlapping;
      ASSERT_GE(m.count, 1) << n;
      EXPECT_LT(deepest, 0.0) << n;
    } else if (d.distance < 0.9) {
      ++apart;
      ASSERT_GE(m.count, 1) << n;
      EXPECT_GE(deepest, d.distance - 1e-9) << n;
      EXPECT_LE(deepest, d.distance + 5e-4) << n;
      const Manifold r = collide(b, tb, a, ta, 1.0);
      ASSERT_GE(r.count, 1) << n;
      if (deepest < d.distance + 1e-9) {
        double rdeep = 1e300;
        for (int k = 0; k < r.count; ++k) rdeep = std::min(rdeep, r.points[k].separation);
        EXPECT_NEAR(rdeep, deepest, 5e-4) << n;
      }
    } else if (d.distance > 1.0) {
      EXPECT_EQ(m.count, 0) << n;  // beyond the speculative distance
    }
  }
  EXPECT_GT(apart, 1000);
  EXPECT_GT(overlapping, 400);  // 594 when written: circles and capsules rarely overlap cores
}

TEST(ShapeTimeOfImpact, RandomSweepsAreConservative) {
  // 300 random pairs of shapes, each moving up to 6 m and turning up to 4 rad over the tick:
  // a hit lands within [target, target + tolerance] and no sampled earlier moment is closer;
  // a miss has no sampled moment closer than the target.
  std::uint64_t state = 4242;
  const double target = 0.005, tolerance = 1e-4;
  int hits = 0, misses = 0;
  for (int n = 0; n < 300; ++n) {
    const Convex a = sc_random_shape(state), b = sc_random_shape(state);
    Sweep sa, sb;
    sa.c0 = {sc_uniform(state, -4, -2), sc_uniform(state, -1, 1)};
    sa.c1 = sa.c0 + Vec2{sc_uniform(state, 0, 6), sc_uniform(state, -2, 2)};
    sa.a0 = sc_uniform(state, -3, 3);
    sa.a1 = sa.a0 + sc_uniform(state, -4, 4);
    sb.c0 = sb.c1 = {sc_uniform(state, -0.5, 0.5), sc_uniform(state, -1, 1)};
    sb.a0 = sc_uniform(state, -3, 3);
    sb.a1 = sb.a0 + sc_uniform(state, -1, 1);
    if (distance(a, pose_at(sa, 0), b, pose_at(sb, 0)).distance <= target + tolerance) continue;
    const Toi r = time_of_impact(a, sa, b, sb, target, tolerance);
    if (r.hit) {
      ++hits;
      const Distance at = distance(a, pose_at(sa, r.t), b, pose_at(sb, r.t));
      EXPECT_GE(at.distance, target - 1e-9) << n;
      if (r.iterations < 64) {
        EXPECT_LE(at.distance, target + tolerance) << n;
      }
    } else {
      ++misses;
    }
    const double end = r.hit ? r.t : 1.0;
    for (int i = 0; i <= 400; ++i) {
      const double t = end * i / 400.0;
      const Distance d = distance(a, pose_at(sa, t), b, pose_at(sb, t));
      ASSERT_GE(d.distance, target - 1e-9) << n << " " << t;
    }
  }
  EXPECT_GT(hits, 50);
  EXPECT_GT(misses, 20);
}

TEST(ShapeTimeOfImpact, FastBoxHitsAThinWallAtTheAnalyticTime) {
  // Centre from x = -5 to 5 over the tick; the wall's face at x = -0.005: the box's face reaches
  // target 0.001 before it when 4.495 - 10 t = 0.001.
  const Convex box = sc_box(0.5, 0.5), wall = sc_box(0.005, 1);
  const Sweep moving{{-5, 0}, {5, 0}, 0, 0}, still{};
  const double target = 0.001, tolerance = 1e-5;
  const Toi r = time_of_impact(box, moving, wall, still, target, tolerance);
  ASSERT_TRUE(r.hit);
  EXPECT_LE(r.t, (4.495 - target) / 10 + 1e-12);
  EXPECT_GE(r.t, (4.495 - target - tolerance) / 10 - 1e-12);
  EXPECT_LE(r.iterations, 3);
  // Along the wall, 2 m beside it: no hit.
  const Toi miss = time_of_impact(box, {{-5, 2}, {5, 2}, 0, 0}, wall, still, target, tolerance);
  EXPECT_FALSE(miss.hit);
  EXPECT_EQ(miss.t, 1.0);
}

TEST(ShapeTimeOfImpact, SpinningBoxStopsBeforeAThinWall) {
  // 500 m/s and 100 rad/s over a tick of 1/60 s (8.33 m, 1.67 rad) at a wall 1 cm thick.
  const Convex box = sc_box(0.5, 0.5), wall = sc_box(0.005, 2);
  const double tick = 1.0 / 60.0;
  const Sweep spin{{-4, 0}, {-4 + 500 * tick, 0}, 0.3, 0.3 + 100 * tick};
  const Sweep still{};
  const double target = 0.005, tolerance = 1e-4;
  const Toi r = time_of_impact(box, spin, wall, still, target, tolerance);
  ASSERT_TRUE(r.hit);
  EXPECT_LT(r.t, 1.0);
  EXPECT_LE(r.iterations, 20);  // 7 when written
  const Distance at = distance(box, pose_at(spin, r.t), wall, pose_at(still, r.t));
  EXPECT_FALSE(at.overlap);
  EXPECT_GE(at.distance, target - 1e-9);
  EXPECT_LE(at.distance, target + tolerance);
  // Conservative: at no earlier moment were they closer than the target.
  for (int i = 0; i < 4000; ++i) {
    const double t = r.t * i / 4000.0;
    const Distance d = distance(box, pose_at(spin, t), wall, pose_at(still, t));
    ASSERT_FALSE(d.overlap) << t;
    ASSERT_GE(d.distance, target - 1e-9) << t;
  }
  // The same spin 3 m above the wall's top: no hit, t = t_max.
  const Sweep above{{-4, 5}, {-4 + 500 * tick, 5}, 0.3, 0.3 + 100 * tick};
  const Toi miss = time_of_impact(box, above, wall, still, target, tolerance, 0.5);
  EXPECT_FALSE(miss.hit);
  EXPECT_EQ(miss.t, 0.5);
}

}  // namespace
