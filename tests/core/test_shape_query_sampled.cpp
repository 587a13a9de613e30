// World's ray, point and circle queries against bodies with random shapes (circles, capsules,
// boxes and polygons, rounded or not, at random poses on moving, turning bodies), checked
// against the test's own distance to each shape sampled along the ray: the hit between the
// last sample outside and the first inside, on the surface, its normal the direction in which
// the distance grows fastest; no hit from inside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/query.hpp"
#include "fixstep/core/random.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {
namespace shape_query_sampled {

/// The test's own distance from q to a placed shape's core (shape_outline), m: a point, a
/// segment, or a counter-clockwise polygon (0 inside).
double core_distance(const ShapeOutline& o, Vec2 q) {
  auto to_segment = [&](Vec2 a, Vec2 b) {
    const Vec2 e = b - a, w = q - a;
    const double u = std::clamp(dot(w, e) / dot(e, e), 0.0, 1.0);
    return std::hypot(w.x - u * e.x, w.y - u * e.y);
  };
  if (o.count == 1) return std::hypot(q.x - o.points[0].x, q.y - o.points[0].y);
  if (o.count == 2) return to_segment(o.points[0], o.points[1]);
  bool inside = true;
  double least = INFINITY;
  for (int i = 0; i < o.count; ++i) {
    const Vec2 a = o.points[i], b = o.points[(i + 1) % o.count];
    if (cross(b - a, q - a) < 0) inside = false;
    least = std::min(least, to_segment(a, b));
  }
  return inside ? 0.0 : least;
}

/// A random shape: a circle, a capsule, a box (rounded or not) or a jittered regular polygon
/// (rounded or not), at a random pose in the body frame.
ShapeDef random_shape(Random& rng) {
  const Vec2 at{rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)};
  const double round = rng.uniform(0, 1) < 0.5 ? 0.0 : rng.uniform(0.02, 0.2);
  switch (int(rng.uniform(0, 4))) {
    case 0:
      return make_circle(rng.uniform(0.1, 0.6), at);
    case 1:
      return make_capsule(at, at + Vec2{rng.uniform(-1, 1), rng.uniform(0.1, 1)},
                          rng.uniform(0.05, 0.4));
    case 2:
      return make_box(rng.uniform(0.05, 0.8), rng.uniform(0.05, 0.8), at, rng.uniform(-3, 3),
                      round);
    default: {
      const int n = 3 + int(rng.uniform(0, 6));
      std::vector<Vec2> pts;
      const double r = rng.uniform(0.2, 0.8), start = rng.uniform(0, 1);
      for (int k = 0; k < n; ++k) {
        const double t = (k + start + rng.uniform(-0.2, 0.2)) * 6.283185307179586 / n;
        pts.push_back(at + r * Vec2{std::cos(t), std::sin(t)});
      }
      return make_polygon(pts, round);
    }
  }
}

TEST(ShapeQueries, RaysPointsAndCirclesMatchABruteForceDistanceSampledAlongTheRay) {
  WorldSettings settings{.dt = 0.01};
  settings.contacts = ContactSettings{};
  World w(WorldDef::empty(Precision::f64, settings));
  Random rng(21);
  std::vector<Entity> ids;
  for (int i = 0; i < 40; ++i) {
    std::vector<ShapeDef> shapes;
    for (int k = 0, n = 1 + int(rng.uniform(0, 3)); k < n; ++k) shapes.push_back(random_shape(rng));
    BodyDef b;
    b.type = i % 4 == 0 ? BodyType::kinematic : BodyType::dynamic;
    b.body = Body{.mass = 1.0,
                  .position = {rng.uniform(-6, 6), rng.uniform(-6, 6)},
                  .velocity = {rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)},
                  .angle = rng.uniform(-3, 3),
                  .angular_velocity = rng.uniform(-2, 2)};
    b.shapes = shapes;
    ids.push_back(w.create_body(b));
  }
  constexpr int samples = 4000;
  int hits_seen = 0;
  for (int round = 0; round < 3; ++round) {
    for (int q = 0; q < 150; ++q) {
      const Vec2 o{rng.uniform(-8, 8), rng.uniform(-8, 8)};
      const double len = rng.uniform(0.5, 12), dir = rng.uniform(0, 6.283185307179586);
      const Vec2 t{len * std::cos(dir), len * std::sin(dir)};
      std::vector<RayHit> hits(w.cast_ray_all(o, t, {}));
      w.cast_ray_all(o, t, hits);
      hits_seen += int(hits.size());
      for (const Entity e : ids) {
        const Body body = w.body(e);
        const auto shapes = w.shapes(e);
        for (std::uint32_t k = 0; k < shapes.size(); ++k) {
          const ShapeOutline out = shape_outline(shapes[k], body.position, body.angle);
          const auto hit = std::find_if(hits.begin(), hits.end(), [&](const RayHit& h) {
            return h.body == e && h.shape == k;
          });
          const std::string where = "ray " + std::to_string(q) + " shape " + std::to_string(k);
          const Aabb box = shape_aabb(shapes[k], body.position, body.angle);
          if (std::max(o.x, o.x + t.x) < box.lower.x || std::min(o.x, o.x + t.x) > box.upper.x ||
              std::max(o.y, o.y + t.y) < box.lower.y || std::min(o.y, o.y + t.y) > box.upper.y) {
            EXPECT_EQ(hit, hits.end()) << where << ": out of its box";
            continue;
          }
          int first = -1;
          double closest = INFINITY;
          for (int j = 0; j <= samples && first < 0; ++j) {
            const double gap = core_distance(out, o + (double(j) / samples) * t) - out.radius;
            closest = std::min(closest, gap);
            if (gap <= 0) first = j;
          }
          if (first == 0) {
            EXPECT_EQ(hit, hits.end()) << where << ": starts inside";
            continue;
          }
          if (first < 0) {  // no sample inside: at most a graze thinner than a sample's step
            if (hit != hits.end()) {
              EXPECT_LT(closest, len / samples) << where;
            }
            continue;
          }
          ASSERT_NE(hit, hits.end()) << where;
          EXPECT_GE(hit->fraction, double(first - 1) / samples - 1e-12) << where;
          EXPECT_LE(hit->fraction, double(first) / samples + 1e-12) << where;
          // On the surface, and the normal the way the distance grows fastest.
          EXPECT_NEAR(core_distance(out, hit->point), out.radius, 1e-9) << where;
          const Vec2 off = hit->point + 1e-3 * hit->normal;
          EXPECT_NEAR(core_distance(out, off) - out.radius, 1e-3, 1e-9) << where;
        }
      }
      // Point and circle queries at the ray's origin against the same distance.
      const double reach = q % 3 == 0 ? 0.0 : rng.uniform(0, 1);
      std::vector<QueryHit> found(w.overlap_circle(o, reach, {}));
      w.overlap_circle(o, reach, found);
      for (const Entity e : ids) {
        const Body body = w.body(e);
        const auto shapes = w.shapes(e);
        for (std::uint32_t k = 0; k < shapes.size(); ++k) {
          const ShapeOutline out = shape_outline(shapes[k], body.position, body.angle);
          const double gap = core_distance(out, o) - out.radius - reach;
          if (std::abs(gap) < 1e-9) continue;  // on the edge: either answer
          const bool in = std::find(found.begin(), found.end(),
                                    QueryHit{e, no_plane, no_plane, k}) != found.end();
          EXPECT_EQ(in, gap < 0) << "circle " << q << " gap " << gap;
        }
      }
    }
    for (int t = 0; t < 25; ++t) w.step();  // new poses: the grid is rebuilt
  }
  EXPECT_GT(hits_seen, 100);
}

TEST(ShapeQueries, ACrowdOfSmallDiscsAndShapesFindsEveryShapeThroughTheGridsCells) {
  // Small discs set fine cells; turned boxes of about their size live in those cells, found
  // from any point of theirs however it falls across the cells.
  WorldSettings settings{.dt = 0.01};
  World w(WorldDef::empty(Precision::f64, settings));
  Random rng(4);
  std::vector<Entity> shaped;
  for (int i = 0; i < 600; ++i) {
    BodyDef b;
    b.type = BodyType::static_body;
    b.body.position = {rng.uniform(-5, 5), rng.uniform(-5, 5)};
    b.body.angle = rng.uniform(-3, 3);
    if (i % 3 == 0) {
      b.shapes = {make_box(rng.uniform(0.05, 0.1), rng.uniform(0.02, 0.1))};
      shaped.push_back(w.create_body(b));
    } else {
      b.collider = Collider{rng.uniform(0.05, 0.1)};
      w.create_body(b);
    }
  }
  std::vector<QueryHit> out(16);
  int inside = 0;
  for (const Entity e : shaped) {
    const Body body = w.body(e);
    const ShapeOutline o = shape_outline(w.shapes(e)[0], body.position, body.angle);
    for (int k = 0; k < o.count; ++k) {  // near each corner, just inside
      const Vec2 p = o.points[k] + 0.01 * (body.position - o.points[k]);
      out.resize(16);
      out.resize(std::min<std::size_t>(16, w.query_point(p, out, {.planes = false})));
      EXPECT_NE(std::find(out.begin(), out.end(), QueryHit{e, no_plane, no_plane, 0}), out.end());
      ++inside;
      std::vector<RayHit> hits(16);  // a short ray onto the corner from outside
      const Vec2 from = o.points[k] + 0.2 * (o.points[k] - body.position);
      hits.resize(std::min<std::size_t>(16, w.cast_ray_all(from, p - from, hits)));
      EXPECT_TRUE(
          std::any_of(hits.begin(), hits.end(), [&](const RayHit& h) { return h.body == e; }))
          << "corner " << k;
    }
  }
  EXPECT_EQ(inside, 4 * int(shaped.size()));
}

}  // namespace shape_query_sampled
}  // namespace fixstep
