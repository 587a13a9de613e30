// The ranges World(def) takes (value_ranges.hpp), boundary by boundary, and the runtime guard
// over every part of the state: a disc's angular velocity beyond max_state_magnitude stops the
// world with a StateFault naming the body and the field, as x and v do.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/value_ranges.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {
namespace {

/// A rolling world with one dynamic disc (m = 1 kg, r = 0.5 m) changed by `edit`.
WorldDef one_disc(const std::function<void(WorldDef&, BodyDef&)>& edit) {
  WorldDef def;
  def.allow_unstable = true;  // the ranges, not the integrator's stability, are checked
  def.settings.contacts = ContactSettings{.friction = 0.5, .rolling = true};
  BodyDef b;
  b.name = "disc";
  b.body = Body{.mass = 1.0, .position = {0.0, 0.5}, .velocity = {}};
  b.collider = Collider{.radius = 0.5};
  edit(def, b);
  def.add_body(b);
  return def;
}

/// "" when World(def) accepts the edited disc, else its message.
std::string refusal(const std::function<void(WorldDef&, BodyDef&)>& edit) {
  try {
    (void)World(one_disc(edit));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

struct Boundary {
  const char* field;  ///< named in the refusal
  std::function<void(BodyDef&, double)> set;
  double edge;    ///< accepted
  double beyond;  ///< refused
};

TEST(ValueRanges, WorldTakesEachBoundaryAndRefusesTheValueBeyondNamingTheField) {
  const double m = max_state_magnitude, c = max_coefficient, tiny = min_coefficient;
  const double above_state = std::nextafter(m, 2 * m), above_coef = std::nextafter(c, 2 * c);
  const double below_tiny = std::nextafter(tiny, 0.0);
  const Boundary cases[] = {
      {"mass", [](BodyDef& b, double v) { b.body.mass = v; }, tiny, below_tiny},
      {"mass", [](BodyDef& b, double v) { b.body.mass = v; }, c, above_coef},
      {"mass", [](BodyDef& b, double v) { b.body.mass = v; }, 1.0, 5e-324},
      {"position", [](BodyDef& b, double v) { b.body.position.x = v; }, -m, -above_state},
      {"velocity", [](BodyDef& b, double v) { b.body.velocity.y = v; }, m, above_state},
      {"angle", [](BodyDef& b, double v) { b.body.angle = v; }, m, above_state},
      {"angular_velocity", [](BodyDef& b, double v) { b.body.angular_velocity = v; }, -m, -1e308},
      {"collider.inertia", [](BodyDef& b, double v) { b.collider->inertia = v; }, tiny, 5e-324},
      {"collider.inertia", [](BodyDef& b, double v) { b.collider->inertia = v; }, c, above_coef},
      {"collider.radius", [](BodyDef& b, double v) { b.collider->radius = v; }, tiny, 5e-324},
      {"collider.friction", [](BodyDef& b, double v) { b.collider->friction = v; }, c, 1e300},
      {"collider.restitution", [](BodyDef& b, double v) { b.collider->restitution = v; }, 1.0, 1.5},
      {"force",
       [](BodyDef& b, double v) {
         b.constant_force = ConstantForce{{v, 0.0}};
       },
       -c, -above_coef},
      {"gravity",
       [](BodyDef& b, double v) {
         b.gravity = Gravity{{0.0, v}};
       },
       c, above_coef},
      {"drag", [](BodyDef& b, double v) { b.drag = LinearDrag{v}; }, c, above_coef},
      {"spring.stiffness", [](BodyDef& b, double v) { b.spring = SpringDamper{.stiffness = v}; }, c,
       above_coef},
      {"spring.damping", [](BodyDef& b, double v) { b.spring = SpringDamper{.damping = v}; }, c,
       above_coef},
      {"spring.anchor",
       [](BodyDef& b, double v) {
         b.spring = SpringDamper{.anchor = {0.0, v}};
       },
       m, above_state},
      {"spring.rest_length",
       [](BodyDef& b, double v) { b.spring = SpringDamper{.rest_length = v}; }, m, above_state},
  };
  for (const Boundary& b : cases) {
    SCOPED_TRACE(b.field);
    EXPECT_EQ(refusal([&](WorldDef&, BodyDef& d) { b.set(d, b.edge); }), "");
    const std::string e = refusal([&](WorldDef&, BodyDef& d) { b.set(d, b.beyond); });
    EXPECT_NE(e.find(std::string("body 'disc': ") + b.field + " must be"), std::string::npos) << e;
  }
  // The contact settings and planes take the same coefficient range.
  EXPECT_NE(refusal([](WorldDef& d, BodyDef&) {
              d.settings.contacts->friction = 1e300;
            }).find("contacts.friction must be in [0, 1e100]"),
            std::string::npos);
  EXPECT_NE(refusal([](WorldDef& d, BodyDef&) {
              d.settings.contacts->restitution = 2.0;
            }).find("contacts.restitution must be in [0, 1]"),
            std::string::npos);
  EXPECT_NE(refusal([](WorldDef& d, BodyDef&) {
              d.planes.push_back(PlaneDef{.offset = -2e12});
            }).find("plane[0]: offset must be"),
            std::string::npos);
}

// A legal disc of radius 1 µm striking a rough floor at 10^7 m/s, as fast along it: the impact's
// friction (μ (1 + e) |v_n| >= the slip) brings it to rolling, ω = ⅔ v / r ~ 7·10^12 rad/s,
// beyond the range. The guard stops it there naming the disc
// and angular_velocity (before it looked at x, y, vx and vy only, and the run went on).
TEST(ValueRanges, TheGuardSeesAnAngularVelocityBeyondTheRange) {
  const double r = 1e-6;
  WorldDef def = one_disc([&](WorldDef& d, BodyDef& b) {
    b.body.position = {0.0, r};
    b.body.velocity = {1e7, -1e7};
    b.collider->radius = r;
    b.gravity = Gravity{{0.0, -9.81}};
    d.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 1.0});
  });
  def.settings.track_dissipation = true;
  World world(def);
  for (int i = 0; i < 10 && !world.fault(); ++i) world.step();
  ASSERT_TRUE(world.fault().has_value()) << "the disc spins beyond 1e12 rad/s unseen";
  const StateFault& f = *world.fault();
  EXPECT_EQ(f.name, "disc");
  EXPECT_EQ(f.field, "angular_velocity");
  EXPECT_GT(std::abs(f.value), max_state_magnitude);
  EXPECT_TRUE(std::isfinite(f.value));
  const std::string why = explain_fault(def.bodies, def.links, def.settings, f);
  EXPECT_NE(why.find("body[0] \"disc\": state left the finite range at tick 1"), std::string::npos)
      << why;
  EXPECT_NE(why.find("angular_velocity = "), std::string::npos) << why;
  EXPECT_NE(why.find(" rad/s ("), std::string::npos) << why;
  EXPECT_NE(why.find("moment of inertia"), std::string::npos) << why;
}

// A box (1 kg, 1 m, I = 1/6 kg*m^2) given an angular impulse of 1e12 N*m*s turns at 6e12 rad/s,
// beyond the range: the guard stops the world there naming the body and angular_velocity, and
// the explanation speaks of its moment of inertia (it looked at x, y, vx and vy only).
TEST(ValueRanges, TheGuardSeesAShapedBodysAngularVelocityBeyondTheRange) {
  WorldDef def = WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.01});
  BodyDef b;
  b.name = "crate";
  b.body.mass = 1.0;
  b.shapes = {make_box(0.5, 0.5)};
  def.add_body(b);
  World world(def);
  TickInput in;
  in.bodies.push_back(BodyInput{.body = world.defined_bodies()[0],
                                .kind = BodyInputKind::angular_impulse,
                                .value = {1e12, 0.0}});
  world.step(in);
  ASSERT_TRUE(world.fault().has_value()) << "the box spins beyond 1e12 rad/s unseen";
  const StateFault& f = *world.fault();
  EXPECT_EQ(f.name, "crate");
  EXPECT_EQ(f.field, "angular_velocity");
  EXPECT_NEAR(f.value, 6e12, 1.0);
  const std::string why = explain_fault(def.bodies, def.links, def.settings, f);
  EXPECT_NE(why.find("body[0] \"crate\": state left the finite range at tick 1"), std::string::npos)
      << why;
  EXPECT_NE(why.find("moment of inertia 0.166667 kg*m^2 (from its shapes"), std::string::npos)
      << why;
}

}  // namespace
}  // namespace fixstep
