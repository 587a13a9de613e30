// Energy: measurement, drift of each integrator on the oscillator, the article's claims.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

/// Unit-mass oscillator x'' = -ω² x - (b/m) x' along x, starting at x = 1 m, v = 0.
detail::WorldKernel<double> oscillator(double omega, double dt, double damping,
                                       Integrator integrator) {
  detail::WorldKernel<double> w(WorldSettings{.dt = dt, .integrator = integrator});
  BodyDef def;
  def.body.position = {1.0, 0.0};
  def.spring = SpringDamper{.anchor = {}, .stiffness = omega * omega, .damping = damping};
  w.create_body(def);
  return w;
}

TEST(EnergyMeasure, PotentialsAndKineticAreExact) {
  detail::WorldKernel<double> w(WorldSettings{.dt = 0.01});
  BodyDef def;
  def.body = Body{.mass = 2.0, .position = {3.0, 4.0}, .velocity = {1.0, -2.0}};
  def.spring = SpringDamper{.anchor = {0.0, 1.0}, .stiffness = 5.0, .damping = 0.3};
  def.gravity = Gravity{{0.0, -9.81}};
  def.constant_force = ConstantForce{{2.0, 1.0}};
  w.create_body(def);
  BodyDef rest;  // rest-length spring: stretch = |(6,8)| - 4 = 6 m
  rest.body = Body{.mass = 1.0, .position = {6.0, 8.0}, .velocity = {}};
  rest.spring = SpringDamper{.anchor = {}, .stiffness = 2.0, .damping = 0.0, .rest_length = 4.0};
  w.create_body(rest);
  const EnergyReport e = w.energy();
  EXPECT_DOUBLE_EQ(e.kinetic, 0.5 * 2.0 * 5.0);                            // ½ m |v|²
  EXPECT_DOUBLE_EQ(e.spring, 0.5 * 5.0 * (9.0 + 9.0) + 0.5 * 2.0 * 36.0);  // ½ k d²
  EXPECT_DOUBLE_EQ(e.gravity, -2.0 * (-9.81 * 4.0));                       // -m g·x
  EXPECT_DOUBLE_EQ(e.constant_force, -(2.0 * 3.0 + 1.0 * 4.0));            // -F·x
  std::vector<double> per(2);
  w.body_energies(per);
  EXPECT_DOUBLE_EQ(per[0] + per[1], e.total());
  EXPECT_DOUBLE_EQ(per[1], 0.5 * 2.0 * 36.0);
}

TEST(EnergyDrift, SemiImplicitEulerBoundedOverAMillionTicks) {
  // ω·dt = 0.1, undamped. Symplectic Euler exactly conserves the modified energy
  // H~ = ½(v² + ω²x² - ω² dt x v) (the sign follows from the velocity-first order: with
  // v' = v - ω²x dt, x' = x + v' dt one checks H~(x', v') = H~(x, v) by expansion), and since
  // |ω x v| <= ½(v² + ω²x²), the true energy stays within E0 (1 ± ωdt/2)/(1 ∓ ωdt/2):
  // |E/E0 - 1| <= ωdt / (1 - ωdt/2) = 0.10526. No secular growth: the mean over the last
  // 10^4 ticks equals the mean over the first 10^4 to 1e-3 (an averaging window of ~159
  // periods leaves ~amplitude/159 of ripple).
  const double omega = 1.0, dt = 0.1;
  auto w = oscillator(omega, dt, 0.0, Integrator::semi_implicit_euler);
  const double e0 = w.energy().total();
  auto modified = [&] {
    const double x = w.x()[0], v = w.vx()[0];
    return 0.5 * (v * v + omega * omega * x * x - omega * omega * dt * x * v);
  };
  const double h0 = modified();
  const int n = 1'000'000, window = 10'000;
  double worst = 0, worst_modified = 0, first_mean = 0, last_mean = 0;
  for (int i = 1; i <= n; ++i) {
    w.step();
    const double e = w.energy().total();
    worst = std::max(worst, std::abs(e / e0 - 1));
    worst_modified = std::max(worst_modified, std::abs(modified() / h0 - 1));
    if (i <= window) first_mean += e / window;
    if (i > n - window) last_mean += e / window;
  }
  EXPECT_LE(worst, omega * dt / (1 - omega * dt / 2));
  EXPECT_GT(worst, 0.04);            // the bound is nearly reached: the oscillation is real
  EXPECT_LT(worst_modified, 1e-10);  // round-off only
  EXPECT_NEAR(last_mean / first_mean, 1.0, 1e-3);
}

TEST(EnergyDrift, ExplicitEulerGrowsByOnePlusOmegaDtSquaredPerTick) {
  // x' = x + v dt, v' = v - ω²x dt gives v'² + ω²x'² = (1 + ω²dt²)(v² + ω²x²) exactly.
  for (double omega_dt : {0.01, 0.1, 0.5}) {
    auto w = oscillator(1.0, omega_dt, 0.0, Integrator::explicit_euler);
    double e = w.energy().total();
    for (int i = 0; i < 1000; ++i) {
      w.step();
      const double next = w.energy().total();
      ASSERT_NEAR(next / e, 1 + omega_dt * omega_dt, 1e-12) << "tick " << i << " ω·dt " << omega_dt;
      e = next;
    }
  }
}

TEST(EnergyDrift, DampedSpringEnergyNeverIncreasesUnderSemiImplicitEuler) {
  // The article's damped spring (m = 1, k = 15, b = 0.1, dt = 0.01). Per tick, the energy of
  // symplectic Euler changes by about dt (½ ω² dt (v² - ω²x²) - (b/m) v²); this is <= 0 for
  // every state when ½ ω² dt <= b/m (here 0.075 <= 0.1), so the energy must fall every tick,
  // up to round-off (1e-12 relative).
  detail::WorldKernel<double> w(WorldSettings{.dt = 0.01});
  BodyDef def;
  def.body.position = {1000.0, 0.0};
  def.spring = SpringDamper{.anchor = {}, .stiffness = 15.0, .damping = 0.1};
  w.create_body(def);
  double e = w.energy().total();
  const double e0 = e;
  for (int i = 0; i < 20'000; ++i) {
    w.step();
    const double next = w.energy().total();
    ASSERT_LE(next, e * (1 + 1e-12)) << "tick " << i;
    e = next;
  }
  // and it decays like e^{-(b/m) t} on average: 200 s gives e^{-20}
  EXPECT_NEAR(std::log(e / e0), -20.0, 0.5);
}

TEST(EnergyDrift, ExplicitEulerGainsEnergyOnTheArticleSpring) {
  // "Instead of damping and converging on the origin, it gains energy over time!"
  detail::WorldKernel<float> w(WorldSettings{.dt = 0.01, .integrator = Integrator::explicit_euler});
  BodyDef def;
  def.body.position = {1000.0, 0.0};
  def.spring = SpringDamper{.anchor = {}, .stiffness = 15.0, .damping = 0.1};
  w.create_body(def);
  const double e0 = w.energy().total();
  for (int i = 0; i < 10'000; ++i) w.step();
  // Per tick, explicit Euler changes the energy by E' - E = ω²dt² E - (b/m) v² dt + O(b dt²);
  // averaged over a period <v²> = E for m = 1 (kinetic is half the energy), so the relative change
  // is ω²dt² - (b/m) dt = 0.0015 - 0.001 = +0.0005 per tick: e^{5} after 10^4 ticks. Asserting at
  // least e^{4} leaves room for the O(dt²) terms.
  EXPECT_GT(w.energy().total(), e0 * std::exp(4.0));
}

/// A 2 kg body on a link (k = 30 N/m, damping b, rest length L) to a kinematic body moving at
/// (1.5, -0.75) m/s, which keeps the body swinging and does work on it. The body starts 1 m to
/// the right of the kinematic body and 0.5 m above, at rest; kinematic_first puts the
/// kinematic body at the link's end a (its force's sign flips). Returns the largest
/// |E + E_dissipated - W_external - E0| (the energy balance) and the largest |W_external| over
/// the last second of 4 s at step h, both J.
std::pair<double, double> driven_balance(Integrator method, double h, double b, double rest,
                                         bool kinematic_first) {
  detail::WorldKernel<double> w(
      WorldSettings{.dt = h, .integrator = method, .track_dissipation = true});
  BodyDef kin;
  kin.type = BodyType::kinematic;
  kin.body = Body{.mass = 1.0, .position = {0.0, 0.0}, .velocity = {1.5, -0.75}};
  BodyDef dyn;
  dyn.body = Body{.mass = 2.0, .position = {1.0, 0.5}, .velocity = {0.0, 0.0}};
  Entity k, d;
  if (kinematic_first) {
    k = w.create_body(kin), d = w.create_body(dyn);
  } else {
    d = w.create_body(dyn), k = w.create_body(kin);
  }
  const LinkSpring spring{.stiffness = 30.0, .damping = b, .rest_length = rest};
  w.create_link(kinematic_first ? LinkDef{k, d, spring} : LinkDef{d, k, spring});
  const double e0 = w.energy().total();
  const auto quarter = static_cast<int>(std::lround(0.25 / h));  // ticks in 0.25 s
  std::pair<double, double> worst{0.0, 0.0};
  for (int t = 1; t <= 16 * quarter; ++t) {
    w.step();
    if (t < 12 * quarter || t % quarter != 0) continue;  // at 3, 3.25, ..., 4 s
    const double work = w.external_work();
    worst.first =
        std::max(worst.first, std::abs(w.energy().total() + w.dissipated_energy() - work - e0));
    worst.second = std::max(worst.second, std::abs(work));
  }
  return worst;
}

// The work a kinematic body does through a link is external: counted with
// each integrator's own stages, the balance shrinks at the integrator's order, undamped and
// damped, with the kinematic body at either end, with and without a rest length.
struct DrivenCase {
  Integrator method;
  double h, order;  ///< s; the integrator's order
};

void PrintTo(const DrivenCase& c, std::ostream* out) {
  *out << integrator_name(c.method) << " at h = " << c.h << " s";
}

class KinematicLinkWork : public testing::TestWithParam<DrivenCase> {};

TEST_P(KinematicLinkWork, IsExternalAndTheBalanceShrinksAtTheIntegratorsOrder) {
  const DrivenCase c = GetParam();
  struct Link {
    double damping, rest;
    bool kinematic_first;
  };
  for (const Link l : {Link{0.0, 0.0, false}, Link{2.0, 0.0, true}, Link{1.0, 0.5, false}}) {
    const auto [coarse, work] = driven_balance(c.method, c.h, l.damping, l.rest, l.kinematic_first);
    const double fine =
        driven_balance(c.method, c.h / 2, l.damping, l.rest, l.kinematic_first).first;
    const double observed = std::log2(coarse / fine);
    // At least the integrator's order; RK4 gains one on the undamped linear link (the
    // modulus of its stability function differs from 1 by (ωh)⁶/72 only).
    EXPECT_GT(observed, c.order - 0.3)
        << "b = " << l.damping << " L = " << l.rest << ": " << coarse << " -> " << fine << " J";
    EXPECT_LT(observed, c.order + 1.3) << "b = " << l.damping << " L = " << l.rest;
    // The work is real, beyond the balance error (left out, it would not shrink).
    EXPECT_GT(work, 2.0 * coarse) << "b = " << l.damping << " L = " << l.rest;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, KinematicLinkWork,
                         testing::Values(DrivenCase{Integrator::semi_implicit_euler, 1.0 / 800,
                                                    1.0},
                                         DrivenCase{Integrator::explicit_euler, 1.0 / 1600, 1.0},
                                         DrivenCase{Integrator::velocity_verlet, 1.0 / 200, 2.0},
                                         DrivenCase{Integrator::rk4, 1.0 / 100, 4.0},
                                         DrivenCase{Integrator::implicit_euler, 1.0 / 400, 1.0},
                                         DrivenCase{Integrator::forest_ruth, 1.0 / 50, 4.0}),
                         [](const testing::TestParamInfo<DrivenCase>& info) {
                           return std::string(integrator_name(info.param.method));
                         });

}  // namespace
}  // namespace fixstep
