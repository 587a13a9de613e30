// Rolling discs (ContactSettings::rolling): friction at the contact point turns the discs.
// Exact checks: a disc released on an incline rolls at a = g sin θ / (1 + I/(m r²)) (⅔ g sin θ
// for a uniform disc) when μ >= tan θ / (1 + m r²/I) and slides at g (sin θ - μ cos θ)
// otherwise; a disc spinning at ω0 dropped on the ground ends rolling at v = I ω0 r / (I +
// m r²) (ω0 r / 3 for a uniform disc), from its angular momentum about the contact point; a
// gas keeps its angular momentum about a point (orbital plus spin), elastic and frictionless
// (no disc turns) as with friction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "packed_pile.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

constexpr Integrator rolling_integrators[] = {
    Integrator::explicit_euler,  Integrator::semi_implicit_euler,
    Integrator::velocity_verlet, Integrator::rk4,
    Integrator::implicit_euler,  Integrator::forest_ruth};

WorldSettings rolling_world(double e, double mu, Integrator integrator) {
  WorldSettings s{.dt = 1.0 / 60.0, .integrator = integrator, .track_dissipation = true};
  s.contacts = ContactSettings{.restitution = e, .friction = mu, .rolling = true};
  return s;
}

BodyDef rolling_disc(Vec2 x, Vec2 v, double r, double w, std::optional<double> inertia = {}) {
  BodyDef b;
  b.body = Body{.mass = 2.0, .position = x, .velocity = v, .angular_velocity = w};
  b.gravity = Gravity{{0.0, -9.81}};
  b.collider = Collider{.radius = r, .inertia = inertia};
  return b;
}

struct InclineRun {
  double accel;  ///< along the slope, down, m/s² (from the speed after `ticks`)
  double slip;   ///< |v| - ω r at the end, m/s (0: rolling)
};

/// A disc (m = 2 kg, r = 0.25 m) released at rest on an incline of angle θ (rad), friction μ,
/// for `ticks` ticks.
InclineRun incline(double theta, double mu, Integrator integrator, std::optional<double> inertia,
                   int ticks) {
  detail::WorldKernel<double> w(rolling_world(0.0, mu, integrator));
  const Vec2 n{-std::sin(theta), std::cos(theta)};
  w.add_plane(PlaneDef{.normal = n, .offset = 0.0, .restitution = 0.0, .friction = mu});
  const double r = 0.25;
  w.create_body(rolling_disc({r * n.x, r * n.y}, {}, r, 0.0, inertia));
  for (int i = 0; i < ticks; ++i) w.step();
  const double down = -(w.vx()[0] * std::cos(theta) + w.vy()[0] * std::sin(theta));
  return {down / (ticks * w.settings().dt), down - w.angular_velocity()[0] * r};
}

TEST(Rolling, ADiscRollsDownAnInclineAtTwoThirdsGSinTheta) {
  const double g = 9.81, theta = std::numbers::pi / 6;  // tan θ / 3 = 0.192
  for (const Integrator integrator : rolling_integrators) {
    for (const double mu : {0.2, 0.5, 1.0}) {
      const InclineRun run = incline(theta, mu, integrator, std::nullopt, 120);
      EXPECT_NEAR(run.accel, 2.0 / 3.0 * g * std::sin(theta), 1e-9) << int(integrator) << mu;
      EXPECT_NEAR(run.slip, 0.0, 1e-9) << int(integrator) << mu;
    }
  }
}

TEST(Rolling, ADiscSlidesDownAnInclineBelowAThirdOfTanTheta) {
  const double g = 9.81, theta = std::numbers::pi / 6;
  for (const Integrator integrator : rolling_integrators) {
    for (const double mu : {0.0, 0.1, 0.18}) {
      const InclineRun run = incline(theta, mu, integrator, std::nullopt, 120);
      EXPECT_NEAR(run.accel, g * (std::sin(theta) - mu * std::cos(theta)), 1e-9)
          << int(integrator) << mu;
      if (mu > 0.0) {
        EXPECT_GT(run.slip, 0.1) << int(integrator) << mu;
      }
    }
  }
}

TEST(Rolling, ARingRollsAtHalfGSinThetaWhenItsInertiaIsGiven) {
  // I = m r² (a ring): a = g sin θ / 2 when μ >= tan θ / 2 (0.289 at 30°), else sliding.
  const double g = 9.81, theta = std::numbers::pi / 6, ring = 2.0 * 0.25 * 0.25;
  const InclineRun rolls = incline(theta, 0.3, Integrator::semi_implicit_euler, ring, 120);
  EXPECT_NEAR(rolls.accel, 0.5 * g * std::sin(theta), 1e-9);
  const InclineRun slides = incline(theta, 0.25, Integrator::semi_implicit_euler, ring, 120);
  EXPECT_NEAR(slides.accel, g * (std::sin(theta) - 0.25 * std::cos(theta)), 1e-9);
}

TEST(Rolling, ASpinningDiscDroppedOnTheGroundLeavesAtAThirdOfOmegaR) {
  // Friction at the contact point keeps the angular momentum about it, I ω + m r v: from
  // v = 0, ω0 it ends rolling at ω = ω0 I / (I + m r²) = ω0 / 3, v = ω0 r / 3 (to the left for
  // ω0 > 0, counter-clockwise).
  const double r = 0.25, w0 = 12.0;
  for (const Integrator integrator : rolling_integrators) {
    for (const double mu : {0.05, 0.3, 2.0}) {
      detail::WorldKernel<double> w(rolling_world(0.0, mu, integrator));
      w.add_plane(PlaneDef{.normal = {0, 1}, .offset = 0.0, .restitution = 0.0, .friction = mu});
      w.create_body(rolling_disc({0.0, r + 0.3}, {}, r, w0));
      for (int i = 0; i < 600; ++i) w.step();
      EXPECT_NEAR(w.vx()[0], -w0 * r / 3.0, 1e-9) << int(integrator) << mu;
      EXPECT_NEAR(w.angular_velocity()[0], w0 / 3.0, 1e-9) << int(integrator) << mu;
      EXPECT_NEAR(w.vy()[0], 0.0, 1e-9) << int(integrator) << mu;
      // What friction took is in the account: ½ I ω0² - (½ I ω² + ½ m v²) = ⅔ · ½ I ω0².
      const double spin0 = 0.5 * (0.5 * 2.0 * r * r) * w0 * w0;
      EXPECT_NEAR(w.energy().kinetic, spin0 / 3.0, 1e-9 * spin0) << int(integrator) << mu;
    }
  }
}

TEST(Rolling, ASpinningDiscDroppedOnABigStaticDiscLeavesAtAThirdOfOmegaR) {
  // The same through disc contacts (the impact at landing, then the resting solver): a static
  // disc of radius 100 km is locally flat ground. The dropped disc stops slipping after about
  // 0.6 s and has rolled about 1 m at 2 s, where the ground has turned by 1e-5 rad: gravity
  // along it has added about 1e-4 m/s by then, within the tolerance of 1e-4 ω0 r (3e-4 m/s).
  const double r = 0.25, w0 = 12.0, big = 1e5;
  for (const Integrator integrator : rolling_integrators) {
    detail::WorldKernel<double> w(rolling_world(0.0, 0.3, integrator));
    w.create_body(rolling_disc({0.0, r + 0.3}, {}, r, w0));
    BodyDef ground;
    ground.type = BodyType::static_body;
    ground.body.position = {0.0, -big};
    ground.collider = Collider{.radius = big};
    w.create_body(ground);
    for (int i = 0; i < 120; ++i) w.step();
    EXPECT_NEAR(w.vx()[0], -w0 * r / 3.0, 1e-4 * w0 * r) << int(integrator);
    EXPECT_NEAR(w.angular_velocity()[0], w0 / 3.0, 1e-4 * w0) << int(integrator);
  }
}

/// Angular momentum about the origin, orbital Σ m x × v plus spin Σ I ω, kg·m²/s.
double angular_momentum(const detail::WorldKernel<double>& w, double r) {
  double l = 0.0;
  for (std::size_t k = 0; k < w.body_count(); ++k) {
    const Body b = w.body(w.entities()[k]);
    l += b.mass * (b.position.x * b.velocity.y - b.position.y * b.velocity.x);
    l += 0.5 * b.mass * r * r * b.angular_velocity;
  }
  return l;
}

/// A gas of 400 discs (r = 0.1 m, 1–2 kg, random velocities and spins), elastic, friction μ,
/// rolling; returns (L at the start, L after 300 ticks, impacts, the largest spin change).
struct GasRun {
  double l0, l1;
  std::size_t impacts;
  double spin_change;
};
GasRun rolling_gas(double mu) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  WorldSettings s{.dt = 1.0 / 60.0};
  s.contacts = ContactSettings{.restitution = 1.0, .friction = mu, .rolling = true};
  detail::WorldKernel<double> w(s);
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) {
      BodyDef b;
      b.body = Body{.mass = 1.0 + 0.5 * (u(rng) + 1.0),
                    .position = {0.5 * i, 0.5 * j},
                    .velocity = {2.0 * u(rng), 2.0 * u(rng)},
                    .angular_velocity = 20.0 * u(rng)};
      b.collider = Collider{.radius = 0.1};
      w.create_body(b);
    }
  }
  std::vector<double> spin0(w.angular_velocity().begin(), w.angular_velocity().end());
  GasRun run{angular_momentum(w, 0.1), 0, 0, 0};
  for (int i = 0; i < 300; ++i) {
    w.step();
    run.impacts += w.contact_stats().impacts;
  }
  run.l1 = angular_momentum(w, 0.1);
  for (std::size_t k = 0; k < spin0.size(); ++k) {
    run.spin_change = std::max(run.spin_change, std::abs(w.angular_velocity()[k] - spin0[k]));
  }
  return run;
}

TEST(Rolling, AnElasticFrictionlessGasKeepsItsAngularMomentum) {
  const GasRun run = rolling_gas(0.0);
  EXPECT_GT(run.impacts, 200u);
  EXPECT_EQ(run.spin_change, 0.0);  // no friction, no turn
  EXPECT_NEAR(run.l1, run.l0, 1e-9 * std::abs(run.l0));
}

TEST(Rolling, AnElasticGasWithFrictionKeepsItsAngularMomentum) {
  // Each friction impulse P acts at the contact point: the orbital change (r_a + r_b) n × P is
  // the spins' -(r_a + r_b) |P| back.
  const GasRun run = rolling_gas(0.5);
  EXPECT_GT(run.impacts, 200u);
  EXPECT_GT(run.spin_change, 1.0);  // the discs did turn each other
  EXPECT_NEAR(run.l1, run.l0, 1e-9 * std::abs(run.l0));
}

// Two discs fall side by side onto a rough floor (μ = 1, e = 0) at the same height and speed;
// B, moving right at 3 m/s, meets A, at rest across, 4 ms into the tick, before either reaches
// the floor (12 ms in): elastic and of equal mass, they swap their horizontal velocities with
// no slip between them (their relative velocity lies along the line of centres), so B lands
// with no horizontal velocity and does not turn, and A lands sliding at 3 m/s and ends rolling
// (v = ω r at the end of the tick: its slip stopped within μ's bound). The plane pass, which
// meets the floor before the disc impacts on each disc's own free motion, turned B by B's
// slip; before the disc pass took a disc's spin from the plane pass only with its motion, B
// landed with that turn and no velocity to match, and rolled off at 0.44 m/s (-4.4 rad/s).
TEST(Rolling, ADiscKnockedBeforeItLandsTurnsByItsOwnLanding) {
  WorldSettings s = rolling_world(1.0, 1.0, Integrator::semi_implicit_euler);
  detail::WorldKernel<double> w(s);
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.0, .friction = 1.0});
  const double r = 0.1, u = 3.0, fall = 1.0, meet = 0.004, land = 0.012;
  // Falling at `fall` m/s under g, they reach the floor `land` s into the tick.
  const double y = r + fall * land + 0.5 * 9.81 * land * land;
  w.create_body(rolling_disc({0.0, y}, {0.0, -fall}, r, 0.0));                // A
  w.create_body(rolling_disc({-2.0 * r - u * meet, y}, {u, -fall}, r, 0.0));  // B
  w.step();
  ASSERT_FALSE(w.fault().has_value());
  EXPECT_EQ(w.contact_stats().impacts, 1u);
  EXPECT_NEAR(w.vx()[1], 0.0, 1e-9);
  EXPECT_NEAR(w.angular_velocity()[1], 0.0, 1e-9);  // B lands without turning
  EXPECT_GT(w.vx()[0], 1.0);                        // A slid on and now rolls
  EXPECT_NEAR(w.vx()[0] + w.angular_velocity()[0] * r, 0.0, 1e-9);
}

// The pile of bench/discs_scene.cpp with rolling discs: 6 000 discs (r = 5 cm, 1 kg) packed
// hexagonally 10 rows deep wall to wall, dropped from a millionth of a diameter apart, plastic
// (e = 0, μ = 0.5). They settle within half a second as the discs without rolling do. Before a
// pair past the impact cap with a disc that met the floor was left to the resting solver where
// the disc ends the tick on the floor, such pairs were held where they met for the rest of the
// tick, and through the held discs' pairs whole columns above them: the pile held hundreds to
// thousands of discs a tick and did not settle (kinetic energy 1.2 J at ticks 30–40, its
// deepest overlap four times the slop).
TEST(Rolling, APileOfRollingDiscsSettles) {
  WorldSettings s{.dt = 1.0 / 60.0};
  s.contacts = ContactSettings{.restitution = 0.0, .friction = 0.5, .rolling = true};
  detail::WorldKernel<double> w(s);
  const double r = 0.05;
  test::add_packed_pile(w, 10, 600, r, 0.5);
  auto kinetic = [&] {
    double e = 0.0;
    for (std::size_t k = 0; k < w.body_count(); ++k) {
      e += 0.5 * (w.vx()[k] * w.vx()[k] + w.vy()[k] * w.vy()[k]);
    }
    return e;
  };
  double most = 0.0;
  for (int tick = 1; tick <= 40; ++tick) {
    w.step();
    ASSERT_FALSE(w.fault().has_value());
    if (tick >= 30) most = std::max(most, kinetic());
  }
  EXPECT_LT(most, 1e-3);  // J, over 5 994 discs: at rest
  EXPECT_LE(w.contact_stats().max_overlap, 0.0051 * r);
}

TEST(Rolling, WorldsWithoutRollingStoreNoAngle) {
  WorldSettings s{.dt = 1.0 / 60.0};
  s.contacts = ContactSettings{.friction = 0.5};
  detail::WorldKernel<double> w(s);
  w.create_body(rolling_disc({0.0, 1.0}, {}, 0.25, 5.0));
  w.step();
  EXPECT_TRUE(w.angle().empty());
  EXPECT_TRUE(w.angular_velocity().empty());
  EXPECT_EQ(w.body(w.entities()[0]).angular_velocity, 0.0);
}

TEST(Rolling, TheAngleFollowsTheSpinAndStaysWithinAHalfTurn) {
  detail::WorldKernel<double> w(rolling_world(0.0, 0.0, Integrator::semi_implicit_euler));
  BodyDef b = rolling_disc({0.0, 0.0}, {}, 0.25, 3.0);
  b.gravity.reset();
  w.create_body(b);
  for (int i = 0; i < 600; ++i) {
    w.step();
    ASSERT_LE(std::abs(w.angle()[0]), std::numbers::pi);
  }
  // 10 s at 3 rad/s: 30 rad, less 5 turns.
  EXPECT_NEAR(w.angle()[0], 30.0 - 10.0 * std::numbers::pi, 1e-9);
}

TEST(Rolling, TheStateHashCoversTheSpin) {
  auto hash = [](double w0) {
    detail::WorldKernel<double> w(rolling_world(0.0, 0.0, Integrator::semi_implicit_euler));
    w.create_body(rolling_disc({0.0, 1.0}, {}, 0.25, w0));
    return w.state_hash();
  };
  EXPECT_NE(hash(1.0), hash(2.0));
}

}  // namespace
}  // namespace fixstep
