// World's spatial queries against brute force: every disc and plane tested by hand, in long
// double for the ray fractions, on worlds of mixed radii (the grid's cells and its list of large
// discs), after steps and edits; the order, truncation, filters and allocations.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/query.hpp"
#include "fixstep/core/random.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "test_bodies.hpp"

// count_new.cpp: this program's operator new, counting the bytes asked for while counting.
extern std::atomic<bool> counting;
extern std::atomic<std::size_t> counted_bytes;

namespace fixstep {
namespace query_tests {

struct Scene {
  World world{WorldDef::empty(Precision::f64, [] {
    WorldSettings s{.dt = 0.01};
    s.contacts = ContactSettings{.restitution = 1.0};
    return s;
  }())};
  std::vector<Entity> ids;
};

/// n discs in a 20 m square, radii 0.05 .. 0.3 m and a few of 2 .. 5 m, some sensors, three
/// categories, moving; two planes.
void fill(Scene& s, int n, std::uint64_t seed) {
  Random rng(seed);
  for (int i = 0; i < n; ++i) {
    BodyDef b = test::ball("d", {rng.uniform(-10, 10), rng.uniform(-10, 10)},
                           {rng.uniform(-1, 1), rng.uniform(-1, 1)});
    b.collider = Collider{i % 50 == 7 ? rng.uniform(2, 5) : rng.uniform(0.05, 0.3)};
    b.collider->filter.category = std::uint64_t{1} << (i % 3);
    b.collider->sensor = i % 17 == 3;
    b.collider->collide = i % 5 != 0;  // fewer contacts: the queries see them all the same
    s.ids.push_back(s.world.create_body(b));
  }
  s.world.add_plane(PlaneDef{.normal = {0, 1}, .offset = -11});
  s.world.add_plane(PlaneDef{.normal = {-1, 0}, .offset = -11});
}

bool seen(const World& w, Entity e, const QueryFilter& f) {
  const Collider c = *w.get<Collider>(e);
  return (f.sensors || !c.sensor) && query_sees(f, c.filter);
}

bool hit_less(const QueryHit& l, const QueryHit& r) {
  if ((l.plane == no_plane) != (r.plane == no_plane)) return l.plane == no_plane;
  return l.plane != no_plane ? l.plane < r.plane : l.body.slot() < r.body.slot();
}

/// Brute force: every disc and plane whose test passes, sorted.
template <class DiscTest, class PlaneTest>
std::vector<QueryHit> brute(const World& w, const QueryFilter& f, DiscTest&& disc,
                            PlaneTest&& plane) {
  std::vector<QueryHit> out;
  for (const Entity e : w.bodies()) {
    if (seen(w, e, f) && disc(w.body(e).position, w.get<Collider>(e)->radius)) out.push_back({e});
  }
  for (std::uint32_t i = 0; f.planes && i < w.planes().size(); ++i) {
    if (plane(w.planes()[i])) out.push_back({Entity{}, i});
  }
  std::sort(out.begin(), out.end(), hit_less);
  return out;
}

std::vector<QueryHit> all_aabb(const World& w, Vec2 lo, Vec2 hi, const QueryFilter& f) {
  std::vector<QueryHit> out(w.overlap_aabb(lo, hi, {}, f));
  EXPECT_EQ(w.overlap_aabb(lo, hi, out, f), out.size());
  return out;
}

std::vector<QueryHit> all_circle(const World& w, Vec2 c, double r, const QueryFilter& f) {
  std::vector<QueryHit> out(w.overlap_circle(c, r, {}, f));
  EXPECT_EQ(w.overlap_circle(c, r, out, f), out.size());
  return out;
}

void check_overlaps(const World& w, Random& rng, const QueryFilter& f) {
  for (int q = 0; q < 60; ++q) {
    const Vec2 c{rng.uniform(-12, 12), rng.uniform(-12, 12)};
    const double r = q % 10 == 0 ? rng.uniform(5, 30) : rng.uniform(0, 2);
    const auto expect = brute(
        w, f, [&](Vec2 p, double rd) { return std::hypot(p.x - c.x, p.y - c.y) <= rd + r + 1e-12; },
        [&](const PlaneDef& p) { return p.normal.x * c.x + p.normal.y * c.y - r < p.offset; });
    ASSERT_EQ(all_circle(w, c, r, f), expect) << "circle " << q;
    const Vec2 lo{c.x - r, c.y - 0.5 * r}, hi{c.x + 0.5 * r, c.y + r};
    const auto box = brute(
        w, f,
        [&](Vec2 p, double rd) {
          const double dx = p.x - std::clamp(p.x, lo.x, hi.x);
          const double dy = p.y - std::clamp(p.y, lo.y, hi.y);
          return std::hypot(dx, dy) <= rd + 1e-12;
        },
        [&](const PlaneDef& p) {
          const double x = p.normal.x > 0 ? lo.x : hi.x, y = p.normal.y > 0 ? lo.y : hi.y;
          return p.normal.x * x + p.normal.y * y < p.offset;
        });
    ASSERT_EQ(all_aabb(w, lo, hi, f), box) << "box " << q;
  }
}

/// Brute force in long double: where the ray enters the disc, or nothing.
std::optional<long double> enter(Vec2 o, Vec2 t, Vec2 c, double r) {
  const long double mx = (long double)o.x - c.x, my = (long double)o.y - c.y;
  const long double a = (long double)t.x * t.x + (long double)t.y * t.y;
  const long double b = mx * t.x + my * t.y, cc = mx * mx + my * my - (long double)r * r;
  if (cc <= 0 || b >= 0 || a == 0) return std::nullopt;
  const long double d = b * b - a * cc;
  if (d < 0) return std::nullopt;
  const long double s = (-b - std::sqrt(d)) / a;
  if (s > 1) return std::nullopt;
  return s;
}

void check_rays(const World& w, Random& rng, const QueryFilter& f) {
  std::vector<RayHit> hits;
  for (int q = 0; q < 60; ++q) {
    const Vec2 o{rng.uniform(-12, 12), rng.uniform(-12, 12)};
    const double len = q % 6 == 0 ? 40.0 : rng.uniform(0.1, 6);
    const double angle = rng.uniform(0, 6.283185307179586);
    const Vec2 t{len * std::cos(angle), len * std::sin(angle)};
    struct Ref {
      long double s;
      QueryHit hit;
    };
    std::vector<Ref> ref;
    for (const Entity e : w.bodies()) {
      if (!seen(w, e, f)) continue;
      if (auto s = enter(o, t, w.body(e).position, w.get<Collider>(e)->radius)) {
        ref.push_back({*s, {e}});
      }
    }
    for (std::uint32_t i = 0; f.planes && i < w.planes().size(); ++i) {
      const PlaneDef& p = w.planes()[i];
      const long double start = p.normal.x * o.x + p.normal.y * o.y - p.offset;
      const long double along = p.normal.x * t.x + p.normal.y * t.y;
      if (start >= 0 && along < 0 && start <= -along) ref.push_back({-start / along, {{}, i}});
    }
    std::sort(ref.begin(), ref.end(), [](const Ref& l, const Ref& r) {
      return l.s != r.s ? l.s < r.s : hit_less(l.hit, r.hit);
    });
    hits.resize(w.cast_ray_all(o, t, {}, f));
    ASSERT_EQ(w.cast_ray_all(o, t, hits, f), ref.size()) << "ray " << q;
    for (std::size_t k = 0; k < ref.size(); ++k) {
      EXPECT_EQ(hits[k].body, ref[k].hit.body) << "ray " << q << " hit " << k;
      EXPECT_EQ(hits[k].plane, ref[k].hit.plane) << "ray " << q << " hit " << k;
      EXPECT_NEAR(hits[k].fraction, double(ref[k].s), 1e-12) << "ray " << q;
      EXPECT_NEAR(hits[k].point.x, o.x + hits[k].fraction * t.x, 1e-12);
      EXPECT_NEAR(std::hypot(hits[k].normal.x, hits[k].normal.y), 1.0, 1e-9);
    }
    const std::optional<RayHit> first = w.cast_ray(o, t, f);
    ASSERT_EQ(first.has_value(), !ref.empty());
    if (first) {
      EXPECT_EQ(*first, hits[0]);
    }
  }
}

TEST(Queries, EveryQueryMatchesBruteForceBeforeAndAfterStepsAndEdits) {
  Scene s;
  fill(s, 600, 11);
  Random rng(5);
  const QueryFilter plain{}, wide{.category = all_categories, .sensors = true};
  const QueryFilter picky{.category = 1, .mask = 0b100, .planes = false};
  for (int round = 0; round < 4; ++round) {
    for (const QueryFilter& f : {plain, wide, picky}) {
      check_overlaps(s.world, rng, f);
      check_rays(s.world, rng, f);
    }
    for (int t = 0; t < 20; ++t) s.world.step();
    s.world.set_position(s.ids[round], Vec2{0.5 * round, 0.25});  // an edit between ticks
    if (round == 2) s.world.destroy(s.ids[100]);
  }
}

TEST(Queries, APointQueryFindsTheDiscsAndPlanesHoldingIt) {
  Scene s;
  BodyDef a = test::ball("a", {0, 0});
  a.collider = Collider{1.0};
  BodyDef b = a;
  b.body.position = {1.5, 0};
  const Entity ea = s.world.create_body(a), eb = s.world.create_body(b);
  s.world.add_plane(PlaneDef{.normal = {0, 1}, .offset = -0.5});
  std::vector<QueryHit> out(4);
  ASSERT_EQ(s.world.query_point({0.75, 0}, out), 2u);
  EXPECT_EQ(out[0], (QueryHit{ea}));
  EXPECT_EQ(out[1], (QueryHit{eb}));
  ASSERT_EQ(s.world.query_point({0.75, -0.6}, out), 3u);  // and under the ground
  EXPECT_EQ(out[2], (QueryHit{Entity{}, 0}));
  EXPECT_EQ(s.world.query_point({5, 5}, out), 0u);
}

TEST(Queries, ATruncatedResultIsThePrefixOfTheWholeAndARayFromInsideMissesItsDisc) {
  Scene s;
  fill(s, 300, 3);
  const auto whole = all_circle(s.world, {0, 0}, 6, {});
  ASSERT_GT(whole.size(), 10u);
  std::vector<QueryHit> part(5);
  EXPECT_EQ(s.world.overlap_circle({0, 0}, 6, part, {}), whole.size());
  EXPECT_TRUE(std::equal(part.begin(), part.end(), whole.begin()));
  // From the centre of a disc outwards: that disc is not hit.
  const Entity e = s.ids[1];
  const Vec2 c = s.world.body(e).position;
  std::vector<RayHit> hits(s.world.cast_ray_all(c, {3, 0}, {}, {.sensors = true}));
  s.world.cast_ray_all(c, {3, 0}, hits, {.sensors = true});
  for (const RayHit& h : hits) EXPECT_NE(h.body, e);
}

TEST(Queries, BadArgumentsAreRefusedByName) {
  Scene s;
  std::vector<QueryHit> out(2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)s.world.cast_ray({nan, 0}, {1, 0}), std::invalid_argument);
  EXPECT_THROW((void)s.world.cast_ray({0, 0}, {INFINITY, 0}), std::invalid_argument);
  EXPECT_THROW(s.world.overlap_circle({0, 0}, -1, out), std::invalid_argument);
  EXPECT_THROW((void)s.world.cast_ray({0, 0}, {1e200, 1e200}), std::invalid_argument);
  EXPECT_THROW((void)s.world.cast_ray({1e16, 0}, {1, 0}), std::invalid_argument);
  EXPECT_NO_THROW((void)s.world.cast_ray({1e12, 0}, {-2e12, 0}));  // across the whole world
  EXPECT_THROW(s.world.overlap_aabb({1, 0}, {0, 1}, out), std::invalid_argument);
  try {
    s.world.query_point({0, nan}, out);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("query_point: point"), std::string::npos) << e.what();
  }
}

TEST(Queries, AWarmGridAllocatesNothingPerQuery) {
  Scene s;
  fill(s, 1000, 9);
  std::vector<QueryHit> out(64);
  std::vector<RayHit> rays(64);
  auto queries = [&] {
    (void)s.world.overlap_circle({1, 1}, 3, out);
    (void)s.world.cast_ray_all({-10, -10}, {20, 19}, rays);
    (void)s.world.overlap_aabb({-2, -2}, {2, 2}, out);
  };
  s.world.step();
  queries();  // builds the grid
  s.world.step();
  ::counted_bytes = 0;
  ::counting = true;
  queries();  // rebuilt into the same storage
  queries();
  ::counting = false;
  EXPECT_EQ(::counted_bytes.load(), 0u);
}

}  // namespace query_tests
}  // namespace fixstep
