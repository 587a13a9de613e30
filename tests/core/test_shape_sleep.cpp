// Bodies with shapes in the sleeping islands (ContactSettings::sleep): a settled pile falls
// asleep and then costs no contact phase and moves not a bit, events do not end for sleeping
// pairs, a thrown box wakes a sleeping stack before it touches it, input wakes a sleeper, and a
// world with sleepers steps to the same bits after a snapshot and on two threads.
#include <gtest/gtest.h>

#include <cmath>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "shape_exact.hpp"

namespace fixstep {
namespace {

/// Three boxes stacked on the ground (entities 0..2 bottom to top) with sleeping on, and
/// optionally a box 6 m to the left thrown at the stack's middle at 8 m/s.
WorldDef stack(bool thrown) {
  WorldSettings s = shape_exact::shape_settings(0.6);
  s.contacts->sleep = true;
  s.contacts->sleep_time = 0.25;
  WorldDef def = WorldDef::empty(Precision::f64, s);
  def.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  for (int i = 0; i < 3; ++i) def.add_body(shape_exact::box_body(0.5, 0.5, {0.0, 0.5 + i}));
  if (thrown) {
    BodyDef b = shape_exact::box_body(0.25, 0.25, {-6.0, 1.5});
    b.gravity.reset();  // straight at the middle box
    b.body.velocity = {8.0, 0.0};
    def.add_body(b);
  }
  return def;
}

TEST(ShapeSleep, ASettledStackFallsAsleepAndThenNeitherMovesNorIsSolved) {
  World w(stack(false));
  std::size_t ended = 0;
  int asleep_at = -1;
  for (int t = 1; t <= 120 && asleep_at < 0; ++t) {
    w.step();
    ended += w.contacts_ended().size();
    if (w.contact_stats().sleeping == 3) asleep_at = t;
  }
  ASSERT_GT(asleep_at, 0) << "the stack never fell asleep in 2 s";
  const auto bodies = w.defined_bodies();
  std::vector<Body> before;
  for (const Entity e : bodies) before.push_back(w.body(e));
  for (int t = 0; t < 120; ++t) {
    w.step();
    EXPECT_EQ(w.contact_stats().shape_points, 0u) << "a sleeping stack is not solved";
    ended += w.contacts_ended().size();
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body b = w.body(bodies[i]);
    EXPECT_EQ(b.position.x, before[i].position.x);
    EXPECT_EQ(b.position.y, before[i].position.y);
    EXPECT_EQ(b.angle, before[i].angle);
    EXPECT_EQ(b.velocity.x, 0.0);
    EXPECT_EQ(b.angular_velocity, 0.0);
  }
  EXPECT_EQ(w.contact_stats().sleeping, 3u);
  EXPECT_EQ(ended, 0u) << "the boxes stay in touch asleep: no contact ends";
}

// The thrown box's broadphase box reaches the middle box's a tick before their faces meet: the
// stack wakes first, so the first contact is between awake bodies, and the middle box is
// knocked away (it moves more than 0.5 m).
TEST(ShapeSleep, AThrownBoxWakesASleepingStackAndKnocksItsMiddleBoxAway) {
  World w(stack(true));
  const auto bodies = w.defined_bodies();
  const Entity middle = bodies[1];
  for (int t = 0; t < 30; ++t) w.step();  // 0.5 s: the stack sleeps, the box is 2 m away
  ASSERT_TRUE(w.asleep(middle));
  const double x0 = w.body(middle).position.x;
  bool woke = false;
  for (int t = 0; t < 60; ++t) {
    w.step();
    if (!woke && !w.asleep(middle)) {
      woke = true;
      EXPECT_GT(w.contact_stats().woken, 0u);
    }
    EXPECT_EQ(w.contact_stats().sleeper_contacts, 0u);
  }
  EXPECT_TRUE(woke);
  EXPECT_GT(w.body(middle).position.x - x0, 0.5);
}

// The work is counted, not timed (ContactStats::shape_visited): asleep, the stack's bodies are
// passed over by no pass of the shape phase, tick after tick, until input wakes one; a
// kinematic box, or a kinematic disc, that moves far from the stack keeps the phase running.
TEST(ShapeSleep, AStackAsleepIsVisitedByNoShapePassUntilWokenOrAKinematicBodyMoves) {
  enum class Mover { none, box, disc };
  for (const Mover mover : {Mover::none, Mover::box, Mover::disc}) {
    SCOPED_TRACE(mover == Mover::none  ? "the stack alone"
                 : mover == Mover::box ? "a kinematic box moving 20 m away"
                                       : "a kinematic disc moving 20 m away");
    WorldDef def = stack(false);
    if (mover != Mover::none) {
      BodyDef k = shape_exact::box_body(0.5, 0.5, {20.0, 5.0});
      if (mover == Mover::disc) k.shapes.clear(), k.collider = Collider{.radius = 0.5};
      k.type = BodyType::kinematic;
      k.gravity.reset();
      k.body.velocity = {1.0, 0.0};
      def.add_body(k);
    }
    World w(def);
    int t = 0;
    for (; t < 120 && w.contact_stats().sleeping < 3; ++t) w.step();
    ASSERT_EQ(w.contact_stats().sleeping, 3u) << "the stack never fell asleep in 2 s";
    const std::size_t bodies = mover != Mover::none ? 4 : 3;
    for (int i = 0; i < 60; ++i) {
      w.step();
      ASSERT_EQ(w.contact_stats().shape_visited, mover != Mover::none ? bodies : 0u)
          << "tick " << t + i;
    }
    const Entity top = w.defined_bodies()[2];
    TickInput in;
    in.bodies.push_back(BodyInput{.body = top, .kind = BodyInputKind::impulse, .value = {0, 2}});
    w.step(in);
    EXPECT_EQ(w.contact_stats().shape_visited, bodies) << "woken: every body with shapes";
  }
}

TEST(ShapeSleep, InputWakesASleepingBox) {
  World w(stack(false));
  for (int t = 0; t < 90; ++t) w.step();
  const Entity top = w.defined_bodies()[2];
  ASSERT_TRUE(w.asleep(top));
  const double y0 = w.body(top).position.y;
  TickInput in;  // thrown upwards at 2 m/s (1 kg)
  in.bodies.push_back(BodyInput{.body = top, .kind = BodyInputKind::impulse, .value = {0.0, 2.0}});
  w.step(in);
  EXPECT_FALSE(w.asleep(top));
  EXPECT_GT(w.body(top).position.y, y0 + 0.01);
}

TEST(ShapeSleep, ASnapshotStepsOnToTheSameBitsAndTwoThreadsMatchOne) {
  World a(stack(true));
  for (int i = 0; i < 20; ++i) a.step();
  WorldSnapshot snap;
  a.save(snap);
  for (int i = 0; i < 100; ++i) a.step();
  const std::uint64_t h = a.state_hash();
  a.restore(snap);
  for (int i = 0; i < 100; ++i) a.step();
  EXPECT_EQ(a.state_hash(), h);
  WorldDef two = stack(true);
  two.settings.threads = 2;
  World b(two);
  for (int i = 0; i < 120; ++i) b.step();
  EXPECT_EQ(b.state_hash(), h);
}

}  // namespace
}  // namespace fixstep
