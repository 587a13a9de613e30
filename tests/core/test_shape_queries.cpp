// World's queries against bodies with shapes: ray casts against turned boxes, capsules and
// rounded boxes at analytic points and normals, misses in a rounded corner's miter, the order
// of all hits, points near a turned triangle's edges, a box query that a corner alone reaches,
// filters and sensors, f32 against f64, a warm query's allocations (the random cross-check
// against a sampled distance is in test_shape_query_sampled.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/query.hpp"
#include "fixstep/core/random.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

// count_new.cpp: this program's operator new, counting the bytes asked for while counting.
extern std::atomic<bool> counting;
extern std::atomic<std::size_t> counted_bytes;

namespace fixstep {
namespace shape_query_tests {

World make_world(Precision p = Precision::f64) {
  WorldSettings s{.dt = 0.01};
  s.contacts = ContactSettings{};
  return World(WorldDef::empty(p, s));
}

Entity put(World& w, std::vector<ShapeDef> shapes, Vec2 at, double angle,
           BodyType type = BodyType::static_body) {
  BodyDef b;
  b.type = type;
  b.body = Body{.mass = 1.0, .position = at, .angle = angle};
  b.shapes = std::move(shapes);
  return w.create_body(b);
}

/// R(θ) v and the pose p + R(θ) v, as the test's own reference (std::cos, std::sin).
Vec2 turn(double a, Vec2 v) {
  return {std::cos(a) * v.x - std::sin(a) * v.y, std::sin(a) * v.x + std::cos(a) * v.y};
}
Vec2 place(Vec2 p, double a, Vec2 v) {
  return p + turn(a, v);
}

void expect_hit(const World& w, Vec2 o, Vec2 t, Entity body, double s, Vec2 point, Vec2 normal) {
  const std::optional<RayHit> h = w.cast_ray(o, t);
  ASSERT_TRUE(h.has_value());
  EXPECT_EQ(h->body, body);
  EXPECT_EQ(h->shape, 0u);
  EXPECT_NEAR(h->fraction, s, 1e-12);
  EXPECT_NEAR(h->point.x, point.x, 1e-12);
  EXPECT_NEAR(h->point.y, point.y, 1e-12);
  EXPECT_NEAR(h->normal.x, normal.x, 1e-12);
  EXPECT_NEAR(h->normal.y, normal.y, 1e-12);
}

TEST(ShapeQueries, ARayMeetsATurnedBoxAtItsFace) {
  World w = make_world();
  const Vec2 p{2, 1};
  const double a = 0.3;
  const Entity box = put(w, {make_box(1, 0.5)}, p, a);
  // In the box's frame: from (4, 0.2) over (-5, -1), the face x = 1 at s = 0.6, y = -0.4.
  expect_hit(w, place(p, a, {4, 0.2}), turn(a, {-5, -1}), box, 0.6, place(p, a, {1, -0.4}),
             turn(a, {1, 0}));
  // A dynamic body whose box sits off its origin, turned in the body frame, beside a circle:
  // the centre of mass is off the origin (local_center), the box still where its pose says.
  World d = make_world();
  const double b = -1.2, tilt = 0.1;
  const Vec2 q{-3, 0.5}, off{0.5, 0.2};
  ShapeDef side = make_box(1, 0.5, off, tilt);
  const Entity body = put(d, {side, make_circle(0.3, {-2, 0})}, q, b, BodyType::dynamic);
  ASSERT_NE(d.local_center(body).x, 0.0);
  const Vec2 c = place(q, b, off);
  const double ab = b + tilt;
  ASSERT_EQ(d.cast_ray_all(place(c, ab, {4, 0.2}), turn(ab, {-5, -1}), {}), 1u);
  const RayHit h = *d.cast_ray(place(c, ab, {4, 0.2}), turn(ab, {-5, -1}));
  EXPECT_EQ(h.body, body);
  EXPECT_EQ(h.shape, 0u);
  EXPECT_NEAR(h.fraction, 0.6, 1e-12);
  EXPECT_NEAR(h.point.x, place(c, ab, {1, -0.4}).x, 1e-12);
  EXPECT_NEAR(h.point.y, place(c, ab, {1, -0.4}).y, 1e-12);
  EXPECT_NEAR(h.normal.x, turn(ab, {1, 0}).x, 1e-12);
  EXPECT_NEAR(h.normal.y, turn(ab, {1, 0}).y, 1e-12);
}

TEST(ShapeQueries, ARayMeetsACapsulesSideAndRoundEnd) {
  World w = make_world();
  const Vec2 p{-1, 2};
  const double a = -0.7;
  const Entity cap = put(w, {make_capsule({-1, 0}, {1, 0}, 0.5)}, p, a);
  // Side: down onto y = 0.5 at x = 0.3.
  expect_hit(w, place(p, a, {0.3, 3}), turn(a, {0, -5}), cap, 0.5, place(p, a, {0.3, 0.5}),
             turn(a, {0, 1}));
  // End: along y = 0.3 into the circle about (1, 0): x = 1 + √(0.25 - 0.09) = 1.4.
  expect_hit(w, place(p, a, {3, 0.3}), turn(a, {-5, 0}), cap, 0.32, place(p, a, {1.4, 0.3}),
             turn(a, {0.8, 0.6}));
}

TEST(ShapeQueries, ARayMeetsARoundedBoxOnItsCornerArcAndFaceAndMissesTheMiter) {
  World w = make_world();
  const Vec2 p{0.5, -1};
  const double a = 1.1, r = 0.25, k = std::sqrt(0.5);
  const Entity box = put(w, {make_box(1, 0.5, {}, 0, r)}, p, a);
  // Along the corner's diagonal: the arc about (1, 0.5) at (1, 0.5) + r (k, k).
  const double s = (2 * std::sqrt(2.0) - r) / (4 * std::sqrt(2.0));
  expect_hit(w, place(p, a, {3, 2.5}), turn(a, {-4, -4}), box, s,
             place(p, a, {1 + r * k, 0.5 + r * k}), turn(a, {k, k}));
  // The face pushed out by the rounding: y = 0.75.
  expect_hit(w, place(p, a, {0.2, 3}), turn(a, {0, -4}), box, 2.25 / 4, place(p, a, {0.2, 0.75}),
             turn(a, {0, 1}));
  // Across the corner's miter (inside the box of the pushed faces) just outside the arc's
  // tangent x + y = 1.5 + r √2: no hit; just inside it: a hit on the arc.
  for (const double gap : {1e-6, -1e-6}) {
    const double c = 1.5 + r * std::sqrt(2.0) + gap;
    const auto hit = w.cast_ray(place(p, a, {c - 3, 3}), turn(a, {5, -5}));
    ASSERT_EQ(hit.has_value(), gap < 0) << gap;
    if (hit) {
      EXPECT_NEAR(hit->normal.x, turn(a, {k, k}).x, 5e-3);
      EXPECT_NEAR(hit->normal.y, turn(a, {k, k}).y, 5e-3);
    }
  }
  // Misses: too short, pointing away, from inside, zero.
  EXPECT_FALSE(w.cast_ray(place(p, a, {0.2, 3}), turn(a, {0, -2})));
  EXPECT_FALSE(w.cast_ray(place(p, a, {0.2, 3}), turn(a, {0, 4})));
  EXPECT_FALSE(w.cast_ray(place(p, a, {0.2, 0.7}), turn(a, {0, 4})));
  EXPECT_FALSE(w.cast_ray(place(p, a, {0.2, 0.7}), turn(a, {0, -4})));
  EXPECT_FALSE(w.cast_ray(place(p, a, {0.2, 3}), {0, 0}));
}

TEST(ShapeQueries, AllHitsComeByFractionThenSlotThenShape) {
  World w = make_world();
  const Entity twin = put(w, {make_box(1, 1)}, {8, 0}, 0);  // the lowest slot at x = 7
  const Entity pair = put(w, {make_box(1, 1), make_box(1, 1)}, {8, 0}, 0);
  const Entity far = put(w, {make_capsule({0, -1}, {0, 1}, 0.5)}, {5, 0}, 0);
  BodyDef disc;
  disc.body.position = {2, 0};
  disc.collider = Collider{0.5};
  const Entity ball = w.create_body(disc);
  std::vector<RayHit> hits(w.cast_ray_all({0, 0}, {10, 0}, {}));
  ASSERT_EQ(hits.size(), 5u);
  ASSERT_EQ(w.cast_ray_all({0, 0}, {10, 0}, hits), 5u);
  EXPECT_EQ(hits[0].body, ball);
  EXPECT_EQ(hits[0].shape, no_plane);
  EXPECT_NEAR(hits[0].fraction, 0.15, 1e-15);
  EXPECT_EQ(hits[1].body, far);
  EXPECT_NEAR(hits[1].fraction, 0.45, 1e-15);
  for (int k = 2; k < 5; ++k) {
    EXPECT_EQ(hits[k].fraction, hits[2].fraction);
    EXPECT_NEAR(hits[k].fraction, 0.7, 1e-15);
  }
  EXPECT_EQ((QueryHit{hits[2].body, no_plane, no_plane, hits[2].shape}),
            (QueryHit{twin, no_plane, no_plane, 0}));
  EXPECT_EQ((QueryHit{hits[3].body, no_plane, no_plane, hits[3].shape}),
            (QueryHit{pair, no_plane, no_plane, 0}));
  EXPECT_EQ((QueryHit{hits[4].body, no_plane, no_plane, hits[4].shape}),
            (QueryHit{pair, no_plane, no_plane, 1}));
  std::vector<RayHit> part(3);
  EXPECT_EQ(w.cast_ray_all({0, 0}, {10, 0}, part), 5u);
  EXPECT_TRUE(std::equal(part.begin(), part.end(), hits.begin()));
  // The same order in the overlap queries: slot, then shape.
  std::vector<QueryHit> out(8);
  ASSERT_EQ(w.overlap_aabb({1, -0.1}, {9, 0.1}, out), 5u);
  EXPECT_EQ(out[0], (QueryHit{twin, no_plane, no_plane, 0}));
  EXPECT_EQ(out[1], (QueryHit{pair, no_plane, no_plane, 0}));
  EXPECT_EQ(out[2], (QueryHit{pair, no_plane, no_plane, 1}));
  EXPECT_EQ(out[3], (QueryHit{far, no_plane, no_plane, 0}));
  EXPECT_EQ(out[4], (QueryHit{ball}));
}

TEST(ShapeQueries, APointNearATurnedTrianglesEdgesIsInsideOnlyOnItsInnerSide) {
  World w = make_world();
  const Vec2 p{1, 1};
  const double a = 0.4;
  const std::vector<Vec2> tri{{0, 0}, {2, 0}, {0, 1}};
  const Entity e = put(w, {make_polygon(tri)}, p, a);
  std::vector<QueryHit> out(2);
  for (int i = 0; i < 3; ++i) {
    const Vec2 u = tri[i], v = tri[(i + 1) % 3], edge = v - u;
    const Vec2 n = Vec2{edge.y, -edge.x} / std::hypot(edge.x, edge.y);
    for (const double along : {0.01, 0.5, 0.99}) {
      const Vec2 m = u + along * edge;
      ASSERT_EQ(w.query_point(place(p, a, m - 1e-9 * n), out), 1u) << i << " " << along;
      EXPECT_EQ(out[0], (QueryHit{e, no_plane, no_plane, 0}));
      EXPECT_EQ(w.query_point(place(p, a, m + 1e-9 * n), out), 0u) << i << " " << along;
    }
  }
  EXPECT_EQ(w.query_point(place(p, a, {2.0 + 1e-9, 0}), out), 0u);  // beyond a vertex
  EXPECT_EQ(w.query_point(place(p, a, {0.5, 0.25}), out), 1u);
}

TEST(ShapeQueries, ABoxQueryFindsATurnedBoxByItsCornerAloneAndNotByItsBox) {
  World w = make_world();
  const double pi = 3.141592653589793;
  const Entity diamond = put(w, {make_box(1, 1)}, {0, 0}, pi / 4);  // corners at ±√2 on the axes
  std::vector<QueryHit> out(2);
  ASSERT_EQ(w.overlap_aabb({1.4, -0.01}, {2, 0.01}, out), 1u);  // the corner at x = 1.414
  EXPECT_EQ(out[0], (QueryHit{diamond, no_plane, no_plane, 0}));
  EXPECT_EQ(w.overlap_aabb({1.42, -0.01}, {2, 0.01}, out), 0u);
  EXPECT_EQ(w.overlap_aabb({1.0, 0.9}, {2, 2}, out), 0u);  // in its box, off its edge
  // The circle and shape queries, the same way.
  EXPECT_EQ(w.overlap_circle({1.5, 0}, 0.09, out), 1u);
  EXPECT_EQ(w.overlap_circle({1.5, 0}, 0.08, out), 0u);
  EXPECT_EQ(w.overlap_circle({1.0, 1.0}, 0.2, out), 0u);
  EXPECT_EQ(w.overlap_shape(make_box(0.1, 0.1), {1.5, 0}, 0.0, out), 1u);
  EXPECT_EQ(w.overlap_shape(make_box(0.1, 0.1), {1.52, 0}, 0.0, out), 0u);
  EXPECT_EQ(w.overlap_shape(make_box(0.1, 0.1), {1.52, 0}, pi / 4, out), 1u);  // 0.141 reach
  EXPECT_EQ(w.overlap_shape(make_capsule({0, 0}, {0, 1}, 0.05), {1.0, 0.75}, 0.0, out), 0u);
  EXPECT_EQ(w.overlap_shape(make_capsule({0, 0}, {0, 1}, 0.05), {0.7, 0.75}, 0.0, out), 1u);
}

TEST(ShapeQueries, FiltersAndSensorsApplyToShapesAsToDiscs) {
  World w = make_world();
  ShapeDef plain = make_box(0.5, 0.5);
  ShapeDef other = make_box(0.5, 0.5, {3, 0});
  other.filter.category = 0b10;
  other.filter.mask = 0b01;
  ShapeDef sensor = make_circle(0.5, {6, 0});
  sensor.sensor = true;
  const Entity e = put(w, {plain, other, sensor}, {0, 0}, 0);
  w.add_plane(PlaneDef{.normal = {0, 1}, .offset = -5});
  struct Case {
    QueryFilter f;
    std::vector<std::uint32_t> shapes;
  };
  const std::vector<Case> cases{
      {{}, {0, 1}},
      {{.sensors = true}, {0, 1, 2}},
      {{.mask = 0b10}, {1}},
      {{.category = 0b10, .sensors = true}, {0, 2}},  // shape 1's mask says no
      {{.mask = 0b100, .sensors = true}, {}},
      {{.mask = 0b01, .sensors = true}, {0, 2}},
  };
  for (const Case& c : cases) {
    std::vector<std::uint32_t> ray, box, circle, shape;
    std::vector<RayHit> hits(8);
    hits.resize(w.cast_ray_all({-2, 0}, {10, 0}, hits, c.f));
    for (const RayHit& h : hits) ray.push_back(h.shape);
    std::vector<QueryHit> out(8);
    out.resize(w.overlap_aabb({-1, -1}, {7, 1}, out, c.f));
    for (const QueryHit& h : out) box.push_back(h.shape);
    out.resize(8);
    out.resize(w.overlap_circle({3, 0}, 3.2, out, c.f));
    for (const QueryHit& h : out) circle.push_back(h.shape);
    out.resize(8);
    out.resize(w.overlap_shape(make_box(4, 0.1), {3, 0}, 0, out, c.f));
    for (const QueryHit& h : out) shape.push_back(h.shape);
    EXPECT_EQ(ray, c.shapes);
    EXPECT_EQ(box, c.shapes);
    EXPECT_EQ(circle, c.shapes);
    EXPECT_EQ(shape, c.shapes);
    for (const std::uint32_t k : c.shapes) {
      std::vector<QueryHit> at(2);
      ASSERT_EQ(w.query_point({3.0 * k, 0.1}, at, c.f), 1u);
      EXPECT_EQ(at[0], (QueryHit{e, no_plane, no_plane, k}));
    }
  }
  std::vector<QueryHit> out(2);  // the plane and segments by the filter's own flags
  EXPECT_EQ(w.overlap_shape(make_circle(0.1), {10, -5}, 0, out), 1u);
  EXPECT_EQ(w.overlap_shape(make_circle(0.1), {10, -5}, 0, out, {.planes = false}), 0u);
  EXPECT_THROW(w.overlap_shape(make_circle(-1), {0, 0}, 0, out), std::invalid_argument);
  EXPECT_THROW(w.overlap_shape(make_circle(1), {0, 0}, NAN, out), std::invalid_argument);
}

TEST(ShapeQueries, AnEditedAngleMovesTheShapeAndSegmentsAndPlanesComeLast) {
  World w = make_world();
  const Entity bar = put(w, {make_box(2, 0.1)}, {0, 0}, 0);
  std::vector<QueryHit> out(4);
  EXPECT_EQ(w.query_point({0, 1.5}, out), 0u);
  Body turned = w.body(bar);
  turned.angle = 1.5707963267948966;  // upright: the edit marks the grid out of date
  w.set_body(bar, turned);
  ASSERT_EQ(w.query_point({0, 1.5}, out), 1u);
  EXPECT_EQ(out[0], (QueryHit{bar, no_plane, no_plane, 0}));
  // A segment and a plane beside it: the shape query finds all three (the plane by its
  // radius alone), body first.
  w.add_segment(SegmentDef{.a = {-1, 2.5}, .b = {1, 2.5}});
  w.add_plane(PlaneDef{.normal = {0, 1}, .offset = -2});
  ASSERT_EQ(w.overlap_shape(make_capsule({0, -1.8}, {0, 2.2}, 0.35), {0.2, 0}, 0.0, out), 3u);
  EXPECT_EQ(out[0], (QueryHit{bar, no_plane, no_plane, 0}));
  EXPECT_EQ(out[1], (QueryHit{Entity{}, 0}));
  EXPECT_EQ(out[2], (QueryHit{Entity{}, no_plane, 0}));
  EXPECT_EQ(w.overlap_shape(make_capsule({0, -1.8}, {0, 2.0}, 0.12), {0.2, 0}, 0.0, out), 1u);
  std::vector<RayHit> hits(4);  // down through the segment, the bar, then the plane
  ASSERT_EQ(w.cast_ray_all({0, 3}, {0, -6}, hits), 3u);
  EXPECT_EQ(hits[0].segment, 0u);
  EXPECT_EQ(hits[1].body, bar);
  EXPECT_NEAR(hits[1].point.y, 2.0, 1e-12);
  EXPECT_NEAR(hits[1].normal.y, 1.0, 1e-12);
  EXPECT_EQ(hits[2].plane, 0u);
}

TEST(ShapeQueries, F32AndF64WorldsGiveTheSameHitsWhereTheirStatesAgree) {
  World w64 = make_world(Precision::f64), w32 = make_world(Precision::f32);
  for (World* w : {&w64, &w32}) {
    put(*w, {make_box(1, 0.5, {}, 0, 0.25)}, {2, 1}, 0.5);
    put(*w, {make_capsule({-1, 0}, {1, 0}, 0.5)}, {-2, 0.5}, -0.25);
  }
  Random rng(7);
  std::vector<RayHit> a(4), b(4);
  std::vector<QueryHit> pa(4), pb(4);
  for (int q = 0; q < 200; ++q) {
    const Vec2 o{rng.uniform(-5, 5), rng.uniform(-3, 3)}, t{rng.uniform(-6, 6), rng.uniform(-6, 6)};
    ASSERT_EQ(w64.cast_ray_all(o, t, a), w32.cast_ray_all(o, t, b));
    EXPECT_EQ(a, b);
    ASSERT_EQ(w64.query_point(o, pa), w32.query_point(o, pb));
    EXPECT_EQ(pa, pb);
  }
}

TEST(ShapeQueries, AWarmGridWithShapesAllocatesNothingPerQuery) {
  World w = make_world();
  Random rng(3);
  for (int i = 0; i < 300; ++i) {
    put(w, {make_box(0.2, 0.1), make_capsule({0, 0}, {0.3, 0}, 0.05)},
        {rng.uniform(-10, 10), rng.uniform(-10, 10)}, rng.uniform(-3, 3), BodyType::kinematic);
  }
  std::vector<QueryHit> out(64);
  std::vector<RayHit> rays(64);
  auto queries = [&] {
    (void)w.overlap_circle({1, 1}, 3, out);
    (void)w.cast_ray_all({-10, -10}, {20, 19}, rays);
    (void)w.overlap_aabb({-2, -2}, {2, 2}, out);
    (void)w.overlap_shape(make_box(2, 1), {0, 0}, 0.3, out);
    (void)w.query_point({0.5, 0.5}, out);
  };
  w.step();
  queries();  // builds the grid
  w.step();
  ::counted_bytes = 0;
  ::counting = true;
  queries();  // rebuilt into the same storage
  queries();
  ::counting = false;
  EXPECT_EQ(::counted_bytes.load(), 0u);
}

}  // namespace shape_query_tests
}  // namespace fixstep
