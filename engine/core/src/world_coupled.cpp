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
#include "fixstep/core/components.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/world_settings.hpp"
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

/// The threads a tick of the multi-pass path on n bodies runs on: WorldSettings::threads
/// (threads_for), and with 0 (automatic) two only from parallel_min_bodies bodies.
int multipass_threads(int want, std::size_t n) {
  return detail::threads_for(want) == 2 && (want >= 2 || n >= parallel_min_bodies) ? 2 : 1;
}

/// What a tick of the multi-pass path steps with: the push (m/s², Real), the step h = dt /
/// substeps and Forest–Ruth's w1·h, w0·h (s), and the shape of the bodies' fields.
template <class Real>
struct MultipassPlan {
  Real push[2];
  StepSizes<Real> sizes;
  SpringShape shape;
  bool accel;  ///< some body has a constant acceleration, or the tick a push
};

/// The plan of a tick from the settings, the bodies' coefficients and the tick's input.
template <class Real, class Coeff>
MultipassPlan<Real> plan_multipass(const WorldSettings& settings, const Coeff& c,
                                   const TickInput& input) {
  const Real h = static_cast<Real>(settings.dt / settings.substeps);
  MultipassPlan<Real> plan{
      .push = {static_cast<Real>(input.push.x), static_cast<Real>(input.push.y)},
      .sizes = {h, static_cast<Real>(forest_ruth_w1 * double(h)),
                static_cast<Real>(forest_ruth_w0 * double(h))},
      .shape = !c.spring       ? SpringShape::none
               : c.rest_length ? SpringShape::rest_length
                               : SpringShape::linear,
      .accel = c.accel};
  plan.accel = plan.accel || plan.push[0] != Real(0) || plan.push[1] != Real(0);
  return plan;
}

/// The stages of a Strang tick: one per velocity Verlet step, three (w1·h, w0·h, w1·h) per
/// Forest–Ruth step; stage i of the tick is at(i).
template <class Real>
struct StrangStages {
  StrangStage<Real> first, inner, last;
  std::size_t per_step = 1;
  [[nodiscard]] StrangStage<Real> at(std::size_t i) const {
    const std::size_t k = i % per_step;
    return k == 0 ? first : k == 1 ? inner : last;
  }
};

/// The stages of a tick of velocity Verlet or Forest–Ruth on a linked world, with the bodies'
/// exact decay over each stage's h/2 (decay(τ): World::damping_decay, with body damping) and
/// the links' damping sweeps (flow(τ): World::link_flow as a SweepFlow, with link damping):
/// around every stage's drift over its own h/2 (DampingSplit::per_stage), or once around the
/// whole Forest–Ruth step over h/2 (per_step: the first stage's C↑ and the last stage's C↓
/// only).
template <class Real, class Decay, class Flow>
StrangStages<Real> strang_stages(Integrator method, DampingSplit split, bool body_damping,
                                 bool link_damping, const StepSizes<Real>& sizes, Decay&& decay,
                                 Flow&& flow) {
  const bool verlet = method == Integrator::velocity_verlet;
  const bool split_per_step = !verlet && split == DampingSplit::per_step;
  auto stage_of = [&](Real hh, bool up, bool down) {
    StrangStage<Real> st{.h = hh};
    if (body_damping) st.decay = decay(0.5 * double(hh));
    if (link_damping && (up || down)) {
      const SweepFlow<Real> f = flow(0.5 * double(split_per_step ? sizes.h : hh));
      if (up) st.up = f;
      if (down) st.down = f;
    }
    return st;
  };
  // Twice: a cache full of other steps' factors is cleared by the first look-up that
  // misses, which could drop the other τ's; the second round finds them all.
  if (!verlet) stage_of(sizes.h1, true, true), stage_of(sizes.h0, true, true);
  const bool inner_flows = !split_per_step;
  StrangStages<Real> stages;
  stages.first = stage_of(verlet ? sizes.h : sizes.h1, true, inner_flows);
  stages.inner = verlet ? stages.first : stage_of(sizes.h0, inner_flows, inner_flows);
  stages.last = verlet ? stages.first : stage_of(sizes.h1, inner_flows, true);
  stages.per_step = verlet ? 1 : 3;
  return stages;
}

/// A tick of velocity Verlet or Forest–Ruth on a linked world: its stages as one Strang chain
/// (strang_network.hpp) with the link sums in acc and the links' directions in (ux, uy);
/// `cached`: the last tick's final force pass left them, and no position moved since.
template <class P, class Real>
void run_strang_chain(P& p, const StrangStages<Real>& stages, int substeps, Real* accx, Real* accy,
                      Real* ux, Real* uy, bool cached) {
  StrangChain<P, Real> chain(p, accx, accy, ux, uy);
  chain.run(
      stages.per_step * static_cast<std::size_t>(substeps),
      [&](std::size_t i) { return stages.at(i); }, cached);
}

/// Whether a and b hold the same bits.
template <class Real>
bool same_positions(const std::vector<Real>& a, const std::vector<Real>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), same_bits<Real>);
}

/// The bodies' exact damping factors e^{-γτ} the fused step of a world without links uses (as
/// the sweep): over h/2 for velocity Verlet, over w1·h/2 and w0·h/2 for Forest–Ruth; null
/// for other methods and without body damping.
template <class Real>
struct BodyDecays {
  const Real *h = nullptr, *h1 = nullptr, *h0 = nullptr;
};

/// BodyDecays from decay(τ) (World::damping_decay).
template <class Real, class Decay>
BodyDecays<Real> body_decays(Integrator method, bool damped, const StepSizes<Real>& sizes,
                             Decay&& decay) {
  BodyDecays<Real> d;
  if (damped && method == Integrator::velocity_verlet) d.h = decay(0.5 * double(sizes.h));
  if (damped && method == Integrator::forest_ruth) {
    d.h1 = decay(0.5 * double(sizes.h1)), d.h0 = decay(0.5 * double(sizes.h0));
  }
  return d;
}

/// One step of a world without links (that keeps the dissipation account): each body's fused
/// step, as in the sweep, with the account.
template <class P, class Real>
void fused_substep(P& p, Integrator method, const StepSizes<Real>& sizes,
                   const BodyDecays<Real>& decays) {
  auto fused = [&]<Integrator I, int Decays>(const Real* d0, const Real* d1) {
    Real *x = p.x, *y = p.y, *vx = p.vx, *vy = p.vy, *diss = p.diss_body;
    p.template bodies<Decays>(p.c.damping, d0, d1, [&](const auto& f, std::size_t j) {
      Real X = x[j], Y = y[j], VX = vx[j], VY = vy[j];
      body_step<I, true>(X, Y, VX, VY, f, sizes, diss[j]);
      x[j] = X, y[j] = Y, vx[j] = VX, vy[j] = VY;
      return out_of_range(X, Y, VX, VY);
    });
  };
  dispatch(method, decays.h, decays.h1, decays.h0, fused);
}

/// One step h (s) of a linked world by Euler, RK4 or implicit Euler (implicit(h):
/// World::step_implicit_network, true if the state left the range).
template <class P, class Real, class Implicit>
void linked_substep(P& p, Integrator method, Real h, Implicit&& implicit) {
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
      break;  // the Strang chain (strang_network.hpp)
    case Integrator::implicit_euler:
      p.flag(implicit(h));
      p.drive({p.x, p.y, p.vx, p.vy}, double(h));  // end of the step
      break;
  }
}

/// The substeps of a tick by every method but the Strang chain, polling for a stop request
/// once a substep (on this thread, with the worker idle between passes).
template <class P, class Real, class Implicit>
void run_substeps(P& p, Integrator method, int substeps, const StepSizes<Real>& sizes,
                  const BodyDecays<Real>& decays, Implicit&& implicit) {
  for (int sub = 0; sub < substeps; ++sub) {
    throw_if_stop_requested();
    if (p.m == 0) {
      fused_substep(p, method, sizes, decays);
    } else {
      linked_substep(p, method, sizes.h, implicit);
    }
  }
}

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
  threads_used_ = multipass_threads(settings_.threads, n);
  if (threads_used_ == 2 && !workers_) workers_.reset(new detail::Workers());
  const MultipassPlan<Real> plan = plan_multipass<Real>(settings_, coeff_, input);
  std::atomic<bool> bad{false};
  auto par = [this](std::size_t count, auto&& pass, std::size_t min_range = min_parallel_range) {
    this->parallel(count, pass, min_range);
  };
  Passes<Real, Network, Coefficients, decltype(par)> p{
      net_,
      coeff_,
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
      plan.push,
      plan.shape,
      plan.accel,
      bad,
      external_work_,
      m == 0 && awake_.on ? &awake_.bodies : nullptr};  // sleepers skipped without links
  const Integrator method = settings_.integrator;
  auto decay = [this](double tau) { return damping_decay(tau); };
  if (m > 0 && (method == Integrator::velocity_verlet || method == Integrator::forest_ruth)) {
    auto sweep = [this](double tau) {
      const LinkFlow& f = link_flow(tau);
      return SweepFlow<Real>{f.ca.data(), f.cb.data()};
    };
    const StrangStages<Real> stages = strang_stages(method, settings_.damping_split, coeff_.damping,
                                                    net_.damped, plan.sizes, decay, sweep);
    // The last tick's final link sums still hold if no position moved since (contacts, drag
    // input, set_state and restore all move them or leave them bit for bit).
    const bool same = fsal_valid_ && same_positions(x_, fsal_x_) && same_positions(y_, fsal_y_);
    run_strang_chain(p, stages, settings_.substeps, d_[0].data(), d_[1].data(), unit_x_.data(),
                     unit_y_.data(), same);
    std::copy(x_.begin(), x_.end(), fsal_x_.begin());
    std::copy(y_.begin(), y_.end(), fsal_y_.begin());
    fsal_valid_ = true;
  } else {
    fsal_valid_ = false;  // d_ is other methods' scratch
    run_substeps(p, method, settings_.substeps, plan.sizes,
                 body_decays(method, coeff_.damping && m == 0, plan.sizes, decay),
                 [&](Real h) { return step_implicit_network(h, plan.push); });
  }
  ++tick_;
  if (bad.load(std::memory_order_relaxed) && !fault_) record_fault();
}

}  // namespace fixstep
