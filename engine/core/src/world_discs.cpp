// The World's side of body types and disc-disc contacts: which bodies are discs, the
// static and kinematic bodies' motion, and the energy account of contacts (the contact model
// itself is in disc_contacts.hpp, disc_events.cpp and disc_rest.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <numeric>

#include "contact_kappa.hpp"
#include "disc_contacts.hpp"
#include "owner_ptrs.hpp"
#include "sorted_lists.hpp"
#include "workers.hpp"
#include "world_kernel.hpp"

namespace fixstep {

namespace detail {
template <class T>
T* ClonePtr<T>::clone(const T& t) {
  return new T(t);
}
template <class T>
void ClonePtr<T>::assign(T*& to, const T* from) {
  if (!from) {
    delete to;
    to = nullptr;
  } else if (to) {
    *to = *from;
  } else {
    to = new T(*from);
  }
}
template <class T>
void ClonePtr<T>::destroy(T* t) {
  delete t;
}
template class ClonePtr<DiscContacts<float>>;
template class ClonePtr<DiscContacts<double>>;
}  // namespace detail

template <class Real>
void detail::WorldKernel<Real>::rebuild_discs() {
  rebuild_immovable();
  disc_of_.clear();
  kinematic_discs_.clear();
  if (!settings_.contacts) {
    discs_.reset();
    return;
  }
  const ContactSettings& cs = *settings_.contacts;
  std::vector<std::uint32_t> order;  // colliders that collide, in dense body order
  for (std::uint32_t i = 0; i < colliders_.data.size(); ++i) {
    if (colliders_.data[i].collide) order.push_back(i);
  }
  auto body_of = [&](std::uint32_t i) { return bodies_.index(colliders_.set.dense[i]); };
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return body_of(a) < body_of(b); });
  std::vector<std::int32_t> plane_slot(body_count(), -1);  // body -> its plane collider slot
  for (std::size_t k = 0; k < contact_.body.size(); ++k) {
    plane_slot[contact_.body[k]] = static_cast<std::int32_t>(k);
  }
  std::vector<detail::Disc> discs(order.size());
  std::vector<CollisionFilter> filters(order.size());
  bool filtered = false;  // some disc has a filter other than the default, or is a sensor
  disc_of_.assign(body_count(), -1);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Collider& c = colliders_.data[order[k]];
    const std::size_t j = body_of(order[k]);
    detail::Disc& d = discs[k];
    d.body = static_cast<std::uint32_t>(j);
    d.radius = c.radius;
    d.restitution = c.restitution.value_or(cs.restitution);
    d.friction = c.friction.value_or(cs.friction);
    d.dynamic = types_[j] == BodyType::dynamic ? 1 : 0;
    d.inv_mass = d.dynamic ? 1.0 / mass_[j] : 0.0;
    d.plane_slot = contact_.active ? plane_slot[j] : -1;
    d.sensor = c.sensor ? 1 : 0;
    d.inv_inertia = rolling_ && d.dynamic && !c.sensor ? 1.0 / inertia_of(mass_[j], c) : 0.0;
    filters[k] = c.filter;
    filtered = filtered || c.sensor || c.filter != CollisionFilter{};
    disc_of_[j] = static_cast<std::int32_t>(k);
    if (types_[j] == BodyType::kinematic) kinematic_discs_.push_back(static_cast<std::uint32_t>(j));
  }
  dynamic_discs_ = static_cast<std::size_t>(
      std::count_if(discs.begin(), discs.end(), [](const detail::Disc& d) { return d.dynamic; }));
  if (!filtered) filters.clear();
  std::vector<std::uint64_t> linked;
  for (const LinkDef& l : link_defs_) {
    const std::int64_t a = disc_of_[bodies_.index(l.body_a)], b = disc_of_[bodies_.index(l.body_b)];
    if (a < 0 || b < 0) continue;
    linked.push_back((std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b)));
  }
  std::sort(linked.begin(), linked.end());
  linked.erase(std::unique(linked.begin(), linked.end()), linked.end());
  if (!discs_) discs_.reset(new detail::DiscContacts<Real>());
  discs_->rebuild(std::move(discs), std::move(linked), std::move(filters), cs);
  discs_->set_accelerations(coeff_.accel_x, coeff_.accel_y);
}

// Kinematic bodies, and static ones and with ContactSettings::sleep the sleepers unless the
// free step skips them (the awake runs: without links, with or without the energy account,
// in a world with sleeping or with a static body).
template <class Real>
void detail::WorldKernel<Real>::rebuild_immovable() {
  if (awake_.on && !awake_.whole) {  // the list is the kinematic bodies, which did not change
    update_awake_runs();
    immovable_dirty_ = false;
    return;
  }
  Immovable& m = immovable_;
  m.body.clear();
  const bool statics =
      std::find(types_.begin(), types_.end(), BodyType::static_body) != types_.end();
  const bool skip = (sleep_ || statics) && net_.a.empty();
  for (std::size_t j = 0; j < body_count(); ++j) {
    const bool sleeps = sleep_ && asleep_[j] != 0;
    const bool rests = types_[j] == BodyType::static_body || sleeps;
    if (types_[j] == BodyType::kinematic || (rests && !skip)) {
      m.body.push_back(static_cast<std::uint32_t>(j));
    }
  }
  for (auto* v : {&m.x0, &m.y0, &m.vx0, &m.vy0}) v->resize(m.body.size());
  immovable_dirty_ = false;
  rebuild_awake_runs(skip);
}

template <class Real>
void detail::WorldKernel<Real>::rebuild_awake_runs(bool on) {
  AwakeRuns& a = awake_;
  a.on = on, a.primed = false;
  a.flipped.clear(), a.whole = !on || !sleep_;
  if (!on) return;
  auto asleep = [&](std::uint32_t j) { return sleep_ && asleep_[j] != 0; };
  // A static body never moves: the free step leaves it where it is, as putting it back did.
  auto awake = [&](std::uint32_t j) { return !asleep(j) && types_[j] != BodyType::static_body; };
  collect_runs(body_count(), awake, a.bodies);
  const auto& body = contact_.body;  // dynamic colliders, in dense order
  auto awake_collider = [&](std::uint32_t k) { return !asleep(body[k]); };
  collect_runs(body.size(), awake_collider, a.colliders);
}

// The runs less the bodies that fell asleep since they were built, and with those that woke:
// O(runs + flips), the same runs as rebuild_awake_runs makes from every body. A body that fell
// asleep is left as a tick over every body would leave a sleeper, so the runs stay primed: its
// previous position is where it sleeps, and its plane motion none.
template <class Real>
void detail::WorldKernel<Real>::update_awake_runs() {
  AwakeRuns& a = awake_;
  std::vector<std::uint32_t>& flipped = a.flipped;
  sort_unique(flipped);
  std::vector<std::uint32_t>& woke = run_scratch_.woke;
  std::vector<std::uint32_t>& slept = run_scratch_.slept;
  woke.clear(), slept.clear();
  for (const std::uint32_t j : flipped) (asleep_[j] == 0 ? woke : slept).push_back(j);
  std::vector<IndexRun>& out = run_scratch_.runs;
  update_runs(a.bodies, woke, slept, out);
  std::swap(a.bodies, out);
  // The colliders' runs: ContactScratch::body is in increasing body order.
  const std::vector<std::uint32_t>& body = contact_.body;
  auto slots = [&](std::span<const std::uint32_t> bodies, std::vector<std::uint32_t>& to) {
    to.clear();
    for (const std::uint32_t j : bodies) {
      const auto at = std::lower_bound(body.begin(), body.end(), j);
      if (at != body.end() && *at == j) to.push_back(static_cast<std::uint32_t>(at - body.begin()));
    }
  };
  slots(woke, run_scratch_.woke_slots), slots(slept, run_scratch_.slept_slots);
  update_runs(a.colliders, run_scratch_.woke_slots, run_scratch_.slept_slots, out);
  std::swap(a.colliders, out);
  for (const std::uint32_t j : slept) {
    if (keep_previous_) prev_x_[j] = x_[j], prev_y_[j] = y_[j];
  }
  for (const std::uint32_t k : run_scratch_.slept_slots) {
    if (k < contact_.after_t.size()) contact_.after_t[k] = -1.0;
  }
  flipped.clear();
}

template <class Real>
void detail::WorldKernel<Real>::save_tick_start(bool discs) {
  Immovable& m = immovable_;
  for (std::size_t i = 0; i < m.body.size(); ++i) {
    const std::uint32_t j = m.body[i];
    m.x0[i] = x_[j], m.y0[i] = y_[j], m.vx0[i] = vx_[j], m.vy0[i] = vy_[j];
  }
  if (sleep_ && settings_.track_dissipation) {  // a sleeper's free step dissipates nothing
    m.d0.resize(m.body.size());
    for (std::size_t i = 0; i < m.body.size(); ++i) m.d0[i] = dissipated_body_[m.body[i]];
  }
  if (discs) {
    discs_->save_start(x_.data(), y_.data(), vx_.data(), vy_.data(),
                       settings_.track_dissipation ? dissipated_body_.data() : nullptr);
    if (rolling_) discs_->save_spin_start(spin_.data());
  }
}

template <class Real>
void detail::WorldKernel<Real>::restore_immovable() {
  const Immovable& m = immovable_;
  const Real dt = static_cast<Real>(settings_.dt);
  for (std::size_t i = 0; i < m.body.size(); ++i) {
    const std::uint32_t j = m.body[i];
    if (types_[j] != BodyType::kinematic) {  // static, or a sleeper: at rest where it was
      x_[j] = m.x0[i], y_[j] = m.y0[i], vx_[j] = Real(0), vy_[j] = Real(0);
      if (!m.d0.empty() && types_[j] == BodyType::dynamic) dissipated_body_[j] = m.d0[i];
    } else {  // kinematic: on at its velocity
      x_[j] = m.x0[i] + m.vx0[i] * dt, y_[j] = m.y0[i] + m.vy0[i] * dt;
      vx_[j] = m.vx0[i], vy_[j] = m.vy0[i];
    }
  }
}

// An automatic world with discs enough to share a pass (DiscContacts::min_parallel_discs)
// times its disc phases on two threads and on one now and then, and keeps the faster
// (thread_choice.hpp): what the second core saves depends on the machine and on how far apart
// its cores are at the time, and on whether ticks run back to back or paced (a worker woken
// each tick). Below that size the passes run on one thread in any case.
template <class Real>
void detail::WorldKernel<Real>::choose_disc_threads() {
  const bool choose =
      settings_.threads == 0 && discs_->busy() >= detail::DiscContacts<Real>::min_parallel_discs;
  disc_count_ = disc_threads_.threads(detail::threads_for(settings_.threads), choose);
}

template <class Real>
void detail::WorldKernel<Real>::resolve_discs() {
  detail::DiscContacts<Real>& dc = *discs_;
  typename detail::DiscContacts<Real>::Tick t{
      x_.data(),
      y_.data(),
      vx_.data(),
      vy_.data(),
      settings_.track_dissipation ? dissipated_body_.data() : nullptr,
      planes_,
      contact_.after,
      contact_.after_t,
      settings_.dt,
      detail::contact_kappa(settings_.integrator, settings_.substeps),
      disc_count_};  // the same states either way
  if (!segments_.empty()) t.segments = &segments_;
  if (rolling_) t.spin = spin_.data();
  if (!plane_work_.empty()) t.plane_work = plane_work_.data();
  if (sleepers_ != 0) {
    t.wake = [](void* kernel) { static_cast<WorldKernel*>(kernel)->wake_near_movers(); };
    t.wake_context = this;
  }
  disc_threads_.timed([&] { return dc.resolve(t, contact_stats_, profile_), 0; });
  const auto discs = dc.discs();
  if (const auto* hit = dc.cap_hit(); hit && !fault_) {  // cold: a cap stopped the tick's work
    const std::uint32_t body = discs[hit->disc].body;
    std::string with;
    if (hit->other != hit->npos) {
      const std::uint32_t o = discs[hit->other].body;
      with = fmt::format("body[{}] \"{}\" (the impact due at {:g} s into the tick)", o, names_[o],
                         hit->time);
    } else {
      const double r = discs[hit->disc].radius;
      with = fmt::format("{} discs (the largest swept box is this disc's, radius {:g} m)",
                         discs.size(), r);
    }
    record_cap_fault(body, hit->cap, hit->limit, with);
  }
  const auto lost = dc.lost();
  const auto external = dc.external();
  bool out_of_range = false;
  dc.each_live([&](std::uint32_t k) {  // the others' are 0
    if (!discs[k].dynamic || (lost[k] == 0.0 && external[k] == 0.0)) return;
    const std::uint32_t j = discs[k].body;
    if (settings_.track_dissipation) dissipated_body_[j] += static_cast<Real>(lost[k]);
    external_work_ += external[k];
    for (const Real value : {x_[j], y_[j], vx_[j], vy_[j]}) {
      out_of_range = out_of_range || !(std::abs(double(value)) <= max_state_magnitude);
    }
  });
  if (out_of_range && !fault_) record_fault();
}

template <class Real>
std::span<const Impact> detail::WorldKernel<Real>::impacts() const {
  if (!discs_) return {};
  return impacts_;
}

}  // namespace fixstep
