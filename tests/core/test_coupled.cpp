// Links (spring-dampers between bodies) and the multi-pass step (engine/core/src/world_coupled.cpp,
// world_implicit.cpp): the API and its errors, the force against its definition, momentum,
// bit-identity (tracked vs fused pass, one vs two threads, SIMD levels), the energy balance
// and its order, and each integrator's order on a damped chain against its exact solution.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/exact.hpp"
#include "fixstep/core/simd.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "link_between.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

BodyDef body_at(double x, double y, double mass = 1.0) {
  BodyDef d;
  d.body = Body{.mass = mass, .position = {x, y}, .velocity = {}};
  return d;
}

TEST(Links, CreateDestroyAndStaleHandles) {
  detail::WorldKernel<double> w(WorldSettings{});
  const Entity a = w.create_body(body_at(0, 0)), b = w.create_body(body_at(1, 0));
  const Entity c = w.create_body(body_at(2, 0));
  const Link ab = w.create_link({a, b, {.stiffness = 5, .damping = 0.5, .rest_length = 1}});
  const Link bc = w.create_link({b, c, {.stiffness = 7}});
  EXPECT_EQ(w.link_count(), 2u);
  EXPECT_EQ(w.link(bc).spring.stiffness, 7.0);
  EXPECT_TRUE(w.active_terms() & term_link);
  w.destroy_link(ab);
  EXPECT_FALSE(w.contains(ab));
  EXPECT_THROW(w.destroy_link(ab), std::invalid_argument);
  EXPECT_THROW((void)w.link(ab), std::invalid_argument);
  EXPECT_THROW(w.destroy_link(Link{}), std::invalid_argument);
  // A reused slot gets a new generation: the old handle stays stale.
  const Link ca = w.create_link({c, a, {.stiffness = 1}});
  EXPECT_EQ(ca.index1, ab.index1);
  EXPECT_NE(ca.generation, ab.generation);
  EXPECT_FALSE(w.contains(ab));
  // Destroying a body destroys its links.
  w.destroy(c);
  EXPECT_FALSE(w.contains(bc));
  EXPECT_FALSE(w.contains(ca));
  EXPECT_EQ(w.link_count(), 0u);
  EXPECT_FALSE(w.active_terms() & term_link);
}

TEST(Links, RejectsBadDefinitionsNamingTheField) {
  detail::WorldKernel<float> w(WorldSettings{});
  const Entity a = w.create_body(body_at(0, 0)), b = w.create_body(body_at(0, 0));
  auto message = [&](const LinkDef& d) {
    try {
      w.create_link(d);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({a, a, {.stiffness = 1}}).find("two different bodies"), std::string::npos);
  EXPECT_NE(message({a, Entity{}, {.stiffness = 1}}).find("null or was destroyed"),
            std::string::npos);
  EXPECT_NE(message({a, b, {.stiffness = -1}}).find("stiffness"), std::string::npos);
  EXPECT_NE(message({a, b, {.stiffness = 1, .damping = NAN}}).find("damping"), std::string::npos);
  EXPECT_NE(message({a, b, {.stiffness = 1e39}}).find("stiffness"), std::string::npos);  // f32
  EXPECT_NE(message({a, b, {.stiffness = 1, .rest_length = 0.5}}).find("same point"),
            std::string::npos);
  EXPECT_EQ(message({a, b, {.stiffness = 1}}), "no error");  // L = 0 at one point is fine
}

TEST(Links, FrequencyAndDampingRatio) {
  // k = m ω², b = 2 m ζ ω with ω = 2π f; μ = m_a m_b / (m_a + m_b).
  const double mu = reduced_mass(2.0, 6.0);
  EXPECT_DOUBLE_EQ(mu, 1.5);
  const LinkSpring s = spring_from_frequency(3.0, 0.25, mu);
  const double omega = 2 * std::numbers::pi * 3.0;
  EXPECT_DOUBLE_EQ(s.stiffness, 1.5 * omega * omega);
  EXPECT_DOUBLE_EQ(s.damping, 2 * 1.5 * 0.25 * omega);
  EXPECT_THROW((void)spring_from_frequency(0.0, 0.1, 1.0), std::invalid_argument);
  EXPECT_THROW((void)spring_from_frequency(1.0, -0.1, 1.0), std::invalid_argument);
  EXPECT_THROW((void)spring_from_frequency(1.0, 0.1, INFINITY), std::invalid_argument);
  EXPECT_THROW((void)reduced_mass(0.0, 1.0), std::invalid_argument);
}

TEST(Links, AccelerationsFollowTheDefinition) {
  for (const double rest : {0.0, 0.8}) {
    detail::WorldKernel<double> w(WorldSettings{});
    BodyDef da = body_at(0.3, -0.2, 2.0), db = body_at(1.5, 0.7, 0.5);
    da.body.velocity = {0.4, -1.0};
    db.body.velocity = {-0.3, 0.6};
    const Entity a = w.create_body(da), b = w.create_body(db);
    w.create_link({a, b, {.stiffness = 12.0, .damping = 0.7, .rest_length = rest}});
    std::vector<double> ax(2), ay(2);
    w.accelerations(ax, ay);
    const double dx = 0.3 - 1.5, dy = -0.2 - 0.7, ux = 0.4 + 0.3, uy = -1.0 - 0.6;
    const double len = std::hypot(dx, dy), nx = dx / len, ny = dy / len;
    double fx = -12.0 * dx - 0.7 * ux, fy = -12.0 * dy - 0.7 * uy;
    if (rest > 0) {
      const double un = ux * nx + uy * ny;
      fx = -12.0 * (len - rest) * nx - 0.7 * un * nx;
      fy = -12.0 * (len - rest) * ny - 0.7 * un * ny;
    }
    EXPECT_NEAR(ax[0], fx / 2.0, 1e-12);
    EXPECT_NEAR(ay[0], fy / 2.0, 1e-12);
    EXPECT_NEAR(ax[1], -fx / 0.5, 1e-12);
    EXPECT_NEAR(ay[1], -fy / 0.5, 1e-12);
  }
}

/// A chain of n bodies along x, zero-rest-length links of stiffness k and damping alpha·k,
/// body 0 anchored at the origin by an anchored spring of the same k (damping alpha·k), the
/// last body pulled out: a linear network with proportional damping (an exact solution).
struct Chain {
  std::vector<BodyDef> bodies;
  std::vector<LinkDef> links;
};
Chain make_chain(int n, double k, double alpha, double rest = 0.0, double mass_ratio = 1.0) {
  Chain c;
  for (int i = 0; i < n; ++i) {
    BodyDef d = body_at(0.5 * (i + 1), 0.1 * i, i % 2 ? mass_ratio : 1.0);
    if (i == n - 1) d.body.position.x += 0.4, d.body.velocity = {0.0, 0.3};
    if (i == 0) d.spring = SpringDamper{.anchor = {}, .stiffness = k, .damping = alpha * k};
    c.bodies.push_back(d);
  }
  for (int i = 0; i + 1 < n; ++i) {
    c.links.push_back(
        fixstep::test::link_between(std::size_t(i), std::size_t(i + 1),
                                    {.stiffness = k, .damping = alpha * k, .rest_length = rest}));
  }
  return c;
}

template <class Real>
std::unique_ptr<detail::WorldKernel<Real>> build(const Chain& c, WorldSettings s) {
  auto w = std::make_unique<detail::WorldKernel<Real>>(s);
  std::vector<Entity> e;
  for (const BodyDef& d : c.bodies) e.push_back(w->create_body(d));
  for (const LinkDef& l : c.links)
    w->create_link({e[l.body_a.slot()], e[l.body_b.slot()], l.spring});
  return w;
}

TEST(Links, FreeNetworkConservesMomentum) {
  Chain c = make_chain(6, 40.0, 0.02, 0.3, 3.0);
  c.bodies[0].spring.reset();  // no anchor: only internal forces
  for (Integrator method : all_integrators) {
    auto w = build<double>(c, WorldSettings{.dt = 0.01, .integrator = method});
    auto momentum = [&] {
      double px = 0, py = 0;
      for (std::size_t j = 0; j < w->body_count(); ++j) {
        px += c.bodies[j].body.mass * w->vx()[j], py += c.bodies[j].body.mass * w->vy()[j];
      }
      return std::hypot(px, py);
    };
    const double p0 = momentum();
    for (int t = 0; t < 500; ++t) w->step();
    EXPECT_NEAR(momentum(), p0, 1e-9) << integrator_name(method);
  }
}

// The tracked path (WorldSettings::track_dissipation) must step a world without links exactly
// as the fused, vectorized pass does: same operations in the same order (body_field.hpp).
TEST(Links, TrackedPassIsTheFusedPassBitForBit) {
  for (Integrator method : all_integrators) {
    for (bool rest : {false, true}) {
      auto make = [&](bool track) {
        auto w = std::make_unique<detail::WorldKernel<float>>(WorldSettings{
            .dt = 1.0 / 60, .integrator = method, .substeps = 2, .track_dissipation = track});
        for (int j = 0; j < 101; ++j) {
          BodyDef d = body_at(0.3 * (j % 7) - 1, 0.2 * (j % 5), 0.5 + 0.25 * (j % 3));
          d.spring = SpringDamper{.anchor = {0.1 * (j % 4), 0},
                                  .stiffness = 3.0 + j % 5,
                                  .damping = 0.2 * (j % 3),
                                  .rest_length = rest && j % 2 ? 0.4 : 0.0};
          if (j % 4 == 0) d.gravity = Gravity{};
          if (j % 5 == 0) d.drag = LinearDrag{0.1};
          w->create_body(d);
        }
        return w;
      };
      auto fused = make(false), tracked = make(true);
      for (int t = 0; t < 200; ++t) fused->step(), tracked->step();
      EXPECT_EQ(fused->state_hash(), tracked->state_hash()) << integrator_name(method);
      EXPECT_EQ(fused->dissipated_energy(), 0.0);
      EXPECT_GT(tracked->dissipated_energy(), 0.0) << integrator_name(method);
    }
  }
}

// One and two threads, and every SIMD level, give the same bits (a fixed gather order per
// body, no float sums across threads).
TEST(Links, TwoThreadsAndEverySimdLevelGiveTheSameBits) {
  const SimdLevel saved = simd_level();
  Chain c = make_chain(3 * 4096 + 17, 50.0, 0.01, 0.0, 2.0);
  for (std::size_t i = 0; i + 7 < c.bodies.size(); i += 7) {  // extra links: a web
    c.links.push_back(fixstep::test::link_between(
        i, i + 7, {.stiffness = 9.0, .damping = 0.1, .rest_length = 0.2}));
  }
  for (Integrator method : all_integrators) {
    // Explicit Euler diverges on this web; implicit Euler's solve is serial (Eigen) and has
    // its own test below.
    if (method == Integrator::explicit_euler || method == Integrator::implicit_euler) continue;
    std::uint64_t reference = 0;
    for (int threads : {1, 2}) {
      for (SimdLevel level : {SimdLevel::baseline, SimdLevel::avx2, SimdLevel::avx512}) {
        if (!simd_supported(level)) continue;
        set_simd_level(level);
        auto w = build<float>(c, WorldSettings{.dt = 1.0 / 120,
                                               .integrator = method,
                                               .track_dissipation = true,
                                               .threads = threads});
        for (int t = 0; t < 8; ++t) w->step();
        EXPECT_EQ(w->threads_used(), threads);
        if (reference == 0) reference = w->state_hash();
        EXPECT_EQ(w->state_hash(), reference)
            << integrator_name(method) << " threads " << threads << " " << simd_level_name(level);
      }
    }
  }
  set_simd_level(saved);
}

// Implicit Euler's network solve (Newton over the whole network, world_implicit.cpp) against
// the per-body closed-form / 2×2 Newton step of the fused pass: a body linked to a body of
// 10¹⁵ kg at rest is a body on an anchored spring (to 1e-15 relative).
TEST(Links, ImplicitNetworkSolveMatchesTheAnchoredSpring) {
  for (const double rest : {0.0, 0.7}) {
    const SpringDamper anchored{
        .anchor = {0.5, -0.25}, .stiffness = 400.0, .damping = 0.0, .rest_length = rest};
    BodyDef free = body_at(1.9, 0.8, 0.5);
    free.body.velocity = {-2.0, 1.5};
    free.drag = LinearDrag{0.3};
    free.gravity = Gravity{};
    detail::WorldKernel<double> single(
        WorldSettings{.dt = 0.05, .integrator = Integrator::implicit_euler});
    BodyDef with_spring = free;
    with_spring.spring = anchored;
    single.create_body(with_spring);
    detail::WorldKernel<double> linked(
        WorldSettings{.dt = 0.05, .integrator = Integrator::implicit_euler});
    const Entity a = linked.create_body(free);
    const Entity b = linked.create_body(body_at(0.5, -0.25, 1e15));
    linked.create_link({a, b, {.stiffness = 400.0, .damping = 0.0, .rest_length = rest}});
    for (int t = 0; t < 100; ++t) {
      single.step(), linked.step();
      ASSERT_NEAR(linked.x()[0], single.x()[0], 1e-9) << "rest " << rest << " tick " << t;
      ASSERT_NEAR(linked.y()[0], single.y()[0], 1e-9) << "rest " << rest << " tick " << t;
      ASSERT_NEAR(linked.vx()[0], single.vx()[0], 1e-8) << "rest " << rest << " tick " << t;
    }
    // ω·h = √(400/0.5)·0.05 = 1.41: stiff enough that the solve matters, and implicit Euler
    // loses energy every step.
    EXPECT_LT(linked.energy().kinetic, 1.0);
  }
}

/// An integrator, a step h (s) and its theoretical order, for the order tests.
struct OrderCase {
  Integrator method;
  double h, order;
};

/// Expects log2(error(h) / error(h/2)) within 0.15 of each case's order; error(method, h) in m.
template <class Error>
void expect_orders(std::initializer_list<OrderCase> cases, Error&& error, const char* what) {
  for (const OrderCase& c : cases) {
    const double coarse = error(c.method, c.h), fine = error(c.method, c.h / 2);
    EXPECT_NEAR(std::log2(coarse / fine), c.order, 0.15)
        << integrator_name(c.method) << " (" << what << "): " << coarse << " -> " << fine << " m";
  }
}

/// Largest position error (m) over the bodies of a damped 6-body chain under gravity after
/// 2 s at step h, against exact::LinearNetwork.
double chain_error(Integrator method, double h, double alpha = 0.02,
                   DampingSplit split = DampingSplit::per_stage) {
  Chain c = make_chain(6, 30.0, alpha);
  for (BodyDef& d : c.bodies) d.gravity = Gravity{};
  const auto exact = exact::LinearNetwork::make(c.bodies, c.links);
  EXPECT_TRUE(exact.has_value());
  auto w = build<double>(c, WorldSettings{.dt = h, .integrator = method, .damping_split = split});
  const auto ticks = static_cast<int>(std::lround(2.0 / h));
  for (int t = 0; t < ticks; ++t) w->step();
  std::vector<Body> truth(c.bodies.size());
  exact->state(w->time(), truth);
  double worst = 0;
  for (std::size_t j = 0; j < truth.size(); ++j) {
    worst = std::max(worst,
                     std::hypot(w->x()[j] - truth[j].position.x, w->y()[j] - truth[j].position.y));
  }
  return worst;
}

// Each integrator keeps its order on a coupled, damped system (links with damping
// proportional to stiffness, so the chain has an exact modal solution).
TEST(Links, EveryIntegratorReachesItsOrderOnADampedChain) {
  expect_orders(
      {{Integrator::semi_implicit_euler, 1.0 / 200, 1.0},
       {Integrator::explicit_euler, 1.0 / 400, 1.0},
       {Integrator::velocity_verlet, 1.0 / 100, 2.0},
       {Integrator::rk4, 1.0 / 50, 4.0},
       {Integrator::implicit_euler, 1.0 / 400, 1.0},
       {Integrator::forest_ruth, 1.0 / 50, 4.0}},
      [](Integrator m, double h) { return chain_error(m, h); }, "damped chain");
  // Heavily damped links (ζ of the fastest mode about 0.8): the split methods keep their
  // orders only if their step stays symmetric with the links' damping flows in it (an
  // ascending colour sweep in place of the descending one drops both to order 1).
  expect_orders(
      {{Integrator::velocity_verlet, 1.0 / 100, 2.0}, {Integrator::forest_ruth, 1.0 / 50, 4.0}},
      [](Integrator m, double h) { return chain_error(m, h, 0.15); }, "heavy damping");
}

// DampingSplit::per_step, the cheaper Forest–Ruth on damped networks (2 link sweeps per step
// instead of 6): the links' damping applied once around the step is a Strang splitting, order
// 2, while the springs keep order 4. Measured on the heavily damped chain (where the damping's
// error dominates): 2. Without link damping it is per_stage bit for bit; velocity Verlet (one
// stage) ignores it.
TEST(Links, PerStepDampingSplitIsOrderTwoAndTheSameWithoutDamping) {
  const auto per_step = [](double alpha) {
    return [alpha](Integrator m, double h) {
      return chain_error(m, h, alpha, DampingSplit::per_step);
    };
  };
  expect_orders({{Integrator::forest_ruth, 1.0 / 100, 2.0}}, per_step(0.15), "per_step, heavy");
  // Cheaper, and less accurate than per_stage where the damping matters.
  EXPECT_GT(chain_error(Integrator::forest_ruth, 1.0 / 100, 0.15, DampingSplit::per_step),
            4 * chain_error(Integrator::forest_ruth, 1.0 / 100, 0.15));
  for (Integrator m : {Integrator::forest_ruth, Integrator::velocity_verlet}) {
    for (double alpha : {0.0, 0.15}) {
      if (m == Integrator::forest_ruth && alpha != 0.0) continue;
      EXPECT_EQ(chain_error(m, 1.0 / 60, alpha, DampingSplit::per_step),
                chain_error(m, 1.0 / 60, alpha))
          << integrator_name(m) << ", alpha " << alpha;
    }
  }
}

// Velocity Verlet and Forest–Ruth reuse the last tick's final force pass when no position
// moved since (world_coupled.cpp). Reused or recomputed, the bits must be the same: a world
// stepped on is compared with a fresh world built from the state before every tick (which
// recomputes it). The last body is kinematic: after the integrator, the tick puts it at
// x0 + v dt, which is not always the bits of the chain's substeps' drifts, and set_body moves
// body 2 between some ticks; either must invalidate the reuse.
TEST(Links, StrangChainReusesItsLastForcePassOnlyWhileItHolds) {
  for (Integrator method : {Integrator::velocity_verlet, Integrator::forest_ruth}) {
    Chain c = make_chain(7, 40.0, 0.05, 0.3);
    c.links.push_back(fixstep::test::link_between(0, 4, {.stiffness = 9.0, .damping = 0.4}));
    c.bodies.back().type = BodyType::kinematic;
    c.bodies.back().body.velocity = {0.37, 0.29};
    const WorldSettings s{.dt = 1.0 / 120, .integrator = method, .substeps = 3};
    auto kept = build<double>(c, s);
    for (int t = 0; t < 40; ++t) {
      if (t % 3 == 0) {
        const Entity e = kept->entities()[2];
        Body b = kept->body(e);
        b.position.x += 0.01;
        kept->set_body(e, b);
      }
      for (std::size_t j = 0; j < c.bodies.size(); ++j)
        c.bodies[j].body = kept->body(kept->entities()[j]);
      auto fresh = build<double>(c, s);
      kept->step(), fresh->step();
      for (std::size_t j = 0; j < c.bodies.size(); ++j) {
        ASSERT_EQ(kept->x()[j], fresh->x()[j]) << integrator_name(method) << " tick " << t;
        ASSERT_EQ(kept->vy()[j], fresh->vy()[j]) << integrator_name(method) << " tick " << t;
      }
    }
  }
}

/// A rest-length network (nonlinear: no exact solution): 5 bodies under gravity, body 0 on an
/// anchored spring, links with rest length 0.5 m and damping along the links, a cross link.
Chain rest_length_network() {
  Chain c = make_chain(5, 60.0, 0.0, 0.5);
  for (std::size_t l = 0; l < c.links.size(); ++l) c.links[l].spring.damping = 0.3;
  c.links.push_back(
      fixstep::test::link_between(0, 2, {.stiffness = 20.0, .damping = 0.1, .rest_length = 0.9}));
  for (BodyDef& d : c.bodies) d.gravity = Gravity{};
  return c;
}

/// The reference: Boost.Odeint's adaptive Dormand–Prince 5(4) at 1e-12 on the same forces,
/// written again here from their definitions (LinkSpring, SpringDamper).
std::vector<Body> odeint_reference(const Chain& c, double t_end) {
  namespace odeint = boost::numeric::odeint;
  using State = std::vector<double>;
  const std::size_t n = c.bodies.size();
  State y(4 * n);
  for (std::size_t j = 0; j < n; ++j) {
    const Body& b = c.bodies[j].body;
    y[4 * j] = b.position.x, y[4 * j + 1] = b.position.y;
    y[4 * j + 2] = b.velocity.x, y[4 * j + 3] = b.velocity.y;
  }
  auto rhs = [&](const State& s, State& dy, double) {
    std::vector<double> fx(n, 0.0), fy(n, 0.0);
    for (std::size_t j = 0; j < n; ++j) {
      const BodyDef& d = c.bodies[j];
      const double m = d.body.mass;
      fx[j] += m * d.gravity.value_or(Gravity{.acceleration = {}}).acceleration.x;
      fy[j] += m * d.gravity.value_or(Gravity{.acceleration = {}}).acceleration.y;
      if (d.spring) {
        fx[j] += -d.spring->stiffness * (s[4 * j] - d.spring->anchor.x) -
                 d.spring->damping * s[4 * j + 2];
        fy[j] += -d.spring->stiffness * (s[4 * j + 1] - d.spring->anchor.y) -
                 d.spring->damping * s[4 * j + 3];
      }
    }
    for (const LinkDef& l : c.links) {
      const std::size_t a = l.body_a.slot(), b = l.body_b.slot();
      const double dx = s[4 * a] - s[4 * b], dy = s[4 * a + 1] - s[4 * b + 1];
      const double ux = s[4 * a + 2] - s[4 * b + 2], uy = s[4 * a + 3] - s[4 * b + 3];
      const double len = std::hypot(dx, dy), nx = dx / len, ny = dy / len;
      const double f = -l.spring.stiffness * (len - l.spring.rest_length) -
                       l.spring.damping * (ux * nx + uy * ny);
      fx[a] += f * nx, fy[a] += f * ny, fx[b] -= f * nx, fy[b] -= f * ny;
    }
    for (std::size_t j = 0; j < n; ++j) {
      dy[4 * j] = s[4 * j + 2], dy[4 * j + 1] = s[4 * j + 3];
      dy[4 * j + 2] = fx[j] / c.bodies[j].body.mass, dy[4 * j + 3] = fy[j] / c.bodies[j].body.mass;
    }
  };
  odeint::integrate_adaptive(
      odeint::make_controlled(1e-13, 1e-13, odeint::runge_kutta_dopri5<State>()), rhs, y, 0.0,
      t_end, 1e-4);
  std::vector<Body> out(n);
  for (std::size_t j = 0; j < n; ++j) {
    out[j].position = {y[4 * j], y[4 * j + 1]}, out[j].velocity = {y[4 * j + 2], y[4 * j + 3]};
  }
  return out;
}

// The orders hold on a nonlinear network too (rest lengths: links pull along themselves,
// implicit Euler runs Newton over the network), against Boost.Odeint at tight tolerance.
TEST(Links, EveryIntegratorReachesItsOrderOnARestLengthNetwork) {
  const Chain c = rest_length_network();
  const std::vector<Body> truth = odeint_reference(c, 1.0);
  auto error = [&](Integrator method, double h) {
    auto w = build<double>(c, WorldSettings{.dt = h, .integrator = method});
    for (int t = 0, ticks = static_cast<int>(std::lround(1.0 / h)); t < ticks; ++t) w->step();
    double worst = 0;
    for (std::size_t j = 0; j < truth.size(); ++j) {
      worst = std::max(
          worst, std::hypot(w->x()[j] - truth[j].position.x, w->y()[j] - truth[j].position.y));
    }
    return worst;
  };
  expect_orders({{Integrator::semi_implicit_euler, 1.0 / 400, 1.0},
                 {Integrator::explicit_euler, 1.0 / 1600, 1.0},
                 {Integrator::velocity_verlet, 1.0 / 200, 2.0},
                 {Integrator::rk4, 1.0 / 100, 4.0},
                 {Integrator::implicit_euler, 1.0 / 400, 1.0},
                 {Integrator::forest_ruth, 1.0 / 100, 4.0}},
                error, "rest-length network");
}

/// (E + E_dissipated - E0)/|E0| after t_end of a damped chain at step h.
double balance_error(Integrator method, double h, double t_end) {
  const Chain c = make_chain(6, 30.0, 0.02);
  auto w =
      build<double>(c, WorldSettings{.dt = h, .integrator = method, .track_dissipation = true});
  const double e0 = w->energy().total();
  const auto ticks = static_cast<int>(std::lround(t_end / h));
  for (int t = 0; t < ticks; ++t) w->step();
  return (w->energy().total() + w->dissipated_energy() - e0) / std::abs(e0);
}

// The energy balance measures the integrator alone: it shrinks at the integrator's order.
TEST(Links, EnergyBalanceShrinksAtTheIntegratorsOrder) {
  struct Case {
    Integrator method;
    double h, order;
  };
  for (const Case& c :
       {Case{Integrator::semi_implicit_euler, 1.0 / 200, 1.0},
        Case{Integrator::velocity_verlet, 1.0 / 100, 2.0},
        Case{Integrator::forest_ruth, 1.0 / 50, 4.0}, Case{Integrator::rk4, 1.0 / 200, 4.0}}) {
    // The largest |balance error| over the last second, at h and h/2.
    auto worst = [&](double h) {
      double m = 0;
      for (double t : {4.0, 4.25, 4.5, 4.75, 5.0})
        m = std::max(m, std::abs(balance_error(c.method, h, t)));
      return m;
    };
    const double coarse = worst(c.h), fine = worst(c.h / 2);
    const double observed = std::log2(coarse / fine);
    EXPECT_NEAR(observed, c.order, 0.3)
        << integrator_name(c.method) << ": " << coarse << " -> " << fine;
    EXPECT_LT(coarse, 0.05) << integrator_name(c.method);
  }
}

// Semi-implicit Euler is symplectic: on an undamped chain its energy error stays bounded
// (no drift) over 10⁶ ticks.
TEST(Links, UndampedChainKeepsBoundedEnergyForAMillionTicks) {
  const Chain c = make_chain(5, 20.0, 0.0);
  auto w = build<double>(c, WorldSettings{.dt = 1.0 / 60});
  const double e0 = w->energy().total();
  double worst_early = 0, worst_late = 0;
  for (int t = 1; t <= 1000000; ++t) {
    w->step();
    if (t % 997 != 0) continue;
    const double err = std::abs(w->energy().total() - e0) / e0;
    (t <= 100000 ? worst_early : worst_late) =
        std::max(t <= 100000 ? worst_early : worst_late, err);
  }
  // ω_max ≈ 2√(k/m) = 8.9 rad/s, ω h ≈ 0.15: the modified-energy bound is a few (ωh)²/4.
  EXPECT_LT(worst_late, 0.05);
  EXPECT_LT(worst_late, 1.5 * worst_early);  // bounded: no secular growth
}

}  // namespace
}  // namespace fixstep
