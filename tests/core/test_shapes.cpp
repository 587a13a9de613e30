// Bodies with shapes in a world: exact checks against closed forms (the incline, the tipping
// box, free spin, the weight on a box's two corners), stacks that stand, a fast spinning box
// that meets a thin wall, and the same bits after a snapshot and on two threads.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

constexpr double g = 9.81;

WorldSettings shape_world(double mu, double e = 0.0) {
  WorldSettings s{.dt = 1.0 / 60.0};
  s.contacts = ContactSettings{.restitution = e, .friction = mu};
  return s;
}

BodyDef box_body(double hx, double hy, Vec2 at, double angle = 0.0, double mass = 1.0) {
  BodyDef b;
  b.body = Body{.mass = mass, .position = at, .angle = angle};
  b.gravity = Gravity{{0.0, -g}};
  b.shapes = {make_box(hx, hy)};
  return b;
}

// --- the incline: a = g (sin θ − μ cos θ) when tan θ > μ, still when tan θ < μ --------------

struct Slide {
  double along = 0.0;   ///< m moved down the slope
  double across = 0.0;  ///< m moved off the plane's line
  double angle = 0.0;   ///< rad turned
};

Slide slide(double theta, double mu, int ticks) {
  detail::WorldKernel<double> w(shape_world(mu));
  const Vec2 n{-std::sin(theta), std::cos(theta)};
  w.add_plane(PlaneDef{.normal = n, .offset = 0.0, .restitution = 0.0, .friction = mu});
  const double hy = 0.25;
  const Entity box = w.create_body(box_body(0.5, hy, hy * n, theta, 2.0));
  w.step();  // settles onto the plane
  const Body b0 = w.body(box);
  for (int i = 1; i < ticks; ++i) w.step();
  const Body b1 = w.body(box);
  const Vec2 d = b1.position - b0.position;
  const Vec2 down{-std::cos(theta), -std::sin(theta)};
  return {dot(d, down), dot(d, n), b1.angle - b0.angle};
}

TEST(ShapeIncline, ABoxSlidesAtGTimesSinMinusMuCos) {
  const double theta = 0.5, mu = 0.2, dt = 1.0 / 60.0;
  const int ticks = 121;
  const Slide s = slide(theta, mu, ticks);
  // From rest after the first tick: semi-implicit Euler's x_n = a dt² n(n+1)/2 over the n
  // ticks after it, with v1 = a dt already gained in the first.
  const double a = g * (std::sin(theta) - mu * std::cos(theta));
  const int n = ticks - 1;
  const double exact = a * dt * dt * (n * (n + 1) / 2.0 + n);
  EXPECT_NEAR(s.along, exact, 1e-3 * exact);
  EXPECT_NEAR(s.across, 0.0, 1e-6);
  EXPECT_NEAR(s.angle, 0.0, 1e-6);
}

TEST(ShapeIncline, ABoxStaysPutWhenTanThetaIsBelowMu) {
  const Slide s = slide(0.3, 0.5, 121);  // tan 0.3 = 0.31 < 0.5; 2 s
  EXPECT_LT(std::abs(s.along), 1e-6);
  EXPECT_LT(std::abs(s.across), 1e-6);
  EXPECT_LT(std::abs(s.angle), 1e-6);
}

// --- the tipping box: back upright below atan(w/h), over above it ----------------------------

/// A box w × h (m) stood on its lower-left corner at the origin, turned by φ (rad) clockwise
/// from upright... counter-clockwise here: its corner at the origin and its centre at
/// R(φ)(w/2, h/2). Returns its angle after 3 s.
double tip(double phi) {
  detail::WorldKernel<double> w(shape_world(1.0));
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.0, .friction = 1.0});
  const double hx = 0.2, hy = 0.5;
  const Vec2 c{std::cos(phi) * hx - std::sin(phi) * hy, std::sin(phi) * hx + std::cos(phi) * hy};
  const Entity box = w.create_body(box_body(hx, hy, c, phi));
  for (int i = 0; i < 180; ++i) w.step();
  return w.body(box).angle;
}

TEST(ShapeTipping, ABoxOnItsCornerTipsBackBelowTheCriticalAngleAndOverAboveIt) {
  const double critical = std::atan(0.4 / 1.0);  // atan(w/h)
  EXPECT_NEAR(tip(critical - 0.01), 0.0, 0.02);
  EXPECT_NEAR(tip(critical + 0.01), std::numbers::pi / 2, 0.02);
}

// --- free spin ---------------------------------------------------------------------------

TEST(ShapeSpin, ABoxSpinningFreelyKeepsItsAngularVelocityAndEnergy) {
  detail::WorldKernel<double> w(shape_world(0.0));
  BodyDef b = box_body(0.5, 0.2, {1.0, 2.0}, 0.3, 3.0);
  b.gravity.reset();
  b.body.angular_velocity = 7.0;
  b.body.velocity = {0.5, -0.25};
  const Entity box = w.create_body(b);
  const double e0 = w.energy().total();
  for (int i = 0; i < 600; ++i) w.step();
  const Body after = w.body(box);
  EXPECT_EQ(after.angular_velocity, 7.0);
  EXPECT_NEAR(w.energy().total(), e0, 1e-12 * e0);
  // θ = 0.3 + 600 dt ω, wrapped to [-π, π].
  EXPECT_NEAR(std::remainder(after.angle - (0.3 + 70.0), 2 * std::numbers::pi), 0.0, 1e-9);
  // I = m (w² + h²) / 12 for a box of 1.0 m × 0.4 m.
  EXPECT_NEAR(w.energy().kinetic,
              0.5 * 3.0 * (0.25 + 0.0625) + 0.5 * 3.0 * (1.0 + 0.16) / 12.0 * 49.0, 1e-12);
}

// --- an elastic frictionless gas of boxes and discs ---------------------------------------

struct GasTotals {
  double energy = 0.0, px = 0.0, py = 0.0, spin = 0.0;  ///< J, kg·m/s, kg·m/s, kg·m²/s
};

// 32 boxes (0.6 m × 0.4 m, turning) and 32 discs (r = 0.25 m) on an 8 × 8 grid 0.9 m apart, in
// random motion without gravity or walls. With e = 1, μ = 0 and no threshold every contact is
// a frictionless impulse that gives its point the opposite normal velocity at one point of
// both bodies: kinetic energy, momentum and angular momentum (about the origin) are unchanged
// by it in exact arithmetic.
TEST(ShapeGas, AnElasticFrictionlessGasKeepsMomentumAngularMomentumAndEnergy) {
  WorldSettings settings{.dt = 1.0 / 120.0};
  settings.contacts = ContactSettings{.restitution = 1.0, .friction = 0.0};
  settings.contacts->restitution_threshold = 0.0;
  detail::WorldKernel<double> w(settings);
  std::vector<Entity> bodies;
  std::vector<double> inertia;
  std::uint64_t seed = 7;
  auto uniform = [&seed] {  // in [-1, 1): a fixed sequence (splitmix64), the same everywhere
    seed += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = seed;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL, z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-52 - 1.0;
  };
  for (int i = 0; i < 64; ++i) {
    BodyDef b;
    b.body = Body{.mass = 1.0 + 0.1 * i,
                  .position = {0.9 * (i % 8), 0.9 * (i / 8)},
                  .velocity = {3.0 * uniform(), 3.0 * uniform()},
                  .angle = uniform()};
    if (i % 2 == 1) {
      b.shapes = {make_box(0.3, 0.2)};
      b.body.angular_velocity = 5.0 * uniform();
      inertia.push_back(b.body.mass * (0.36 + 0.16) / 12.0);  // m (w² + h²) / 12
    } else {
      b.collider = Collider{.radius = 0.25};
      inertia.push_back(0.0);  // discs do not turn (rolling off)
    }
    bodies.push_back(w.create_body(b));
  }
  auto totals = [&] {
    GasTotals t{.energy = w.energy().total()};
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const Body b = w.body(bodies[i]);
      t.px += b.mass * b.velocity.x, t.py += b.mass * b.velocity.y;
      t.spin += b.mass * cross(b.position, b.velocity) + inertia[i] * b.angular_velocity;
    }
    return t;
  };
  const GasTotals before = totals();
  std::size_t bounces = 0, disc_impacts = 0;
  double deepest = 0.0;
  for (int tick = 0; tick < 1200; ++tick) {
    const double e = w.energy().kinetic;
    w.step();
    const ContactStats& c = w.contact_stats();
    disc_impacts += c.impacts;
    deepest = std::max({deepest, c.deepest_shape_overlap, c.max_overlap});
    // A box's bounce changes its energy by rounding only, so count a tick of shape points with
    // a changed velocity of some box.
    if (c.shape_points > 0 && e != w.energy().kinetic) ++bounces;
  }
  const GasTotals after = totals();
  EXPECT_GT(bounces, 20u);
  EXPECT_GT(disc_impacts, 5u);
  // Rounding: about 1e-16 of each total per impulse over some hundred impulses.
  EXPECT_NEAR(after.energy, before.energy, 1e-12 * before.energy);
  const double p = std::hypot(before.px, before.py);
  EXPECT_NEAR(after.px, before.px, 1e-12 * p);
  EXPECT_NEAR(after.py, before.py, 1e-12 * p);
  EXPECT_NEAR(after.spin, before.spin, 1e-12 * std::abs(before.spin));
  EXPECT_LE(deepest, 0.0);  // speculative contacts: they bounce before they meet
}

// --- rolling resistance -----------------------------------------------------------------

// A uniform disc (a circle shape, I = ½ m r²) rolling without slipping on flat ground with
// rolling resistance c: the torque c r N against its turning and friction F at the ground give
// m a = −F, I α = F r − c r N with a = α r, so a = −c g m r² / (I + m r²) = −(2/3) c g, until it
// stops, and then it stays put.
TEST(ShapeRolling, AUniformDiscSlowsAtTwoThirdsCGAndStops) {
  detail::WorldKernel<double> w(shape_world(0.8));
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.0, .friction = 0.8});
  const double r = 0.3, c = 0.05, v0 = 2.0;
  BodyDef b;
  b.body =
      Body{.mass = 2.0, .position = {0.0, r}, .velocity = {v0, 0.0}, .angular_velocity = -v0 / r};
  b.gravity = Gravity{{0.0, -g}};
  b.shapes = {make_circle(r)};
  b.shapes[0].rolling_resistance = c;
  const Entity disc = w.create_body(b);
  for (int i = 0; i < 60; ++i) w.step();  // 1 s
  const double a = 2.0 / 3.0 * c * g;
  EXPECT_NEAR(w.body(disc).velocity.x, v0 - a * 1.0, 1e-3 * v0);
  EXPECT_NEAR(w.body(disc).angular_velocity * r, -w.body(disc).velocity.x, 1e-6);  // rolls
  for (int i = 0; i < 600; ++i) w.step();  // it stops after v0 / a = 6.1 s
  EXPECT_NEAR(w.body(disc).velocity.x, 0.0, 1e-9);
  EXPECT_NEAR(w.body(disc).angular_velocity, 0.0, 1e-9);
  // the distance rolled: v0² / (2a), within a tick's travel
  EXPECT_NEAR(w.body(disc).position.x, v0 * v0 / (2.0 * a), v0 / 60.0);
}

// --- a box dropped flat rests flat, half its weight on each corner -----------------------

TEST(ShapeRest, ABoxDroppedFlatRestsOnBothCornersWithHalfItsWeightEach) {
  detail::WorldKernel<double> w(shape_world(0.5));
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.0, .friction = 0.5});
  const Entity box = w.create_body(box_body(0.5, 0.25, {0.0, 0.5}, 0.0, 2.0));
  for (int i = 0; i < 120; ++i) w.step();
  const detail::ShapeWorld* sw = w.shape_world();
  ASSERT_NE(sw, nullptr);
  ASSERT_EQ(sw->rows().size(), 2u);
  const double weight_impulse = 2.0 * g * w.settings().dt;
  for (const detail::ShapeRow& r : sw->rows())
    EXPECT_NEAR(r.ln, 0.5 * weight_impulse, 0.01 * 0.5 * weight_impulse);
  EXPECT_NEAR(w.body(box).angle, 0.0, 1e-9);
  EXPECT_NEAR(w.body(box).position.y, 0.25, 0.006);  // within the slop
}

// --- stacks --------------------------------------------------------------------------------

TEST(ShapeStack, ATowerOfTwentyBoxesStandsStillForTenSeconds) {
  detail::WorldKernel<double> w(shape_world(0.6));
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.0, .friction = 0.6});
  const double h = 0.5;
  Entity top;
  for (int i = 0; i < 20; ++i) top = w.create_body(box_body(h, h, {0.0, h + 2 * h * i}));
  for (int i = 0; i < 60; ++i) w.step();
  const Body b0 = w.body(top);
  for (int i = 0; i < 600; ++i) w.step();
  const Body b1 = w.body(top);
  EXPECT_LT(std::hypot(b1.position.x - b0.position.x, b1.position.y - b0.position.y), 0.01 * 2 * h);
  EXPECT_LT(w.contact_stats().deepest_shape_overlap, 0.01);
}

TEST(ShapeStack, ATwentyRowPyramidStandsStillForTenSeconds) {
  detail::WorldKernel<double> w(shape_world(0.6));
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.0, .friction = 0.6});
  const double h = 0.5;
  Entity top;
  for (int row = 0; row < 20; ++row) {
    for (int i = 0; i < 20 - row; ++i) {
      const double x = (i - (19 - row) * 0.5) * 2 * h;
      top = w.create_body(box_body(h, h, {x, h + 2 * h * row}));
    }
  }
  for (int i = 0; i < 60; ++i) w.step();
  const Body b0 = w.body(top);
  for (int i = 0; i < 600; ++i) w.step();
  const Body b1 = w.body(top);
  EXPECT_LT(std::hypot(b1.position.x - b0.position.x, b1.position.y - b0.position.y), 0.01 * 2 * h);
}

// --- a fast spinning box does not pass a thin wall ------------------------------------------

TEST(ShapeContinuous, AFastSpinningBoxDoesNotPassAOneCentimetreWall) {
  detail::WorldKernel<double> w(shape_world(0.3));
  BodyDef wall;
  wall.type = BodyType::static_body;
  wall.body.position = {10.0, 0.0};
  wall.shapes = {make_box(0.005, 5.0)};
  w.create_body(wall);
  BodyDef b = box_body(0.5, 0.25, {0.0, 0.0});
  b.gravity.reset();
  b.body.velocity = {500.0, 0.0};
  b.body.angular_velocity = 100.0;
  const Entity box = w.create_body(b);
  for (int i = 0; i < 120; ++i) {
    w.step();
    ASSERT_LT(w.body(box).position.x, 10.0) << "tick " << i;
  }
}

// --- events and sensors --------------------------------------------------------------------

TEST(ShapeEvents, ABoxLandingOnABoxBeginsAContactAndASensorSeesItPass) {
  World w(WorldDef::empty(Precision::f64, shape_world(0.5)));
  BodyDef base;
  base.type = BodyType::static_body;
  base.shapes = {make_box(2.0, 0.5)};
  const Entity floor = w.create_body(base);
  BodyDef gate;  // a sensor box the falling box passes through on its way down
  gate.type = BodyType::static_body;
  gate.body.position = {0.0, 3.0};
  gate.shapes = {make_box(1.0, 0.1)};
  gate.shapes[0].sensor = true;
  const Entity sensor = w.create_body(gate);
  const Entity box = w.create_body(box_body(0.5, 0.5, {0.0, 5.0}));
  int begun = 0, sensed_in = 0, sensed_out = 0;
  double speed = 0.0;
  for (int i = 0; i < 180; ++i) {
    w.step();
    for (const ContactEvent& e : w.contacts_begun()) {
      EXPECT_TRUE((e.a == floor && e.b == box) || (e.a == box && e.b == floor));
      ++begun, speed = e.normal_speed;
    }
    for (const SensorEvent& e : w.sensors_begun()) {
      EXPECT_EQ(e.sensor, sensor);
      EXPECT_EQ(e.visitor, box);
      ++sensed_in;
    }
    sensed_out += static_cast<int>(w.sensors_ended().size());
  }
  EXPECT_EQ(begun, 1);
  // It falls 4 m (from a centre at 5 m to its face on the floor at 0.5 m... 4 m) from rest:
  // v = √(2 g h) within a tick's gain.
  EXPECT_NEAR(speed, std::sqrt(2.0 * g * 4.0), g / 60.0 + 0.1);
  EXPECT_EQ(sensed_in, 1);
  EXPECT_EQ(sensed_out, 1);
  EXPECT_TRUE(w.contacts_ended().empty());
}

// A disc sensor sees bodies with shapes as a sensor shape sees discs: a box falling through a
// static sensor disc begins and ends one overlap, at the ticks its faces cross the disc's
// circle (it falls from rest at 5 m: its bottom face reaches the top of the disc, y = 3.25 m,
// at t = √(2 · 1.25 m / g), its top face leaves the bottom, y = 2.75 m, at √(2 · 2.75 m / g)).
TEST(ShapeEvents, ADiscSensorSeesABoxFallThroughIt) {
  World w(WorldDef::empty(Precision::f64, shape_world(0.5)));
  BodyDef ring;
  ring.type = BodyType::static_body;
  ring.body.position = {0.0, 3.0};
  ring.collider = Collider{.radius = 0.25, .sensor = true};
  const Entity sensor = w.create_body(ring);
  BodyDef falling = box_body(0.5, 0.5, {0.0, 5.0});
  const Entity box = w.create_body(falling);
  std::vector<int> in, out;
  for (int i = 1; i <= 120; ++i) {
    w.step();
    for (const SensorEvent& e : w.sensors_begun()) {
      EXPECT_EQ(e.sensor, sensor);
      EXPECT_EQ(e.visitor, box);
      in.push_back(i);
    }
    for (const SensorEvent& e : w.sensors_ended()) {
      EXPECT_EQ(e.visitor, box);
      out.push_back(i);
    }
  }
  ASSERT_EQ(in.size(), 1u);
  ASSERT_EQ(out.size(), 1u);
  // The first tick that ends with the faces past the circle: semi-implicit Euler's fall by
  // tick n is g dt² n (n + 1) / 2.
  auto first_tick_past = [](double drop) {
    const double dt = 1.0 / 60.0;
    int n = 0;
    while (g * dt * dt * n * (n + 1) / 2.0 < drop) ++n;
    return n;
  };
  EXPECT_EQ(in[0], first_tick_past(1.25));
  EXPECT_EQ(out[0], first_tick_past(2.75));
}

// --- the energy account ------------------------------------------------------------------

TEST(ShapeEnergy, TheAccountBalancesForATumblingPileAndAKinematicPaddle) {
  WorldSettings settings = shape_world(0.4, 0.3);
  settings.track_dissipation = true;
  settings.integrator = Integrator::velocity_verlet;  // exact in free fall: no drift to count
  World w(WorldDef::empty(Precision::f64, settings));
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.3, .friction = 0.4});
  for (int i = 0; i < 12; ++i) {
    BodyDef b = box_body(0.3, 0.2, {0.5 * (i % 4) - 0.75, 0.5 + 0.6 * (i / 4)}, 0.3 * i);
    if (i % 3 == 1) b.shapes = {make_capsule({-0.25, 0.0}, {0.25, 0.0}, 0.15)};
    w.create_body(b);
  }
  BodyDef paddle;  // a kinematic paddle turning through the pile: its work is external
  paddle.type = BodyType::kinematic;
  paddle.body.position = {0.0, 0.6};
  paddle.body.angular_velocity = 3.0;
  paddle.shapes = {make_box(1.5, 0.05)};
  w.create_body(paddle);
  const double e0 = w.energy().total();
  for (int i = 0; i < 240; ++i) {
    w.step();
    const double balance = w.energy().total() + w.dissipated_energy() - w.external_work() - e0;
    ASSERT_NEAR(balance, 0.0, 1e-9 * (std::abs(e0) + w.external_work())) << "tick " << i;
  }
  EXPECT_GT(w.dissipated_energy(), 0.0);
  EXPECT_GT(std::abs(w.external_work()), 0.0);
}

// --- no silent caps -----------------------------------------------------------------------

TEST(ShapeCaps, ACrowdOfOverlappingBoxesStopsWithALocatedFault) {
  World w(WorldDef::empty(Precision::f64, shape_world(0.5)));
  for (int i = 0; i < 2000; ++i) w.create_body(box_body(0.5, 0.5, {0.001 * i, 0.0}));
  w.step();
  ASSERT_TRUE(w.fault().has_value());
  EXPECT_EQ(w.fault()->cap, "max_candidate_pairs");
  EXPECT_EQ(w.fault()->field, "contacts");
  EXPECT_NE(w.fault()->with.find("2000 shapes"), std::string::npos) << w.fault()->with;
}

// --- the same bits -------------------------------------------------------------------------

WorldDef box_rain() {
  WorldDef def = WorldDef::empty(Precision::f64, shape_world(0.5, 0.2));
  def.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.5});
  for (int i = 0; i < 40; ++i) {
    BodyDef b =
        box_body(0.3 + 0.01 * (i % 5), 0.2, {0.7 * (i % 8) - 2.5, 1.0 + 0.6 * (i / 8)}, 0.1 * i);
    if (i % 3 == 0) b.shapes = {make_capsule({-0.3, 0.0}, {0.3, 0.0}, 0.15)};
    def.add_body(b);
  }
  return def;
}

TEST(ShapeDeterminism, ASnapshotStepsOnToTheSameBitsAndTwoThreadsMatchOne) {
  World a(box_rain());
  for (int i = 0; i < 60; ++i) a.step();
  WorldSnapshot snap;
  a.save(snap);
  for (int i = 0; i < 60; ++i) a.step();
  const std::uint64_t h = a.state_hash();
  a.restore(snap);
  for (int i = 0; i < 60; ++i) a.step();
  EXPECT_EQ(a.state_hash(), h);
  WorldDef two = box_rain();
  two.settings.threads = 2;
  World b(two);
  for (int i = 0; i < 120; ++i) b.step();
  EXPECT_EQ(b.state_hash(), h);
}

// In f32 a body's angle and angular velocity are floats after every tick, as its position and
// velocity are. GCC 12 on x86-64 merged the write-back's two double(static_cast<float>(x))
// stores into one vector store without the rounding (world_kernel.hpp, rounded_to), and f32
// worlds with shapes stepped to other bits than on aarch64 from their second tick.
TEST(ShapeDeterminism, AnF32WorldKeepsItsAnglesAndSpinsInFloat) {
  detail::WorldKernel<float> w(shape_world(0.5));
  BodyDef paddle = box_body(1.0, 0.1, {0.0, 3.0}, 0.3);
  paddle.type = BodyType::kinematic;
  paddle.body.angular_velocity = 2.0;
  const Entity turning = w.create_body(paddle);
  BodyDef thrown = box_body(0.3, 0.3, {-3.0, 1.0}, 0.4);
  thrown.body.angular_velocity = -6.0;
  const Entity spinning = w.create_body(thrown);
  const auto is_float = [](double v) { return double(static_cast<float>(v)) == v; };
  for (int t = 0; t < 30; ++t) {
    w.step();
    for (const Entity e : {turning, spinning}) {
      const Body b = w.body(e);
      EXPECT_TRUE(is_float(b.angle)) << "tick " << t + 1 << ": angle " << b.angle;
      EXPECT_TRUE(is_float(b.angular_velocity)) << "tick " << t + 1 << ": " << b.angular_velocity;
    }
  }
}

}  // namespace
}  // namespace fixstep
