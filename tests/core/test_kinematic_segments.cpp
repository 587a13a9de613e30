// Segments a kinematic body carries (SegmentDef::body): a moving platform, a lift, a paddle.
// Exact checks, in the plane pass (a world without disc contacts) and in the disc solver (a
// world with [contacts]): a disc at rest on a platform that moves sideways at u is accelerated
// by friction at μ g until it moves at u, then rides it; an elastic disc meeting a segment
// that moves at u head-on leaves at 2u - v; a lift moving up carries a disc without sinking
// into it; the energy balance closes with the carrying body's work (World::external_work);
// snapshots and the sync test; a static segment's results are unchanged (the golden hashes of
// level.toml guard that).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/sync_test.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {
namespace carried_segments_test {  // named: a unity batch shares anonymous namespaces

constexpr double g = 9.81;  // m/s²
constexpr double r = 0.25;  // m

WorldSettings settings(bool contacts, Integrator integrator = Integrator::semi_implicit_euler) {
  WorldSettings s{.dt = 1.0 / 60.0, .integrator = integrator, .track_dissipation = true};
  if (contacts) s.contacts = ContactSettings{};
  return s;
}

BodyDef disc(Vec2 at, Vec2 v, bool gravity = true) {
  BodyDef b;
  b.body = Body{.mass = 2.0, .position = at, .velocity = v};
  if (gravity) b.gravity = Gravity{{0.0, -g}};
  b.collider = Collider{.radius = r};
  return b;
}

Entity carrier(World& w, Vec2 at, Vec2 v) {
  BodyDef b;
  b.type = BodyType::kinematic;
  b.body = Body{.mass = 1.0, .position = at, .velocity = v};
  return w.create_body(b);
}

// A platform (a segment from x = -20 to 20 m at y = 0) moving right at u = 1 m/s under a disc
// at rest on it, μ = 0.2: friction accelerates the disc at μ g (1.962 m/s²) until it moves at
// u, after u/(μ g) = 0.51 s, and it rides along after that. Asserted: at 0.25 s the disc's
// speed is μ g t (to 1e-9 m/s; semi-implicit Euler's friction is exact per tick), at 1 s it
// is u (to 1e-9) and it still rests on the platform (y = r to 1e-9 m).
TEST(KinematicSegments, ADiscOnAPlatformMovingSidewaysReachesItsSpeedAtMuG) {
  for (const bool contacts : {false, true}) {
    SCOPED_TRACE(contacts ? "disc solver" : "plane pass");
    World w(WorldDef::empty(Precision::f64, settings(contacts)));
    const Entity body = carrier(w, {0.0, 0.0}, {1.0, 0.0});
    w.add_segment(SegmentDef{.a = {-20.0, 0.0}, .b = {20.0, 0.0}, .friction = 0.2, .body = body});
    const Entity d = w.create_body(disc({0.0, r}, {}));
    const double e0 = w.energy().total();
    for (int t = 0; t < 15; ++t) w.step();
    EXPECT_NEAR(w.body(d).velocity.x, 0.2 * g * 0.25, 1e-9);
    for (int t = 15; t < 60; ++t) w.step();
    EXPECT_NEAR(w.body(d).velocity.x, 1.0, 1e-9);
    EXPECT_NEAR(w.body(d).position.y, r, 1e-9);
    EXPECT_NEAR(w.body(d).velocity.y, 0.0, 1e-9);
    // The platform is where its body is: 1 m on.
    EXPECT_NEAR(w.segments()[0].a.x, -19.0, 1e-12);
    // Its work, m u² (½ m u² the disc's, ½ m u² lost to friction while it slid), closes the
    // balance.
    EXPECT_NEAR(w.external_work(), 2.0, 1e-9);
    EXPECT_NEAR(energy_balance(w, e0), 0.0, 1e-11);
  }
}

// Two discs stacked on the platform (with disc contacts): the top one's weight reaches the
// platform through the bottom one's resting contacts, so the resting solver holds the pair
// against the moving segment; friction (μ = 0.5 between discs and on the platform) brings both
// to the platform's 1 m/s (to 1e-6 m/s after 2 s), and the stack stands.
TEST(KinematicSegments, AStackRidesAPlatform) {
  World w(WorldDef::empty(Precision::f64, [] {
    WorldSettings s = settings(true);
    s.contacts->friction = 0.5;
    return s;
  }()));
  const Entity body = carrier(w, {0.0, 0.0}, {1.0, 0.0});
  w.add_segment(SegmentDef{.a = {-20.0, 0.0}, .b = {20.0, 0.0}, .friction = 0.5, .body = body});
  const Entity low = w.create_body(disc({0.0, r}, {}));
  const Entity high = w.create_body(disc({0.0, 3.0 * r}, {}));
  for (int t = 0; t < 120; ++t) w.step();
  for (const Entity d : {low, high}) {
    EXPECT_NEAR(w.body(d).velocity.x, 1.0, 1e-6);
    EXPECT_NEAR(w.body(d).velocity.y, 0.0, 1e-6);
  }
  // The top one lagged a little while the two were accelerated (8 mm), and stands there.
  EXPECT_NEAR(w.body(high).position.x - w.body(low).position.x, 0.0, 0.1 * r);
  EXPECT_NEAR(w.body(high).position.y, 3.0 * r, 0.01 * r);
  EXPECT_NEAR(w.body(low).position.y, r, 0.005 * r);
}

// An elastic disc (no gravity) at v = -3 m/s meets a vertical segment moving right at u = 2 m/s:
// in the segment's frame it arrives at v - u = -5 and leaves at +5, so it leaves at 2u - v =
// 7 m/s. Exact to rounding (1e-12).
TEST(KinematicSegments, AnElasticDiscMeetingAMovingSegmentHeadOnLeavesAtTwoUMinusV) {
  for (const bool contacts : {false, true}) {
    SCOPED_TRACE(contacts ? "disc solver" : "plane pass");
    World w(WorldDef::empty(Precision::f64, settings(contacts, Integrator::velocity_verlet)));
    const Entity body = carrier(w, {0.0, 0.0}, {2.0, 0.0});
    w.add_segment(SegmentDef{.a = {0.0, -5.0}, .b = {0.0, 5.0}, .restitution = 1.0, .body = body});
    const Entity d = w.create_body(disc({2.0, 0.0}, {-3.0, 0.0}, false));
    for (int t = 0; t < 30; ++t) w.step();
    EXPECT_NEAR(w.body(d).velocity.x, 7.0, 1e-12);
    // The balance closes with the segment's work: ½ m (7² - 3²) = 40 J, all of it external.
    EXPECT_NEAR(w.external_work(), 40.0, 1e-9);
    EXPECT_NEAR(w.dissipated_energy(), 0.0, 1e-9);
  }
}

// A lift (a horizontal segment) moving up at 0.5 m/s with a disc at rest on it: the disc rises
// with it, never sinks into it beyond rounding, and moves up at 0.5 m/s; the lift's work
// (m g h plus the kinetic energy it gave) is in the account, so the balance closes.
TEST(KinematicSegments, ALiftCarriesADiscUp) {
  for (const bool contacts : {false, true}) {
    SCOPED_TRACE(contacts ? "disc solver" : "plane pass");
    World w(WorldDef::empty(Precision::f64, settings(contacts)));
    const Entity body = carrier(w, {0.0, 0.0}, {0.0, 0.5});
    w.add_segment(SegmentDef{.a = {-2.0, 0.0}, .b = {2.0, 0.0}, .body = body});
    const Entity d = w.create_body(disc({0.0, r}, {}));
    const double e0 = w.energy().total();
    double deepest = 0.0;
    for (int t = 0; t < 120; ++t) {
      w.step();
      const double lift = w.body(body).position.y;
      deepest = std::max(deepest, lift + r - w.body(d).position.y);
    }
    EXPECT_LE(deepest, 0.005 * r);  // the slop
    EXPECT_NEAR(w.body(d).velocity.y, 0.5, 1e-9);
    EXPECT_NEAR(w.body(d).position.y, 1.0 + r, 0.005 * r);
    EXPECT_NEAR(energy_balance(w, e0), 0.0, 1e-11);
    // The lift's work: m g h, plus m u² for the jolt at its start (half of it the disc's
    // kinetic energy, half dissipated in that inelastic impact).
    const double h = w.body(d).position.y - r;
    EXPECT_NEAR(w.external_work(), 2.0 * g * h + 2.0 * 0.25, 1e-9);
    EXPECT_NEAR(w.dissipated_energy(), 0.25, 1e-12);
  }
}

// A paddle sweeping along a floor with friction (μ = 0.4) pushes a row of three discs, the
// first through its own contact, the others through the discs' resting contacts: the
// balance E + E_dissipated - W_external - E0 closes to rounding (1e-12 J) over 5 s, the work
// the paddle does in the plane pass reaching the account of the discs the resting solver
// measures from the tick's start.
TEST(KinematicSegments, APaddlePushingARowAlongAFloorKeepsTheBalance) {
  WorldSettings s = settings(true);
  s.contacts->restitution = 0.2, s.contacts->friction = 0.4;
  World w(WorldDef::empty(Precision::f64, s));
  w.add_plane(PlaneDef{.normal = {0, 1}, .offset = 0.0, .restitution = 0.2, .friction = 0.4});
  const Entity body = carrier(w, {2.0, 0.0}, {-0.6, 0.0});
  w.add_segment(SegmentDef{.a = {2.0, 0.0}, .b = {2.0, 1.0}, .friction = 0.1, .body = body});
  for (int i = 0; i < 3; ++i) w.create_body(disc({1.0 - 0.6 * i, r}, {}));
  const double e0 = w.energy().total();
  for (int t = 0; t < 300; ++t) w.step();
  EXPECT_GT(w.external_work(), 10.0);  // it pushed: about μ m g u per disc and second
  EXPECT_NEAR(w.energy().total() + w.dissipated_energy() - w.external_work() - e0, 0.0, 1e-12);
}

TEST(KinematicSegments, OnlyALiveKinematicBodyCarriesASegment) {
  World w(WorldDef::empty(Precision::f64, settings(false)));
  const Entity dynamic = w.create_body(disc({0.0, 5.0}, {}));
  EXPECT_THROW(w.add_segment(SegmentDef{.a = {0, 0}, .b = {1, 0}, .body = dynamic}),
               std::invalid_argument);
  const Entity body = carrier(w, {0.0, 0.0}, {});
  w.destroy(body);
  EXPECT_THROW(w.add_segment(SegmentDef{.a = {0, 0}, .b = {1, 0}, .body = body}),
               std::invalid_argument);
}

// A WorldDef's carried segment names its body by the definition's handle; the world from it
// and a snapshot of it step on to the same bits; the sync test rolls back through impacts with
// a moving paddle (rollbacks of 1 and 7 ticks).
TEST(KinematicSegments, DefinitionsSnapshotsAndTheSyncTestCarryThem) {
  WorldDef def;
  def.settings = settings(true);
  def.settings.contacts->restitution = 0.5;
  BodyDef paddle;
  paddle.type = BodyType::kinematic;
  paddle.body = Body{.mass = 1.0, .position = {-3.0, 0.0}, .velocity = {2.0, 0.0}};
  const Entity p = def.add_body(paddle);
  def.segments.push_back(SegmentDef{
      .a = {-3.0, -1.0}, .b = {-3.0, 1.0}, .restitution = 0.8, .friction = 0.3, .body = p});
  def.planes.push_back(PlaneDef{.normal = {-1.0, 0.0}, .offset = -3.0, .restitution = 0.8});
  for (int i = 0; i < 5; ++i) def.add_body(disc({-1.0 + 0.6 * i, 0.1 * i}, {0.5, 0.0}, false));
  for (const int k : {1, 7}) {
    World plain(def), tested(def);
    SyncTest sync(tested, k);
    for (std::uint64_t t = 0; t < 120; ++t) {
      plain.step(TickInput{.tick = t});
      ASSERT_TRUE(sync.step(TickInput{.tick = t})) << "tick " << sync.mismatch()->tick;
    }
    EXPECT_EQ(plain.state_hash(), tested.state_hash());
  }
  World w(def);
  for (int t = 0; t < 40; ++t) w.step();
  WorldSnapshot snap;
  w.save(snap);
  World again(def);
  again.restore(snap);
  for (int t = 0; t < 40; ++t) w.step(), again.step();
  EXPECT_EQ(w.state_hash(), again.state_hash());
  EXPECT_NE(w.external_work(), 0.0);  // the paddle struck
  // A handle that is not the definition's is refused, naming the segment.
  WorldDef bad = def;
  bad.segments[0].body = Entity{99, 1};
  EXPECT_THROW(World{bad}, std::invalid_argument);
}

}  // namespace carried_segments_test
}  // namespace fixstep
