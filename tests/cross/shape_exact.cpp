// The exact checks of bodies with shapes (shape_exact.hpp): each world, what it measures and the
// closed form or bound, with the derivation beside it.
#include "shape_exact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "fixstep/core/components.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep::shape_exact {

namespace {

constexpr double g = 9.81;

WorldSettings shape_world(double mu, double e = 0.0) {
  return shape_settings(mu, e);
}

PlaneDef ground(double mu) {
  return PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.0, .friction = mu};
}

// --- the incline: a = g (sin θ − μ cos θ) when tan θ > μ, still when tan θ < μ ---------------

struct Slide {
  double along = 0.0;   ///< m moved down the slope
  double across = 0.0;  ///< m moved off the plane's line
  double angle = 0.0;   ///< rad turned
};

/// A 1 m × 0.5 m box of 2 kg on a plane tilted by θ, from the tick after it settles on it.
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

std::vector<Measure> incline_slides() {
  const double theta = 0.5, mu = 0.2, dt = 1.0 / 60.0;
  const int ticks = 121;
  const Slide s = slide(theta, mu, ticks);
  // From rest after the first tick: semi-implicit Euler's x_n = a dt² n(n+1)/2 over the n
  // ticks after it, with v1 = a dt already gained in the first.
  const double a = g * (std::sin(theta) - mu * std::cos(theta));
  const int n = ticks - 1;
  const double exact = a * dt * dt * (n * (n + 1) / 2.0 + n);
  return {near("distance slid in 2 s (m)", s.along, exact, 1e-3 * exact),
          near("distance off the plane (m)", s.across, 0.0, 1e-6),
          near("turn (rad)", s.angle, 0.0, 1e-6)};
}

std::vector<Measure> incline_sticks() {
  const Slide s = slide(0.3, 0.5, 121);  // tan 0.3 = 0.31 < 0.5; 2 s
  return {near("distance slid in 2 s (m)", s.along, 0.0, 1e-6),
          near("distance off the plane (m)", s.across, 0.0, 1e-6),
          near("turn (rad)", s.angle, 0.0, 1e-6)};
}

// --- the tipping box: back upright below atan(w/h), over above it ----------------------------

/// A box w × h = 0.4 m × 1 m stood on its lower-left corner at the origin, turned by φ (rad)
/// counter-clockwise: its centre at R(φ)(w/2, h/2). Returns its angle after 3 s.
double tip(double phi) {
  detail::WorldKernel<double> w(shape_world(1.0));
  w.add_plane(ground(1.0));
  const double hx = 0.2, hy = 0.5;
  const Vec2 c{std::cos(phi) * hx - std::sin(phi) * hy, std::sin(phi) * hx + std::cos(phi) * hy};
  const Entity box = w.create_body(box_body(hx, hy, c, phi));
  for (int i = 0; i < 180; ++i) w.step();
  return w.body(box).angle;
}

std::vector<Measure> tipping() {
  const double critical = std::atan(0.4 / 1.0);  // atan(w/h)
  return {
      near("angle after 3 s from 0.01 rad below atan(w/h) (rad)", tip(critical - 0.01), 0.0, 0.02),
      near("angle after 3 s from 0.01 rad above atan(w/h) (rad)", tip(critical + 0.01),
           std::numbers::pi / 2, 0.02)};
}

// --- free spin ---------------------------------------------------------------------------

std::vector<Measure> free_spin() {
  detail::WorldKernel<double> w(shape_world(0.0));
  BodyDef b = box_body(0.5, 0.2, {1.0, 2.0}, 0.3, 3.0);
  b.gravity.reset();
  b.body.angular_velocity = 7.0;
  b.body.velocity = {0.5, -0.25};
  const Entity box = w.create_body(b);
  const double e0 = w.energy().total();
  for (int i = 0; i < 600; ++i) w.step();
  const Body after = w.body(box);
  // I = m (w² + h²) / 12 for a box of 1.0 m × 0.4 m; θ = 0.3 + 600 dt ω, wrapped to [-π, π].
  const double kinetic = 0.5 * 3.0 * (0.25 + 0.0625) + 0.5 * 3.0 * (1.0 + 0.16) / 12.0 * 49.0;
  return {near("ω after 10 s (rad/s), to the bit", after.angular_velocity, 7.0, 0.0),
          near("energy after 10 s (J)", w.energy().total(), e0, 1e-12 * e0),
          near("kinetic energy, ½ m v² + ½ I ω² (J)", w.energy().kinetic, kinetic, 1e-12),
          near("angle, wrapped (rad)",
               std::remainder(after.angle - (0.3 + 70.0), 2 * std::numbers::pi), 0.0, 1e-9)};
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
std::vector<Measure> elastic_gas() {
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
  double bounces = 0.0, disc_impacts = 0.0, deepest = 0.0;
  for (int tick = 0; tick < 1200; ++tick) {
    const double e = w.energy().kinetic;
    w.step();
    const ContactStats& c = w.contact_stats();
    disc_impacts += static_cast<double>(c.impacts);
    deepest = std::max({deepest, c.deepest_shape_overlap, c.max_overlap});
    // A bounce changes the energy by rounding only: a tick of shape points with a changed
    // kinetic energy had one.
    if (c.shape_points > 0 && e != w.energy().kinetic) ++bounces;
  }
  const GasTotals after = totals();
  const double p = std::hypot(before.px, before.py), most = std::numeric_limits<double>::max();
  // Rounding: about 1e-16 of each total per impulse over some hundred impulses.
  return {
      {"ticks with a shape bounce", bounces, 21.0, most},
      {"disc-disc impacts", disc_impacts, 6.0, most},
      near("energy after 10 s (J)", after.energy, before.energy, 1e-12 * before.energy),
      near("momentum x (kg m/s)", after.px, before.px, 1e-12 * p),
      near("momentum y (kg m/s)", after.py, before.py, 1e-12 * p),
      near("angular momentum (kg m²/s)", after.spin, before.spin, 1e-12 * std::abs(before.spin)),
      {"deepest overlap (m): they bounce before they meet", deepest, -most, 0.0}};
}

// --- a box dropped flat rests flat, half its weight on each corner -----------------------

std::vector<Measure> rests_flat() {
  detail::WorldKernel<double> w(shape_world(0.5));
  w.add_plane(ground(0.5));
  const Entity box = w.create_body(box_body(0.5, 0.25, {0.0, 0.5}, 0.0, 2.0));
  for (int i = 0; i < 120; ++i) w.step();
  const detail::ShapeWorld* sw = w.shape_world();
  const double half_weight = 0.5 * 2.0 * g * w.settings().dt;  // N·s a tick
  std::vector<Measure> m{
      near("manifold points", sw ? static_cast<double>(sw->rows().size()) : 0.0, 2.0, 0.0)};
  if (sw) {
    for (const detail::ShapeRow& r : sw->rows()) {
      m.push_back(near("a corner's normal impulse (N s)", r.ln, half_weight, 0.01 * half_weight));
    }
  }
  m.push_back(near("angle (rad)", w.body(box).angle, 0.0, 1e-9));
  m.push_back(near("centre height (m), within the slop", w.body(box).position.y, 0.25, 0.006));
  return m;
}

// --- stacks --------------------------------------------------------------------------------

/// The top box's drift (m) from 1 s to 11 s of boxes 1 m wide stacked in `rows` rows of
/// `rows`, `rows` − 1, … (a pyramid) or one a row (a tower), and the deepest overlap left.
std::vector<Measure> stack(int rows, bool pyramid) {
  detail::WorldKernel<double> w(shape_world(0.6));
  w.add_plane(ground(0.6));
  const double h = 0.5;
  Entity top;
  for (int row = 0; row < rows; ++row) {
    const int n = pyramid ? rows - row : 1;
    for (int i = 0; i < n; ++i) {
      const double x = (i - (n - 1) * 0.5) * 2 * h;
      top = w.create_body(box_body(h, h, {x, h + 2 * h * row}));
    }
  }
  for (int i = 0; i < 60; ++i) w.step();
  const Body b0 = w.body(top);
  for (int i = 0; i < 600; ++i) w.step();
  const Body b1 = w.body(top);
  const double drift = std::hypot(b1.position.x - b0.position.x, b1.position.y - b0.position.y);
  return {{"top box's drift over 10 s (m), under 1 % of its size", drift, 0.0, 0.01 * 2 * h},
          {"deepest overlap (m)", w.contact_stats().deepest_shape_overlap, 0.0, 0.01}};
}

// --- a fast spinning box does not pass a thin wall ------------------------------------------

std::vector<Measure> thin_wall() {
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
  double furthest = 0.0;
  for (int i = 0; i < 120; ++i) {
    w.step();
    furthest = std::max(furthest, w.body(box).position.x);
  }
  return {{"furthest centre x over 2 s (m), short of the wall's middle at 10 m", furthest, 0.0,
           std::nextafter(10.0, 0.0)}};
}

// --- rolling resistance -----------------------------------------------------------------

// A uniform disc (a circle shape, I = ½ m r²) rolling without slipping on flat ground with
// rolling resistance c: the torque c r N against its turning and friction F at the ground give
// m a = −F, I α = F r − c r N with a = α r, so a = −c g m r² / (I + m r²) = −(2/3) c g, until it
// stops, and then it stays put.
std::vector<Measure> rolling_resistance() {
  detail::WorldKernel<double> w(shape_world(0.8));
  w.add_plane(ground(0.8));
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
  const Body one = w.body(disc);
  for (int i = 0; i < 600; ++i) w.step();  // it stops after v0 / a = 6.1 s
  const Body end = w.body(disc);
  return {near("speed after 1 s (m/s)", one.velocity.x, v0 - a * 1.0, 1e-3 * v0),
          near("rim speed ω r + v after 1 s (m/s): it rolls", one.angular_velocity * r,
               -one.velocity.x, 1e-6),
          near("speed after 11 s (m/s)", end.velocity.x, 0.0, 1e-9),
          near("ω after 11 s (rad/s)", end.angular_velocity, 0.0, 1e-9),
          near("distance rolled, v0² / 2a (m), within a tick's travel", end.position.x,
               v0 * v0 / (2.0 * a), v0 / 60.0)};
}

}  // namespace

WorldSettings shape_settings(double mu, double e) {
  WorldSettings s{.dt = 1.0 / 60.0};
  s.contacts = ContactSettings{.restitution = e, .friction = mu};
  return s;
}

BodyDef box_body(double hx, double hy, Vec2 at, double angle, double mass) {
  BodyDef b;
  b.body = Body{.mass = mass, .position = at, .angle = angle};
  b.gravity = Gravity{{0.0, -g}};
  b.shapes = {make_box(hx, hy)};
  return b;
}

std::vector<Check> checks() {
  return {
      {"InclineSlidesAtGTimesSinMinusMuCos", incline_slides},
      {"InclineSticksWhenTanThetaIsBelowMu", incline_sticks},
      {"BoxOnItsCornerTipsBackBelowTheCriticalAngleAndOverAboveIt", tipping},
      {"BoxSpinningFreelyKeepsItsAngularVelocityAndEnergy", free_spin},
      {"ElasticFrictionlessGasKeepsMomentumAngularMomentumAndEnergy", elastic_gas},
      {"BoxDroppedFlatRestsOnBothCornersWithHalfItsWeightEach", rests_flat},
      {"TowerOfTwentyBoxesStandsStillForTenSeconds", [] { return stack(20, false); }},
      {"TwentyRowPyramidStandsStillForTenSeconds", [] { return stack(20, true); }},
      {"FastSpinningBoxDoesNotPassAOneCentimetreWall", thin_wall},
      {"UniformDiscWithRollingResistanceSlowsAtTwoThirdsCGAndStops", rolling_resistance},
  };
}

}  // namespace fixstep::shape_exact
