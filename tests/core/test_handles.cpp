// The handle API of a running world: bodies, components and links by handle on World.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "test_bodies.hpp"

namespace fixstep {
namespace {

using test::ball;

TEST(Handles, EveryEditOfARunningWorldIsReachableOnSimulationWithoutVisit) {
  World sim(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.01}));
  const Entity a = sim.create_body(ball("a", {0, 0}));
  const Entity b = sim.create_body(ball("b", {1, 0}));
  const Entity c = sim.create_body(ball("c", {2, 0}));
  EXPECT_EQ(sim.find("b"), b);
  EXPECT_TRUE(sim.find("nobody").is_null());
  sim.set(b, Gravity{{0.0, -9.81}});
  ASSERT_TRUE(sim.get<Gravity>(b).has_value());
  EXPECT_EQ(sim.get<Gravity>(b)->acceleration.y, -9.81);
  EXPECT_FALSE(sim.get<Gravity>(a).has_value());
  const Link l = sim.create_link(LinkDef{a, c, LinkSpring{.stiffness = 10.0}});
  EXPECT_TRUE(sim.contains(l));
  EXPECT_EQ(sim.link(l).body_b, c);
  // Destroying a moves c (the last body) into its dense slot: handles still name the bodies.
  sim.destroy(a);
  EXPECT_FALSE(sim.contains(a));
  EXPECT_FALSE(sim.contains(l));  // a's link went with it
  EXPECT_EQ(sim.index_of(c), 0u);
  EXPECT_EQ(sim.bodies()[0], c);
  EXPECT_EQ(sim.name(c), "c");
  EXPECT_EQ(sim.body(c).position.x, 2.0);
  sim.set_body(c, Body{.mass = 2.0, .position = {5, 6}});
  EXPECT_EQ(sim.body(c).position.y, 6.0);
  sim.remove<Gravity>(b);
  EXPECT_FALSE(sim.get<Gravity>(b).has_value());
  EXPECT_EQ(sim.type(b), BodyType::dynamic);
  EXPECT_FALSE(sim.get<Gravity>(a).has_value());  // a stale handle reads as absent
  EXPECT_THROW(sim.destroy(a), std::invalid_argument);
  EXPECT_THROW((void)sim.body(a), std::invalid_argument);
  EXPECT_THROW(sim.set(a, Gravity{}), std::invalid_argument);
}

}  // namespace
}  // namespace fixstep
