// The handle API of a running world: bodies and links by
// handle on World, per-body input (forces, impulses, kinematic velocities), contact
// events, the stability guard's warnings, and per-body input in recordings.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/definition_checks.hpp"
#include "fixstep/detail/defined_entity.hpp"
#include "fixstep/recording.hpp"
#include "fixstep/recording_file.hpp"
#include "fixstep/world.hpp"

namespace fixstep {
namespace {

constexpr Integrator all_integrators[] = {
    Integrator::explicit_euler,  Integrator::semi_implicit_euler,
    Integrator::velocity_verlet, Integrator::rk4,
    Integrator::forest_ruth,     Integrator::implicit_euler};

BodyDef ball(const std::string& name, Vec2 at, Vec2 v = {}, double mass = 1.0) {
  BodyDef b;
  b.name = name;
  b.body = Body{.mass = mass, .position = at, .velocity = v};
  return b;
}

// --- the handle API ----------------------------------------------------------------------

TEST(Handles, EveryEditOfARunningWorldIsReachableOnSimulationWithoutVisit) {
  World sim(Precision::f64, WorldSettings{.dt = 0.01});
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

// --- per-body input ----------------------------------------------------------------------

TEST(BodyInput, AnImpulseChangesTheVelocityByJOverMAtTheTicksStart) {
  // Semi-implicit Euler on a free body: v1 = v0 + J/m, x1 = x0 + v1 dt, exactly.
  World sim(Precision::f64, WorldSettings{.dt = 0.25});
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
  World sim(Precision::f64, s);
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
  World sim(Precision::f64, WorldSettings{.dt = 0.5});
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
  World sim(Precision::f64, WorldSettings{.dt = 0.01});
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
  World twin(Precision::f64, WorldSettings{.dt = 0.01});
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

// --- contact events ----------------------------------------------------------------------

TEST(ContactEvents, TwoDiscsThatStrikeAndPartGiveOneBegunAndOneEndedWithTheClosingSpeed) {
  WorldSettings s{.dt = 0.01};
  s.contacts = ContactSettings{.restitution = 1.0, .friction = 0.0};
  World sim(Precision::f64, s);
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
  World sim(Precision::f64, s);
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

// --- the guard's warnings ----------------------------------------------------------------

TEST(GuardWarnings, CheckStabilityReturnsANearLimitWarningWhereAProgramCanReadIt) {
  // Semi-implicit Euler is stable for ω dt < 2; ω dt = 1.9 is within 10 % of the bound.
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef b = ball("spring", {1, 0});
  const double omega = 1.9 / def.settings.dt;
  b.spring = SpringDamper{.stiffness = omega * omega};
  def.bodies.push_back(b);
  EXPECT_EQ(check_definition(def).size(), 1u);
  def.bodies[0].spring->stiffness = 1.0;
  EXPECT_TRUE(check_definition(def).empty());
}

// --- per-body input in recordings -------------------------------------------------------

TEST(BodyInputRecording, PerBodyInputsRoundTripAndReplayBitForBit) {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef k = ball("paddle", {0, -1});
  k.type = BodyType::kinematic;
  def.bodies = {ball("ship", {0, 0}), k};
  World sim = World(def);
  Recorder recorder(def, "code-built", 5);
  for (std::uint64_t t = 0; t < 30; ++t) {
    TickInput in{.tick = t};
    if (t % 7 == 1)
      in.bodies.push_back({detail::defined_entity(0), BodyInputKind::impulse, {0.1, 1.0 / 3}});
    if (t >= 10 && t < 14)
      in.bodies.push_back({detail::defined_entity(0), BodyInputKind::force, {0, 4}});
    if (t == 12)
      in.bodies.push_back({detail::defined_entity(1), BodyInputKind::velocity, {1.5, 0}});
    sim.step(in);
    recorder.record(in, sim);
  }
  const Recording rec = recorder.finish(sim);
  const Recording back = parse_recording(format_recording(rec), "mem");
  EXPECT_EQ(back, rec);
  EXPECT_TRUE(replay(def, back).ok());
  // Without the impulses the replay diverges at the first stored hash after tick 1.
  Recording stripped = back;
  for (TickInput& in : stripped.inputs) in.bodies.clear();
  const ReplayReport r = replay(def, stripped);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.mismatch->tick, 5u);
}

TEST(BodyInputRecording, AVersion1DragIndexReadsAsTheBodysInitialHandle) {
  const std::string v1 =
      "fixstep-recording 1\nscene s.toml\ndefinition 0000000000000001\n"
      "integrator semi_implicit_euler\nprecision f64\ndt 0.01\nsubsteps 1\nhash_every 60\n"
      "tick 0 push=0,0 held=100 pressed=100 released=0 pointer=1,2 drag=3\n"
      "end 1 0000000000000002\n";
  const Recording rec = parse_recording(v1, "v1.rec");
  ASSERT_EQ(rec.inputs.size(), 1u);
  EXPECT_EQ(rec.inputs[0].drag_body, detail::defined_entity(3));
  // Per-body words belong to version 2 only.
  std::string extra = v1;
  extra.replace(extra.find("drag=3"), 6, "drag=3 impulse=1:1,0,1");
  EXPECT_THROW((void)parse_recording(extra, "v1.rec"), RecordingError);
  std::string v2 = extra;
  v2.replace(v2.find("recording 1"), 11, "recording 2");
  v2.replace(v2.find("drag=3"), 6, "drag=4:1");
  const Recording rec2 = parse_recording(v2, "v2.rec");
  ASSERT_EQ(rec2.inputs[0].bodies.size(), 1u);
  EXPECT_EQ(rec2.inputs[0].bodies[0], (BodyInput{{1, 1}, BodyInputKind::impulse, {0, 1}}));
  EXPECT_EQ(rec2.inputs[0].drag_body, (Entity{4, 1}));
  for (const char* bad :
       {"impulse=0:1,0,1", "impulse=1:1,0", "kick=1:1,0,1", "impulse=1:1,0,inf"}) {
    std::string b = v2;
    b.replace(b.find("impulse=1:1,0,1"), 15, bad);
    EXPECT_THROW((void)parse_recording(b, "v2.rec"), RecordingError) << bad;
  }
}

}  // namespace
}  // namespace fixstep
