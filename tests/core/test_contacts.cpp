// Contacts with static half-planes (world_contacts.cpp): time of impact inside the tick,
// restitution, Coulomb friction, resting contact, and nothing at all for worlds without planes.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

constexpr double g = 9.81;  // m/s²
constexpr double r = 0.5;   // m, the ball's radius

/// A world with a ground plane y >= 0 (restitution e, friction mu) and one ball of radius r
/// whose centre starts at height r + h (m) with velocity v (m/s) under gravity.
detail::WorldKernel<double> drop(Integrator integrator, double dt, double h, double e,
                                 double mu = 0.0, Vec2 v = {}, bool track = false) {
  detail::WorldKernel<double> w(
      WorldSettings{.dt = dt, .integrator = integrator, .track_dissipation = track});
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = e, .friction = mu});
  BodyDef ball;
  ball.name = "ball";
  ball.body = Body{.mass = 2.0, .position = {0.0, r + h}, .velocity = v};
  ball.gravity = Gravity{{0.0, -g}};
  ball.collider = Collider{r};
  w.create_body(ball);
  return w;
}

/// Times of impact (s) of the ball in w over `duration`: after each tick whose vy turns from
/// < 0 to > 0, reconstructed from the end state by ballistics (v+ = √(v1² + 2 g (y1 - r)),
/// τ = (v+ - v1)/g before the tick's end).
std::vector<double> bounce_times(detail::WorldKernel<double>& w, double duration) {
  std::vector<double> times;
  const auto ticks = static_cast<long>(std::llround(duration / w.settings().dt));
  for (long i = 0; i < ticks; ++i) {
    const double before = w.vy()[0];
    w.step();
    const double v1 = w.vy()[0], y1 = w.y()[0];
    if (before < 0.0 && v1 > 0.0) {
      const double v_plus = std::sqrt(v1 * v1 + 2.0 * g * (y1 - r));
      times.push_back(w.time() - (v_plus - v1) / g);
    }
  }
  return times;
}

/// Largest |t_k - t_k exact| over the first `count` bounces of a drop from rest at height h
/// with e = 1: t_k = (2k + 1) √(2h/g) (fall time √(2h/g), then a full up-and-down of twice
/// that per bounce).
double bounce_time_error(Integrator integrator, double dt, double h, int count) {
  detail::WorldKernel<double> w = drop(integrator, dt, h, 1.0);
  const double fall = std::sqrt(2.0 * h / g);
  const std::vector<double> t = bounce_times(w, (2 * count + 0.5) * fall);
  EXPECT_GE(static_cast<int>(t.size()), count);
  double worst = 0.0;
  for (int k = 0; k < count && k < static_cast<int>(t.size()); ++k) {
    worst = std::max(worst, std::abs(t[k] - (2 * k + 1) * fall));
  }
  return worst;
}

bool exact_on_constant_forces(Integrator i) {
  return i == Integrator::velocity_verlet || i == Integrator::rk4 || i == Integrator::forest_ruth;
}

// (b) Drop from rest at h = 5 m, e = 1: the first 10 bounce times against t_k = (2k+1)√(2h/g).
// Measured at dt = 1/60, 1/120, 1/240 s: the Euler methods (semi-implicit, explicit, implicit)
// err 8.2e-3, 4.1e-3, 2.1e-3 s (order 0.98, 1.00: the velocity they report lags the parabola
// they move on by g dt/2, read by the ballistic reconstruction); velocity Verlet, RK4 and
// Forest–Ruth are exact for gravity and err < 3e-13 s at every dt (rounding: better than any
// order). Asserted: Euler orders within 0.9 .. 1.1; the others below 1e-11 s.
TEST(Contacts, BounceTimesConvergeAtTheIntegratorsOrder) {
  const double h = 5.0, dt = 1.0 / 60.0;
  for (const Integrator i : all_integrators) {
    SCOPED_TRACE(std::string(integrator_name(i)));
    double err[3];
    for (int level = 0; level < 3; ++level)
      err[level] = bounce_time_error(i, dt / (1 << level), h, 10);
    if (exact_on_constant_forces(i)) {
      for (const double e : err) EXPECT_LT(e, 1e-11);
    } else {
      for (int level = 0; level < 2; ++level) {
        const double order = std::log2(err[level] / err[level + 1]);
        EXPECT_NEAR(order, 1.0, 0.1) << err[level] << " s then " << err[level + 1] << " s";
      }
      EXPECT_LT(err[0], 0.6 * dt);  // about g dt/2 / g = dt/2
    }
  }
}

// (a) e = 1, drop from 5 m, ~10 bounces in 20 s. Bound on |E - E0|/E0 at every tick:
// Euler methods 1.1 × v_max g dt/2 / E0 (their reported velocity is off the parabola's by
// g dt/2, so E wobbles by up to v g dt/2 — measured 1.51e-2 at dt = 1/60, 3.76e-3 at 1/240,
// with no drift from bounce to bounce); Verlet, RK4, Forest–Ruth 1e-13 (exact for gravity,
// measured < 3e-14).
TEST(Contacts, ElasticBallKeepsItsEnergy) {
  const double h = 5.0;
  for (const Integrator i : all_integrators) {
    for (const double dt : {1.0 / 60.0, 1.0 / 240.0}) {
      SCOPED_TRACE(fmt::format("{} dt {}", integrator_name(i), dt));
      detail::WorldKernel<double> w = drop(i, dt, h, 1.0);
      const double e0 = w.energy().total() - w.energy().gravity;  // relative to the ground
      const double base = w.energy().total();
      const double v_max = std::sqrt(2.0 * g * h);
      const double bound =
          exact_on_constant_forces(i) ? 1e-13 : 1.1 * v_max * g * dt / 2.0 / (g * (h + r));
      double worst = 0.0;
      int bounces = 0;
      for (long k = 0; k < std::lround(20.0 / dt); ++k) {
        const double before = w.vy()[0];
        w.step();
        bounces += before < 0.0 && w.vy()[0] > 0.0;
        worst = std::max(worst, std::abs(w.energy().total() - base) / (base - e0 + 1e-300));
      }
      EXPECT_GE(bounces, 9);
      EXPECT_LT(worst, bound);
    }
  }
}

// Two walls and the ground, e = 1: a ball thrown sideways hits walls and ground (corners too)
// and keeps its energy exactly with Verlet.
TEST(Contacts, BoxKeepsEnergyWithWallsAndGround) {
  detail::WorldKernel<double> w =
      drop(Integrator::velocity_verlet, 1.0 / 60.0, 3.0, 1.0, 0.0, {7.0, 1.0});
  w.add_plane(PlaneDef{.normal = {1.0, 0.0}, .offset = -4.0, .restitution = 1.0});
  w.add_plane(PlaneDef{.normal = {-2.0, 0.0}, .offset = -4.0, .restitution = 1.0});  // x <= 4
  EXPECT_EQ(w.planes()[2].normal.x, -1.0);                                           // normalised
  const double e0 = w.energy().total();
  for (int k = 0; k < 6000; ++k) {
    w.step();
    ASSERT_GE(w.x()[0], -4.0 + r - 1e-9);
    ASSERT_LE(w.x()[0], 4.0 - r + 1e-9);
    ASSERT_GE(w.y()[0], r - 1e-9);
  }
  EXPECT_NEAR(w.energy().total(), e0, 1e-10 * e0);
  EXPECT_NEAR(std::abs(w.vx()[0]), 7.0, 1e-12);
}

/// Apex heights above the ground contact (m) of the ball in w over `duration` s.
std::vector<double> apexes(detail::WorldKernel<double>& w, double duration) {
  std::vector<double> out;
  for (long k = 0; k < std::lround(duration / w.settings().dt); ++k) {
    const double before = w.vy()[0];
    w.step();
    const double v = w.vy()[0];
    // The apex inside the tick, from the end state (gravity only between bounces).
    if (before > 0.0 && v <= 0.0) out.push_back(w.y()[0] - r + v * v / (2.0 * g));
  }
  return out;
}

// (c) e = 0.7: each bounce keeps e² of the energy, so apex heights fall by e² = 0.49 per bounce
// (exactly with Verlet and RK4: measured to 1e-12 relative; Euler to O(dt)).
TEST(Contacts, RestitutionScalesBounceHeightsByESquared) {
  const double e = 0.7, h = 5.0;
  for (const Integrator i :
       {Integrator::velocity_verlet, Integrator::rk4, Integrator::semi_implicit_euler}) {
    SCOPED_TRACE(std::string(integrator_name(i)));
    detail::WorldKernel<double> w = drop(i, 1.0 / 120.0, h, e);
    const std::vector<double> a = apexes(w, 6.0);
    ASSERT_GE(a.size(), 5u);
    const double tol = exact_on_constant_forces(i) ? 1e-10 : 5e-3;
    for (std::size_t k = 0; k < 5; ++k) {
      EXPECT_NEAR(a[k] / (h * std::pow(e * e, double(k + 1))), 1.0, tol) << "bounce " << k + 1;
    }
  }
}

// (d) A ball at rest on the ground stays there: no sinking, no jitter, over 10 000 ticks, in
// every integrator and both precisions; a dropped ball with e < 1 comes to rest too.
TEST(Contacts, RestingBallStaysAtRest) {
  for (const Integrator i : all_integrators) {
    SCOPED_TRACE(std::string(integrator_name(i)));
    detail::WorldKernel<double> w = drop(i, 1.0 / 60.0, 0.0, 0.5, 0.4);
    detail::WorldKernel<float> f(WorldSettings{.dt = 1.0 / 60.0, .integrator = i});
    f.add_plane(PlaneDef{.normal = {0.0, 1.0}, .restitution = 0.5, .friction = 0.4});
    BodyDef b;
    b.body.position = {3.0, r};
    b.gravity = Gravity{{0.0, -g}};
    b.collider = Collider{r};
    f.create_body(b);
    for (int k = 0; k < 10000; ++k) w.step(), f.step();
    EXPECT_EQ(w.y()[0], r);
    EXPECT_EQ(w.vy()[0], 0.0);
    EXPECT_EQ(w.x()[0], 0.0);
    EXPECT_EQ(f.y()[0], float(r));
    EXPECT_EQ(f.vy()[0], 0.0f);
    detail::WorldKernel<double> d = drop(i, 1.0 / 60.0, 2.0, 0.5);
    for (int k = 0; k < 600; ++k) d.step();  // 10 s: the bounces have died out
    for (int k = 0; k < 600; ++k) {
      d.step();
      ASSERT_NEAR(d.y()[0], r, 1e-12);
      ASSERT_EQ(d.vy()[0], 0.0);
    }
  }
}

// (e) A ball sliding on the ground at 5 m/s with μ = 0.2 slows as Coulomb says:
// v(t) = v0 - μ g t until it stops at v0/(μ g) = 2.548 s, then stays; x(t) = v0 t - ½ μ g t².
// The energy friction took is counted as dissipated (balance exact to rounding). Velocities
// exact in every integrator; positions too, but explicit Euler's (which lag by ½ μ g dt per
// tick, its own first-order error).
TEST(Contacts, FrictionSlowsASlidingBallAsCoulombPredicts) {
  const double v0 = 5.0, mu = 0.2, dt = 1.0 / 100.0;
  for (const Integrator i : all_integrators) {
    SCOPED_TRACE(std::string(integrator_name(i)));
    detail::WorldKernel<double> w = drop(i, dt, 0.0, 0.0, mu, {v0, 0.0}, true);
    const double e0 = w.energy().total();
    for (int k = 1; k <= 400; ++k) {
      w.step();
      const double t = k * dt, stop = v0 / (mu * g);
      const double v = std::max(v0 - mu * g * t, 0.0);
      const double x = t < stop ? v0 * t - 0.5 * mu * g * t * t : 0.5 * v0 * stop;
      ASSERT_NEAR(w.vx()[0], v, 1e-12) << "tick " << k;
      // Explicit Euler moves each tick with the velocity before friction: ½ μ g dt² per tick.
      const double slack = i == Integrator::explicit_euler ? 0.5 * mu * g * dt * t : 0.0;
      ASSERT_NEAR(w.x()[0], x, (t < stop ? 1e-11 : 0.5 * v0 * dt) + slack) << "tick " << k;
    }
    // Explicit Euler gains ½ (g dt)² per kg each tick it rests (v1 = v0 - g dt at x1 = x0),
    // which the contact takes out again and books as dissipated: ½ m g² dt t in 4 s.
    const double slack = i == Integrator::explicit_euler ? 1.01 * 0.5 * 2.0 * g * g * dt * 4.0 : 0;
    EXPECT_NEAR(w.energy().total() + w.dissipated_energy(), e0, 1e-12 * e0 + slack);
  }
}

// (e) At an impact, friction takes μ (1 + e) |v_n| of the tangential speed.
TEST(Contacts, FrictionImpulseAtImpact) {
  detail::WorldKernel<double> w =
      drop(Integrator::velocity_verlet, 1.0 / 100.0, 2.0, 0.5, 0.1, {3.0, 0.0});
  const double vn = std::sqrt(2.0 * g * 2.0);  // speed at impact
  for (int k = 0; k < 100; ++k) w.step();      // one bounce (fall 0.64 s, rise 0.32 s)
  EXPECT_NEAR(w.vx()[0], 3.0 - 0.1 * 1.5 * vn, 1e-12);
}

// (f) Colliders without planes, and planes without colliders, change nothing: the same state
// bits as a world without either, for every integrator (the golden hashes of the shipped
// scenes, whose bodies with a radius now have colliders, are unchanged too:
// test_determinism).
TEST(Contacts, NoPlanesOrNoCollidersChangeNothing) {
  for (const Integrator i : all_integrators) {
    for (const bool track : {false, true}) {
      auto make = [&](bool colliders, bool plane) {
        detail::WorldKernel<double> w(
            WorldSettings{.dt = 0.01, .integrator = i, .track_dissipation = track});
        if (plane) w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = -1e6});
        for (int j = 0; j < 5; ++j) {
          BodyDef b;
          b.body = Body{.mass = 1.0 + j, .position = {double(j), 0.1 * j}, .velocity = {1.0, 2.0}};
          b.gravity = Gravity{};
          b.spring = SpringDamper{.anchor = {0.0, 0.0}, .stiffness = 3.0, .damping = 0.1};
          if (colliders) b.collider = Collider{0.5};
          w.create_body(b);
        }
        for (int k = 0; k < 1000; ++k) w.step();
        return std::pair(w.state_hash(), w.dissipated_energy());
      };
      const auto plain = make(false, false);
      EXPECT_EQ(make(true, false), plain);
      EXPECT_EQ(make(false, true), plain);
    }
  }
}

TEST(Contacts, AddPlaneRejectsBadValuesNamingTheField) {
  detail::WorldKernel<double> w(WorldSettings{});
  auto message = [&](const PlaneDef& p) {
    try {
      w.add_plane(p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({.normal = {0.0, 0.0}}).find("plane[0]: normal must be a non-zero"),
            std::string::npos);
  EXPECT_NE(message({.normal = {NAN, 1.0}}).find("normal"), std::string::npos);
  EXPECT_NE(message({.offset = INFINITY}).find("offset"), std::string::npos);
  EXPECT_NE(message({.restitution = 1.5}).find("restitution must be in [0, 1]"), std::string::npos);
  EXPECT_NE(message({.friction = -0.1}).find("friction"), std::string::npos);
  EXPECT_EQ(w.planes().size(), 0u);
  detail::WorldKernel<float> f(WorldSettings{});
  EXPECT_THROW(f.add_plane({.offset = 1e39}), std::invalid_argument);  // inf as a float
  BodyDef b;
  b.collider = Collider{0.0};
  EXPECT_THROW(w.create_body(b), std::invalid_argument);
}

// (g) [[plane]] tables.
TEST(ScenePlanes, ParsesPlanesAndRadiusGivesACollider) {
  const Scene s = parse_scene(R"([world]
dt = 0.01
[[plane]]
normal = [0.0, 2.0]
restitution = 0.5
[[plane]]
normal = [-1.0, 0.0]
point = [4.0, 7.0]
friction = 0.3
[[body]]
mass = 1.0
position = [0.0, 1.0]
radius = 0.25
)",
                              "planes.toml");
  ASSERT_EQ(s.def.planes.size(), 2u);
  EXPECT_EQ(s.def.planes[0].normal.y, 1.0);
  EXPECT_EQ(s.def.planes[0].offset, 0.0);
  EXPECT_EQ(s.def.planes[0].restitution, 0.5);
  EXPECT_EQ(s.def.planes[1].offset, -4.0);
  EXPECT_EQ(s.def.planes[1].friction, 0.3);
  EXPECT_EQ(s.source.plane_lines, (std::vector<std::size_t>{3, 6}));
  ASSERT_TRUE(s.def.bodies[0].collider.has_value());
  EXPECT_EQ(s.def.bodies[0].collider->radius, 0.25);
  const WorldDef def = s.def;
  EXPECT_EQ(def.planes.size(), 2u);
  EXPECT_EQ(World(s.def).planes().size(), 2u);
}

TEST(ScenePlanes, BadValuesAreSceneErrorsWithFileLineAndKey) {
  auto error = [](const std::string& plane) {
    try {
      (void)parse_scene(
          "[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, 1.0]\n"
          "[[plane]]\n" +
              plane,
          "p.toml");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("normal = [0.0, 0.0]\n"),
            "p.toml:7:10: plane[0].normal: must be a non-zero vector (got [0, 0])");
  EXPECT_EQ(error("normal = [0.0, 1.0]\nrestitution = 1.5\n"),
            "p.toml:8:15: plane[0].restitution: must be in [0, 1] (got 1.5)");
  EXPECT_EQ(error("normal = [0.0, 1.0]\nfriction = -1\n"),
            "p.toml:8:12: plane[0].friction: must be >= 0 (got -1)");
  EXPECT_EQ(error("normal = [0.0, nan]\n"),
            "p.toml:7:16: plane[0].normal[1]: must be finite (got nan)");
  EXPECT_EQ(error("offset = 1.0\n"),
            "p.toml:6:1: plane[0].normal: missing (required): [x, y] into free space");
  EXPECT_EQ(
      error("normal = [0.0, 1.0]\noffset = 1.0\npoint = [0.0, 0.0]\n"),
      "p.toml:9:9: plane[0].point: `offset` and `point` both given: a plane takes one of them");
}

}  // namespace
}  // namespace fixstep
