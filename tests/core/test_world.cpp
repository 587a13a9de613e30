// The entity/component world: handles, components, force terms only where declared.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_stability.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

BodyDef at(double x, double y) {
  BodyDef d;
  d.body.position = {x, y};
  return d;
}

TEST(Entity, ZeroIsNullAndHandlesAreGenerational) {
  EXPECT_TRUE(Entity{}.is_null());
  detail::WorldKernel<double> w(WorldSettings{});
  const Entity a = w.create_body(at(1, 0));
  EXPECT_FALSE(a.is_null());
  EXPECT_TRUE(w.contains(a));
  EXPECT_FALSE(w.contains(Entity{}));
  w.destroy(a);
  EXPECT_FALSE(w.contains(a));
  const Entity b = w.create_body(at(2, 0));  // reuses the slot with a new generation
  EXPECT_EQ(b.slot(), a.slot());
  EXPECT_NE(b.generation, a.generation);
  EXPECT_FALSE(w.contains(a));
  EXPECT_THROW(w.destroy(a), std::invalid_argument);
  EXPECT_THROW((void)w.body(Entity{}), std::invalid_argument);
  EXPECT_EQ(w.body(b).position.x, 2.0);
}

TEST(WorldDef, AddBodyGivesTheHandlesTheWorldGivesAndLinksUseThem) {
  WorldDef def;
  BodyDef b;
  b.name = "a";
  const Entity a = def.add_body(b);
  b.name = "b";
  b.body.position = {1.0, 0.0};
  const Entity c = def.add_body(b);
  def.add_link(a, c, {.stiffness = 3.0, .rest_length = 1.0});
  const World w(def);
  ASSERT_EQ(w.defined_bodies().size(), 2u);
  EXPECT_EQ(w.defined_bodies()[0], a);
  EXPECT_EQ(w.defined_bodies()[1], c);
  EXPECT_EQ(w.name(a), "a");
  EXPECT_EQ(w.name(c), "b");
  ASSERT_EQ(w.link_count(), 1u);
  std::uint32_t ea = 9, eb = 9;
  w.link_ends(std::span(&ea, 1), std::span(&eb, 1));
  EXPECT_EQ(ea, 0u);
  EXPECT_EQ(eb, 1u);
  // A handle the definition did not give (a later generation, a slot past its bodies) is
  // refused, naming the link.
  WorldDef bad = def;
  bad.links[0].body_b = Entity{2, 2};
  try {
    (void)World(bad);
    FAIL() << "a stale handle was linked";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("link[0]: body 2:2 is not one of the definition's 2"),
              std::string::npos)
        << e.what();
  }
  bad.links[0].body_b = Entity{3, 1};
  EXPECT_THROW((void)World(bad), std::invalid_argument);
}

TEST(World, InterpolatedPositionsLieBetweenTheLastTwoTicks) {
  World w(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.5}));
  BodyDef b;
  b.body.velocity = {2.0, -4.0};  // m/s: 1 m and -2 m a tick, no forces
  (void)w.create_body(b);
  w.set_keep_previous(true);
  w.step();
  float x = 0, y = 0;
  w.interpolate_positions(0.25, std::span(&x, 1), std::span(&y, 1));
  EXPECT_FLOAT_EQ(x, 0.25f);
  EXPECT_FLOAT_EQ(y, -0.5f);
  std::vector<float> wrong(2);
  EXPECT_THROW(w.interpolate_positions(0.0, wrong, wrong), std::invalid_argument);
}

TEST(World, DestroyKeepsOtherBodiesAndTheirComponents) {
  detail::WorldKernel<double> w(WorldSettings{.dt = 0.01});
  BodyDef s = at(5, 0);
  s.name = "spring";
  s.spring = SpringDamper{.anchor = {}, .stiffness = 4.0};
  const Entity a = w.create_body(at(0, 0));
  const Entity b = w.create_body(s);
  w.destroy(a);  // b moves to dense index 0; its spring must follow
  ASSERT_EQ(w.body_count(), 1u);
  EXPECT_EQ(w.name(0), "spring");
  std::vector<double> ax(1), ay(1);
  w.accelerations(std::span(ax), std::span(ay));
  EXPECT_DOUBLE_EQ(ax[0], -4.0 * 5.0);  // F = -k x on the surviving body
  ASSERT_NE(w.get<SpringDamper>(b), nullptr);
  w.remove<SpringDamper>(b);
  EXPECT_EQ(w.get<SpringDamper>(b), nullptr);
  w.accelerations(std::span(ax), std::span(ay));
  EXPECT_EQ(ax[0], 0.0);
}

TEST(World, AccelerationsSumEveryDeclaredTerm) {
  detail::WorldKernel<double> w(WorldSettings{});
  BodyDef d = at(2, 3);
  d.body.mass = 2.0;
  d.body.velocity = {1, -1};
  d.spring = SpringDamper{.anchor = {1, 1}, .stiffness = 3.0, .damping = 0.5};
  d.constant_force = ConstantForce{{4, 6}};
  d.drag = LinearDrag{0.25};
  d.gravity = Gravity{{0, -9.81}};
  w.create_body(d);
  std::vector<double> ax(1), ay(1);
  w.accelerations(std::span(ax), std::span(ay), TickInput{.tick = 0, .push = {0.5, 0}});
  // F = -k(x - anchor) - b v + F_c - c v;  a = F/m + g + push
  EXPECT_DOUBLE_EQ(ax[0], (-3.0 * 1 - 0.5 * 1 + 4 - 0.25 * 1) / 2 + 0.5);
  EXPECT_DOUBLE_EQ(ay[0], (-3.0 * 2 + 0.5 * 1 + 6 + 0.25 * 1) / 2 - 9.81);
}

TEST(World, RestLengthSpringPullsAlongTheSpring) {
  detail::WorldKernel<double> w(WorldSettings{});
  BodyDef d = at(0, 5);
  d.spring = SpringDamper{.anchor = {}, .stiffness = 2.0, .damping = 0, .rest_length = 3.0};
  w.create_body(d);
  std::vector<double> ax(1), ay(1);
  w.accelerations(std::span(ax), std::span(ay));
  EXPECT_DOUBLE_EQ(ax[0], 0.0);
  EXPECT_DOUBLE_EQ(ay[0], -2.0 * (5.0 - 3.0));  // stretched by 2 m towards the anchor
}

TEST(World, OnlyDeclaredForceTermsRun) {
  // A projectile scene declares no spring: the spring term must not exist.
  const Scene projectile = load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/projectile.toml");
  World sim = World(projectile.def);
  const unsigned terms = sim.active_terms();
  EXPECT_EQ(terms & term_spring, 0u);
  EXPECT_NE(terms & term_gravity, 0u);
  EXPECT_NE(terms & term_drag, 0u);

  detail::WorldKernel<double> w(WorldSettings{});
  EXPECT_EQ(w.active_terms(), 0u);
  BodyDef d = at(1, 0);
  d.spring = SpringDamper{.anchor = {}, .stiffness = 1.0};
  const Entity e = w.create_body(d);
  EXPECT_EQ(w.active_terms(), unsigned(term_spring));
  w.remove<SpringDamper>(e);
  EXPECT_EQ(w.active_terms(), 0u);
}

TEST(World, RejectsInvalidValuesNamingBodyAndField) {
  detail::WorldKernel<float> w(WorldSettings{});
  BodyDef d = at(0, 0);
  d.name = "bob";
  d.body.mass = 0.0;
  try {
    w.create_body(d);
    FAIL() << "mass 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("body 'bob': mass"), std::string::npos) << e.what();
  }
  d.body.mass = 1.0;
  d.body.position = {1e39, 0.0};  // finite double, infinite float
  EXPECT_THROW(w.create_body(d), std::invalid_argument);
  d.body.position = {std::nan(""), 0.0};
  EXPECT_THROW(w.create_body(d), std::invalid_argument);
  d.body.position = {};
  d.spring = SpringDamper{.anchor = {}, .stiffness = -1.0};
  EXPECT_THROW(w.create_body(d), std::invalid_argument);
  EXPECT_EQ(w.body_count(), 0u);  // nothing half-created
  EXPECT_THROW(detail::WorldKernel<double>(WorldSettings{.dt = 0.0}), std::invalid_argument);
  EXPECT_THROW(
      detail::WorldKernel<double>(WorldSettings{.dt = std::numeric_limits<double>::infinity()}),
      std::invalid_argument);
}

TEST(World, StateHashSeesEveryBit) {
  detail::WorldKernel<double> a(WorldSettings{}), b(WorldSettings{});
  a.create_body(at(1, 2));
  b.create_body(at(1, 2));
  EXPECT_EQ(a.state_hash(), b.state_hash());
  detail::WorldKernel<double> c(WorldSettings{});
  c.create_body(at(std::nextafter(1.0, 2.0), 2));  // one ulp apart
  EXPECT_NE(a.state_hash(), c.state_hash());
}

TEST(World, KeepPreviousStoresTheLastTick) {
  detail::WorldKernel<double> w(WorldSettings{.dt = 0.5});
  BodyDef d = at(0, 0);
  d.body.velocity = {2, 0};
  w.create_body(d);
  w.set_keep_previous(true);
  w.step();
  w.step();
  EXPECT_DOUBLE_EQ(w.previous_x()[0], 1.0);
  EXPECT_DOUBLE_EQ(w.x()[0], 2.0);
}

// --- the runtime guard (World::fault) ------------------------------------------------------

/// Semi-implicit Euler on x'' = -ω² x with ω·h = 3 (beyond its bound 2): |state| grows by the
/// spectral radius ((ω h)² - 2 + ω h √((ω h)² - 4)) / 2 = 6.854 per tick.
template <class Real>
void expect_guard_names_first_tick_out_of_range() {
  detail::WorldKernel<Real> w(WorldSettings{.dt = 0.1});
  BodyDef calm = at(1, 0);
  calm.name = "calm";
  calm.spring = SpringDamper{.stiffness = 1.0};
  BodyDef stiff = at(1, 0);
  stiff.name = "stiff";
  stiff.spring = SpringDamper{.stiffness = 900.0};  // ω = 30 rad/s
  w.create_body(calm);
  w.create_body(stiff);
  // Independent reference: the same recurrence in double, and the first tick whose x or v
  // exceeds max_state_magnitude.
  double x = 1, v = 0;
  std::uint64_t expected_tick = 0;
  std::string expected_field;
  for (std::uint64_t t = 1; expected_tick == 0; ++t) {
    v += -900.0 * x * 0.1;
    x += v * 0.1;
    if (std::abs(x) > max_state_magnitude)
      expected_tick = t, expected_field = "x";
    else if (std::abs(v) > max_state_magnitude)
      expected_tick = t, expected_field = "vx";
  }
  for (std::uint64_t t = 1; t < expected_tick; ++t) {
    w.step();
    ASSERT_FALSE(w.fault().has_value()) << "tick " << t;
  }
  w.step();
  ASSERT_TRUE(w.fault().has_value());
  const StateFault& f = *w.fault();
  EXPECT_EQ(f.body, fixstep::defined_entity(1));
  EXPECT_EQ(f.name, "stiff");
  EXPECT_EQ(f.tick, expected_tick);
  EXPECT_DOUBLE_EQ(f.time, 0.1 * double(expected_tick));
  EXPECT_EQ(f.field, expected_field);
  EXPECT_GT(std::abs(f.value), max_state_magnitude);
  // The first fault is kept while stepping goes on.
  w.step();
  EXPECT_EQ(w.fault()->tick, expected_tick);
}

TEST(Guard, NamesTheBodyFieldAndFirstTickOutOfRangeF64) {
  expect_guard_names_first_tick_out_of_range<double>();
}
TEST(Guard, NamesTheBodyFieldAndFirstTickOutOfRangeF32) {
  expect_guard_names_first_tick_out_of_range<float>();
}

TEST(Guard, CatchesAHugeStartAndStaysQuietOnLongBoundedRuns) {
  detail::WorldKernel<double> w(WorldSettings{.dt = 0.01});
  // A start beyond the range is refused at creation (value_ranges.hpp); one at its edge that
  // moves out is caught on the tick it leaves.
  EXPECT_THROW(w.create_body(at(2e12, 0)), std::invalid_argument);
  BodyDef far = at(max_state_magnitude, 0);
  far.body.velocity = {max_state_magnitude, 0.0};
  far.name = "far";
  BodyDef near = at(max_state_magnitude * 0.5, 0);
  near.body.velocity = {1.0, 0.0};
  w.create_body(near);
  w.create_body(far);
  w.step();
  ASSERT_TRUE(w.fault().has_value());
  EXPECT_EQ(w.fault()->name, "far");
  EXPECT_EQ(w.fault()->field, "x");
  EXPECT_EQ(w.fault()->tick, 1u);

  detail::WorldKernel<double> bounded(WorldSettings{.dt = 1.0 / 60.0});
  BodyDef spring = at(1000, 0);  // the article's spring, x0 = 1000 m
  spring.spring = SpringDamper{.stiffness = 15.0, .damping = 0.1};
  bounded.create_body(spring);
  for (int t = 0; t < 100000; ++t) bounded.step();
  EXPECT_FALSE(bounded.fault().has_value());
}

TEST(Guard, ExplainsTheCauseWithTheStabilityBound) {
  Scene scene = parse_scene(R"(
[world]
dt = 0.1
allow_unstable = true
[[body]]
name = "stiff"
mass = 1.0
position = [1.0, 0.0]
spring = { anchor = [0.0, 0.0], stiffness = 900.0 }
[[body]]
name = "thrown"
mass = 1.0
position = [0.0, 0.0]
gravity = [0.0, -9.81]
)",
                            "blow.toml");
  StateFault f{.body = fixstep::defined_entity(0),
               .name = "stiff",
               .tick = 14,
               .time = 1.4,
               .field = "vx",
               .value = 7e12,
               .cap = {},
               .with = {}};
  const std::string m = explain_fault(scene, f);
  EXPECT_NE(m.find("blow.toml:5: body[0] \"stiff\""), std::string::npos) << m;
  EXPECT_NE(m.find("at tick 14"), std::string::npos) << m;
  EXPECT_NE(m.find("vx = 7e+12 m/s"), std::string::npos) << m;
  EXPECT_NE(m.find("Likely cause"), std::string::npos) << m;
  EXPECT_NE(m.find("ω·h = 3 exceeds the stability bound 2"), std::string::npos) << m;
  EXPECT_NE(m.find("substeps = 2"), std::string::npos) << m;
  f.body = fixstep::defined_entity(1), f.name = "thrown", f.field = "y";
  const std::string g = explain_fault(scene, f);
  EXPECT_NE(g.find("within semi_implicit_euler's stability bound"), std::string::npos) << g;
  EXPECT_NE(g.find("gravity"), std::string::npos) << g;
}

// A kinematic body has no spring or force to blame: the guard names its velocity.
TEST(World, RuntimeGuardOfAKinematicBodyNamesItsVelocityNotSprings) {
  const Scene scene = parse_scene(R"([world]
dt = 1
[[body]]
name = "paddle"
type = "kinematic"
position = [9e11, 0.0]
velocity = [1e12, 0.0]
)",
                                  "fast.toml");
  World sim = World(scene.def);
  sim.step();
  ASSERT_TRUE(sim.fault().has_value());
  const std::string m = explain_fault(scene, *sim.fault());
  EXPECT_NE(m.find("fast.toml:3: body[0] \"paddle\""), std::string::npos) << m;
  EXPECT_NE(m.find("the body is kinematic"), std::string::npos) << m;
  EXPECT_NE(m.find("1e+12, 0 m/s"), std::string::npos) << m;
  EXPECT_EQ(m.find("spring"), std::string::npos) << m;
}

}  // namespace
}  // namespace fixstep
