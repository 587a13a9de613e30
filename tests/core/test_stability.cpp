// Stability at the edges of each integrator, the guard at scene load, parameter extremes, and
// float hygiene.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/definition_checks.hpp"
#include "fixstep/core/exact.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_stability.hpp"
#include "link_between.hpp"
#include "scene_guard.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {
using test::check_stability;
using test::enforce_stability;
using test::located_world;

/// Unit-mass undamped oscillator (ω = 1 rad/s) from x = 1 m, stepped at dt = omega_dt.
detail::WorldKernel<double> oscillator(Integrator integrator, double omega_dt) {
  detail::WorldKernel<double> w(WorldSettings{.dt = omega_dt, .integrator = integrator});
  BodyDef d;
  d.body.position = {1.0, 0.0};
  d.spring = SpringDamper{.anchor = {}, .stiffness = 1.0};
  w.create_body(d);
  return w;
}

/// Largest |x| over n steps.
double max_amplitude(detail::WorldKernel<double>& w, int n) {
  double m = 0;
  for (int i = 0; i < n; ++i) {
    w.step();
    m = std::max(m, std::abs(w.x()[0]));
  }
  return m;
}

TEST(StabilityEdges, SymplecticEulerAndVerletBoundedBelowTwoGrowingAbove) {
  for (Integrator i : {Integrator::semi_implicit_euler, Integrator::velocity_verlet}) {
    // At ω·dt = 1.99 the invariant ellipse of the one-step map stretches |x| by at most
    // 1/sqrt(1 - (ω dt/2)²) ≈ 10; 10^5 steps must stay inside it.
    auto w = oscillator(i, 1.99);
    EXPECT_LE(max_amplitude(w, 100'000), 1.0 / std::sqrt(1 - 0.995 * 0.995) + 1e-6)
        << integrator_name(i);
    // At 2.01 the eigenvalues are real, the larger |λ| ≈ 1.22: growth past 1e6 in 200 steps.
    auto u = oscillator(i, 2.01);
    EXPECT_GT(max_amplitude(u, 200), 1e6) << integrator_name(i);
  }
}

TEST(StabilityEdges, Rk4BoundedWithEnergyNonIncreasingAt280GrowingAt285) {
  // |R(iy)|² = 1 - y⁶/72 + y⁸/576: 0.866 at y = 2.80, 1.114 at 2.85; the step is normal in the
  // energy norm, so the energy changes by exactly that factor every step.
  auto w = oscillator(Integrator::rk4, 2.80);
  double e = w.energy().total();
  for (int n = 0; n < 1000; ++n) {
    w.step();
    const double next = w.energy().total();
    ASSERT_LE(next, e) << "step " << n;
    e = next;
  }
  auto u = oscillator(Integrator::rk4, 2.85);
  const double e0 = u.energy().total();
  for (int n = 0; n < 100; ++n) u.step();
  EXPECT_NEAR(u.energy().total() / e0, std::pow(1.1143, 100), 0.05 * std::pow(1.1143, 100));
}

TEST(StabilityEdges, ImplicitEulerLosesEnergyEveryTickEvenAtOmegaDtThousand) {
  for (double omega_dt : {0.1, 10.0, 1000.0}) {
    auto w = oscillator(Integrator::implicit_euler, omega_dt);
    double e = w.energy().total();
    for (int n = 0; n < 40; ++n) {  // at ω·dt = 1000, 40 steps take E0 to 1e-240 J
      w.step();
      const double next = w.energy().total();
      // exactly e / (1 + (ω dt)²) per step for the undamped oscillator
      ASSERT_NEAR(next, e / (1 + omega_dt * omega_dt), 1e-12 * e) << omega_dt;
      ASSERT_LT(next, e);
      e = next;
    }
  }
}

TEST(StabilityEdges, ComputedBoundsMatchTheory) {
  // Largest stable ω·h on the undamped oscillator: symplectic Euler and Verlet 2, RK4 2√2
  // (imaginary-axis limit of its stability function), Forest–Ruth ≈ 1.5734, explicit Euler 0,
  // implicit Euler unbounded. Bisection is to 1e-12; the tolerances allow the scan's tolerance.
  EXPECT_NEAR(max_stable_step(Integrator::semi_implicit_euler, 1.0, 0.0), 2.0, 1e-6);
  EXPECT_NEAR(max_stable_step(Integrator::velocity_verlet, 1.0, 0.0), 2.0, 1e-6);
  EXPECT_NEAR(max_stable_step(Integrator::rk4, 1.0, 0.0), 2.0 * std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(max_stable_step(Integrator::forest_ruth, 1.0, 0.0), 1.5734, 1e-3);
  EXPECT_EQ(max_stable_step(Integrator::explicit_euler, 1.0, 0.0), 0.0);
  EXPECT_TRUE(std::isinf(max_stable_step(Integrator::implicit_euler, 1.0, 0.0)));
  // Explicit Euler with damping γ = 2ζω: stable for ω h < 2ζ (|1 - γh + ...| analysis)
  EXPECT_NEAR(max_stable_step(Integrator::explicit_euler, 1.0, 0.2), 0.2, 1e-6);
  // Pure drag (no spring): v' = -γ v is stable for γh < 2 with either Euler
  EXPECT_NEAR(max_stable_step(Integrator::semi_implicit_euler, 0.0, 3.0), 2.0 / 3.0, 1e-6);
}

TEST(ImplicitEuler, NewtonSolvesTheBackwardEulerEquationsForRestLengthSprings) {
  // A stiff rest-length spring under gravity at a large step: after one step the backward
  // Euler equations x1 = x0 + h v1, v1 = v0 + h a(x1, v1) must hold to round-off (1e-12 of
  // the terms' scale), whatever Newton's path.
  const double h = 0.5, k = 200.0, b = 1.0, c = 0.5, L = 2.0, g = -9.81;
  detail::WorldKernel<double> w(WorldSettings{.dt = h, .integrator = Integrator::implicit_euler});
  BodyDef d;
  d.body = Body{.mass = 2.0, .position = {3.0, 1.0}, .velocity = {-1.0, 4.0}};
  d.spring = SpringDamper{.anchor = {0.0, 0.0}, .stiffness = k, .damping = b, .rest_length = L};
  d.gravity = Gravity{{0.0, g}};
  d.drag = LinearDrag{c};
  w.create_body(d);
  w.step();
  const double x = w.x()[0], y = w.y()[0], vx = w.vx()[0], vy = w.vy()[0];
  const double len = std::hypot(x, y), m = 2.0;
  const double ax = (-k * (len - L) * x / len - (b + c) * vx) / m;
  const double ay = (-k * (len - L) * y / len - (b + c) * vy) / m + g;
  EXPECT_NEAR(x, 3.0 + h * vx, 1e-12 * 10);
  EXPECT_NEAR(y, 1.0 + h * vy, 1e-12 * 10);
  EXPECT_NEAR(vx, -1.0 + h * ax, 1e-12 * 1000);
  EXPECT_NEAR(vy, 4.0 + h * ay, 1e-12 * 1000);
}

TEST(Substeps, ATickOfNSubstepsIsNStepsOfDtOverN) {
  // Bit for bit: substeps only divide the tick; every integrator, f32 and f64.
  for (Integrator i : all_integrators) {
    detail::WorldKernel<float> a(WorldSettings{.dt = 0.04, .integrator = i, .substeps = 4});
    detail::WorldKernel<float> b(WorldSettings{.dt = 0.04 / 4, .integrator = i});
    BodyDef d;
    d.body = Body{.mass = 1.5, .position = {1.0, 2.0}, .velocity = {0.5, 0.0}};
    d.spring = SpringDamper{.anchor = {}, .stiffness = 9.0, .damping = 0.3, .rest_length = 0.5};
    d.drag = LinearDrag{0.1};
    a.create_body(d);
    b.create_body(d);
    for (int t = 0; t < 50; ++t) {
      a.step();
      for (int s = 0; s < 4; ++s) b.step();
    }
    EXPECT_EQ(a.state_hash(), b.state_hash()) << integrator_name(i);
    EXPECT_EQ(a.tick(), 50u);
    EXPECT_EQ(b.tick(), 200u);
  }
}

// --- the guard --------------------------------------------------------------------------------

std::string scene_text(double k, double m, double dt, const char* integrator, int substeps = 1,
                       bool allow = false, double b = 0.0) {
  return fmt::format(
      "[world]\ndt = {}\nintegrator = \"{}\"\nsubsteps = {}\nallow_unstable = {}\n\n"
      "[[body]]\nname = \"bob\"\nmass = {}\nposition = [1.0, 0.0]\n"
      "spring = {{ anchor = [0.0, 0.0], stiffness = {}, damping = {} }}\n",
      dt, integrator, substeps, allow ? "true" : "false", m, k, b);
}

TEST(Guard, RefusesWithTheSmallestStableSubstepCountWhichThenRuns) {
  // k = 400 N/m, m = 1 kg: ω = 20 rad/s; dt = 0.25 s gives ω·dt = 5 > 2 for symplectic Euler,
  // so the smallest stable substep count is ceil(5 / 2) = 3.
  const Scene scene = parse_scene(scene_text(400, 1, 0.25, "semi_implicit_euler"), "stiff.toml");
  try {
    (void)located_world(scene);
    FAIL() << "unstable scene accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.line(), 7u) << what;  // the [[body]] line
    EXPECT_NE(what.find("body 'bob'"), std::string::npos) << what;
    EXPECT_NE(what.find("ω·h = 5 "), std::string::npos) << what;
    EXPECT_NE(what.find("bound 2"), std::string::npos) << what;
    EXPECT_NE(what.find("substeps = 3"), std::string::npos) << what;
  }
  const auto report = check_stability(scene);
  ASSERT_EQ(report.size(), 1u);
  EXPECT_EQ(report[0].min_substeps, 3);

  Scene fixed = parse_scene(scene_text(400, 1, 0.25, "semi_implicit_euler", 3), "stiff.toml");
  World sim = located_world(fixed);
  const double e0 = sim.energy().total();
  for (int i = 0; i < 10'000; ++i) sim.step();
  // bounded: ω h = 5/3, so |E/E0 - 1| <= (ωh)/(1 - ωh/2) = 10 at most, far from blow-up
  EXPECT_LT(sim.energy().total() / e0, 11.0);
  EXPECT_TRUE(std::isfinite(sim.body(sim.bodies()[0]).position.x));
}

TEST(Guard, TheRefusalSaysWhatToDoBeforeTheNumbersThatExplainIt) {
  // What is wrong and what to do come first, so that they survive a reader (or the table of
  // docs/BAD_INPUTS.md) that stops after a couple of hundred characters; the rates and the
  // growth per step follow.
  const Scene stiff = parse_scene(scene_text(400, 1, 0.25, "semi_implicit_euler"), "stiff.toml");
  try {
    (void)located_world(stiff);
    FAIL() << "unstable scene accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("stiff.toml:7: body[0]: body 'bob' is unstable with semi_implicit_euler "
                         "at dt = 0.25 s: ω·h = 5 exceeds the stability bound 2; use substeps = 3 "
                         "in [world] (or dt <= 0.1 s), or set allow_unstable = true — ω = 20 "
                         "rad/s, growth ",
                         0),
              0u)
        << what;
    EXPECT_TRUE(what.ends_with("x per step")) << what;
  }
  const Scene euler = parse_scene(scene_text(1, 1, 0.01, "explicit_euler"), "e.toml");
  try {
    (void)located_world(euler);
    FAIL() << "unstable scene accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("e.toml:7: body[0]: body 'bob' is unstable with explicit_euler at every "
                         "dt: its energy grows each step; use another integrator: "
                         "semi_implicit_euler, velocity_verlet, rk4, implicit_euler or "
                         "forest_ruth, or set allow_unstable = true — ω·h = 0.01, growth ",
                         0),
              0u)
        << what;
  }
}

TEST(Guard, AWorldBuiltInCodeIsJudgedWithoutAScene) {
  // The same stiff body as above (ω·dt = 5 with symplectic Euler) as a WorldDef: World(def)
  // refuses it with the core's finding (UnstableDefinition), which states the fault and the
  // smallest stable substep count and says nothing of scene files (no "[world]", no
  // "allow_unstable"); with def.allow_unstable it builds and keeps the finding as a warning.
  WorldDef def;
  def.settings = {.dt = 0.25, .integrator = Integrator::semi_implicit_euler};
  BodyDef bob;
  bob.name = "bob";
  bob.body.position = {1.0, 0.0};
  bob.spring = SpringDamper{.anchor = {}, .stiffness = 400.0};
  def.bodies.push_back(bob);
  try {
    (void)World(def);
    FAIL() << "unstable world accepted";
  } catch (const UnstableDefinition& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("body 'bob' is unstable"), std::string::npos) << what;
    EXPECT_NE(what.find("ω·h = 5 "), std::string::npos) << what;
    EXPECT_NE(what.find("stable from substeps = 3"), std::string::npos) << what;
    EXPECT_EQ(what.find("[world]"), std::string::npos) << what;
    EXPECT_EQ(what.find("allow_unstable"), std::string::npos) << what;
    ASSERT_TRUE(e.finding().body.has_value());
    EXPECT_EQ(e.finding().body->min_substeps, 3);
    EXPECT_EQ(e.finding().verdict, Stability::unstable);
  }
  EXPECT_THROW((void)check_stability(def), UnstableDefinition);  // the same check, on its own
  def.settings.substeps = 3;
  EXPECT_TRUE(World(def).warnings().empty());
  def.settings.substeps = 1;
  def.allow_unstable = true;
  const World allowed(def);
  ASSERT_EQ(allowed.warnings().size(), 1u);
  EXPECT_NE(allowed.warnings()[0].message.find("body 'bob' is unstable"), std::string::npos)
      << allowed.warnings()[0].message;
  // A link to a body the definition does not have is refused, by World and by the guard.
  def.links.push_back(fixstep::test::link_between(0, 1, {.stiffness = 1.0}));
  EXPECT_THROW((void)World(def), std::invalid_argument);
  EXPECT_THROW((void)check_stability(def), std::invalid_argument);
}

TEST(Guard, AllowUnstableWarnsAndNearLimitWarns) {
  const Scene allowed =
      parse_scene(scene_text(400, 1, 0.25, "semi_implicit_euler", 1, true), "a.toml");
  const auto warnings = enforce_stability(allowed);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("allowed (allow_unstable), so the run may diverge; substeps = 3 in "
                             "[world] (or dt <= 0.1 s) would be stable"),
            std::string::npos)
      << warnings[0];
  // ω·dt = 1.9: stable but within 10 % of 2
  const Scene near = parse_scene(scene_text(361, 1, 0.1, "semi_implicit_euler"), "n.toml");
  const auto near_warnings = enforce_stability(near);
  ASSERT_EQ(near_warnings.size(), 1u);
  EXPECT_NE(near_warnings[0].find("within 10 %"), std::string::npos) << near_warnings[0];
  // explicit Euler on an undamped spring: no substep count helps
  const Scene euler = parse_scene(scene_text(1, 1, 0.01, "explicit_euler"), "e.toml");
  try {
    (void)located_world(euler);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("at every dt"), std::string::npos) << e.what();
  }
}

TEST(Guard, ParameterExtremesRunBoundedOrAreRefusedNeverNaN) {
  // k from 1e-6 to 1e9 N/m, m from 1e-6 to 1e6 kg, dt from 1e-6 to 0.1 s, every integrator:
  // each case is refused with a message naming the body, or runs 2000 ticks with a finite state
  // whose position stays within the exact solution's amplitude (1 m here, plus v0/ω = 0) times
  // the worst stable band 1/sqrt(1 - (ωh/2)²) for ωh <= 1.9 (3.2), and whose error against the
  // exact solution is bounded by that too.
  int ran = 0, refused = 0;
  for (double k : {1e-6, 1.0, 1e9})
    for (double m : {1e-6, 1.0, 1e6})
      for (double dt : {1e-6, 1e-3, 0.1})
        for (Integrator integrator : all_integrators) {
          const std::string name(integrator_name(integrator));
          const Scene scene =
              parse_scene(scene_text(k, m, dt, name.c_str(), 1, false, 0.0), "x.toml");
          std::optional<World> sim;
          try {
            sim.emplace(located_world(scene));
          } catch (const SceneError& e) {
            ++refused;
            EXPECT_NE(std::string(e.what()).find("body 'bob'"), std::string::npos) << e.what();
            continue;
          }
          ++ran;
          for (int i = 0; i < 2000; ++i) sim->step();
          const Body b = sim->body(sim->bodies()[0]);
          const auto exact = exact::solve(scene.def.bodies[0], sim->time());
          const std::string where = fmt::format("{} k={} m={} dt={}", name, k, m, dt);
          ASSERT_TRUE(std::isfinite(b.position.x) && std::isfinite(b.velocity.x)) << where;
          EXPECT_LE(std::abs(b.position.x), 3.3) << where;
          EXPECT_LE(std::abs(b.position.x - exact->position.x), 4.3) << where;
        }
  EXPECT_GT(ran, 100);     // most cases run...
  EXPECT_GT(refused, 10);  // ...and the stiff ones at large dt are refused
}

// --- float hygiene ------------------------------------------------------------------------

bool any_subnormal(const detail::WorldKernel<float>& w) {
  for (auto span : {w.x(), w.y(), w.vx(), w.vy()})
    for (float v : span)
      if (std::fpclassify(v) == FP_SUBNORMAL) return true;
  return false;
}

TEST(FloatHygiene, DampedF32StateFlushesToZeroInsteadOfStayingSubnormal) {
  // A strongly damped f32 spring (ζ = 2.5) decays by e^{-0.1} per tick: it passes 1e-38 after
  // some 900 ticks. With flush_denormals a damped body's values are flushed below 2^-55 at the
  // end of every step, so no tick leaves a subnormal state and the state ends exactly 0
  // (tests/core/test_subnormals.cpp counts the subnormals produced within the ticks too);
  // without, the state stays subnormal for hundreds of ticks.
  for (bool flush : {true, false}) {
    detail::WorldKernel<float> w(WorldSettings{.dt = 0.01, .flush_denormals = flush});
    BodyDef d;
    d.body.position = {1.0, 1.0};
    d.spring = SpringDamper{.anchor = {}, .stiffness = 100.0, .damping = 50.0};
    w.create_body(d);
    int subnormal_ticks = 0;
    for (int i = 0; i < 20'000; ++i) {
      w.step();
      subnormal_ticks += any_subnormal(w);
    }
    if (flush) {
      EXPECT_EQ(subnormal_ticks, 0);
      EXPECT_EQ(w.x()[0], 0.0f);
      EXPECT_EQ(w.vx()[0], 0.0f);
    } else {
      EXPECT_GT(subnormal_ticks, int(flush_denormals_every));
    }
  }
}

// A rate so small that the dimensionless scan's step s / γ overflows (a
// subnormal drag, or a drag over a huge mass) made World refuse an infinite dt, and the scene
// got "world: dt must be finite and > 0 s (got inf)" with no file or key. Every step is
// stable then: the bound is infinite and the scene loads and runs.
TEST(Stability, ARateSoSmallItsBoundOverflowsIsStableAtEveryStep) {
  for (const Integrator i : {Integrator::semi_implicit_euler, Integrator::explicit_euler,
                             Integrator::rk4, Integrator::implicit_euler}) {
    EXPECT_EQ(max_stable_step(i, 0.0, 1e-310), std::numeric_limits<double>::infinity())
        << integrator_name(i);
  }
  // The smallest rate a scene can give, γ = c/m = 1e-100 / 1e100 (value_ranges.hpp): its bound
  // is far beyond any dt, and the world steps. Rates below it (a subnormal drag, a drag over a
  // mass of 1e308) are refused at their key now.
  const Scene s = parse_scene(
      "[world]\ndt = 0.01\n[[body]]\nposition = [0.0, 0.0]\nmass = 1e100\ndrag = 1e-100\n",
      "s.toml");
  EXPECT_NO_THROW((void)enforce_stability(s));
  World sim = World(s.def);
  sim.step({});
  EXPECT_EQ(sim.body(sim.defined_bodies()[0]).position, (Vec2{0.0, 0.0}));
  for (const char* body :
       {"mass = 1.0\ndrag = 1e-310", "mass = 1e308\ndrag = 1.0", "mass = 1.0\ndrag = 4.9e-324"}) {
    EXPECT_THROW((void)parse_scene(
                     fmt::format("[world]\ndt = 0.01\n[[body]]\nposition = [0.0, 0.0]\n{}\n", body),
                     "s.toml"),
                 SceneError)
        << body;
  }
}

}  // namespace
}  // namespace fixstep
