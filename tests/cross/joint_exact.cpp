// The exact checks of joints (joint_exact.hpp): each world, what it measures and the closed
// form or bound, with the derivation beside it.
#include "joint_exact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep::joint_exact {

namespace {

using shape_exact::Measure;
using shape_exact::near;

constexpr double g0 = 9.81;  // m/s², the bodies' gravity
constexpr double dt = 1.0 / 60.0;
constexpr double slop = 0.005;  // m, the joints' linear slop (Box2D's)

World empty_world() {
  return World(WorldDef::empty(Precision::f64, shape_exact::shape_settings(0.6)));
}

BodyDef floating(BodyDef b) {
  b.gravity.reset();
  return b;
}

// --- the rigid pendulum ------------------------------------------------------------------
// A 0.2 m × 1 m box of 1 kg hung from its top end on a revolute joint to the world: d = 0.5 m
// from pivot to centre of mass, I_pivot = m (w² + h²)/12 + m d². Small angles: T = 2π √(I_pivot
// / (m g d)); released at θ0: T = 4 √(I_pivot / (m g d)) K(sin(θ0/2)) (the complete elliptic
// integral of the first kind).

struct Pendulum {
  World world = empty_world();
  Entity box;
  double d = 0.5, inertia_cm = (0.2 * 0.2 + 1.0) / 12.0;
  [[nodiscard]] double inertia_pivot() const { return inertia_cm + d * d; }
};

Pendulum pendulum(double theta0) {
  Pendulum p;
  const Vec2 centre{p.d * std::sin(theta0), -p.d * std::cos(theta0)};
  p.box = p.world.create_body(shape_exact::box_body(0.1, 0.5, centre, theta0));
  p.world.create_joint(JointDef{.type = JointType::revolute, .body_b = p.box, .anchor = {}});
  return p;
}

/// The mean period (s) over `periods` periods, from the upward zero crossings of the angle
/// (linearly interpolated between ticks).
double measured_period(Pendulum& p, int periods, double expected) {
  std::vector<double> crossings;
  double last = p.world.body(p.box).angle;
  const int ticks = static_cast<int>((periods + 1.5) * expected / dt);
  for (int t = 1; t <= ticks; ++t) {
    p.world.step();
    const double now = p.world.body(p.box).angle;
    if (last < 0.0 && now >= 0.0) crossings.push_back((t - 1 + (-last / (now - last))) * dt);
    last = now;
  }
  if (crossings.size() < 2) return 0.0;
  const std::size_t n = std::min<std::size_t>(crossings.size() - 1, periods);
  return (crossings[n] - crossings[0]) / static_cast<double>(n);
}

std::vector<Measure> pendulum_small_angle() {
  Pendulum p = pendulum(0.02);
  const double exact = 2.0 * std::numbers::pi * std::sqrt(p.inertia_pivot() / (g0 * p.d));
  return {near("period at 0.02 rad (s)", measured_period(p, 10, exact), exact, 1e-3 * exact)};
}

/// The complete elliptic integral of the first kind, K(k) = π / (2 AGM(1, √(1 − k²))) (Gauss's
/// arithmetic-geometric mean; libc++ has no std::comp_ellint_1).
double elliptic_k(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 30 && a != b; ++i) {
    const double mean = 0.5 * (a + b);
    b = std::sqrt(a * b), a = mean;
  }
  return std::numbers::pi / (2.0 * a);
}

std::vector<Measure> pendulum_released_horizontal() {
  const double theta0 = std::numbers::pi / 2.0;
  Pendulum p = pendulum(theta0);
  const double exact =
      4.0 * std::sqrt(p.inertia_pivot() / (g0 * p.d)) * elliptic_k(std::sin(theta0 / 2.0));
  return {
      near("period released horizontal (s)", measured_period(p, 5, exact), exact, 5e-3 * exact)};
}

std::vector<Measure> pendulum_energy_bounded() {
  Pendulum p = pendulum(1.0);
  auto energy = [&] {
    const Body b = p.world.body(p.box);
    const Vec2 c = b.position;  // the box's centre is its origin
    return 0.5 * (dot(b.velocity, b.velocity) +
                  p.inertia_cm * b.angular_velocity * b.angular_velocity) +
           g0 * c.y;
  };
  const double e0 = energy();
  const double period = 2.0 * std::numbers::pi * std::sqrt(p.inertia_pivot() / (g0 * p.d));
  double worst = 0.0, end = 0.0;
  const int ticks = static_cast<int>(100 * period / dt);
  for (int t = 0; t < ticks; ++t) {
    p.world.step();
    worst = std::max(worst, std::abs(energy() - e0));
  }
  end = energy() - e0;
  const double scale = g0 * p.d;  // J: the swing's potential scale (m = 1 kg)
  return {near("largest energy error over 100 periods / (m g d)", worst / scale, 0.0, 0.02),
          near("energy change after 100 periods / (m g d)", end / scale, 0.0, 0.02)};
}

// The pendulum released horizontal with its hinge limited to ±0.5 rad of its start: it swings
// down to the lower limit and stops there, within the angular slop (2°).
std::vector<Measure> revolute_limit_stops() {
  Pendulum p = pendulum(std::numbers::pi / 2.0);
  const Joint j = p.world.joints()[0];
  p.world.destroy_joint(j);
  const Joint limited = p.world.create_joint(JointDef{
      .type = JointType::revolute, .body_b = p.box, .anchor = {}, .lower = -0.5, .upper = 0.5});
  double lowest = 0.0;
  for (int t = 0; t < 240; ++t) {
    p.world.step();
    lowest = std::min(lowest, p.world.joint_state(limited).value);
  }
  const double slop_angle = 2.0 / 180.0 * std::numbers::pi;
  return {near("lowest joint angle (rad)", lowest, -0.5, slop_angle),
          near("joint angle at rest (rad)", p.world.joint_state(limited).value, -0.5, slop_angle)};
}

// --- springs: a body hung on a wheel joint's suspension or a distance spring rests where the
// spring carries its weight, k x = m g with k = m ω² (ω = 2π f): x = g / ω² ------------------

std::vector<Measure> springs_carry_the_weight() {
  World w = empty_world();
  const double f = 2.0, omega = 2.0 * std::numbers::pi * f, sag = g0 / (omega * omega);
  BodyDef wheel = shape_exact::box_body(0.1, 0.1, {0.0, 0.0});
  wheel.shapes = {make_circle(0.3)};
  const Entity hub = w.create_body(wheel);
  const Joint suspension = w.create_joint(JointDef{.type = JointType::wheel,
                                                   .body_b = hub,
                                                   .anchor = {0.0, 0.0},
                                                   .axis = {0.0, 1.0},
                                                   .frequency = f,
                                                   .damping_ratio = 1.0});
  const Entity bob = w.create_body(shape_exact::box_body(0.1, 0.1, {5.0, -1.0}, 0.0, 3.0));
  const Joint spring = w.create_joint(JointDef{.type = JointType::distance,
                                               .body_b = bob,
                                               .anchor = {5.0, 0.0},
                                               .anchor_b = Vec2{5.0, -1.0},
                                               .frequency = f,
                                               .damping_ratio = 1.0});
  for (int t = 0; t < 600; ++t) w.step();
  return {
      near("wheel's sag on its suspension (m)", w.joint_state(suspension).value, -sag, 1e-4 * sag),
      near("distance spring's stretch (m)", w.joint_state(spring).value - 1.0, sag, 1e-4 * sag)};
}

// --- the hanging chain ---------------------------------------------------------------------
// 30 boxes 0.1 m × 0.5 m of 1 kg each, hinged end to end and to the world at the top, start
// straight and at rest. The stretch: the bottom end's distance from the top hinge against the
// chain's 15 m.

struct Chain {
  World world = empty_world();
  std::vector<Entity> links;
};

Chain chain(int n) {
  Chain c;
  Entity above{};
  for (int i = 0; i < n; ++i) {
    const Entity box =
        c.world.create_body(shape_exact::box_body(0.05, 0.25, {0.0, -0.25 - 0.5 * i}));
    c.world.create_joint(JointDef{
        .type = JointType::revolute, .body_a = above, .body_b = box, .anchor = {0.0, -0.5 * i}});
    c.links.push_back(box);
    above = box;
  }
  return c;
}

/// The chain's stretch (dimensionless) and its fastest link's speed (m/s) after `ticks`.
std::pair<double, double> settle(Chain& c, int ticks, double length) {
  for (int t = 0; t < ticks; ++t) c.world.step();
  const Body last = c.world.body(c.links.back());
  const double a = last.angle;
  const Vec2 tip = last.position + Vec2{0.25 * std::sin(a), -0.25 * std::cos(a)};
  double fastest = 0.0;
  for (const Entity e : c.links) {
    const Body b = c.world.body(e);
    fastest = std::max(fastest, std::sqrt(dot(b.velocity, b.velocity)));
  }
  return {std::sqrt(dot(tip, tip)) / length - 1.0, fastest};
}

std::vector<Measure> chain_hangs() {
  Chain c = chain(30);
  const auto [stretch, fastest] = settle(c, 180, 15.0);
  return {near("stretch of a 30-box chain / its length", stretch, 0.0, 1e-3),
          near("fastest link after 3 s (m/s)", fastest, 0.0, 1e-3)};
}

std::vector<Measure> chain_holds_a_load() {
  Chain c = chain(30);
  const Entity load =
      c.world.create_body(shape_exact::box_body(0.25, 0.25, {0.0, -15.25}, 0.0, 10.0));
  c.world.create_joint(JointDef{.type = JointType::revolute,
                                .body_a = c.links.back(),
                                .body_b = load,
                                .anchor = {0.0, -15.0}});
  const auto [stretch, fastest] = settle(c, 180, 15.0);
  // (the load's start sets the chain bouncing a little: the solver keeps energy)
  return {near("stretch of the chain under a 10 kg box / its length", stretch, 0.0, 5e-3),
          near("fastest link after 3 s (m/s)", fastest, 0.0, 1e-2)};
}

// --- a revolute motor: ω = (τ / I) t until the motor speed, then held -------------------------

std::vector<Measure> motor_spins_up() {
  World w = empty_world();
  BodyDef disc = floating(shape_exact::box_body(0.1, 0.1, {}));
  disc.shapes = {make_circle(0.5)};
  disc.body.mass = 2.0;  // I = m r² / 2 = 0.25 kg·m²
  const Entity e = w.create_body(disc);
  const double tau = 1.0, inertia = 0.25, speed = 10.0;
  w.create_joint(JointDef{.type = JointType::revolute,
                          .body_b = e,
                          .anchor = {},
                          .motor_speed = speed,
                          .max_motor_torque = tau});
  for (int t = 0; t < 60; ++t) w.step();
  const double at_one_second = w.body(e).angular_velocity;
  for (int t = 60; t < 300; ++t) w.step();
  const double at_five = w.body(e).angular_velocity;
  const Body b = w.body(e);
  return {near("ω after 1 s (rad/s)", at_one_second, tau / inertia * 1.0, 1e-9),
          near("ω after 5 s (rad/s)", at_five, speed, 1e-9),
          near("centre's drift (m)", std::hypot(b.position.x, b.position.y), 0.0, 1e-12)};
}

// --- a prismatic slide at θ to gravity: a = g sin θ along the axis, nothing across ------------

struct AxisSlide {
  double along = 0.0, across = 0.0, turn = 0.0, lowest = 0.0;
};

AxisSlide prismatic_slide(double theta, std::optional<double> lower, int ticks) {
  World w = empty_world();
  const Entity box = w.create_body(shape_exact::box_body(0.5, 0.25, {}, 0.0, 2.0));
  const Vec2 axis{std::cos(theta), std::sin(theta)};
  const Joint j = w.create_joint(JointDef{
      .type = JointType::prismatic, .body_b = box, .anchor = {}, .axis = axis, .lower = lower});
  AxisSlide s{.lowest = 0.0};
  for (int t = 0; t < ticks; ++t) {
    w.step();
    s.lowest = std::min(s.lowest, w.joint_state(j).value);
  }
  const Body b = w.body(box);
  s.along = dot(b.position, axis), s.across = cross(axis, b.position), s.turn = b.angle;
  return s;
}

std::vector<Measure> prismatic_slides() {
  const double theta = 0.5;
  const int n = 120;
  const AxisSlide s = prismatic_slide(theta, std::nullopt, n);
  // Semi-implicit Euler from rest: x_n = a dt² n(n+1)/2 with a = −g sin θ along the axis.
  const double exact = -g0 * std::sin(theta) * dt * dt * n * (n + 1) / 2.0;
  return {near("distance slid along the axis in 2 s (m)", s.along, exact, 1e-9 * std::abs(exact)),
          near("distance across the axis (m)", s.across, 0.0, 1e-9),
          near("turn (rad)", s.turn, 0.0, 1e-9)};
}

std::vector<Measure> prismatic_limit_stops() {
  const AxisSlide s = prismatic_slide(0.5, -1.0, 240);
  return {near("lowest translation (m)", s.lowest, -1.0, slop),
          near("translation at rest (m)", s.along, -1.0, slop)};
}

// --- a welded L spins with the composite inertia -----------------------------------------------
// A 1 m × 0.2 m bar and a 0.2 m × 1 m post, 1 kg each, welded into an L, no gravity; an angular
// impulse L on the bar alone. The L turns as one body: ω = L / I with I the composite inertia
// about the common centre of mass (parallel axes), as semi-implicit Euler turns a rigid body:
// each centre of mass steps along the chord of its circle (radius R) while the angle steps by
// ω dt, so the angular momentum is I_own ω + m R² sin(ω dt)/dt per part, within (ω dt)²/6 of
// I ω; the check takes that ω (a fixed point, exact to rounding) and the continuous one within
// the integrator's error.

std::vector<Measure> weld_spins_as_one() {
  World w = empty_world();
  const Entity bar = w.create_body(floating(shape_exact::box_body(0.5, 0.1, {0.0, 0.0})));
  const Entity post = w.create_body(floating(shape_exact::box_body(0.1, 0.5, {0.4, 0.6})));
  w.create_joint(
      JointDef{.type = JointType::weld, .body_a = bar, .body_b = post, .anchor = {0.4, 0.1}});
  const double own = (1.0 + 0.04) / 12.0;                       // each box's, kg·m²
  const double lever = 0.2 * 0.2 + 0.3 * 0.3;                   // each centre's, from (0.2, 0.3)
  const double composite = 2.0 * (own + lever), impulse = 1.0;  // kg·m², N·m·s
  TickInput in;
  in.bodies.push_back({bar, BodyInputKind::angular_impulse, {impulse, 0.0}});
  w.step(in);
  for (int t = 1; t < 120; ++t) w.step();
  const Body a = w.body(bar), b = w.body(post);
  const Vec2 apart = b.position - a.position;
  double discrete = impulse / composite;
  for (int k = 0; k < 50; ++k) {
    const double x = discrete * dt;
    discrete = impulse / (2.0 * own + 2.0 * lever * std::sin(x) / x);
  }
  const double exact = impulse / composite;
  return {near("bar's ω after 2 s (rad/s)", a.angular_velocity, discrete, 1e-9 * discrete),
          near("post's ω after 2 s (rad/s)", b.angular_velocity, discrete, 1e-9 * discrete),
          near("ω against the continuous composite's (rad/s)", a.angular_velocity, exact,
               std::pow(exact * dt, 2) / 6.0 * exact),
          near("centres' distance (m)", std::sqrt(dot(apart, apart)), std::sqrt(0.52), 1e-6),
          near("relative angle (rad)", b.angle - a.angle, 0.0, 1e-6)};
}

// --- a rope: slack below its length, taut at it, never longer past the slop -------------------
// A 1 kg disc 1 m beside the rope's world end, at rest, on a 2 m rope (a distance joint with
// only an upper limit).

std::vector<Measure> rope_slack_and_taut() {
  World w = empty_world();
  BodyDef ball = shape_exact::box_body(0.1, 0.1, {1.0, 0.0});
  ball.shapes = {make_circle(0.1)};
  const Entity e = w.create_body(ball);
  w.create_joint(JointDef{.type = JointType::distance,
                          .body_b = e,
                          .anchor = {},
                          .anchor_b = Vec2{1.0, 0.0},
                          .upper = 2.0});
  const int free_ticks = 20;
  for (int t = 0; t < free_ticks; ++t) w.step();
  const double fallen = w.body(e).position.y;
  // Free fall while slack: y_n = −g dt² n(n+1)/2.
  const double exact = -g0 * dt * dt * free_ticks * (free_ticks + 1) / 2.0;
  double longest = 0.0;
  for (int t = free_ticks; t < 600; ++t) {
    w.step();
    const Vec2 p = w.body(e).position;
    longest = std::max(longest, std::sqrt(dot(p, p)));
  }
  return {near("fall while slack in 1/3 s (m)", fallen, exact, 1e-12),
          {"longest over 10 s (m)", longest, 2.0 - slop, 2.0 + slop}};
}

}  // namespace

std::vector<shape_exact::Check> checks() {
  return {{"PendulumSmallAngle", pendulum_small_angle},
          {"PendulumReleasedHorizontal", pendulum_released_horizontal},
          {"PendulumEnergyBounded", pendulum_energy_bounded},
          {"RevoluteLimitStops", revolute_limit_stops},
          {"SpringsCarryTheWeight", springs_carry_the_weight},
          {"ChainHangs", chain_hangs},
          {"ChainHoldsALoad", chain_holds_a_load},
          {"MotorSpinsUp", motor_spins_up},
          {"PrismaticSlides", prismatic_slides},
          {"PrismaticLimitStops", prismatic_limit_stops},
          {"WeldSpinsAsOne", weld_spins_as_one},
          {"RopeSlackAndTaut", rope_slack_and_taut}};
}

}  // namespace fixstep::joint_exact
