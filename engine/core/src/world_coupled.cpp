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
// Velocity Verlet and Forest–Ruth run the symmetric chain of strang_network.hpp: the links'
// damping as their exact per-link flows, composed by colours (link_damping.hpp), so the
// methods keep orders 2 and 4 at the cost of their force passes plus one loop over the links.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "body_field.hpp"
#include "fixstep/core/bits.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/stop_request.hpp"
#include "link_damping.hpp"
#include "link_passes.hpp"
#include "strang_network.hpp"
#include "workers.hpp"
#include "world_kernel.hpp"

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
void detail::WorldKernel<Real>::parallel(std::size_t n, Pass&& pass, std::size_t min_range) {
  if (threads_used_ < 2 || n < min_range) {
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
void detail::WorldKernel<Real>::rebuild_network() {
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
  net.all_rest_length = m > 0;
  for (std::size_t l = 0; l < m; ++l) {
    const LinkDef& d = link_defs_[l];
    net.a[l] = static_cast<std::uint32_t>(bodies_.index(d.body_a));
    net.b[l] = static_cast<std::uint32_t>(bodies_.index(d.body_b));
    net.k[l] = static_cast<Real>(d.spring.stiffness);
    net.damping[l] = static_cast<Real>(d.spring.damping);
    net.rest[l] = static_cast<Real>(d.spring.rest_length);
    net.rest_length = net.rest_length || net.rest[l] != Real(0);
    net.all_rest_length = net.all_rest_length && net.rest[l] != Real(0);
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
  net.color_offset.clear(), net.by_color.clear();
  if (net.damped) color_links(n, net.a, net.b, net.color_offset, net.by_color);
  const std::size_t colored = net.by_color.size();
  net.color_a.resize(colored), net.color_b.resize(colored);
  net.color_k.resize(colored), net.color_rest.resize(colored);
  for (std::size_t i = 0; i < colored; ++i) {
    const std::uint32_t l = net.by_color[i];
    net.color_a[i] = net.a[l], net.color_b[i] = net.b[l];
    net.color_k[i] = net.k[l], net.color_rest[i] = net.rest[l];
  }
  link_flows_.clear();
  fx_.assign(m, Real(0)), fy_.assign(m, Real(0)), power_link_.assign(m, Real(0));
  unit_x_.assign(net.damped ? m : 0, Real(0)), unit_y_.assign(net.damped ? m : 0, Real(0));
  fsal_x_.assign(n, Real(0)), fsal_y_.assign(n, Real(0));
  fsal_valid_ = false;
  for (auto& v : s_) v.assign(n, Real(0));
  for (auto& v : d_) v.assign(n, Real(0));
  power_body_.assign(n, Real(0));
  implicit_.reset();  // its matrix pattern changed
}

// Each link's exact damping flow over τ (link_damping.hpp), from the masses and dampers in
// double, rounded once; cached per τ (Verlet needs one, Forest–Ruth two).
template <class Real>
const typename detail::WorldKernel<Real>::LinkFlow& detail::WorldKernel<Real>::link_flow(
    double tau) {
  for (const LinkFlow& f : link_flows_) {
    if (f.tau == tau) return f;
  }
  if (link_flows_.size() >= 4) link_flows_.clear();  // the step sizes changed
  LinkFlow f;
  f.tau = tau;
  const std::size_t m = net_.by_color.size();  // in colour order
  f.ca.resize(m), f.cb.resize(m);
  auto inverse_mass = [&](std::uint32_t j) {
    return types_[j] == BodyType::dynamic ? 1.0 / mass_[j] : 0.0;
  };
  for (std::size_t i = 0; i < m; ++i) {
    const std::uint32_t l = net_.by_color[i];
    const double ia = inverse_mass(net_.a[l]), ib = inverse_mass(net_.b[l]);
    const double sum = ia + ib, mu = link_defs_[l].spring.damping * sum;
    const double q = sum > 0.0 ? det::expm1(-mu * tau) / sum : 0.0;
    f.ca[i] = static_cast<Real>(ia * q), f.cb[i] = static_cast<Real>(ib * q);
  }
  link_flows_.push_back(std::move(f));
  return link_flows_.back();
}

template <class Real>
void detail::WorldKernel<Real>::step_multipass(const TickInput& input) {
  const std::size_t n = x_.size(), m = net_.a.size();
  const int want = settings_.threads;
  threads_used_ = detail::threads_for(want) == 2 && (want >= 2 || n >= parallel_min_bodies) ? 2 : 1;
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
  auto par = [this](std::size_t count, auto&& pass, std::size_t min_range = min_parallel_range) {
    this->parallel(count, pass, min_range);
  };
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
  // Exact per-body damping factors, as the fused sweep uses them (worlds without links).
  const bool per_body_decay = c.damping && m == 0;
  const Real* decay_h = per_body_decay && method == Integrator::velocity_verlet
                            ? damping_decay(0.5 * double(h))
                            : nullptr;
  const bool fr = per_body_decay && method == Integrator::forest_ruth;
  const Real* decay_h1 = fr ? damping_decay(0.5 * double(sizes.h1)) : nullptr;
  const Real* decay_h0 = fr ? damping_decay(0.5 * double(sizes.h0)) : nullptr;
  const bool strang =
      m > 0 && (method == Integrator::velocity_verlet || method == Integrator::forest_ruth);
  if (!strang) fsal_valid_ = false;  // d_ is other methods' scratch
  if (strang) {
    // One stage per Verlet step, three (w1·h, w0·h, w1·h) per Forest–Ruth step. The links'
    // damping sweeps: around every stage's drift over its own h/2 (DampingSplit::per_stage),
    // or once around the whole Forest–Ruth step over h/2 (per_step: the first stage's C↑ and
    // the last stage's C↓ only).
    const bool verlet = method == Integrator::velocity_verlet;
    const bool split_per_step = !verlet && settings_.damping_split == DampingSplit::per_step;
    auto sweep = [&](double tau) {
      const LinkFlow& f = link_flow(tau);
      return SweepFlow<Real>{f.ca.data(), f.cb.data()};
    };
    auto stage_of = [&](Real hh, bool up, bool down) {
      StrangStage<Real> st{.h = hh};
      if (c.damping) st.decay = damping_decay(0.5 * double(hh));
      if (net_.damped && (up || down)) {
        const SweepFlow<Real> flow = sweep(0.5 * double(split_per_step ? h : hh));
        if (up) st.up = flow;
        if (down) st.down = flow;
      }
      return st;
    };
    // Twice: a cache full of other steps' factors is cleared by the first look-up that
    // misses, which could drop the other τ's; the second round finds them all.
    if (!verlet) stage_of(sizes.h1, true, true), stage_of(sizes.h0, true, true);
    const bool inner_flows = !split_per_step;
    const StrangStage<Real> first = stage_of(verlet ? h : sizes.h1, true, inner_flows);
    const StrangStage<Real> inner = verlet ? first : stage_of(sizes.h0, inner_flows, inner_flows);
    const StrangStage<Real> last = verlet ? first : stage_of(sizes.h1, inner_flows, true);
    const std::size_t per_step = verlet ? 1 : 3;
    StrangChain<decltype(p), Real> chain(p, d_[0].data(), d_[1].data(), unit_x_.data(),
                                         unit_y_.data());
    // The last tick's final link sums still hold if no position moved since (contacts, drag
    // input, set_state and restore all move them or leave them bit for bit).
    const bool same = fsal_valid_ &&
                      std::equal(x_.begin(), x_.end(), fsal_x_.begin(), same_bits<Real>) &&
                      std::equal(y_.begin(), y_.end(), fsal_y_.begin(), same_bits<Real>);
    chain.run(
        per_step * static_cast<std::size_t>(settings_.substeps),
        [&](std::size_t i) {
          const std::size_t k = i % per_step;
          return k == 0 ? first : k == 1 ? inner : last;
        },
        same);
    std::copy(x_.begin(), x_.end(), fsal_x_.begin()),
        std::copy(y_.begin(), y_.end(), fsal_y_.begin());
    fsal_valid_ = true;
    ++tick_;
    if (bad.load(std::memory_order_relaxed) && !fault_) record_fault();
    return;
  }

  for (int sub = 0; sub < settings_.substeps; ++sub) {
    throw_if_stop_requested();  // on this thread, with the worker idle between passes
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
      case Integrator::forest_ruth:
        break;  // the Strang chain above
      case Integrator::implicit_euler:
        if (step_implicit_network(h, push)) bad.store(true, std::memory_order_relaxed);
        p.drive({x_.data(), y_.data(), vx_.data(), vy_.data()}, double(h));  // end of the step
        break;
    }
  }
  ++tick_;
  if (bad.load(std::memory_order_relaxed) && !fault_) record_fault();
}

#define FIXSTEP_INSTANTIATE(Real)                                            \
  template void detail::WorldKernel<Real>::step_multipass(const TickInput&); \
  template void detail::WorldKernel<Real>::rebuild_network();                \
  template const detail::WorldKernel<Real>::LinkFlow& detail::WorldKernel<Real>::link_flow(double);
FIXSTEP_INSTANTIATE(float)
FIXSTEP_INSTANTIATE(double)
#undef FIXSTEP_INSTANTIATE

}  // namespace fixstep
