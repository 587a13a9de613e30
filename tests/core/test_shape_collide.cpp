// Manifolds between shapes (collide, collide_plane, collide_segment), their distances and
// times of impact (engine/core/src/shape_geom.hpp), against hand-computed values. Each check
// states its tolerance; exact geometry (axis-aligned boxes) is checked to 1e-12 m.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  // Both faces: a circle under a free segment is pushed down.
  const Manifold below = collide_segment(sc_segment({-1, 0}, {1, 0}, std::nullopt, std::nullopt),
                                         sc_circle(0.5), sc_at(0.2, -0.4), 0.01);
  ASSERT_EQ(below.count, 1);
  sc_expect_vec(below.normal, {0, -1}, sc_exact);
  EXPECT_NEAR(below.points[0].separation, -0.1, sc_exact);
}

}  // namespace
