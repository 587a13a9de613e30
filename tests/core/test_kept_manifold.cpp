// Contact recycling (engine/core/src/kept_manifold.hpp): a kept manifold made again at the poses
// it was kept at is collide()'s own, it follows a vertex point as collide() does, it holds only
// while the pair's relative motion and the speculative distance's growth stay within the
// tolerance, and a world never carries a kept manifold over to shapes made after a destroy.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../../engine/core/src/kept_manifold.hpp"
#include "../../engine/core/src/shape_geom.hpp"
#include "../cross/shape_exact.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace {

using fixstep::Vec2;
using namespace fixstep::detail;

Convex km_box(double hx, double hy) {
  return to_convex(fixstep::make_box(hx, hy), {});
}

// A pose and its angle, as the shape world holds them.
struct KmPlaced {
  Pose pose;
  double angle = 0.0;
};
KmPlaced km_at(Vec2 p, double angle) {
  return {{p, rot_of(angle)}, angle};
}

// The same rigid motion (a turn by `turn` about the origin, then a shift) applied to a placement.
KmPlaced km_moved(const KmPlaced& k, double turn, Vec2 shift) {
  const Rot q = rot_of(turn);
  return km_at(rotate(q, k.pose.p) + shift, k.angle + turn);
}

constexpr double km_speculative = 0.02;  // m: four slops, a resting pair's
constexpr double km_tolerance = 0.005;   // m: the shape world's (one slop)

void km_expect_same(const Manifold& got, const Manifold& want, double tol) {
  ASSERT_EQ(got.count, want.count);
  EXPECT_NEAR(got.normal.x, want.normal.x, tol);
  EXPECT_NEAR(got.normal.y, want.normal.y, tol);
  for (int i = 0; i < want.count; ++i) {
    const ManifoldPoint &g = got.points[i], &w = want.points[i];
    EXPECT_EQ(g.id, w.id) << i;
    EXPECT_NEAR(g.separation, w.separation, tol) << i;
    EXPECT_NEAR(g.point.x, w.point.x, tol) << i;
    EXPECT_NEAR(g.point.y, w.point.y, tol) << i;
    EXPECT_NEAR(g.anchor_a.x, w.anchor_a.x, tol) << i;
    EXPECT_NEAR(g.anchor_a.y, w.anchor_a.y, tol) << i;
    EXPECT_NEAR(g.anchor_b.x, w.anchor_b.x, tol) << i;
    EXPECT_NEAR(g.anchor_b.y, w.anchor_b.y, tol) << i;
  }
}

// Made again at the poses it was kept at, a kept manifold is collide()'s (to rounding: 1e-12 m
// on metre-sized shapes), whichever frame the pair is in: a box resting flat on a wider one
// (two points, one of them clipped) and a tilted box on its corner (one point).
TEST(KeptManifold, MadeAgainWhereItWasKeptIsCollideItself) {
  const Convex wide = km_box(2.0, 0.5), small = km_box(0.5, 0.25);
  const KmPlaced flat_a = km_at({0.0, 0.0}, 0.0), flat_b = km_at({1.8, 0.749}, 0.0);
  const KmPlaced tilt_a = km_at({0.0, 0.0}, 0.0);
  const double tilt = 0.4;  // the corner (-0.5, -0.25) turned is the lowest point
  const Vec2 corner = rotate(rot_of(tilt), Vec2{-0.5, -0.25});
  const KmPlaced tilt_b = km_at({0.3, 0.5 + 0.001 - corner.y}, tilt);
  for (const double turn : {0.0, 0.7, -2.9}) {
    for (const auto& [a, b, points] :
         {std::tuple{flat_a, flat_b, 2}, std::tuple{tilt_a, tilt_b, 1}}) {
      const KmPlaced ta = km_moved(a, turn, {3.0, -7.0}), tb = km_moved(b, turn, {3.0, -7.0});
      const Manifold m = collide(wide, ta.pose, small, tb.pose, km_speculative);
      ASSERT_EQ(m.count, points) << turn;
      const KeptManifold k =
          keep_manifold(7, m, ta.pose, ta.angle, tb.pose, tb.angle, km_speculative);
      EXPECT_EQ(k.pair, 7u);
      km_expect_same(recycle(k, ta.pose, tb.pose), m, 1e-12);
    }
  }
}

// A corner over a face: after B slides 2 mm along the face, sinks 1.5 mm and turns 1 mrad, the
// kept point's separation is collide()'s to 1e-6 m (the kept point sits half a separation from
// the corner, and the turn moves it 1e-3 times that unlike the corner itself), its id is the
// same, and its point lags by half the slide (the point on A stays where it was made).
TEST(KeptManifold, FollowsACornerAsCollideDoes) {
  const Convex wide = km_box(2.0, 0.5), small = km_box(0.5, 0.25);
  const double tilt = 0.4;
  const Vec2 corner = rotate(rot_of(tilt), Vec2{-0.5, -0.25});
  const KmPlaced a = km_at({0.0, 0.0}, 0.0), b = km_at({0.3, 0.5 + 0.001 - corner.y}, tilt);
  const Manifold made = collide(wide, a.pose, small, b.pose, km_speculative);
  ASSERT_EQ(made.count, 1);
  const KeptManifold k = keep_manifold(1, made, a.pose, a.angle, b.pose, b.angle, km_speculative);
  const KmPlaced now = km_at(b.pose.p + Vec2{0.002, -0.0015}, tilt + 1e-3);
  const Manifold fresh = collide(wide, a.pose, small, now.pose, km_speculative);
  const Manifold kept = recycle(k, a.pose, now.pose);
  ASSERT_EQ(fresh.count, 1);
  ASSERT_EQ(kept.count, 1);
  EXPECT_EQ(kept.points[0].id, fresh.points[0].id);
  EXPECT_NEAR(kept.points[0].separation, fresh.points[0].separation, 1e-6);
  EXPECT_NEAR(kept.normal.y, 1.0, 1e-15);
  EXPECT_NEAR(kept.points[0].point.x, 0.5 * (made.points[0].point.x + fresh.points[0].point.x),
              1e-6);
  // Lever arms to one point: an impulse there moves no angular momentum between the bodies.
  const Vec2 pa = a.pose.p + kept.points[0].anchor_a, pb = now.pose.p + kept.points[0].anchor_b;
  EXPECT_NEAR(pa.x, pb.x, 1e-15);
  EXPECT_NEAR(pa.y, pb.y, 1e-15);
}

// It holds while the relative motion (|Δc| + extent |Δθ|) plus the speculative distance's
// growth is within the tolerance, whatever the pair does together; never for a NaN.
TEST(KeptManifold, HoldsOnlyWhileTheRelativeMotionIsWithinTheTolerance) {
  const Convex wide = km_box(2.0, 0.5), small = km_box(0.5, 0.25);
  const double extent = std::hypot(0.5, 0.25);
  const KmPlaced a = km_at({0.0, 0.0}, 0.0), b = km_at({1.8, 0.749}, 0.0);
  const Manifold m = collide(wide, a.pose, small, b.pose, km_speculative);
  const KeptManifold k = keep_manifold(1, m, a.pose, a.angle, b.pose, b.angle, km_speculative);
  auto holds = [&](const KmPlaced& ta, const KmPlaced& tb, double speculative) {
    return kept_holds(k, ta.pose, ta.angle, tb.pose, tb.angle, extent, speculative, km_tolerance);
  };
  EXPECT_TRUE(holds(a, b, km_speculative));
  // The pair turned and carried far together: B has not moved relative to A.
  EXPECT_TRUE(holds(km_moved(a, 1.3, {40.0, 5.0}), km_moved(b, 1.3, {40.0, 5.0}), km_speculative));
  const Vec2 p = b.pose.p;
  EXPECT_TRUE(holds(a, km_at(p + Vec2{0.0049, 0.0}, 0.0), km_speculative));
  EXPECT_FALSE(holds(a, km_at(p + Vec2{0.0051, 0.0}, 0.0), km_speculative));
  EXPECT_FALSE(holds(a, km_at(p + Vec2{0.0036, -0.0036}, 0.0), km_speculative));  // 5.09 mm
  EXPECT_TRUE(holds(a, km_at(p, 0.99 * km_tolerance / extent), km_speculative));
  EXPECT_FALSE(holds(a, km_at(p, 1.01 * km_tolerance / extent), km_speculative));
  // A turns instead: B's centre swings through A's frame.
  EXPECT_FALSE(holds(km_at({0.0, 0.0}, 0.01), b, km_speculative));
  // The speculative distance: shrunk, nothing to add; grown, it counts as motion.
  EXPECT_TRUE(holds(a, b, 0.5 * km_speculative));
  EXPECT_TRUE(holds(a, b, km_speculative + 0.99 * km_tolerance));
  EXPECT_FALSE(holds(a, b, km_speculative + 1.01 * km_tolerance));
  EXPECT_FALSE(holds(a, km_at(p + Vec2{0.003, 0.0}, 0.0), km_speculative + 0.003));
#ifndef FIXSTEP_FP_TRAPS  // (Debug builds trap the comparison of a NaN, as the engine's guard)
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(holds(a, km_at({nan, 0.749}, 0.0), km_speculative));
  EXPECT_FALSE(holds(a, b, nan));
#endif
}

// A world keeps its pairs' manifolds by the shapes' indices: a box destroyed and another of
// another size made at its place (in the slot it freed, at the same pose) is collided afresh,
// so its first manifold has its own gap (1 cm) and not the old box's (resting, about 0).
TEST(KeptManifold, AShapeMadeAfterADestroyIsCollidedAfresh) {
  using namespace fixstep;
  WorldSettings settings = shape_exact::shape_settings(0.5);
  detail::WorldKernel<double> w(settings);
  BodyDef ground = shape_exact::box_body(4.0, 0.5, {0.0, -0.5});
  ground.type = BodyType::static_body;
  ground.gravity.reset();
  w.create_body(ground);
  const Entity first = w.create_body(shape_exact::box_body(0.5, 0.25, {0.0, 0.25}));
  for (int i = 0; i < 30; ++i) w.step();
  const detail::ShapeWorld* sw = w.shape_world();
  ASSERT_NE(sw, nullptr);
  ASSERT_EQ(sw->rows().size(), 2u);
  EXPECT_NEAR(sw->rows()[0].separation, 0.0, 0.006);
  const Vec2 at = w.body(first).position;
  w.destroy(first);
  BodyDef thinner = shape_exact::box_body(0.5, 0.24, at);  // its bottom 1 cm above the old one's
  thinner.body.velocity = {};
  const Entity second = w.create_body(thinner);
  EXPECT_EQ(second.slot(), first.slot());
  w.step();
  sw = w.shape_world();
  ASSERT_EQ(sw->rows().size(), 2u);
  for (const detail::ShapeRow& r : sw->rows()) EXPECT_NEAR(r.separation, 0.01, 0.002);
}

}  // namespace
