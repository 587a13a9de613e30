// exact::LinearNetwork: one body against exact::solve, two linked bodies against their
// closed form (centre of mass and relative coordinate), a damped six-body chain under gravity
// against Boost.Odeint's Dormand–Prince 5(4), the cases it must refuse and argument checking.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/exact.hpp"
#include "link_between.hpp"

namespace fixstep {
namespace {

std::vector<Body> network_state(const exact::LinearNetwork& net, double t) {
  std::vector<Body> out(net.size());
  net.state(t, out);
  return out;
}

/// Bodies covering every regime of exact::solve (under-, critically and over-damped, undamped,
/// no spring with drag, gravity and a constant force), each in its own network and all of them
/// together: unlinked bodies are separate components, so their damping need not be related.
std::vector<BodyDef> single_bodies() {
  std::vector<BodyDef> defs;
  auto add = [&](double m, Vec2 x, Vec2 v, std::optional<SpringDamper> s,
                 std::optional<LinearDrag> c, std::optional<Gravity> g,
                 std::optional<ConstantForce> f) {
    BodyDef d;
    d.name = fmt::format("b{}", defs.size());
    d.body = Body{.mass = m, .position = x, .velocity = v};
    d.spring = s, d.drag = c, d.gravity = g, d.constant_force = f;
    defs.push_back(d);
  };
  add(2.0, {1.0, -0.5}, {0.3, 2.0}, SpringDamper{{0.5, 1.0}, 18.0, 0.6, 0.0}, LinearDrag{0.2},
      Gravity{}, std::nullopt);  // under
  add(1.0, {3.0, 0.0}, {0.0, -1.0}, SpringDamper{{}, 4.0, 4.0, 0.0}, std::nullopt, std::nullopt,
      ConstantForce{{1.5, -2.0}});  // critical
  add(0.5, {-1.0, 2.0}, {4.0, 0.0}, SpringDamper{{1.0, 1.0}, 2.0, 9.0, 0.0}, std::nullopt,
      Gravity{}, std::nullopt);  // over
  add(3.0, {0.0, 1.0}, {1.0, 0.0}, SpringDamper{{}, 27.0, 0.0, 0.0}, std::nullopt, std::nullopt,
      std::nullopt);  // undamped
  add(1.5, {0.0, 0.0}, {5.0, 10.0}, std::nullopt, LinearDrag{0.3}, Gravity{},
      ConstantForce{{0.5, 0.0}});  // projectile
  return defs;
}

TEST(ExactNetwork, OneBodyWithoutLinksIsExactSolve) {
  const std::vector<BodyDef> defs = single_bodies();
  const auto all = exact::LinearNetwork::make(defs, {});
  ASSERT_TRUE(all.has_value());
  for (std::size_t i = 0; i < defs.size(); ++i) {
    const auto one = exact::LinearNetwork::make(std::span(&defs[i], 1), {});
    ASSERT_TRUE(one.has_value()) << defs[i].name;
    for (double t : {0.0, 0.3, 2.0, 9.0}) {
      const Body want = *exact::solve(defs[i], t);
      for (const Body& got : {network_state(*one, t)[0], network_state(*all, t)[i]}) {
        SCOPED_TRACE(fmt::format("{} at t = {}", defs[i].name, t));
        // Through q = √m x and back: a few roundings of the amplitude.
        const double sx = 1e-13 * (1.0 + std::abs(want.position.x) + std::abs(want.position.y));
        const double sv = 1e-13 * (1.0 + std::abs(want.velocity.x) + std::abs(want.velocity.y));
        EXPECT_NEAR(got.position.x, want.position.x, sx);
        EXPECT_NEAR(got.position.y, want.position.y, sx);
        EXPECT_NEAR(got.velocity.x, want.velocity.x, sv);
        EXPECT_NEAR(got.velocity.y, want.velocity.y, sv);
        EXPECT_EQ(got.mass, defs[i].body.mass);
      }
    }
  }
}

TEST(ExactNetwork, TwoLinkedBodiesAreCentreOfMassAndRelativeOscillator) {
  // m1 = 2 kg and m2 = 5 kg joined by k = 30 N/m, b = 1.2 N*s/m, in gravity, body 1 pushed by
  // F = (1.5, -0.5) N. Centre of mass X = (m1 x1 + m2 x2)/M moves as X0 + V0 t + A t²/2 with
  // A = F/M + g; the relative coordinate r = x1 - x2 obeys r'' = -(k/μ) r - (b/μ) r' + F/m1
  // (μ = m1 m2/M; gravity cancels), an under-damped oscillator about r_eq = (F/m1) μ/k:
  //   r - r_eq = e^{-γt/2} (y0 cos ω_d t + (u0 + γ y0/2)/ω_d sin ω_d t),  ω_d² = k/μ - γ²/4
  // (Thornton & Marion §3.5), and x1 = X + (m2/M) r, x2 = X - (m1/M) r.
  const double m1 = 2.0, m2 = 5.0, k = 30.0, b = 1.2, M = m1 + m2, mu = m1 * m2 / M;
  const Vec2 force{1.5, -0.5}, g{0.0, -9.81};
  std::vector<BodyDef> defs(2);
  defs[0].body = Body{.mass = m1, .position = {1.0, 0.5}, .velocity = {0.0, 2.0}};
  defs[0].constant_force = ConstantForce{force};
  defs[1].body = Body{.mass = m2, .position = {-0.5, 0.0}, .velocity = {1.0, -0.4}};
  for (BodyDef& d : defs) d.gravity = Gravity{g};
  const std::vector<LinkDef> links{fixstep::test::link_between(0, 1, LinkSpring{k, b, 0.0})};
  const auto net = exact::LinearNetwork::make(defs, links);
  ASSERT_TRUE(net.has_value());

  const double gamma = b / mu, wd = std::sqrt(k / mu - 0.25 * gamma * gamma);
  for (double t : {0.0, 0.4, 1.7, 6.0}) {
    const std::vector<Body> s = network_state(*net, t);
    double want[2][2][2];  // [body][axis][x or v]
    for (int axis = 0; axis < 2; ++axis) {
      auto get = [&](const Vec2& v) { return axis == 0 ? v.x : v.y; };
      const double x1 = get(defs[0].body.position), x2 = get(defs[1].body.position);
      const double v1 = get(defs[0].body.velocity), v2 = get(defs[1].body.velocity);
      const double a = get(force) / M + get(g);
      const double X = (m1 * x1 + m2 * x2) / M + (m1 * v1 + m2 * v2) / M * t + 0.5 * a * t * t;
      const double V = (m1 * v1 + m2 * v2) / M + a * t;
      const double r_eq = get(force) / m1 * mu / k, y0 = x1 - x2 - r_eq, u0 = v1 - v2;
      const double e = std::exp(-0.5 * gamma * t), c = std::cos(wd * t), sn = std::sin(wd * t);
      const double B = (u0 + 0.5 * gamma * y0) / wd;
      const double r = r_eq + e * (y0 * c + B * sn);
      const double u = e * (-0.5 * gamma * (y0 * c + B * sn) + wd * (-y0 * sn + B * c));
      want[0][axis][0] = X + m2 / M * r, want[0][axis][1] = V + m2 / M * u;
      want[1][axis][0] = X - m1 / M * r, want[1][axis][1] = V - m1 / M * u;
    }
    for (int i = 0; i < 2; ++i) {
      SCOPED_TRACE(fmt::format("body {} at t = {}", i, t));
      const double tol = 1e-12 * (1.0 + 0.5 * 9.81 * t * t);  // relative to the fall
      EXPECT_NEAR(s[i].position.x, want[i][0][0], tol);
      EXPECT_NEAR(s[i].velocity.x, want[i][0][1], tol);
      EXPECT_NEAR(s[i].position.y, want[i][1][0], tol);
      EXPECT_NEAR(s[i].velocity.y, want[i][1][1], tol);
    }
  }
}

TEST(ExactNetwork, FreeChainsCentreOfMassFollowsTheParabola) {
  // No anchor: the rigid motion is a mode with ω² = 0, whatever round-off the eigen-solver
  // leaves (+6e-16 1/s² for these four bodies; as ω² > 0 it would put the equilibrium
  // accel/ω² some 1e16 m away). The centre of mass obeys M X'' = Σ F + M g exactly.
  const double mass[] = {0.7, 3.3, 5.9, 2.0}, k[] = {30.0, 81.0, 64.0};
  std::vector<BodyDef> defs(4);
  std::vector<LinkDef> links;
  double total = 0.0;
  Vec2 x0{}, p0{};
  for (std::size_t i = 0; i < 4; ++i) {
    defs[i].body = Body{.mass = mass[i],
                        .position = {1.0 * i, 0.2 * (i % 2)},
                        .velocity = {0.3 * i, 1.0 - 0.5 * i}};
    defs[i].gravity = Gravity{};
    total += mass[i];
    x0 = {x0.x + mass[i] * defs[i].body.position.x, x0.y + mass[i] * defs[i].body.position.y};
    p0 = {p0.x + mass[i] * defs[i].body.velocity.x, p0.y + mass[i] * defs[i].body.velocity.y};
    if (i > 0)
      links.push_back(
          fixstep::test::link_between(i - 1, i, LinkSpring{k[i - 1], 0.01 * k[i - 1], 0.0}));
  }
  defs[2].constant_force = ConstantForce{{2.0, 1.0}};
  const auto net = exact::LinearNetwork::make(defs, links);
  ASSERT_TRUE(net.has_value());
  const Vec2 a{2.0 / total, 1.0 / total - 9.81};
  for (double t : {0.5, 3.0, 10.0}) {
    const std::vector<Body> s = network_state(*net, t);
    Vec2 x{}, p{};
    for (const Body& b : s) {
      x = {x.x + b.mass * b.position.x, x.y + b.mass * b.position.y};
      p = {p.x + b.mass * b.velocity.x, p.y + b.mass * b.velocity.y};
    }
    const double tol = 1e-12 * (1.0 + 9.81 * t * t);
    EXPECT_NEAR(x.x / total, x0.x / total + p0.x / total * t + 0.5 * a.x * t * t, tol) << t;
    EXPECT_NEAR(x.y / total, x0.y / total + p0.y / total * t + 0.5 * a.y * t * t, tol) << t;
    EXPECT_NEAR(p.x / total, p0.x / total + a.x * t, tol) << t;
    EXPECT_NEAR(p.y / total, p0.y / total + a.y * t, tol) << t;
  }
}

/// A chain of six bodies hanging from an anchor under gravity, with Rayleigh damping
/// α = 0.02 s, β = 0.1 1/s: link dampers b = α k, body 0's anchored damper α k0, drag β m.
struct Chain {
  std::vector<BodyDef> bodies;
  std::vector<LinkDef> links;
};

Chain damped_chain() {
  const double alpha = 0.02, beta = 0.1, k0 = 50.0;
  const double mass[] = {1.0, 2.5, 0.7, 4.0, 1.3, 3.0}, k[] = {40.0, 25.0, 60.0, 35.0, 45.0};
  Chain c;
  for (int i = 0; i < 6; ++i) {
    BodyDef d;
    d.name = fmt::format("c{}", i);
    d.body = Body{.mass = mass[i],
                  .position = {0.8 * i + 0.1 * (i % 2), -0.3 * i},
                  .velocity = {0.5 * ((i % 3) - 1), 0.2 * i}};
    d.gravity = Gravity{};
    d.drag = LinearDrag{beta * mass[i]};
    if (i == 0) d.spring = SpringDamper{{0.0, 0.0}, k0, alpha * k0, 0.0};
    c.bodies.push_back(d);
  }
  for (std::size_t l = 0; l < 5; ++l)
    c.links.push_back(fixstep::test::link_between(l, l + 1, LinkSpring{k[l], alpha * k[l], 0.0}));
  return c;
}

TEST(ExactNetwork, DampedChainUnderGravityAgreesWithOdeintDopri5) {
  namespace odeint = boost::numeric::odeint;
  const Chain chain = damped_chain();
  const auto net = exact::LinearNetwork::make(chain.bodies, chain.links);
  ASSERT_TRUE(net.has_value());
  const std::size_t n = chain.bodies.size();
  using State = std::vector<double>;  // x, y, vx, vy of body i at 4i .. 4i + 3
  const auto rhs = [&](const State& s, State& ds, double /*t*/) {
    for (std::size_t i = 0; i < n; ++i) {
      const BodyDef& d = chain.bodies[i];
      double fx = -d.drag->coefficient * s[4 * i + 2], fy = -d.drag->coefficient * s[4 * i + 3];
      fy += d.body.mass * d.gravity->acceleration.y;
      if (d.spring) {
        fx -= d.spring->stiffness * (s[4 * i] - d.spring->anchor.x) +
              d.spring->damping * s[4 * i + 2];
        fy -= d.spring->stiffness * (s[4 * i + 1] - d.spring->anchor.y) +
              d.spring->damping * s[4 * i + 3];
      }
      ds[4 * i] = s[4 * i + 2], ds[4 * i + 1] = s[4 * i + 3];
      ds[4 * i + 2] = fx, ds[4 * i + 3] = fy;
    }
    for (const LinkDef& l : chain.links) {
      const std::size_t a = 4 * l.body_a.slot(), b = 4 * l.body_b.slot();
      for (int c = 0; c < 2; ++c) {
        const double f = -l.spring.stiffness * (s[a + c] - s[b + c]) -
                         l.spring.damping * (s[a + 2 + c] - s[b + 2 + c]);
        ds[a + 2 + c] += f, ds[b + 2 + c] -= f;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      ds[4 * i + 2] /= chain.bodies[i].body.mass, ds[4 * i + 3] /= chain.bodies[i].body.mass;
    }
  };
  State y(4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Body& b = chain.bodies[i].body;
    y[4 * i] = b.position.x, y[4 * i + 1] = b.position.y;
    y[4 * i + 2] = b.velocity.x, y[4 * i + 3] = b.velocity.y;
  }
  auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<State>());
  double t = 0.0, worst = 0.0;
  for (double until : {0.5, 2.0, 5.0, 12.0}) {
    odeint::integrate_adaptive(stepper, rhs, y, t, until, 1e-4);
    t = until;
    const std::vector<Body> s = network_state(*net, t);
    // The chain sinks up to 12 m and moves at a few m/s: odeint's per-step tolerance
    // of 1e-12 (1 + |y|) over its steps leaves ~1e-11 (measured: 8.8e-12 at most).
    for (std::size_t i = 0; i < n; ++i) {
      SCOPED_TRACE(fmt::format("body {} at t = {}", i, t));
      const double got[] = {s[i].position.x, s[i].position.y, s[i].velocity.x, s[i].velocity.y};
      for (int c = 0; c < 4; ++c) {
        EXPECT_NEAR(got[c], y[4 * i + c], 1e-10);
        worst = std::max(worst, std::abs(got[c] - y[4 * i + c]));
      }
    }
  }
  RecordProperty("max_abs_difference", fmt::format("{:.3g}", worst));
  // It is a real comparison: after 12 s the chain has not yet settled at equilibrium.
  EXPECT_GT(std::abs(y[4 * 5 + 3]), 1e-3);
}

TEST(ExactNetwork, NonlinearOrNonProportionalNetworksAreRefused) {
  const Chain base = damped_chain();
  auto make = [](const Chain& c) { return exact::LinearNetwork::make(c.bodies, c.links); };
  ASSERT_TRUE(make(base).has_value());
  Chain rest = base;  // a link with rest length
  rest.links[2].spring.rest_length = 0.5;
  EXPECT_FALSE(make(rest).has_value());
  Chain anchored = base;  // the anchored spring with rest length
  anchored.bodies[0].spring->rest_length = 1.0;
  EXPECT_FALSE(make(anchored).has_value());
  Chain link_damper = base;  // one link damper not α k
  link_damper.links[3].spring.damping *= 1.0 + 1e-6;
  EXPECT_FALSE(make(link_damper).has_value());
  Chain drag = base;  // one drag not β m
  drag.bodies[4].drag->coefficient *= 1.1;
  EXPECT_FALSE(make(drag).has_value());
  Chain undragged = base;  // a body without drag forces β = 0, contradicting the others
  undragged.bodies[2].drag.reset();
  EXPECT_FALSE(make(undragged).has_value());
  Chain dashpot = base;  // a pure damper (k = 0, b > 0) is never α k
  dashpot.links[0].spring.stiffness = 0.0;
  EXPECT_FALSE(make(dashpot).has_value());
  // Within 1e-9 per damper counts as proportional (round-off in b = α k).
  Chain rounded = base;
  rounded.links[1].spring.damping *= 1.0 + 1e-12;
  EXPECT_TRUE(make(rounded).has_value());
  // Undamped everywhere: α = β = 0.
  Chain undamped = base;
  for (BodyDef& d : undamped.bodies) d.drag.reset();
  undamped.bodies[0].spring->damping = 0.0;
  for (LinkDef& l : undamped.links) l.spring.damping = 0.0;
  EXPECT_TRUE(make(undamped).has_value());
}

TEST(ExactNetwork, RejectsInvalidArguments) {
  Chain c = damped_chain();
  auto throws = [](const Chain& x) {
    EXPECT_THROW((void)exact::LinearNetwork::make(x.bodies, x.links), std::invalid_argument);
  };
  Chain out_of_range = c;
  out_of_range.links[0].body_b = fixstep::defined_entity(6);
  throws(out_of_range);
  Chain self = c;
  self.links[1].body_b = self.links[1].body_a;
  throws(self);
  Chain negative = c;
  negative.links[2].spring.stiffness = -1.0;
  throws(negative);
  Chain mass = c;
  mass.bodies[3].body.mass = 0.0;
  throws(mass);
  Chain nan_position = c;
  nan_position.bodies[1].body.position.y = std::nan("");
  throws(nan_position);
  const auto net = exact::LinearNetwork::make(c.bodies, c.links);
  ASSERT_TRUE(net.has_value());
  std::vector<Body> small(5);
  EXPECT_THROW(net->state(1.0, small), std::invalid_argument);
  std::vector<Body> right(6);
  EXPECT_THROW(net->state(INFINITY, right), std::invalid_argument);
  EXPECT_NO_THROW(net->state(-1.0, right));  // the exact flow backwards
}

}  // namespace
}  // namespace fixstep
