// What the resting solver reports of its own work (ContactStats: velocity and push-out sweeps,
// whether they converged) and where a tick's time went (World::profile(), StepProfile): a
// resting disc converges in a sweep or two, a column that the sweeps cannot settle in one tick
// says so at the bound, a world without touching discs runs none, and the profile is measured
// only with disc contacts.
#include <gtest/gtest.h>

#include "fixstep/world.hpp"

namespace fixstep {
namespace contact_profile_tests {

WorldDef ground_world() {
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{.restitution = 0.0, .friction = 0.3};
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .friction = 0.3});
  return def;
}

BodyDef falling_disc(Vec2 x, double r) {
  BodyDef b;
  b.body = Body{.mass = 1.0, .position = x, .velocity = {}};
  b.collider = Collider{.radius = r};
  b.gravity = Gravity{};
  return b;
}

// One disc resting on the ground: a single contact, warm started, is solved by the first sweep
// and the second finds nothing left to change (converged at 2, or at 1 when the warm start was
// already exact); nothing is deeper than the slop.
TEST(ContactSweeps, ADiscRestingOnTheGroundConvergesInTwoSweeps) {
  WorldDef def = ground_world();
  def.bodies.push_back(falling_disc({0.0, 0.1}, 0.1));
  World w(def);
  for (int i = 0; i < 120; ++i) w.step();
  const ContactStats& s = w.contact_stats();
  ASSERT_EQ(s.touching, 1u);
  EXPECT_TRUE(s.velocity_converged);
  EXPECT_GE(s.velocity_sweeps, 1);
  EXPECT_LE(s.velocity_sweeps, 2);
  EXPECT_GE(s.position_sweeps, 1);
  EXPECT_TRUE(s.positions_settled);
}

// A column of 40 discs dropped onto the ground at once: Gauss–Seidel passes an impulse one disc
// further per sweep, so the first ticks cannot converge within the bound, and the stats say so
// (sweeps at the bound, converged false) instead of passing for a solved tick.
TEST(ContactSweeps, AColumnBeyondTheSweepBoundSaysItStoppedThere) {
  WorldDef def = ground_world();
  const double r = 0.1;
  for (int i = 0; i < 40; ++i) def.bodies.push_back(falling_disc({0.0, r + 2 * r * i}, r));
  World w(def);
  bool hit_bound = false;
  for (int i = 0; i < 30; ++i) {
    w.step();
    const ContactStats& s = w.contact_stats();
    ASSERT_GE(s.velocity_sweeps, 1) << "tick " << i;
    ASSERT_LE(s.velocity_sweeps, ContactStats::max_velocity_sweeps) << "tick " << i;
    ASSERT_LE(s.position_sweeps, ContactStats::max_position_sweeps) << "tick " << i;
    // Converged exactly when the sweeps stopped before the bound.
    if (s.velocity_sweeps < ContactStats::max_velocity_sweeps) {
      EXPECT_TRUE(s.velocity_converged) << "tick " << i;
    }
    if (!s.velocity_converged) {
      EXPECT_EQ(s.velocity_sweeps, ContactStats::max_velocity_sweeps) << "tick " << i;
      hit_bound = true;
    }
  }
  EXPECT_TRUE(hit_bound);
}

// Discs apart, with contacts on: no pair touches, no sweep runs, and nothing is unconverged.
TEST(ContactSweeps, NoTouchingPairsRunNoSweeps) {
  WorldDef def = ground_world();
  def.planes.clear();
  def.bodies.push_back(falling_disc({0.0, 0.0}, 0.1));
  def.bodies.push_back(falling_disc({1.0, 0.0}, 0.1));
  World w(def);
  w.step();
  const ContactStats& s = w.contact_stats();
  EXPECT_EQ(s.touching, 0u);
  EXPECT_EQ(s.velocity_sweeps, 0);
  EXPECT_EQ(s.position_sweeps, 0);
  EXPECT_TRUE(s.velocity_converged);
  EXPECT_TRUE(s.positions_settled);
}

// With disc contacts every tick is timed, its phases within the whole; without, nothing is.
TEST(StepProfile, PhasesOfATickWithDiscContactsAddUpWithinTheStep) {
  WorldDef def = ground_world();
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j)
      def.bodies.push_back(falling_disc({0.25 * j, 0.1 + 0.25 * i}, 0.1));
  }
  World w(def);
  for (int i = 0; i < 60; ++i) w.step();
  const StepProfile& p = w.profile();
  EXPECT_GT(p.step, 0.0);
  EXPECT_GT(p.broadphase, 0.0);
  EXPECT_GT(p.resting, 0.0);
  for (const double phase : {p.integrate, p.broadphase, p.impacts, p.resting, p.events}) {
    EXPECT_GE(phase, 0.0);
  }
  const double phases = p.integrate + p.broadphase + p.impacts + p.resting + p.events;
  EXPECT_LE(phases, p.step * (1 + 1e-9));
  EXPECT_GE(phases, 0.5 * p.step);  // only clock reads lie between the phases

  WorldDef free_fall;
  free_fall.settings.dt = 1.0 / 60.0;
  free_fall.bodies.push_back(falling_disc({0.0, 0.0}, 0.1));
  World f(free_fall);
  f.step();
  EXPECT_EQ(f.profile().step, 0.0);
  EXPECT_EQ(f.profile().integrate, 0.0);
}

}  // namespace contact_profile_tests
}  // namespace fixstep
