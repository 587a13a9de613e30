// The integrators against the tables of Fiedler's "Integration Basics" and exact solutions.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/exact.hpp"
#include "fixstep/core/integrators.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

/// 1 kg at rest at the origin pushed by a constant 10 N (the article's first example).
template <class Real>
detail::WorldKernel<Real> pushed_mass(double dt, Integrator integrator) {
  detail::WorldKernel<Real> w(WorldSettings{.dt = dt, .integrator = integrator});
  BodyDef def;
  def.body.mass = 1.0;
  def.constant_force = ConstantForce{{10.0, 0.0}};
  w.create_body(def);
  return w;
}

TEST(ArticleTables, ExplicitEulerDtOneSecond) {
  // "Integration Basics", table for dt = 1: t=10: position = 450 velocity = 100 (exact in f32).
  auto w = pushed_mass<float>(1.0, Integrator::explicit_euler);
  for (int i = 0; i < 10; ++i) w.step();
  EXPECT_EQ(w.x()[0], 450.0f);
  EXPECT_EQ(w.vx()[0], 100.0f);
  EXPECT_EQ(w.y()[0], 0.0f);
}

TEST(ArticleTables, ExplicitEulerDtHundredthF32) {
  // The article's table for dt = 1/100 in float: t=10.00: position = 499.497070
  // velocity = 99.999046. Both printed with 6 decimals, so they must match to the last digit
  // (the f32 spacing near 500 is 3e-5, so a single rounding difference would show).
  auto w = pushed_mass<float>(0.01, Integrator::explicit_euler);
  for (int i = 0; i < 1000; ++i) w.step();
  EXPECT_EQ(fmt::format("{:.6f}", w.x()[0]), "499.497070");
  EXPECT_EQ(fmt::format("{:.6f}", w.vx()[0]), "99.999046");
}

TEST(ArticleTables, ExactSolutionOfConstantForce) {
  // s = u t + a t^2 / 2 = 500 m at t = 10 s. Explicit Euler is short by a t dt / 2 = 0.5 m
  // at dt = 0.01 (sum of a dt^2 k for k < n); semi-implicit Euler is long by the same amount.
  auto ee = pushed_mass<double>(0.01, Integrator::explicit_euler);
  auto si = pushed_mass<double>(0.01, Integrator::semi_implicit_euler);
  for (int i = 0; i < 1000; ++i) ee.step(), si.step();
  EXPECT_NEAR(ee.x()[0], 500.0 - 0.5, 1e-9);
  EXPECT_NEAR(si.x()[0], 500.0 + 0.5, 1e-9);
  EXPECT_NEAR(ee.vx()[0], 100.0, 1e-9);  // velocity is exact: the acceleration is constant
}

TEST(SpringDamper, SemiImplicitTracksExactDampedOscillator) {
  // The article's system: m = 1, x0 = 1000, k = 15, b = 0.1, dt = 0.01, against the exact
  // underdamped solution (exact.hpp, tested on its own in test_exact.cpp).
  detail::WorldKernel<double> w(WorldSettings{.dt = 0.01});
  BodyDef def;
  def.body.position = {1000.0, 0.0};
  def.spring = SpringDamper{.anchor = {}, .stiffness = 15.0, .damping = 0.1};
  w.create_body(def);
  double worst = 0;
  for (int i = 1; i <= 1000; ++i) {
    w.step();
    const double exact = exact::linear(1000.0, 0.0, 15.0, 0.1, 0.0, 0.0, i * 0.01).x;
    worst = std::max(worst, std::abs(w.x()[0] - exact));
  }
  // First order: the phase error after 10 s is about ω³dt²t/24 ≈ 0.0024 rad ... plus the
  // O(dt) amplitude offset of symplectic Euler (ω dt / 2 ≈ 2 %): within 25 m of 1000 m.
  EXPECT_LT(worst, 25.0);
  EXPECT_GT(worst, 1.0);  // and it is a first-order method, not exact
}

/// A 1 kg body on a spring (k = 15 N/m) at x = 1 m, damped by b (N·s/m).
BodyDef damped_spring(double damping) {
  BodyDef def;
  def.body.position = {1.0, 0.5};
  def.spring = SpringDamper{.anchor = {}, .stiffness = 15.0, .damping = damping};
  return def;
}

// The fused sweep takes a γ shared by every body as one value, and loads each body's own
// otherwise: a body steps to the same bits alone (its world's γ uniform) and beside a body
// damped otherwise (γ per body), with every integrator, in f64 and in f32.
template <class Real>
void expect_own_damping() {
  for (const Integrator integrator : all_integrators) {
    WorldSettings settings{.dt = 0.01, .integrator = integrator};
    detail::WorldKernel<Real> alone(settings), beside(settings);
    alone.create_body(damped_spring(2.0));
    beside.create_body(damped_spring(0.1));
    beside.create_body(damped_spring(2.0));
    for (int i = 0; i < 500; ++i) alone.step(), beside.step();
    const std::string name(integrator_name(integrator));
    EXPECT_EQ(alone.x()[0], beside.x()[1]) << name;
    EXPECT_EQ(alone.y()[0], beside.y()[1]) << name;
    EXPECT_EQ(alone.vx()[0], beside.vx()[1]) << name;
    EXPECT_EQ(alone.vy()[0], beside.vy()[1]) << name;
    EXPECT_NE(beside.x()[0], beside.x()[1]) << name;  // the other body's damping differs
  }
}

TEST(SpringDamper, EachBodyStepsWithItsOwnDampingAloneOrBesideAnother) {
  expect_own_damping<double>();
  expect_own_damping<float>();
}

}  // namespace
}  // namespace fixstep
