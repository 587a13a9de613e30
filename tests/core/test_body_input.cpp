// Per-body input of a tick: forces, impulses and kinematic velocities by handle, checked and
// sampled.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "test_bodies.hpp"

namespace fixstep {
namespace {

using test::ball;

constexpr Integrator all_integrators[] = {
    Integrator::explicit_euler,  Integrator::semi_implicit_euler,
    Integrator::velocity_verlet, Integrator::rk4,
    Integrator::forest_ruth,     Integrator::implicit_euler};

TEST(BodyInput, AnImpulseChangesTheVelocityByJOverMAtTheTicksStart) {
  // Semi-implicit Euler on a free body: v1 = v0 + J/m, x1 = x0 + v1 dt, exactly.
  World sim(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.25}));
  const Entity e = sim.create_body(ball("e", {1, 2}, {0.5, 0}, 4.0));
  TickInput in;
  in.bodies.push_back({e, BodyInputKind::impulse, {2.0, -1.0}});
  sim.step(in);
  EXPECT_EQ(sim.body(e).velocity.x, 0.5 + 2.0 / 4.0);
  EXPECT_EQ(sim.body(e).velocity.y, -0.25);
  EXPECT_EQ(sim.body(e).position.x, 1.0 + 1.0 * 0.25);
  sim.step();  // an impulse is for its tick only
  EXPECT_EQ(sim.body(e).velocity.x, 1.0);
}

/// The state after `ticks` ticks of a world whose body 1 gets `force` (N) in tick 2, by input
/// (by_input) or by a ConstantForce set before that tick and removed after it.
std::vector<Body> forced_run(Integrator method, bool linked, bool by_input, Vec2 force) {
  WorldSettings s{.dt = 0.01, .integrator = method};
  World sim(WorldDef::empty(Precision::f64, s));
  BodyDef a = ball("a", {0, 0}, {0.3, 0.1}, 2.0);
  a.gravity = Gravity{{0.0, -9.81}};
  a.spring = SpringDamper{.anchor = {0, 0}, .stiffness = 40.0, .damping = 0.5};
  const Entity ea = sim.create_body(a);
  const Entity eb = sim.create_body(ball("b", {1, 0}, {0, 0.2}, 3.0));
  if (linked) sim.create_link(LinkDef{ea, eb, LinkSpring{.stiffness = 30.0, .damping = 0.2}});
  for (int t = 0; t < 6; ++t) {
    TickInput in;
    if (t == 2 && by_input) in.bodies.push_back({eb, BodyInputKind::force, force});
    if (t == 2 && !by_input) sim.set(eb, ConstantForce{force});
    sim.step(in);
    if (t == 2 && !by_input) sim.remove<ConstantForce>(eb);
  }
  return {sim.body(ea), sim.body(eb)};
}

TEST(BodyInput, AForceForOneTickStepsAsAConstantForceForThatTickBitForBit) {
  // Every integrator's stages see the force, on a single body (the fused sweep) and on a
  // network (the link passes; implicit Euler's own solve).
  for (const Integrator method : all_integrators) {
    for (const bool linked : {false, true}) {
      const auto by_input = forced_run(method, linked, true, {3.0, -2.0});
      const auto by_component = forced_run(method, linked, false, {3.0, -2.0});
      const auto without = forced_run(method, linked, true, {0.0, 0.0});
      for (std::size_t i = 0; i < 2; ++i) {
        SCOPED_TRACE(::testing::Message() << integrator_name(method) << " linked=" << linked);
        EXPECT_EQ(by_input[i].position.x, by_component[i].position.x);
        EXPECT_EQ(by_input[i].position.y, by_component[i].position.y);
        EXPECT_EQ(by_input[i].velocity.x, by_component[i].velocity.x);
        EXPECT_EQ(by_input[i].velocity.y, by_component[i].velocity.y);
      }
      EXPECT_NE(by_input[1].velocity.x, without[1].velocity.x);  // the force did act
    }
  }
}

TEST(BodyInput, AKinematicBodyMovesAtTheVelocityItIsGivenAndKeepsIt) {
  World sim(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.5}));
  BodyDef k = ball("paddle", {0, 0});
  k.type = BodyType::kinematic;
  const Entity e = sim.create_body(k);
  const Entity d = sim.create_body(ball("d", {5, 0}));
  TickInput in;
  in.bodies.push_back({e, BodyInputKind::velocity, {2.0, -1.0}});
  in.bodies.push_back({d, BodyInputKind::velocity, {9.0, 9.0}});  // dynamic: ignored
  sim.step(in);
  EXPECT_EQ(sim.body(e).position.x, 1.0);
  EXPECT_EQ(sim.body(e).position.y, -0.5);
  EXPECT_EQ(sim.body(d).velocity.x, 0.0);
  sim.step();  // held until changed
  EXPECT_EQ(sim.body(e).position.x, 2.0);
}

TEST(BodyInput, CheckInputNamesWhatStepWouldIgnore) {
  World sim(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.01}));
  const Entity d = sim.create_body(ball("d", {0, 0}));
  BodyDef s = ball("wall", {3, 0});
  s.type = BodyType::static_body;
  const Entity w = sim.create_body(s);
  const Entity gone = sim.create_body(ball("gone", {6, 0}));
  sim.destroy(gone);
  auto check = [&](BodyInput b) {
    TickInput in;
    in.bodies.push_back(b);
    try {
      sim.check_input(in);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(check({d, BodyInputKind::impulse, {1, 0}}), "accepted");
  EXPECT_NE(check({gone, BodyInputKind::impulse, {1, 0}}).find("no such body"), std::string::npos);
  EXPECT_NE(check({d, BodyInputKind::velocity, {1, 0}}).find("kinematic bodies only"),
            std::string::npos);
  EXPECT_NE(check({w, BodyInputKind::force, {1, 0}}).find("never moves"), std::string::npos);
  EXPECT_NE(check({d, BodyInputKind::force, {NAN, 0}}).find("finite"), std::string::npos);
  // What check_input refuses, step ignores: the world steps as without it.
  World twin(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.01}));
  twin.create_body(ball("d", {0, 0}));
  TickInput bad;
  bad.bodies = {{gone, BodyInputKind::impulse, {1, 0}},
                {w, BodyInputKind::force, {5, 5}},
                {d, BodyInputKind::force, {INFINITY, 0}}};
  sim.step(bad);
  twin.step();
  EXPECT_EQ(sim.body(d).position.x, twin.body(twin.bodies()[0]).position.x);
  EXPECT_EQ(sim.body(d).velocity.x, 0.0);
}

TEST(BodyInput, TheSamplerHoldsForcesAsLevelsAndImpulsesAsEvents) {
  InputSampler sampler;
  const Entity e{3, 1};
  sampler.set_force(e, {0, 40});
  sampler.apply_impulse(e, {1, 0});
  const TickInput t0 = sampler.sample(0);
  const TickInput t1 = sampler.sample(1);
  sampler.set_force(e, {0, 0});
  const TickInput t2 = sampler.sample(2);
  ASSERT_EQ(t0.bodies.size(), 2u);
  EXPECT_EQ(t0.bodies[0], (BodyInput{e, BodyInputKind::force, {0, 40}}));
  EXPECT_EQ(t0.bodies[1].kind, BodyInputKind::impulse);
  ASSERT_EQ(t1.bodies.size(), 1u);  // the force is held, the impulse was once
  EXPECT_EQ(t1.bodies[0].kind, BodyInputKind::force);
  EXPECT_TRUE(t2.bodies.empty());
}

}  // namespace
}  // namespace fixstep
