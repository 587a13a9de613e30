// What a sleeping island costs (ContactSettings::sleep): the free step and the plane pass visit
// the awake bodies only (ContactStats::free_stepped, plane_tested), so a world asleep steps no
// body; sleepers stay bit for bit where they are, their previous positions (interpolation) are
// where they sleep, and waking, snapshots and threads give the same bits as ever. The work is
// counted, not timed.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/integrators.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {
namespace {

constexpr double disc_radius = 0.05;  // m

/// A frictionless floor (e = 0) and `count` discs of 1 kg resting on it 0.15 m apart from
/// x = 0 (each an island of its own), under gravity; the free step is the fused sweep (no
/// links, no energy account), which skips the sleepers.
WorldDef floor_row(int count, Precision precision = Precision::f64, int threads = 1) {
  WorldDef def;
  def.precision = precision;
  def.settings.dt = 1.0 / 60.0;
  def.settings.threads = threads;
  def.settings.contacts = ContactSettings{.restitution = 0.0, .friction = 0.0, .sleep = true};
  def.settings.contacts->sleep_time = 0.25;
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0});
  for (int i = 0; i < count; ++i) {
    BodyDef b;
    b.body = Body{.mass = 1.0, .position = {0.15 * i, disc_radius}};
    b.collider = Collider{.radius = disc_radius};
    b.gravity = Gravity{};
    def.bodies.push_back(b);
  }
  return def;
}

/// A disc of 1 kg at (x, y) m moving at (vx, vy) m/s under gravity.
BodyDef disc_at(double x, double y, double vx, double vy) {
  BodyDef b;
  b.body = Body{.mass = 1.0, .position = {x, y}, .velocity = {vx, vy}};
  b.collider = Collider{.radius = disc_radius};
  b.gravity = Gravity{};
  return b;
}

/// The bodies the free step moves: awake, and not static.
std::size_t awake_count(const World& w) {
  std::size_t n = 0;
  for (const Entity e : w.bodies()) {
    n += w.asleep(e) || w.type(e) == BodyType::static_body ? 0 : 1;
  }
  return n;
}

std::vector<Vec2> positions_of(const World& w) {
  std::vector<Vec2> out;
  for (const Entity e : w.bodies()) out.push_back(w.body(e).position);
  return out;
}

/// Steps w until `sleepers` of its bodies sleep (at most 600 ticks); false: never.
bool step_until_sleeping(World& w, std::size_t sleepers) {
  for (int t = 0; t < 600; ++t) {
    w.step();
    if (w.contact_stats().sleeping == sleepers) return true;
  }
  return false;
}

TEST(SleepWork, AWorldAsleepStepsNoBody) {
  for (const bool account : {false, true}) {  // the energy account's pass skips them too
    for (const Precision p : {Precision::f64, Precision::f32}) {
      SCOPED_TRACE(precision_name(p));
      SCOPED_TRACE(account ? "energy account" : "no account");
      WorldDef def = floor_row(8, p);
      def.settings.track_dissipation = account;
      World w(def);
      w.step();
      EXPECT_EQ(w.contact_stats().free_stepped, 8u);  // awake: every body
      EXPECT_EQ(w.contact_stats().plane_tested, 8u);
      ASSERT_TRUE(step_until_sleeping(w, 8));
      const std::vector<Vec2> at_sleep = positions_of(w);
      for (int t = 0; t < 100; ++t) {
        w.step();
        ASSERT_EQ(w.contact_stats().free_stepped, 0u) << t;
        // The first tick after the islands fell asleep passes over every body once more.
        if (t > 0) {
          ASSERT_EQ(w.contact_stats().plane_tested, 0u) << t;
        }
      }
      EXPECT_EQ(positions_of(w), at_sleep);  // bit for bit
      for (const Entity e : w.bodies()) EXPECT_EQ(w.body(e).velocity.y, 0.0);
    }
  }
}

TEST(SleepWork, HalfAsleepTheFreeStepAndThePlanePassVisitTheAwakeOnly) {
  WorldDef def = floor_row(8);
  def.bodies.push_back(disc_at(-5.0, disc_radius, -1.0, 0.0));  // slides on, never sleeps
  BodyDef wall = disc_at(-3.0, disc_radius, 0.0, 0.0);
  wall.type = BodyType::static_body;  // never stepped: it never moves
  wall.gravity.reset();
  def.bodies.push_back(wall);
  World w(def);
  ASSERT_TRUE(step_until_sleeping(w, 8));
  const std::vector<Vec2> at_sleep = positions_of(w);
  for (int t = 0; t < 60; ++t) {
    w.step();
    EXPECT_EQ(w.contact_stats().free_stepped, awake_count(w)) << t;  // the slider
    EXPECT_EQ(w.contact_stats().free_stepped, 1u) << t;
    if (t > 0) {
      EXPECT_EQ(w.contact_stats().plane_tested, 1u) << t;  // the slider
    }
  }
  const std::vector<Vec2> now = positions_of(w);
  for (std::size_t k = 0; k < 8; ++k) EXPECT_EQ(now[k], at_sleep[k]) << k;
  EXPECT_NE(now[8], at_sleep[8]);  // the slider moved on
  EXPECT_EQ(now[9], at_sleep[9]);  // the wall did not
  // Input wakes one disc's island: from its tick on, the free step steps it as well.
  const Entity struck = w.bodies()[3];
  TickInput in;
  in.bodies.push_back(BodyInput{.body = struck, .kind = BodyInputKind::impulse, .value = {0, 1}});
  w.step(in);
  EXPECT_EQ(awake_count(w), 2u);
  EXPECT_EQ(w.contact_stats().free_stepped, 2u);
  EXPECT_GT(w.body(struck).position.y, at_sleep[3].y);
  w.step();
  EXPECT_EQ(w.contact_stats().free_stepped, 2u);
  EXPECT_EQ(w.contact_stats().plane_tested, 2u);
}

// A static body never moves, with sleeping or without: the free step leaves it alone (it was
// stepped and put back), so it costs the step nothing. One defined with a velocity and gravity
// rests all the same, its velocity zero from the start.
TEST(SleepWork, StaticBodiesAreNeverStepped) {
  for (const bool sleep : {false, true}) {
    SCOPED_TRACE(sleep ? "sleeping on" : "sleeping off");
    WorldDef def = floor_row(3);
    def.settings.contacts->sleep = sleep;
    for (const double x : {-0.5, 0.8}) {
      BodyDef post = disc_at(x, 0.3, 1.0, 2.0);  // a velocity and gravity, which it ignores
      post.type = BodyType::static_body;
      def.bodies.push_back(post);
    }
    def.bodies.push_back(disc_at(-0.5, 1.0, 0.0, 0.0));  // falls onto the first post
    World w(def);
    const std::vector<Vec2> start = positions_of(w);
    for (const Entity e : w.bodies()) {
      if (w.type(e) == BodyType::static_body) {
        EXPECT_EQ(w.body(e).velocity, (Vec2{0.0, 0.0}));
      }
    }
    for (int t = 0; t < 120; ++t) {
      w.step();
      // Every disc but the posts (asleep, fewer: a tick's sleepers fall asleep after its step).
      if (sleep) {
        ASSERT_LE(w.contact_stats().free_stepped, 4u) << t;
      } else {
        ASSERT_EQ(w.contact_stats().free_stepped, 4u) << t;
      }
    }
    const std::vector<Vec2> now = positions_of(w);
    for (std::size_t k = 3; k < 5; ++k) {
      EXPECT_EQ(now[k], start[k]) << k;
      EXPECT_EQ(w.body(w.bodies()[k]).velocity, (Vec2{0.0, 0.0})) << k;
    }
    EXPECT_LT(now[5].y, 0.3 + 3 * disc_radius) << "the falling disc rests on the post";
    EXPECT_GT(now[5].y, 0.3 + disc_radius) << "the falling disc rests on the post";
  }
}

TEST(SleepWork, ASleepersPreviousPositionIsWhereItSleeps) {
  // Discs sliding at 0.5 m/s on the frictionless floor with a sleep speed of 1 m/s: each
  // falls asleep after 0.25 s having moved in its last tick; from the next tick on, the
  // position to draw from (alpha 0) is where it sleeps.
  WorldDef def = floor_row(0);
  def.settings.contacts->sleep_speed = 1.0;
  for (int i = 0; i < 3; ++i) def.bodies.push_back(disc_at(0.3 * i, disc_radius, 0.5, 0.0));
  def.bodies.push_back(disc_at(-2.0, disc_radius, -3.0, 0.0));  // fast: keeps the world awake
  World w(def);
  w.set_keep_previous(true);
  std::vector<float> px(4), py(4);
  std::vector<bool> was_asleep(4, false);
  int checked = 0;
  for (int t = 0; t < 60; ++t) {
    w.step();
    w.interpolate_positions(0.0, px, py);
    for (std::size_t k = 0; k < 4; ++k) {
      const Entity e = w.bodies()[k];
      if (was_asleep[k] && w.asleep(e)) {
        EXPECT_EQ(px[k], static_cast<float>(w.body(e).position.x)) << "tick " << t << " " << k;
        EXPECT_EQ(py[k], static_cast<float>(w.body(e).position.y)) << "tick " << t << " " << k;
        ++checked;
      }
      was_asleep[k] = w.asleep(e);
    }
  }
  EXPECT_GE(checked, 3 * 30);  // not vacuous: all three slept for most of the run
}

TEST(SleepWork, TheAwakeStepAsInAWorldWithoutSleeping) {
  // Sleeping discs and awake point bodies (no collider: they never sleep) in turn, so the free
  // step's runs start all over the arrays; each point body has its own spring (with and
  // without rest length), damping, drag and force, so a run that read another body's
  // coefficients would step differently from the world that does not sleep. With the energy
  // account, their dissipated energy too.
  for (const bool account : {false, true}) {
    for (const Integrator integrator : all_integrators) {
      SCOPED_TRACE(integrator_name(integrator));
      SCOPED_TRACE(account ? "energy account" : "no account");
      WorldDef def;
      def.settings.dt = 1.0 / 60.0;
      def.settings.integrator = integrator;
      def.settings.track_dissipation = account;
      def.settings.contacts = ContactSettings{.restitution = 0.0, .friction = 0.0, .sleep = true};
      def.settings.contacts->sleep_time = 0.25;
      def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0});
      for (int i = 0; i < 12; ++i) {
        def.bodies.push_back(disc_at(0.15 * i, disc_radius, 0.0, 0.0));
        for (int m = 0; m < i % 3 + 1; ++m) {
          BodyDef b;
          const double s = 1.0 + 0.1 * i + 0.37 * m;
          b.body = Body{.mass = s, .position = {0.15 * i, 2.0 + m}, .velocity = {0.1 * m, -s}};
          b.spring = SpringDamper{.anchor = {0.15 * i, 3.0 + s},
                                  .stiffness = 10.0 * s,
                                  .damping = 0.5 * s * (m + 1),
                                  .rest_length = (i + m) % 2 == 0 ? 0.0 : 0.5 * s};
          if (m == 1) b.drag = LinearDrag{.coefficient = 0.2 * s};
          b.constant_force = ConstantForce{.force = {0.1 * i, -0.2 * m}};
          def.bodies.push_back(b);
        }
      }
      WorldDef awake_def = def;
      awake_def.settings.contacts->sleep = false;
      World w(def), awake(awake_def);
      std::size_t slept = 0;
      for (int t = 0; t < 120; ++t) {
        w.step(), awake.step();
        slept = std::max(slept, w.contact_stats().sleeping);
        for (std::size_t k = 0; k < w.body_count(); ++k) {
          const Entity e = w.bodies()[k];
          if (w.body(e).mass == 1.0) continue;  // a disc
          ASSERT_EQ(w.body(e).position, awake.body(awake.bodies()[k]).position) << t << " " << k;
          ASSERT_EQ(w.body(e).velocity, awake.body(awake.bodies()[k]).velocity) << t << " " << k;
        }
      }
      EXPECT_EQ(slept, 12u);  // every disc slept
      EXPECT_LT(w.contact_stats().free_stepped, w.body_count());
    }
  }
}

/// A 6 × 5 stack of discs on the floor and a ball thrown up above it that comes down on it
/// after the stack has fallen asleep, on `threads` threads.
WorldDef stack_and_ball(int threads) {
  WorldDef def = floor_row(0, Precision::f64, threads);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 6; ++j) {
      def.bodies.push_back(disc_at(0.1 * j + (i % 2) * 0.05, disc_radius + 0.1 * i, 0.0, 0.0));
    }
  }
  def.planes.push_back(PlaneDef{.normal = {1, 0}, .offset = -0.05});
  def.planes.push_back(PlaneDef{.normal = {-1, 0}, .offset = -0.6});
  def.bodies.push_back(disc_at(0.27, 1.5, 0.0, 14.0));
  return def;
}

TEST(SleepWork, WakingGivesTheSameBitsOnOneThreadAndTwo) {
  World one(stack_and_ball(1)), two(stack_and_ball(2));
  std::size_t slept = 0, woken = 0;
  for (int t = 0; t < 300; ++t) {
    one.step(), two.step();
    ASSERT_EQ(one.state_hash(), two.state_hash()) << "tick " << t;
    slept = std::max(slept, one.contact_stats().sleeping);
    woken += one.contact_stats().woken;
  }
  EXPECT_GE(slept, 30u);  // not vacuous: the stack slept while the ball flew, and was woken
  EXPECT_GE(woken, 1u);
}

TEST(SleepWork, ASnapshotOfSleepersStepsOnToTheSameBits) {
  // Disc B, dropped from 0.3 m, lands on the floor at x = 0 and falls asleep; disc C slides on
  // the floor towards it from x = 3 m at 1 m/s and wakes it about 3 s in. The snapshot of B
  // asleep is restored into a world of the same scene in which B was knocked sideways and is
  // landing 0.4 m further on: were its plane pass's scratch for that landing taken for the
  // sleeper's, B would move or wake early.
  WorldDef def = floor_row(0);
  def.bodies.push_back(disc_at(0.0, 0.3, 0.0, 0.0));
  def.bodies.push_back(disc_at(3.0, disc_radius, -1.0, 0.0));
  World w(def), other(def);
  const Entity b = w.bodies()[0];
  ASSERT_TRUE(step_until_sleeping(w, 1));
  for (int t = 0; t < 5; ++t) w.step();
  TickInput knock;
  knock.bodies.push_back(BodyInput{.body = b, .kind = BodyInputKind::impulse, .value = {2, 0}});
  other.step(knock);
  bool landed = false;
  for (int t = 0; t < 60 && !landed; ++t) {
    const double vy = other.body(b).velocity.y;
    other.step();
    landed = vy < -1.0 && other.body(b).velocity.y > -0.5;
  }
  ASSERT_TRUE(landed);
  ASSERT_GT(other.body(b).position.x, 0.3);
  WorldSnapshot snap;
  w.save(snap);
  other.restore(snap);
  std::size_t woken = 0;
  for (int t = 0; t < 240; ++t) {
    w.step(), other.step();
    woken += w.contact_stats().woken;
    ASSERT_EQ(other.state_hash(), w.state_hash()) << "tick " << t;
  }
  EXPECT_EQ(woken, 1u);  // C woke B
  EXPECT_EQ(positions_of(other), positions_of(w));
}

}  // namespace
}  // namespace fixstep
