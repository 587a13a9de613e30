// The multi-pass path of World::step: worlds with links (spring-dampers between bodies) and
// worlds that keep the dissipation account (WorldSettings::track_dissipation).
//
// A force evaluation of a linked world is two passes: one over the links (each link's force
// on its end a, from both ends' states) and one over the bodies (each body's own field, see
// body_field.hpp, plus the forces of its links gathered in link order through the CSR lists
// of World::Network). Every value is written by exactly one pass element and no sum ever
// crosses a thread, so one and two threads give the same bits. Multi-stage methods run the
// pair once per stage, with stage states in scratch arrays sized at rebuild, never per tick.
//
// Link damping couples the bodies' velocities, so the damping flow D(τ) of the Strang-split
// methods (velocity Verlet, Forest–Ruth; see integrators.hpp) is no longer a per-body factor:
// it is v(τ) = exp(-τC) v with C the damping matrix (per-body γ on the diagonal, the links'
// b/m coupling the ends). fixstep applies exp(-τC) as its fourth-order Taylor polynomial,
// w = v; w = v - (τ/k) C w for k = 4, 3, 2, 1 (Horner), whose local error O(τ⁵) keeps Verlet at
// order 2 and the triple jump at order 4 (Hairer, Lubich & Wanner, Geometric Numerical
// Integration, §III.3 and §II.4: a composition keeps its order when each factor is
// approximated beyond it). One factor is stable for τ·λ_max(C) <= 2.785 (RK4's real-axis
// bound), but the factors of a step combine: a pure damping mode stays bounded for
// h·λ <= 5.571 under Verlet and only h·λ <= 2.857 under Forest–Ruth. The network stability
// guard (stability_network.cpp) measures the real step, so it applies the combined bounds.
// Without link damping D stays the exact per-body factor.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>
#include <type_traits>

#include "body_field.hpp"
#include "fixstep/world.hpp"
#include "link_passes.hpp"
#include "workers.hpp"

namespace fixstep {

namespace detail {

void WorkersDeleter::operator()(Workers* w) const {
  delete w;
}

}  // namespace detail

namespace {

/// Smallest range worth handing to the second thread.
constexpr std::size_t min_parallel_range = 4096;

}  // namespace

template <class Real>
template <class Pass>
void World<Real>::parallel(std::size_t n, Pass&& pass) {
  if (threads_used_ < 2 || n < min_parallel_range) {
    pass(std::size_t{0}, n);
    return;
  }
  const std::size_t mid = n / 2;
  struct Context {
    std::remove_reference_t<Pass>* pass;
    std::size_t begin, end;
  } ctx{&pass, mid, n};
  workers_->submit(
      [](void* p) {
        auto* c = static_cast<Context*>(p);
        (*c->pass)(c->begin, c->end);
      },
      &ctx);
  pass(std::size_t{0}, mid);
  workers_->wait();
}

template <class Real>
void World<Real>::rebuild_network() {
  Network& net = net_;
  const std::size_t n = body_count(), m = link_defs_.size();
  net.a.resize(m), net.b.resize(m);
  net.k.resize(m), net.damping.resize(m), net.rest.resize(m);
  net.inv_mass.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    // Static and kinematic ends are immovable: links do not accelerate them.
    net.inv_mass[j] = types_[j] == BodyType::dynamic ? static_cast<Real>(1.0 / mass_[j]) : Real(0);
  }
  net.offset.assign(n + 1, 0);
  net.rest_length = net.damped = false;
  for (std::size_t l = 0; l < m; ++l) {
    const LinkDef& d = link_defs_[l];
    net.a[l] = static_cast<std::uint32_t>(bodies_.index(d.body_a));
    net.b[l] = static_cast<std::uint32_t>(bodies_.index(d.body_b));
    net.k[l] = static_cast<Real>(d.spring.stiffness);
    net.damping[l] = static_cast<Real>(d.spring.damping);
    net.rest[l] = static_cast<Real>(d.spring.rest_length);
    net.rest_length = net.rest_length || net.rest[l] != Real(0);
    net.damped = net.damped || net.damping[l] != Real(0);
    ++net.offset[net.a[l] + 1], ++net.offset[net.b[l] + 1];
  }
  net.driven.clear();  // links a static or kinematic end may do work through
  for (std::size_t l = 0; l < m; ++l) {
    if (net.inv_mass[net.a[l]] == Real(0) || net.inv_mass[net.b[l]] == Real(0)) {
      net.driven.push_back(static_cast<std::uint32_t>(l));
    }
  }
  for (std::size_t j = 0; j < n; ++j) net.offset[j + 1] += net.offset[j];
  net.incident.resize(2 * m);
  std::vector<std::uint32_t> fill(net.offset.begin(), net.offset.end() - 1);
  for (std::size_t l = 0; l < m; ++l) {  // link order within each body's list
    net.incident[fill[net.a[l]]++] = static_cast<std::uint32_t>(2 * l);
    net.incident[fill[net.b[l]]++] = static_cast<std::uint32_t>(2 * l + 1);
  }
  fx_.assign(m, Real(0)), fy_.assign(m, Real(0)), power_link_.assign(m, Real(0));
  for (auto& v : s_) v.assign(n, Real(0));
  for (auto& v : d_) v.assign(n, Real(0));
  power_body_.assign(n, Real(0));
  implicit_.reset();  // its matrix pattern changed
}

template <class Real>
void World<Real>::step_multipass(const TickInput& input) {
  const std::size_t n = x_.size(), m = net_.a.size();
  const int want = settings_.threads;
  static const bool second_core = std::thread::hardware_concurrency() >= 2;  // a syscall: once
  threads_used_ = want == 1 ? 1 : want >= 2 ? 2 : (second_core && n >= parallel_min_bodies) ? 2 : 1;
  if (threads_used_ == 2 && !workers_) workers_.reset(new detail::Workers());
  const Real push[2] = {static_cast<Real>(input.push.x), static_cast<Real>(input.push.y)};
  const Real h = static_cast<Real>(settings_.dt / settings_.substeps);
  const StepSizes<Real> sizes{h, static_cast<Real>(forest_ruth_w1 * double(h)),
                              static_cast<Real>(forest_ruth_w0 * double(h))};
  const Coefficients& c = coeff_;
  const SpringShape shape = !c.spring       ? SpringShape::none
                            : c.rest_length ? SpringShape::rest_length
                                            : SpringShape::linear;
  const bool accel = c.accel || push[0] != Real(0) || push[1] != Real(0);
  const Integrator method = settings_.integrator;
  std::atomic<bool> bad{false};
  auto par = [this](std::size_t count, auto&& pass) { this->parallel(count, pass); };
  Passes<Real, Network, Coefficients, decltype(par)> p{
      net_,
      c,
      par,
      n,
      m,
      x_.data(),
      y_.data(),
      vx_.data(),
      vy_.data(),
      fx_.data(),
      fy_.data(),
      {s_[0].data(), s_[1].data(), s_[2].data(), s_[3].data()},
      {d_[0].data(), d_[1].data(), d_[2].data(), d_[3].data()},
      power_body_.data(),
      power_link_.data(),
      dissipated_body_.data(),
      dissipated_link_.data(),
      settings_.track_dissipation,
      threads_used_ < 2,
      push,
      shape,
      accel,
      bad,
      external_work_};
  // Exact per-body damping factors, as the fused sweep uses them.
  const bool per_body_decay = c.damping && (m == 0 || !net_.damped);
  const Real* decay_h = per_body_decay && method == Integrator::velocity_verlet
                            ? damping_decay(0.5 * double(h))
                            : nullptr;
  const bool fr = per_body_decay && method == Integrator::forest_ruth;
  const Real* decay_h1 = fr ? damping_decay(0.5 * double(sizes.h1)) : nullptr;
  const Real* decay_h0 = fr ? damping_decay(0.5 * double(sizes.h0)) : nullptr;

  for (int sub = 0; sub < settings_.substeps; ++sub) {
    if (m == 0) {
      // No links: each body's fused step, as in the sweep, with the dissipation account.
      auto fused = [&]<Integrator I, int Decays>(const Real* d0, const Real* d1) {
        Real* diss = dissipated_body_.data();
        p.template bodies<Decays>(c.damping, d0, d1, [&](const auto& f, std::size_t j) {
          Real X = x_[j], Y = y_[j], VX = vx_[j], VY = vy_[j];
          body_step<I, true>(X, Y, VX, VY, f, sizes, diss[j]);
          x_[j] = X, y_[j] = Y, vx_[j] = VX, vy_[j] = VY;
          return out_of_range(X, Y, VX, VY);
        });
      };
      dispatch(method, decay_h, decay_h1, decay_h0, fused);
      continue;
    }
    switch (method) {
      case Integrator::semi_implicit_euler:
        p.template euler<false>(h);
        break;
      case Integrator::explicit_euler:
        p.template euler<true>(h);
        break;
      case Integrator::rk4:
        p.rk4(h);
        break;
      case Integrator::velocity_verlet:
        p.strang(h, decay_h);
        break;
      case Integrator::forest_ruth:
        p.strang(sizes.h1, decay_h1);
        p.strang(sizes.h0, decay_h0);
        p.strang(sizes.h1, decay_h1);
        break;
      case Integrator::implicit_euler:
        if (step_implicit_network(h, push)) bad.store(true, std::memory_order_relaxed);
        p.drive({x_.data(), y_.data(), vx_.data(), vy_.data()}, double(h));  // end of the step
        break;
    }
  }
  ++tick_;
  if (bad.load(std::memory_order_relaxed) && !fault_) record_fault();
}

#define FIXSTEP_INSTANTIATE(Real)                              \
  template void World<Real>::step_multipass(const TickInput&); \
  template void World<Real>::rebuild_network();
FIXSTEP_INSTANTIATE(float)
FIXSTEP_INSTANTIATE(double)
#undef FIXSTEP_INSTANTIATE

}  // namespace fixstep
