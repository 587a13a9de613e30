// Sleeping islands (ContactSettings::sleep): a pile at rest falls asleep and then stays bit for
// bit where it is; a disc dropped on it wakes it before they touch (no contact is resolved
// against a sleeper); input and edits wake an island and only it; snapshots and the sync test
// carry the sleep state; the energy account keeps what falling asleep takes; worlds without
// sleeping step as before (their golden hashes are guarded elsewhere).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/sync_test.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {
namespace {

constexpr double r = 0.05;  // m, every disc's radius

/// `columns` × `rows` jittered discs of 1 kg poured under gravity onto the floor from x = cx
/// - 0.3 m on, between two walls 0.3 m from x = cx (e = 0, μ = 0.3) when `walls`.
void add_pile(WorldDef& def, double cx, int columns, int rows, std::uint32_t seed,
              bool walls = true) {
  const double half = 0.3;
  if (walls) {
    def.planes.push_back(PlaneDef{.normal = {1, 0}, .offset = cx - half, .friction = 0.3});
    def.planes.push_back(PlaneDef{.normal = {-1, 0}, .offset = -cx - half, .friction = 0.3});
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.2 * r, 0.2 * r);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) {
      BodyDef b;
      b.body =
          Body{.mass = 1.0,
               .position = {cx - half + 2 * r + 2.4 * r * j + jitter(rng), 2 * r + 2.4 * r * i}};
      b.collider = Collider{.radius = r};
      b.gravity = Gravity{};
      def.bodies.push_back(b);
    }
  }
}

WorldDef sleepy_world(Precision precision = Precision::f64,
                      Integrator integrator = Integrator::semi_implicit_euler) {
  WorldDef def;
  def.precision = precision;
  def.settings.dt = 1.0 / 60.0;
  def.settings.integrator = integrator;
  def.settings.track_dissipation = true;
  def.settings.contacts =
      ContactSettings{.restitution = 0.0, .friction = 0.3, .sleep = true, .sleep_time = 0.25};
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .friction = 0.3});
  return def;
}

/// Steps w until every one of its bodies sleeps, at most `ticks` ticks; returns the ticks taken
/// (ticks + 1: never).
int step_until_asleep(World& w, int ticks) {
  for (int t = 1; t <= ticks; ++t) {
    w.step();
    if (w.contact_stats().sleeping == w.body_count()) return t;
  }
  return ticks + 1;
}

std::vector<double> positions(const World& w) {
  std::vector<double> out;
  for (const Entity e : w.bodies()) {
    const Body b = w.body(e);
    out.push_back(b.position.x), out.push_back(b.position.y);
  }
  return out;
}

TEST(Sleep, ASettledPileFallsAsleepAndStaysBitForBit) {
  for (const Precision p : {Precision::f64, Precision::f32}) {
    SCOPED_TRACE(precision_name(p));
    WorldDef def = sleepy_world(p);
    add_pile(def, 0.0, 5, 6, 7);
    World w(def);
    const int took = step_until_asleep(w, 1200);
    ASSERT_LE(took, 1200) << "asleep: " << w.contact_stats().sleeping << " of 30";
    const std::vector<double> at_sleep = positions(w);
    for (const Entity e : w.bodies()) {
      EXPECT_TRUE(w.asleep(e));
      EXPECT_EQ(w.body(e).velocity.x, 0.0);
      EXPECT_EQ(w.body(e).velocity.y, 0.0);
    }
    for (int t = 0; t < 300; ++t) w.step();
    EXPECT_EQ(positions(w), at_sleep);  // bit for bit
    EXPECT_EQ(w.contact_stats().sleeping, w.body_count());
    EXPECT_EQ(w.contact_stats().woken, 0u);
    // Still a pile, not sunk: every disc above the floor by its radius less the slop.
    for (std::size_t k = 1; k < at_sleep.size(); k += 2) EXPECT_GE(at_sleep[k], 0.99 * r);
  }
}

TEST(Sleep, ATouchingPairStaysTouchingAsleepWithNoEvents) {
  WorldDef def = sleepy_world();
  add_pile(def, 0.0, 3, 3, 5);
  World w(def);
  ASSERT_LE(step_until_asleep(w, 1200), 1200);
  w.step();
  EXPECT_TRUE(w.contacts_begun().empty());
  EXPECT_TRUE(w.contacts_ended().empty());
  EXPECT_TRUE(w.impacts().empty());
}

TEST(Sleep, ADiscDroppedOnASleepingPileWakesItBeforeTheyTouch) {
  WorldDef def = sleepy_world();
  add_pile(def, 0.0, 5, 4, 11);
  // Thrown up from above the pile: back down on it about 4 s later, long after it sleeps.
  BodyDef ball;
  ball.body = Body{.mass = 1.0, .position = {0.02, 1.0}, .velocity = {0.0, 18.0}};
  ball.collider = Collider{.radius = r};
  ball.gravity = Gravity{};
  def.bodies.push_back(ball);
  World w(def);
  const Entity thrown = w.bodies().back();
  std::size_t slept = 0, woken = 0, sleeper_contacts = 0, hits = 0;
  for (int t = 0; t < 360; ++t) {
    w.step();
    slept = std::max(slept, w.contact_stats().sleeping);
    woken += w.contact_stats().woken;
    sleeper_contacts += w.contact_stats().sleeper_contacts;
    for (const Impact& i : w.impacts()) hits += (i.a == thrown || i.b == thrown) ? 1 : 0;
  }
  EXPECT_GE(slept, 20u);            // the whole pile slept while the ball flew
  EXPECT_GE(hits, 1u);              // the ball came down on it
  EXPECT_GE(woken, 1u);             // and woke it
  EXPECT_EQ(sleeper_contacts, 0u);  // before they touched: no sleeper acted as a static disc
}

TEST(Sleep, InputAndEditsWakeTheirIslandOnly) {
  WorldDef def = sleepy_world();
  add_pile(def, -1.0, 3, 3, 2, false);  // two piles 2 m apart on the floor: two islands
  add_pile(def, 1.0, 3, 3, 3, false);
  World w(def);
  ASSERT_LE(step_until_asleep(w, 1200), 1200);
  const std::vector<Entity> ids(w.bodies().begin(), w.bodies().end());
  const Entity left = ids[4], right = ids[13];
  const std::vector<double> before = positions(w);
  TickInput in;
  in.bodies.push_back(BodyInput{.body = left, .kind = BodyInputKind::impulse, .value = {0, 0.5}});
  w.step(in);
  EXPECT_EQ(w.contact_stats().woken, 1u);  // one island: the struck disc's
  EXPECT_FALSE(w.asleep(left));
  EXPECT_NE(w.body(left).position.y, before[2 * 4 + 1]);
  for (std::size_t k = 9; k < ids.size(); ++k) {  // the other pile sleeps on, unmoved
    EXPECT_TRUE(w.asleep(ids[k])) << k;
    EXPECT_EQ(w.body(ids[k]).position.y, before[2 * k + 1]) << k;
  }
  // An edit wakes its body's island; World::wake as well.
  w.set_velocity(right, {0.0, 0.1});
  EXPECT_FALSE(w.asleep(right));
  ASSERT_LE(step_until_asleep(w, 1200), 1200);
  w.wake(ids[0]);
  EXPECT_FALSE(w.asleep(ids[0]));
  for (std::size_t k = 9; k < ids.size(); ++k) EXPECT_TRUE(w.asleep(ids[k])) << k;
}

TEST(Sleep, ASnapshotStepsOnToTheSameBits) {
  WorldDef def = sleepy_world();
  add_pile(def, 0.0, 4, 4, 9);
  World w(def);
  std::uint64_t first_asleep = 0;
  for (int t = 0; t < 1200 && first_asleep == 0; ++t) {
    w.step();
    if (w.contact_stats().sleeping > 0) first_asleep = w.tick();
  }
  ASSERT_GT(first_asleep, 0u);
  // Some ticks before the first island slept: the still-tick counts are what decides.
  World replay(def);
  for (std::uint64_t t = 0; t + 10 < first_asleep; ++t) replay.step();
  WorldSnapshot snap;
  replay.save(snap);
  World again(def);
  again.restore(snap);
  for (int t = 0; t < 10; ++t) replay.step(), again.step();
  EXPECT_EQ(again.state_hash(), replay.state_hash());
  EXPECT_EQ(replay.state_hash(), w.state_hash());
  EXPECT_EQ(again.contact_stats().sleeping, w.contact_stats().sleeping);
}

TEST(Sleep, TheStateHashSaysWhoSleeps) {
  WorldDef def = sleepy_world();
  add_pile(def, 0.0, 3, 2, 4);
  World w(def);
  ASSERT_LE(step_until_asleep(w, 1200), 1200);
  World woken = w;
  woken.wake(woken.bodies()[0]);  // same positions and velocities, awake
  EXPECT_EQ(positions(woken), positions(w));
  EXPECT_NE(woken.state_hash(), w.state_hash());
}

TEST(Sleep, TheEnergyAccountKeepsWhatFallingAsleepTakes) {
  // A disc sliding at 0.5 m/s on a frictionless floor, with a sleep speed of 1 m/s: it falls
  // asleep after 0.25 s, and the kinetic energy it held (0.125 J) goes to the account.
  WorldDef def = sleepy_world();
  def.planes[0].friction = 0.0;
  def.settings.contacts->friction = 0.0;
  def.settings.contacts->sleep_speed = 1.0;
  BodyDef b;
  b.body = Body{.mass = 1.0, .position = {0.0, r}, .velocity = {0.5, 0.0}};
  b.collider = Collider{.radius = r};
  b.gravity = Gravity{};
  def.bodies.push_back(b);
  World w(def);
  const double e0 = w.energy().total();
  ASSERT_LE(step_until_asleep(w, 60), 60);
  EXPECT_EQ(w.energy().kinetic, 0.0);
  EXPECT_NEAR(w.dissipated_energy(), 0.125, 1e-12);
  EXPECT_NEAR(energy_balance(w, e0), 0.0, 1e-12);
  for (int t = 0; t < 60; ++t) w.step();
  EXPECT_NEAR(energy_balance(w, e0), 0.0, 1e-12);
}

TEST(Sleep, LinkedDiscsSleepAndWakeTogether) {
  // Two discs on the floor 1 m apart, joined by a damped link: one island though they never
  // touch. Input on one wakes the other.
  WorldDef def = sleepy_world();
  for (const double x : {-0.5, 0.5}) {
    BodyDef b;
    b.body = Body{.mass = 1.0, .position = {x, r}};
    b.collider = Collider{.radius = r};
    b.gravity = Gravity{};
    def.bodies.push_back(b);
  }
  LinkDef link;
  link.spring = LinkSpring{.stiffness = 50.0, .damping = 2.0, .rest_length = 1.0};
  World w(def);
  const std::vector<Entity> ids(w.bodies().begin(), w.bodies().end());
  link.body_a = ids[0], link.body_b = ids[1];
  w.create_link(link);
  ASSERT_LE(step_until_asleep(w, 600), 600);
  TickInput in;
  in.bodies.push_back(BodyInput{.body = ids[0], .kind = BodyInputKind::impulse, .value = {0.2, 0}});
  w.step(in);
  EXPECT_FALSE(w.asleep(ids[0]));
  EXPECT_FALSE(w.asleep(ids[1]));  // woken through the link
}

TEST(Sleep, ASpinningDiscStaysAwakeWhileItsRimMoves) {
  // A rolling disc spinning in place on a frictionless floor: its centre is still, its rim
  // moves at ω r = 0.5 m/s, above the sleep speed, so it never sleeps.
  WorldDef def = sleepy_world();
  def.settings.contacts->rolling = true;
  def.settings.contacts->friction = 0.0;
  def.planes[0].friction = 0.0;
  BodyDef b;
  b.body = Body{.mass = 1.0, .position = {0.0, r}, .angular_velocity = 10.0};
  b.collider = Collider{.radius = r};
  b.gravity = Gravity{};
  def.bodies.push_back(b);
  World w(def);
  EXPECT_EQ(step_until_asleep(w, 300), 301);
  EXPECT_EQ(w.body(w.bodies()[0]).angular_velocity, 10.0);
}

TEST(Sleep, AMovingKinematicDiscKeepsWhatRestsOnItAwake) {
  // A disc resting on a kinematic disc that drifts sideways at 1 cm/s (below the sleep
  // speed): the rider's island touches a moving body, so it must not sleep (it would be left
  // behind, hanging in the air).
  WorldDef def = sleepy_world();
  def.settings.contacts->friction = 1.0;
  BodyDef carrier;
  carrier.type = BodyType::kinematic;
  carrier.body = Body{.mass = 1.0, .position = {0.0, 0.5}, .velocity = {0.01, 0.0}};
  carrier.collider = Collider{.radius = 0.2};
  def.bodies.push_back(carrier);
  BodyDef rider;
  rider.body = Body{.mass = 1.0, .position = {0.0, 0.5 + 0.2 + r}};
  rider.collider = Collider{.radius = r};
  rider.gravity = Gravity{};
  def.bodies.push_back(rider);
  World w(def);
  for (int t = 0; t < 300; ++t) {
    w.step();
    ASSERT_EQ(w.contact_stats().sleeping, 0u) << "tick " << t;
  }
}

TEST(Sleep, AMovingSegmentWakesWhatItWillReachAndKeepsItsRidersAwake) {
  // A pile asleep on the floor; a wall (a segment carried by a kinematic body) then moves in
  // from the left at 0.5 m/s: the pile wakes before the wall reaches it, and is pushed, never
  // entered (every disc's centre stays r, less the slop, from the wall).
  WorldDef def = sleepy_world();
  add_pile(def, 0.0, 3, 2, 12, false);
  BodyDef pusher;
  pusher.type = BodyType::kinematic;
  pusher.body = Body{.mass = 1.0, .position = {-1.0, 0.0}};
  const Entity p = def.add_body(pusher);
  def.segments.push_back(SegmentDef{.a = {-1.0, 0.0}, .b = {-1.0, 1.0}, .body = p});
  World w(def);
  const std::vector<Entity> ids(w.bodies().begin(), w.bodies().end());
  const Entity wall = ids.back();
  for (int t = 0; t < 1200 && w.contact_stats().sleeping < 6; ++t) w.step();
  ASSERT_EQ(w.contact_stats().sleeping, 6u);
  const double first_x = w.body(ids[0]).position.x;
  w.set_velocity(wall, {0.5, 0.0});
  std::size_t woken = 0;
  for (int t = 0; t < 120; ++t) {
    w.step();
    woken += w.contact_stats().woken;
    const double at = w.segments()[0].a.x;
    for (std::size_t k = 0; k < 6; ++k) {
      ASSERT_GE(w.body(ids[k]).position.x - at, 0.99 * r) << "disc " << k << " tick " << t;
    }
  }
  EXPECT_GE(woken, 1u);
  EXPECT_GT(w.body(ids[0]).position.x, first_x + 0.1);  // pushed along
}

TEST(Sleep, ADiscRidingAMovingPlatformNeverSleeps) {
  WorldDef def = sleepy_world();
  BodyDef carrier;
  carrier.type = BodyType::kinematic;
  carrier.body = Body{.mass = 1.0, .position = {0.0, 0.0}, .velocity = {0.01, 0.0}};
  const Entity c = def.add_body(carrier);
  def.segments.push_back(SegmentDef{.a = {-5.0, 0.5}, .b = {5.0, 0.5}, .friction = 0.5, .body = c});
  BodyDef b;
  b.body = Body{.mass = 1.0, .position = {0.0, 0.5 + r}};
  b.collider = Collider{.radius = r};
  b.gravity = Gravity{};
  def.bodies.push_back(b);
  World w(def);
  for (int t = 0; t < 300; ++t) {
    w.step();
    ASSERT_EQ(w.contact_stats().sleeping, 0u) << "tick " << t;
  }
  EXPECT_NEAR(w.body(w.bodies()[1]).velocity.x, 0.01, 1e-9);  // carried along
}

/// The sync test (rollbacks of 1 and 7 ticks) over a pile that falls asleep and a ball that
/// wakes it, every integrator, f64 and f32.
TEST(Sleep, TheSyncTestRollsBackSleepAndWakeBitExactly) {
  for (const Precision p : {Precision::f64, Precision::f32}) {
    for (const Integrator integrator : all_integrators) {
      SCOPED_TRACE(testing::Message() << integrator_name(integrator) << " " << precision_name(p));
      WorldDef def = sleepy_world(p, integrator);
      def.settings.contacts->sleep_time = 0.1;
      add_pile(def, 0.0, 3, 2, 8);
      BodyDef ball;
      ball.body = Body{.mass = 1.0, .position = {0.0, 0.6}, .velocity = {0.0, 6.0}};
      ball.collider = Collider{.radius = r};
      ball.gravity = Gravity{};
      def.bodies.push_back(ball);
      for (const int k : {1, 7}) {
        World plain(def), tested(def);
        SyncTest sync(tested, k);
        std::size_t slept = 0, woken = 0;
        for (std::uint64_t t = 0; t < 150; ++t) {
          plain.step(TickInput{.tick = t});
          ASSERT_TRUE(sync.step(TickInput{.tick = t})) << "tick " << sync.mismatch()->tick;
          slept = std::max(slept, plain.contact_stats().sleeping);
          woken += plain.contact_stats().woken;
        }
        EXPECT_EQ(tested.state_hash(), plain.state_hash());
        EXPECT_GE(slept, 6u);  // not vacuous: the pile slept, and the ball woke it
        EXPECT_GE(woken, 1u);
      }
    }
  }
}

}  // namespace
}  // namespace fixstep
