// Sensors (Collider::sensor) and collision filters (CollisionFilter): a sensor reports the discs
// it overlaps and moves nothing; a filtered pair never reaches the narrowphase. Checked against
// brute-force references: a twin world without the sensor, and every pair tested by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/disc_overlap.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "test_bodies.hpp"

namespace fixstep {
namespace sensor_tests {

using test::ball;

WorldSettings contact_settings(double restitution = 1.0) {
  WorldSettings s{.dt = 0.01};
  s.contacts = ContactSettings{.restitution = restitution, .friction = 0.0};
  return s;
}

BodyDef disc(const char* name, Vec2 at, Vec2 v, double r, BodyType type = BodyType::dynamic) {
  BodyDef b = ball(name, at, v);
  b.type = type;
  b.collider = Collider{r};
  return b;
}

BodyDef sensor_disc(const char* name, Vec2 at, double r, BodyType type) {
  BodyDef b = disc(name, at, {}, r, type);
  b.collider->sensor = true;
  return b;
}

TEST(CollisionFilter, ShouldCollideFollowsBox2DsRule) {
  const CollisionFilter plain{};
  CollisionFilter a{.category = 0b01, .mask = 0b10, .group = 0};
  CollisionFilter b{.category = 0b10, .mask = 0b01, .group = 0};
  EXPECT_TRUE(should_collide(plain, plain));
  EXPECT_TRUE(should_collide(a, b));   // each category in the other's mask
  EXPECT_FALSE(should_collide(a, a));  // 0b01 is not in mask 0b10
  b.mask = 0b10;                       // b no longer accepts a
  EXPECT_FALSE(should_collide(a, b));  // one side refusing is enough
  EXPECT_FALSE(should_collide(b, a));  // symmetric
  a.group = b.group = 3;               // same positive group: always
  EXPECT_TRUE(should_collide(a, b));
  CollisionFilter c = plain, d = plain;
  c.group = d.group = -2;  // same negative group: never
  EXPECT_FALSE(should_collide(c, d));
  d.group = -3;  // different groups: the bits decide
  EXPECT_TRUE(should_collide(c, d));
}

/// Two discs 2 m apart closing at 2 m/s: whether they bounce (e = 1) or pass through.
bool bounce(CollisionFilter fa, CollisionFilter fb) {
  World sim(WorldDef::empty(Precision::f64, contact_settings()));
  BodyDef a = disc("a", {-1, 0}, {1, 0}, 0.25), b = disc("b", {1, 0}, {-1, 0}, 0.25);
  a.collider->filter = fa, b.collider->filter = fb;
  const Entity ea = sim.create_body(a);
  sim.create_body(b);
  for (int t = 0; t < 200; ++t) sim.step();
  const Body end = sim.body(ea);
  if (end.velocity.x == 1.0) {  // untouched: exactly the free flight
    EXPECT_NEAR(end.position.x, 1.0, 1e-12) << "a filtered pair moved";
    return false;
  }
  EXPECT_NEAR(end.velocity.x, -1.0, 1e-12);  // the elastic exchange
  return true;
}

TEST(CollisionFilter, FilteredPairsPassThroughAndOthersBounce) {
  const CollisionFilter plain{};
  EXPECT_TRUE(bounce(plain, plain));
  EXPECT_FALSE(bounce(CollisionFilter{.category = 2, .mask = all_categories, .group = 0},
                      CollisionFilter{.category = 1, .mask = 1, .group = 0}));
  EXPECT_FALSE(bounce(CollisionFilter{.category = 1, .mask = all_categories, .group = -1},
                      CollisionFilter{.category = 1, .mask = all_categories, .group = -1}));
  EXPECT_TRUE(bounce(CollisionFilter{.category = 1, .mask = 0, .group = 5},
                     CollisionFilter{.category = 1, .mask = 0, .group = 5}));
}

TEST(CollisionFilter, AFilteredPairReachesNoNarrowphaseAndAGasImpactsOnlyAcceptedPairs) {
  // A dense gas: three categories, category 2 ignoring category 1, and a negative group.
  World sim(WorldDef::empty(Precision::f64, contact_settings()));
  std::vector<Entity> ids;
  std::vector<CollisionFilter> filters;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) {
      const double vx = std::sin(i * 7.0 + j), vy = std::cos(j * 5.0 + i);
      BodyDef b = disc("g", {i * 0.6, j * 0.6}, {vx, vy}, 0.2);
      const int k = (i + 2 * j) % 3;
      b.collider->filter.category = std::uint64_t{1} << k;
      if (k == 2) b.collider->filter.mask = ~std::uint64_t{0b010};
      if ((i * j) % 5 == 1) b.collider->filter.group = -1;
      ids.push_back(sim.create_body(b));
      filters.push_back(b.collider->filter);
    }
  }
  auto filter_of = [&](Entity e) { return filters[sim.index_of(e)]; };
  std::size_t accepted_impacts = 0;
  for (int t = 0; t < 300; ++t) {
    sim.step();
    for (const Impact& hit : sim.impacts()) {
      ASSERT_TRUE(should_collide(filter_of(hit.a), filter_of(hit.b)))
          << "tick " << t << ": an impact between a pair the filters reject";
      ++accepted_impacts;
    }
  }
  EXPECT_GT(accepted_impacts, 100u);

  // Every pair filtered apart (one negative group): no candidate pair at all, on any tick.
  World none(WorldDef::empty(Precision::f64, contact_settings()));
  for (int i = 0; i < 10; ++i) {
    BodyDef b = disc("n", {i * 0.3, 0}, {i % 2 ? -1.0 : 1.0, 0}, 0.2);
    b.collider->filter.group = -7;
    none.create_body(b);
  }
  for (int t = 0; t < 50; ++t) {
    none.step();
    ASSERT_EQ(none.contact_stats().candidate_pairs, 0u) << "tick " << t;
  }
}

TEST(CollisionFilter, DiscsFilteredApartMayOverlapAtTheStart) {
  std::vector<BodyDef> bodies{disc("a", {0, 0}, {}, 0.5), disc("b", {0.2, 0}, {}, 0.5)};
  ASSERT_TRUE(first_disc_overlap(bodies, {}).has_value());
  bodies[1].collider->filter.mask = 0b10;  // b ignores a's category 1
  EXPECT_FALSE(first_disc_overlap(bodies, {}).has_value());
  EXPECT_FALSE(discs_may_touch(bodies[0], bodies[1]));
  bodies[1].collider->filter = CollisionFilter{};
  bodies[1].collider->sensor = true;  // a sensor overlaps what it likes
  EXPECT_FALSE(first_disc_overlap(bodies, {}).has_value());
}

/// A ball falling past sensors of every body type: events against a brute-force overlap test
/// of a twin world without the sensors (whose ball must move bit for bit the same).
void check_fall_through(BodyType sensor_type) {
  WorldSettings s = contact_settings();
  World with(WorldDef::empty(Precision::f64, s)), twin(WorldDef::empty(Precision::f64, s));
  BodyDef ball_def = disc("ball", {0.05, 3}, {}, 0.1);
  ball_def.gravity = Gravity{};
  const Entity b = with.create_body(ball_def), tb = twin.create_body(ball_def);
  const Entity sensor = with.create_body(sensor_disc("bucket", {0, 0}, 0.5, sensor_type));
  with.add_plane(PlaneDef{.normal = {0, 1}, .offset = -2, .restitution = 0.9});
  twin.add_plane(PlaneDef{.normal = {0, 1}, .offset = -2, .restitution = 0.9});
  bool inside = false;
  int begun = 0, ended = 0;
  for (int t = 0; t < 400; ++t) {
    with.step(), twin.step();
    const Body p = with.body(b), q = twin.body(tb);
    ASSERT_EQ(p.position.x, q.position.x) << "tick " << t << ": the sensor pushed the ball";
    ASSERT_EQ(p.position.y, q.position.y) << "tick " << t;
    ASSERT_EQ(p.velocity.y, q.velocity.y) << "tick " << t;
    const double d = std::hypot(p.position.x, p.position.y);
    const bool now = d < 0.6;
    const bool began = !with.sensors_begun().empty(), stopped = !with.sensors_ended().empty();
    ASSERT_EQ(began, now && !inside) << "tick " << t << " at distance " << d;
    ASSERT_EQ(stopped, inside && !now) << "tick " << t << " at distance " << d;
    if (began) {
      EXPECT_EQ(with.sensors_begun()[0], (SensorEvent{sensor, b}));
    }
    ASSERT_EQ(with.sensor_overlaps().size(), now ? 1u : 0u) << "tick " << t;
    begun += began, ended += stopped;
    inside = now;
  }
  EXPECT_GE(begun, 2);  // it falls in, bounces on the ground and comes back through
  EXPECT_GE(ended, 2);
  EXPECT_EQ(with.body(sensor).position.y, 0.0);  // nothing moved the sensor
}

TEST(Sensors, StaticAndKinematicSensorsSeeABallFallThroughAndPushNothing) {
  check_fall_through(BodyType::static_body);
  check_fall_through(BodyType::kinematic);
}

TEST(Sensors, ADynamicSensorFallsThroughTheGroundAndSeesStaticPegs) {
  World sim(WorldDef::empty(Precision::f64, contact_settings()));
  BodyDef probe = sensor_disc("probe", {0, 2}, 0.1, BodyType::dynamic);
  probe.gravity = Gravity{};
  const Entity p = sim.create_body(probe);
  const Entity peg = sim.create_body(disc("peg", {0, 0}, {}, 0.2, BodyType::static_body));
  sim.add_plane(PlaneDef{.normal = {0, 1}, .offset = -1});
  World free(WorldDef::empty(Precision::f64, contact_settings()));
  BodyDef alone = ball("probe", {0, 2});
  alone.gravity = Gravity{};
  const Entity fp = free.create_body(alone);
  int seen = 0;
  for (int t = 0; t < 150; ++t) {
    sim.step(), free.step();
    ASSERT_EQ(sim.body(p).position.y, free.body(fp).position.y) << "tick " << t;
    for (const SensorEvent& e : sim.sensors_begun()) seen += e.visitor == peg;
  }
  EXPECT_EQ(seen, 1);
  EXPECT_LT(sim.body(p).position.y, -1.5);  // through the plane
}

TEST(Sensors, AFastBallCrossingWithinOneTickBeginsAndEndsInThatTick) {
  World sim(WorldDef::empty(Precision::f64, contact_settings()));
  const Entity ball_e = sim.create_body(disc("ball", {-1, 0}, {150, 0}, 0.05));
  const Entity gate = sim.create_body(sensor_disc("gate", {0, 0}, 0.1, BodyType::static_body));
  sim.step();  // x: -1 -> 0.5, through the gate (|x| < 0.15) within the tick
  ASSERT_EQ(sim.sensors_begun().size(), 1u);
  ASSERT_EQ(sim.sensors_ended().size(), 1u);
  EXPECT_EQ(sim.sensors_begun()[0], (SensorEvent{gate, ball_e}));
  EXPECT_TRUE(sim.sensor_overlaps().empty());
  sim.step();
  EXPECT_TRUE(sim.sensors_begun().empty());
  EXPECT_TRUE(sim.sensors_ended().empty());
}

TEST(Sensors, FiltersLinksAndOtherSensorsAreHonoured) {
  World sim(WorldDef::empty(Precision::f64, contact_settings()));
  BodyDef s = sensor_disc("s", {0, 0}, 0.5, BodyType::static_body);
  s.collider->filter.mask = 0b10;  // sees category 2 only
  const Entity se = sim.create_body(s);
  BodyDef one = disc("one", {0.1, 0}, {}, 0.1), two = disc("two", {-0.1, 0}, {}, 0.1);
  two.collider->filter.category = 0b10;
  const Entity oe = sim.create_body(one);
  const Entity te = sim.create_body(two);
  // A second sensor over both: it sees the two discs, and no sensor sees the other sensor.
  BodyDef other = sensor_disc("other", {0, 0.1}, 0.1, BodyType::dynamic);
  other.collider->filter.category = 0b10;
  const Entity se2 = sim.create_body(other);
  sim.step();
  const std::vector<SensorEvent> overlaps(sim.sensor_overlaps().begin(),
                                          sim.sensor_overlaps().end());
  const std::vector<SensorEvent> expect{{se, te}, {se2, oe}, {se2, te}};
  EXPECT_EQ(overlaps, expect);
  // Linked to the sensor, a disc is not seen.
  sim.create_link(LinkDef{se2, oe, LinkSpring{}});
  sim.step();
  const std::vector<SensorEvent> linked(sim.sensor_overlaps().begin(), sim.sensor_overlaps().end());
  const std::vector<SensorEvent> expect_linked{{se, te}, {se2, te}};
  EXPECT_EQ(linked, expect_linked);
}

TEST(Sensors, EventsComeBackAfterARestoreAndADestroyedVisitorEnds) {
  World sim(WorldDef::empty(Precision::f64, contact_settings()));
  BodyDef b = disc("ball", {0, 2}, {}, 0.1);
  b.gravity = Gravity{};
  const Entity ball_e = sim.create_body(b);
  sim.create_body(sensor_disc("zone", {0, 0}, 0.5, BodyType::static_body));
  sim.add_plane(PlaneDef{.normal = {0, 1}, .offset = -0.3});  // the ball comes to rest inside
  WorldSnapshot snap;
  sim.save(snap);
  std::vector<std::pair<int, std::size_t>> first, again;
  for (int t = 0; t < 80; ++t) {
    sim.step();
    if (!sim.sensors_begun().empty()) first.emplace_back(t, sim.sensors_begun().size());
  }
  sim.restore(snap);
  for (int t = 0; t < 80; ++t) {
    sim.step();
    if (!sim.sensors_begun().empty()) again.emplace_back(t, sim.sensors_begun().size());
  }
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first, again);
  ASSERT_EQ(sim.sensor_overlaps().size(), 1u);  // at rest on the plane, inside the zone
  sim.destroy(ball_e);
  sim.step();
  ASSERT_EQ(sim.sensors_ended().size(), 1u);
  EXPECT_EQ(sim.sensors_ended()[0].visitor, ball_e);
}

TEST(Sensors, ASlotReusedBetweenTicksEndsTheOldVisitorAndBeginsTheNew) {
  World sim(WorldDef::empty(Precision::f64, contact_settings()));
  const Entity zone = sim.create_body(sensor_disc("zone", {0, 0}, 0.5, BodyType::static_body));
  const Entity old_ball = sim.create_body(disc("old", {0.1, 0}, {}, 0.1));
  sim.step();
  ASSERT_EQ(sim.sensors_begun().size(), 1u);
  sim.destroy(old_ball);
  const Entity new_ball = sim.create_body(disc("new", {-0.1, 0}, {}, 0.1));
  ASSERT_EQ(new_ball.slot(), old_ball.slot());  // the same slot, a new generation
  sim.step();
  ASSERT_EQ(sim.sensors_ended().size(), 1u);
  EXPECT_EQ(sim.sensors_ended()[0], (SensorEvent{zone, old_ball}));
  ASSERT_EQ(sim.sensors_begun().size(), 1u);
  EXPECT_EQ(sim.sensors_begun()[0], (SensorEvent{zone, new_ball}));
  // Moved out between ticks through the sensor's far side: one end, not an end and a crossing.
  sim.set_position(new_ball, Vec2{3, 0});
  sim.step();
  EXPECT_EQ(sim.sensors_ended().size(), 1u);
  EXPECT_TRUE(sim.sensors_begun().empty());
  // Inside again, then put far left and thrown through the sensor within one tick: it left
  // (one end) and crossed (a begin); the pair ends once.
  sim.set_position(new_ball, Vec2{0, 0});
  sim.step();
  ASSERT_EQ(sim.sensors_begun().size(), 1u);
  sim.set_position(new_ball, Vec2{-3, 0});
  sim.set_velocity(new_ball, Vec2{600, 0});  // 6 m in the tick, through the zone
  sim.step();
  EXPECT_EQ(sim.sensors_begun().size(), 1u);
  EXPECT_EQ(sim.sensors_ended().size(), 1u);
  EXPECT_TRUE(sim.sensor_overlaps().empty());
}

TEST(Sensors, ASensorNeedsDiscContacts) {
  World sim(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.01}));
  EXPECT_THROW(sim.create_body(sensor_disc("s", {0, 0}, 0.5, BodyType::static_body)),
               std::invalid_argument);
  const Entity e = sim.create_body(disc("d", {0, 0}, {}, 0.5));
  Collider c{0.5};
  c.sensor = true;
  EXPECT_THROW(sim.set(e, c), std::invalid_argument);
}

}  // namespace sensor_tests
}  // namespace fixstep
