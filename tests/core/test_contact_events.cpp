// Contact events: disc pairs that begin and end touching, by handle, with the closing speed.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "test_bodies.hpp"

namespace fixstep {
namespace {

using test::ball;

TEST(ContactEvents, TwoDiscsThatStrikeAndPartGiveOneBegunAndOneEndedWithTheClosingSpeed) {
  WorldSettings s{.dt = 0.01};
  s.contacts = ContactSettings{.restitution = 1.0, .friction = 0.0};
  World sim(WorldDef::empty(Precision::f64, s));
  BodyDef a = ball("a", {-1, 0}, {2, 0});
  BodyDef b = ball("b", {1, 0}, {-1, 0});
  a.collider = b.collider = Collider{0.5};
  const Entity ea = sim.create_body(a), eb = sim.create_body(b);
  std::vector<ContactEvent> begun, ended;
  for (int t = 0; t < 200; ++t) {
    sim.step();
    begun.insert(begun.end(), sim.contacts_begun().begin(), sim.contacts_begun().end());
    ended.insert(ended.end(), sim.contacts_ended().begin(), sim.contacts_ended().end());
  }
  ASSERT_EQ(begun.size(), 1u);
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(begun[0].a, ea);
  EXPECT_EQ(begun[0].b, eb);
  EXPECT_NEAR(begun[0].normal_speed, 3.0, 1e-12);  // closing speed 2 - (-1)
  EXPECT_EQ(ended[0].normal_speed, 0.0);
}

TEST(ContactEvents, ADiscComingToRestOnAnotherBeginsOnceAndEndsWhenOneIsDestroyed) {
  WorldSettings s{.dt = 0.01};
  s.contacts = ContactSettings{.restitution = 0.0, .friction = 0.5};
  World sim(WorldDef::empty(Precision::f64, s));
  BodyDef floor = ball("floor", {0, 0});
  floor.type = BodyType::static_body;
  floor.collider = Collider{1.0};
  BodyDef top = ball("top", {0, 1.6});
  top.collider = Collider{0.5};
  top.gravity = Gravity{{0, -9.81}};
  const Entity ef = sim.create_body(floor), et = sim.create_body(top);
  int begun = 0, ended = 0;
  for (int t = 0; t < 300; ++t) {
    sim.step();
    begun += static_cast<int>(sim.contacts_begun().size());
    ended += static_cast<int>(sim.contacts_ended().size());
  }
  EXPECT_EQ(begun, 1);  // resting contact: no flicker of begin/end events
  EXPECT_EQ(ended, 0);
  sim.destroy(ef);
  sim.step();
  ASSERT_EQ(sim.contacts_ended().size(), 1u);
  EXPECT_EQ(sim.contacts_ended()[0].a, ef);  // a destroyed body's handle: stale now
  EXPECT_EQ(sim.contacts_ended()[0].b, et);
  EXPECT_FALSE(sim.contains(sim.contacts_ended()[0].a));
}

}  // namespace
}  // namespace fixstep
