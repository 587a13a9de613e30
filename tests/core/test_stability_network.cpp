// The network stability guard: ω_max by power iteration against closed forms, its predicted
// largest stable step against the step at which a linked World really diverges (chains of
// 2 to 1000 bodies, equal and 1:1000 masses, damped links with their swept flows), and
// the guard at scene load and in explain_fault.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_stability.hpp"
#include "link_between.hpp"
#include "scene_guard.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {
using test::check_scene_network;
using test::check_stability;
using test::enforce_stability;
using test::located_world;

enum class Masses { equal, alternating, graded };  // 1:1, 1:1000 alternating, 1 .. 1000 graded

const char* masses_name(Masses m) {
  return m == Masses::equal         ? "1:1"
         : m == Masses::alternating ? "1:1000 alternating"
                                    : "1..1000 graded";
}

/// A chain of n bodies with rest length 0: body 0 anchored at the origin by k, body i linked
/// to body i + 1 by k (and b). Started in the alternating displacement x_i = (-1)^i m, which
/// excites the top mode (the fastest mode of a chain alternates from body to body).
struct Chain {
  std::vector<BodyDef> bodies;
  std::vector<LinkDef> links;
};

Chain chain(std::size_t n, Masses masses, double k = 1.0, double b = 0.0) {
  Chain c;
  for (std::size_t i = 0; i < n; ++i) {
    BodyDef d;
    d.name = fmt::format("c{}", i);
    const double u = n > 1 ? double(i) / double(n - 1) : 0.0;
    d.body.mass = masses == Masses::equal         ? 1.0
                  : masses == Masses::alternating ? (i % 2 ? 1000.0 : 1.0)
                                                  : std::pow(1000.0, u);
    d.body.position = {i % 2 ? -1.0 : 1.0, 0.0};
    if (i == 0) d.spring = SpringDamper{.anchor = {}, .stiffness = k, .damping = b};
    c.bodies.push_back(d);
    if (i > 0) c.links.push_back(fixstep::test::link_between(i - 1, i, LinkSpring{k, b, 0.0}));
  }
  return c;
}

/// Steps the chain in a detail::WorldKernel<double> at step h for up to `ticks` ticks; returns the
/// largest |x| seen over start |x| = 1 m, stopping early once it passes `stop`.
double growth(const Chain& c, Integrator integrator, double h, int ticks, double stop,
              DampingSplit split = DampingSplit::per_stage) {
  detail::WorldKernel<double> w(
      WorldSettings{.dt = h, .integrator = integrator, .threads = 1, .damping_split = split});
  std::vector<Entity> e;
  for (const BodyDef& d : c.bodies) e.push_back(w.create_body(d));
  for (const LinkDef& l : c.links)
    w.create_link(LinkDef{e[l.body_a.slot()], e[l.body_b.slot()], l.spring});
  double largest = 1.0;
  for (int t = 0; t < ticks && largest <= stop; ++t) {
    w.step();
    for (double x : w.x()) largest = std::max(largest, std::abs(x));
  }
  return largest;
}

TEST(NetworkOmega, PowerIterationMatchesTheUniformChainWithinThreePermille) {
  // Anchored uniform chain: K = k T, T tridiagonal (2, -1) with 1 in the free end's corner;
  // eigenvalues 4 sin²((2j - 1)π / (2(2n + 1))), j = 1..n. The top ones cluster (gap ~ 1/n²),
  // yet the Rayleigh quotient converges in value (the guard needs ω_max to 1 %; the stopping
  // rule aims at 5e-4 and its estimate may be up to 3 times short).
  for (std::size_t n : {1u, 2u, 10u, 100u, 1000u}) {
    const Chain c = chain(n, Masses::equal, 4.0);
    const NetworkStability r =
        check_network_stability(c.bodies, c.links, Integrator::semi_implicit_euler, 0.01, 1);
    const double exact = 2.0 * 2.0 * std::sin((2.0 * n - 1.0) * std::numbers::pi / (4.0 * n + 2.0));
    SCOPED_TRACE(fmt::format("n = {}: {} iterations, estimated shortfall {:.2g}", n, r.iterations,
                             r.omega_error));
    EXPECT_LE(r.omega_max, exact * (1 + 1e-12));  // a Rayleigh quotient: never above
    EXPECT_GT(r.omega_max, exact * (1 - 3e-3));
    EXPECT_LE(exact / r.omega_max - 1.0, 3.0 * r.omega_error + 1e-12);
    EXPECT_LE(r.iterations, 1000);
    EXPECT_EQ(r.bodies, n);
    EXPECT_EQ(r.springs, n - 1);
  }
}

TEST(NetworkOmega, RestLengthSpringIsStiffestAlongItself) {
  // One body on an anchored spring with L > 0, stretched or compressed: the tangent stiffness
  // has k along the spring and k(1 - L/ℓ) (clamped at 0) across, so ω_max = sqrt(k/m) as the
  // per-body guard has it.
  for (double len : {0.5, 3.0}) {
    BodyDef d;
    d.body = Body{.mass = 2.0, .position = {0.6 * len, 0.8 * len}};
    d.spring = SpringDamper{.anchor = {}, .stiffness = 50.0, .damping = 0.0, .rest_length = 1.0};
    const NetworkStability r =
        check_network_stability(std::span(&d, 1), {}, Integrator::rk4, 0.01, 1);
    EXPECT_NEAR(r.omega_max, 5.0, 5.0 * 1e-6) << len;
  }
}

TEST(NetworkOmega, StiffnessPerMassBeyondADoubleIsUnstableNotNaN) {
  Chain c = chain(3, Masses::equal);
  c.bodies[1].body.mass = 1e-300;
  c.links[1].spring.stiffness = 1e300;  // k/m = 1e600 1/s²
  for (Integrator integrator : all_integrators) {
    const NetworkStability r = check_network_stability(c.bodies, c.links, integrator, 0.01, 1);
    EXPECT_EQ(r.verdict, Stability::unstable);
    EXPECT_NE(r.message.find("beyond the range of a double"), std::string::npos) << r.message;
  }
}

struct DivergenceCase {
  std::size_t n;
  Masses masses;
  Integrator integrator;
  double b;  // link and anchor damping, N*s/m
};

/// The guard's largest stable step h* must bracket the divergence of the real World: bounded
/// (max |x| < 20 start over 2000 ticks) at 0.97 h*, growing past 1e3 start within 3000 ticks
/// at 1.03 h*. So h* is within 3 % of the measured threshold.
void expect_bracketed(const DivergenceCase& c, bool conservative_only = false) {
  const Chain ch = chain(c.n, c.masses, 1.0, c.b);
  const NetworkStability r = check_network_stability(ch.bodies, ch.links, c.integrator, 1.0, 1);
  SCOPED_TRACE(
      fmt::format("{} bodies, masses {}, {}, b = {}: h* = {:.6g} s ({}, ω_max = {:.6g}, "
                  "λ_max(M⁻¹C) = {:.6g})",
                  c.n, masses_name(c.masses), integrator_name(c.integrator), c.b, r.max_step,
                  r.damping_bound ? "damping mode" : "top mode", r.omega_max, r.damping_rate));
  ASSERT_TRUE(std::isfinite(r.max_step) && r.max_step > 0.0);
  EXPECT_LT(growth(ch, c.integrator, 0.97 * r.max_step, 2000, 1e6), 20.0);
  if (!conservative_only) {
    EXPECT_GT(growth(ch, c.integrator, 1.03 * r.max_step, 3000, 1e3), 1e3);
  }
}

TEST(NetworkGuard, PredictedStepBracketsTheDivergenceOfUndampedChains) {
  for (Integrator integrator : {Integrator::semi_implicit_euler, Integrator::rk4}) {
    for (Masses masses : {Masses::equal, Masses::alternating, Masses::graded}) {
      for (std::size_t n : {2u, 10u, 100u, 1000u}) {
        expect_bracketed({n, masses, integrator, 0.0});
      }
    }
  }
}

TEST(NetworkGuard, PredictedStepBracketsTheDivergenceOfDampedChains) {
  // b = 5 N*s/m on k = 1 N/m: λ_max(M⁻¹C) ≈ 20 1/s against ω_max ≈ 2 rad/s, so the damping
  // binds: symplectic Euler's explicit damping near γh = 2 and RK4's near 2.785; Verlet's and
  // Forest–Ruth's swept link damping at the measured λh = 5.0 and 1.8, which only bound the
  // divergence from below (a 2-body chain under Verlet holds to λh ≈ 43, 100 bodies to 5.5):
  // for them the guard is conservative, not sharp. Lightly damped (b = 0.05), the top mode
  // binds instead and is sharp for all four.
  for (Integrator integrator : {Integrator::semi_implicit_euler, Integrator::rk4,
                                Integrator::velocity_verlet, Integrator::forest_ruth}) {
    for (double b : {5.0, 0.05}) {
      const bool swept = b > 1.0 && (integrator == Integrator::velocity_verlet ||
                                     integrator == Integrator::forest_ruth);
      for (std::size_t n : {2u, 10u, 100u})
        expect_bracketed({n, Masses::equal, integrator, b}, swept);
      expect_bracketed({10, Masses::alternating, integrator, b}, swept);
    }
  }
}

// Forest–Ruth with DampingSplit::per_step sweeps the links' damping once per step over h/2,
// never over the inner stage's negative w0·h/2 as per_stage does (the flow that amplifies and
// sets per_stage's measured bound, λh = 1.8). The guard judges both by per_stage's bound: at
// 0.97 of the guard's step every heavily damped chain must stay bounded under per_step too.
TEST(NetworkGuard, PerStepDampingSplitIsStableWhereTheGuardAllowsForestRuth) {
  for (std::size_t n : {2u, 10u, 100u}) {
    for (Masses masses : {Masses::equal, Masses::alternating}) {
      const Chain ch = chain(n, masses, 1.0, 5.0);
      const NetworkStability r =
          check_network_stability(ch.bodies, ch.links, Integrator::forest_ruth, 1.0, 1);
      EXPECT_LT(
          growth(ch, Integrator::forest_ruth, 0.97 * r.max_step, 2000, 1e6, DampingSplit::per_step),
          20.0)
          << n << " bodies, " << masses_name(masses);
    }
  }
}

TEST(NetworkGuard, NonProportionalDampingBindsThroughTheDampingMode) {
  // An undamped uniform chain of 10 (ω_max ≈ 2 rad/s) with an 11th body hung from its end by
  // a soft dashpot (k = 0.01 N/m, b = 5 N*s/m): the fastest mode is hardly damped, but the
  // dashpot's own mode decays at λ_max(M⁻¹C) ≈ 10 1/s. Not proportional, so no mode carries
  // both; the guard's damping mode (0, λ_max) must find the bound.
  for (Integrator integrator : {Integrator::semi_implicit_euler, Integrator::rk4,
                                Integrator::velocity_verlet, Integrator::forest_ruth}) {
    Chain c = chain(10, Masses::equal);
    BodyDef tail;
    tail.name = "tail";
    tail.body.position = {1.0, 0.0};
    c.bodies.push_back(tail);
    c.links.push_back(fixstep::test::link_between(9, 10, LinkSpring{0.01, 5.0, 0.0}));
    const NetworkStability r = check_network_stability(c.bodies, c.links, integrator, 1.0, 1);
    SCOPED_TRACE(fmt::format("{}: h* = {:.6g} s, λ_max(M⁻¹C) = {:.6g}", integrator_name(integrator),
                             r.max_step, r.damping_rate));
    EXPECT_TRUE(r.damping_bound);
    EXPECT_EQ(r.strongest_damper, std::optional<std::size_t>(9));
    EXPECT_LT(growth(c, integrator, 0.97 * r.max_step, 2000, 1e6), 20.0);
    // Verlet and Forest–Ruth: the swept bound is conservative (see the damped chains).
    if (integrator == Integrator::semi_implicit_euler || integrator == Integrator::rk4) {
      EXPECT_GT(growth(c, integrator, 1.03 * r.max_step, 3000, 1e3), 1e3);
    }
  }
}

// --- static and kinematic bodies: immovable anchors -------------------------------------------

/// A 1 kg body linked by k (N/m, rest length 0) to a 1e-6 kg body of type `type`, anchored
/// by nothing else.
Chain anchored_pair(BodyType type, double k) {
  Chain c;
  BodyDef bob, anchor;
  bob.name = "bob";
  bob.body = Body{.mass = 1.0, .position = {1.0, 0.0}};
  anchor.name = "hook";
  anchor.type = type;
  anchor.body.mass = 1e-6;  // ignored unless dynamic
  c.bodies = {bob, anchor};
  c.links = {fixstep::test::link_between(0, 1, LinkSpring{k, 0.0, 0.0})};
  return c;
}

TEST(NetworkAnchors, ALinkToAStaticOrKinematicBodyIsJudgedWithTheDynamicMassAlone) {
  // k = 100 N/m on 1 kg: ω = 10 rad/s, ω·h = 1 at h = 0.1 s, within symplectic Euler's 2. Were
  // the 1e-6 kg end free, the pair's ω = sqrt(k/μ) ≈ 1e4 rad/s would be refused.
  for (const BodyType type : {BodyType::static_body, BodyType::kinematic}) {
    const Chain c = anchored_pair(type, 100.0);
    const NetworkStability r =
        check_network_stability(c.bodies, c.links, Integrator::semi_implicit_euler, 0.1, 1);
    EXPECT_NEAR(r.omega_max, 10.0, 1e-9) << body_type_name(type);
    EXPECT_EQ(r.verdict, Stability::stable) << r.message;
    EXPECT_EQ(r.fastest_body, fixstep::defined_entity(0));  // the anchor never moves
    EXPECT_EQ(r.stiffest_link, std::optional<std::size_t>(0));
  }
  const Chain free = anchored_pair(BodyType::dynamic, 100.0);
  EXPECT_EQ(
      check_network_stability(free.bodies, free.links, Integrator::semi_implicit_euler, 0.1, 1)
          .verdict,
      Stability::unstable);
  // Its mass need not be valid: it is not used.
  Chain zero = anchored_pair(BodyType::static_body, 100.0);
  zero.bodies[1].body.mass = 0.0;
  EXPECT_NO_THROW((void)check_network_stability(zero.bodies, zero.links,
                                                Integrator::semi_implicit_euler, 0.1, 1));
}

TEST(NetworkAnchors, StiffestLinkWeighsAnAnchoredLinkByTheDynamicMass) {
  // 'a' (1 kg) linked to the static 'hook' by k = 100 (k/m = 100) and to 'b' (1 kg) by k = 60
  // (k/μ = 120): the stiffest is a–b. With the hook's 1e-6 kg counted, hook–a would be.
  Chain c = anchored_pair(BodyType::static_body, 100.0);
  c.bodies[0].name = "a";
  BodyDef b;
  b.name = "b";
  b.body = Body{.mass = 1.0, .position = {2.0, 0.0}};
  c.bodies.push_back(b);
  c.links.push_back(fixstep::test::link_between(0, 2, LinkSpring{60.0, 0.0, 0.0}));
  const NetworkStability r =
      check_network_stability(c.bodies, c.links, Integrator::semi_implicit_euler, 0.01, 1);
  EXPECT_EQ(r.stiffest_link, std::optional<std::size_t>(1));
  // ω_max of [[160, -60], [-60, 60]] (anchored a, free b): 110 + sqrt(50² + 60²).
  EXPECT_NEAR(r.omega_max * r.omega_max, 110.0 + std::hypot(50.0, 60.0), 0.2);
}

TEST(NetworkAnchors, LinksBetweenTwoAnchorsAndAnchorsOwnSpringsDoNothing) {
  // A stable 1 kg body on k = 100, plus two static bodies joined by k = 1e12 and a static body
  // with a 1e12 N/m spring and 1e-9 kg: neither counts, per body or in the network.
  Chain c = anchored_pair(BodyType::static_body, 100.0);
  BodyDef s1, s2;
  s1.type = s2.type = BodyType::static_body;
  s1.name = "s1", s2.name = "s2";
  s1.body.mass = s2.body.mass = 1e-9;
  s2.body.position = {1.0, 0.0};
  s1.spring = SpringDamper{.anchor = {}, .stiffness = 1e12, .damping = 1e6};
  c.bodies.push_back(s1);
  c.bodies.push_back(s2);
  c.links.push_back(fixstep::test::link_between(2, 3, LinkSpring{1e12, 1e6, 0.0}));
  const NetworkStability r =
      check_network_stability(c.bodies, c.links, Integrator::semi_implicit_euler, 0.1, 1);
  EXPECT_NEAR(r.omega_max, 10.0, 1e-9);
  EXPECT_EQ(r.damping_rate, 0.0);
  EXPECT_EQ(r.verdict, Stability::stable) << r.message;
  EXPECT_TRUE(check_stability(c.bodies, Integrator::semi_implicit_euler, 0.1, 1).empty());
}

// --- at scene load and in explain_fault ---------------------------------------------------------

/// Three bodies: 'top' anchored by k = 100 N/m, linked to 'mid' by k = 100 and 'mid' to 'tip'
/// by k = 400 (the stiffest, spring[1]); unit masses, and an unlinked, stable 'solo'.
Scene network_scene(double dt, int substeps, bool allow = false) {
  Scene s;
  s.file = "chain.toml";
  s.def.settings.dt = dt;
  s.def.settings.substeps = substeps;
  s.def.settings.integrator = Integrator::semi_implicit_euler;
  s.def.allow_unstable = allow;
  for (const char* name : {"top", "mid", "tip", "solo"}) {
    BodyDef d;
    d.name = name;
    d.body.position = {1.0, 0.0};
    s.def.bodies.push_back(d);
    s.source.body_lines.push_back(4 * s.def.bodies.size());
  }
  s.def.bodies[0].spring = SpringDamper{.anchor = {}, .stiffness = 100.0};
  s.def.bodies[3].spring = SpringDamper{.anchor = {}, .stiffness = 1.0};
  s.def.links = {fixstep::test::link_between(0, 1, LinkSpring{100.0, 0.0, 0.0}),
                 fixstep::test::link_between(1, 2, LinkSpring{400.0, 0.0, 0.0})};
  s.source.link_lines = {30, 34};
  s.source.link_keys = {"spring[0]", "spring[1]"};
  return s;
}

TEST(NetworkGuard, SceneWithAnUnstableNetworkIsRefusedNamingTheStiffestSpring) {
  // Each body alone is stable at dt = 0.1 s ('top': ω·h = 10·0.1 = 1), but the network's top
  // mode is three times faster (ω_max = 29.35 rad/s, mostly 'mid' against 'tip'): the guard
  // judges the linked bodies together.
  const Scene scene = network_scene(0.1, 1);
  for (const BodyStability& b : check_stability(scene)) EXPECT_EQ(b.verdict, Stability::stable);
  const NetworkStability net = *check_scene_network(scene);
  ASSERT_EQ(net.verdict, Stability::unstable);
  EXPECT_EQ(net.bodies, 3u);  // 'solo' is not part of it
  EXPECT_EQ(net.stiffest_link, std::optional<std::size_t>(1));
  EXPECT_EQ(net.fastest_body, fixstep::defined_entity(1));  // 'mid' swings hardest in the top mode
  EXPECT_NEAR(net.omega_max, 29.3543, 0.01);
  try {
    (void)located_world(scene);
    FAIL() << "unstable network accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.line(), 34u) << what;
    EXPECT_EQ(e.key(), "spring[1]") << what;
    for (const std::string& part :
         {std::string("network of 3 bodies and 2 springs is unstable with semi_implicit_euler"),
          fmt::format("ω_max·h = {:.4g} exceeds the stability bound {:.4g}", net.omega_max * 0.1,
                      net.omega_max * net.max_step),
          std::string("stiffest link 'mid'–'tip', k = 400 N/m"), std::string("fastest body 'mid'"),
          fmt::format("; use substeps = {} in [world]", net.min_substeps)}) {
      EXPECT_NE(what.find(part), std::string::npos) << part << "\nin: " << what;
    }
  }
  // The bound is 2 (symplectic Euler, undamped) and the advice is the smallest that works.
  EXPECT_NEAR(net.omega_max * net.max_step, 2.0, 1e-6);
  EXPECT_EQ(net.min_substeps, 2);  // ω_max·dt = 2.94
  const Scene fixed = network_scene(0.1, net.min_substeps);
  EXPECT_TRUE(enforce_stability(fixed).empty());
  World sim = located_world(fixed);
  for (int i = 0; i < 5000; ++i) sim.step();
  EXPECT_FALSE(sim.fault().has_value());
}

TEST(NetworkGuard, NearLimitWarnsAllowUnstableWarnsUnlinkedBodiesStayPerBody) {
  const NetworkStability net = *check_scene_network(network_scene(0.1, 1));
  // 95 % of the largest stable step: stable, but within 10 %.
  const std::vector<std::string> near = enforce_stability(network_scene(0.95 * net.max_step, 1));
  ASSERT_EQ(near.size(), 1u);
  EXPECT_NE(
      near[0].find("chain.toml:34: spring[1]: network of 3 bodies and 2 springs is within 10 %"),
      std::string::npos)
      << near[0];
  const std::vector<std::string> allowed = enforce_stability(network_scene(0.1, 1, true));
  ASSERT_EQ(allowed.size(), 1u);
  EXPECT_NE(allowed[0].find("allowed (allow_unstable), so the run may diverge"), std::string::npos)
      << allowed[0];
  // An unlinked body is still judged on its own, with its own line and key.
  Scene solo = network_scene(0.1, 4);
  solo.def.bodies[3].spring->stiffness = 4e3;  // ω·h = 63 · 0.025 = 1.6: fine; at 1e5, 7.9: not
  EXPECT_TRUE(enforce_stability(solo).empty());
  solo.def.bodies[3].spring->stiffness = 1e5;
  try {
    (void)enforce_stability(solo);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "body[3]") << e.what();
    EXPECT_NE(std::string(e.what()).find("body 'solo'"), std::string::npos) << e.what();
  }
}

TEST(NetworkGuard, ExplainFaultUsesTheNetworkFinding) {
  const Scene scene = network_scene(0.1, 1, true);
  World sim = located_world(scene);
  for (int i = 0; i < 2000 && !sim.fault(); ++i) sim.step();
  ASSERT_TRUE(sim.fault().has_value());
  const std::string m = explain_fault(scene, *sim.fault());
  EXPECT_NE(m.find("Likely cause: network of 3 bodies and 2 springs is unstable"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("ω_max·h"), std::string::npos) << m;
  EXPECT_EQ(m.find("allow_unstable"), std::string::npos) << m;
}

}  // namespace
}  // namespace fixstep
