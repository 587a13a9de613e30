// Contacts of disc colliders (Collider) with static half-planes (PlaneDef), resolved at their
// time of impact inside the tick.
//
// The model. A tick first integrates every body as if no plane existed (world_step.cpp). For
// each collider body, its start state (x0, v0) and end state (x1, v1) then define a motion of
// constant acceleration a = (v1 - v0)/dt through both end positions:
//   x(s) = x0 + u s + ½ a s²,  u(s) = u + a s,  u = v0 + δ,  δ = (x1 - x0)/dt - (v0 + v1)/2,
// for 0 <= s <= dt, and the integrator's velocity is the model's minus the offset δ. For
// gravity and constant forces a is exact for every integrator, and δ = 0 for those exact on
// constant forces (velocity Verlet, RK4, Forest–Ruth). Semi-implicit Euler moves along an exact
// parabola whose velocity leads its own by δ = a dt/2 (x1 = x0 + v1 dt): reflecting the
// parabola's velocity keeps its energy, whereas reflecting v0 + a s (δ = 0, the model through
// (x0, v0) alone) loses |v_n| |a_n| dt per bounce, 29 % of a 5 m drop's energy in 10 bounces
// at 60 Hz (measured). The gap to
// plane (n, offset) is g(s) = n·x(s) - offset - r, a quadratic in s; the first root in the tick
// where the body approaches is its time of impact. There the normal velocity v_n < 0 becomes
// -e v_n (Newton's law of restitution) and the tangential velocity v_t loses
// min(|v_t|, μ (1 + e) |v_n|) (Coulomb friction over the impulse; Mirtich & Canny, "Impulse-
// based simulation of rigid bodies", 1995), and the motion continues with the same a until
// the next impact or the end of the tick. A tick without an impact keeps the integrator's end
// state bit for bit. After a body's max_impacts-th event of the tick (a corner of a wall and
// the ground takes two), only bounces are resolved: a body settling into a corner (an event
// that brings it to rest, which in a narrow corner recurs without end) finishes settling in the
// next ticks, while a body bouncing between close planes goes on bouncing, each further test
// counted against max_tick_predictions (limits.hpp): past it the world records a StateFault
// naming the cap, the body and the plane.
//
// Resting. A body whose bounce e |v_n| is at most one tick of its normal acceleration |a_n| dt
// would hit again within about a tick (a ball with e < 1 bounces infinitely often in finite
// time): it comes to rest on the plane instead. Its normal velocity is dropped, it is placed
// on n·x = offset + r, and for the rest of the tick its normal acceleration is cancelled (the
// normal force N = m |a_n|) and its tangential motion feels Coulomb friction μ |a_n| against
// its velocity: over the remaining time T, the tangential velocity without friction
// v_t + a_t T loses min(|v_t + a_t T|, μ |a_n| T), and the body moves with the constant
// acceleration that gives that end velocity. A body on a slope with μ >= tan θ stays put.
//
// Rolling discs (ContactSettings::rolling). Friction acts at the contact point instead: its
// slip u = v·t - ω r (t = (-n_y, n_x), ω counter-clockwise) is what a friction change Δ of the
// tangential velocity stops, turning the disc by -Δ s / r (s = m r² / I); so Δ = -u / (1 + s),
// within μ (1 + e) |v_n| at an impact and μ |a_n| T over the rest T of the tick (of the
// integrator's velocity at rest, which the next tick starts from). A disc released on a slope
// then rolls at a_t / (1 + 1/s) while that bound allows (μ >= tan θ / (1 + s)) and slides at
// a_t - μ |a_n| otherwise, exactly per tick; I ω + m r v_t stays as it was while only friction
// acts (the spinning drop). The rotational energy ½ I ω² it changes is in the account.
//
// Energy. With track_dissipation, the kinetic energy each impact and each push-out removes,
// and the work of friction while resting, are added to dissipated_energy(), so the balance
// E + E_dissipated - E0 stays the integrator's error.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/value_ranges.hpp"
#include "plane_contact.hpp"
#include "world_kernel.hpp"

namespace fixstep {

using namespace plane_contact;  // the model of plane_contact.hpp

template <class Real>
std::size_t detail::WorldKernel<Real>::add_plane(const PlaneDef& def) {
  const IeeeFloatMode ieee;  // a state never depends on the caller's FPU mode (float_mode.hpp)
  const std::string who = fmt::format("plane[{}]", planes_.size());
  auto check = [&](double v, bool ok, const char* field, const char* allowed) {
    if (!std::isfinite(v) || !std::isfinite(static_cast<Real>(v)) || !ok) {
      throw std::invalid_argument(
          fmt::format("{}: {} must be {} (got {})", who, field, allowed, v));
    }
  };
  check(def.normal.x, true, "normal", "finite");
  check(def.normal.y, true, "normal", "finite");
  const double len = det::hypot(def.normal.x, def.normal.y);
  if (!(len > 0.0) || !std::isfinite(len)) {
    throw std::invalid_argument(fmt::format("{}: normal must be a non-zero vector (got [{}, {}])",
                                            who, def.normal.x, def.normal.y));
  }
  check(def.offset, within_state(def.offset), "offset", "finite with |value| <= 1e12 (m)");
  const double e = def.restitution, mu = def.friction;
  check(e, std::isfinite(e) && e >= 0.0 && e <= 1.0, "restitution", "in [0, 1]");
  check(mu, within_coefficient(mu) && mu >= 0.0, "friction", "in [0, 1e100]");
  PlaneDef p = def;
  p.normal = Vec2{def.normal.x / len, def.normal.y / len};
  planes_.push_back(p);
  terms_dirty_ = true;
  return planes_.size() - 1;
}

template <class Real>
void detail::WorldKernel<Real>::rebuild_contacts() {
  ContactScratch& c = contact_;
  const std::size_t n = colliders_.data.size();
  // Dynamic colliders: planes do not move the others, and push no sensor.
  std::vector<std::uint32_t> order;
  auto dynamic = [&](std::uint32_t i) {
    return types_[bodies_.index(colliders_.set.dense[i])] == BodyType::dynamic &&
           !colliders_.data[i].sensor;
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    if (dynamic(i)) order.push_back(i);
  }
  auto body_of = [&](std::uint32_t i) { return bodies_.index(colliders_.set.dense[i]); };
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return body_of(a) < body_of(b); });
  c.body.resize(order.size());
  c.radius.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    c.body[k] = static_cast<std::uint32_t>(body_of(order[k]));
    c.radius[k] = colliders_.data[order[k]].radius;
  }
  for (auto* v : {&c.x0, &c.y0, &c.vx0, &c.vy0}) v->resize(order.size());
  c.after_t.assign(order.size(), -1.0);
  c.after.assign(order.size(), detail::PlaneMotion{});
  c.active = (!planes_.empty() || !segments_.empty()) && !order.empty();
  segments_.build();
}

template <class Real>
void detail::WorldKernel<Real>::save_contact_start() {
  ContactScratch& c = contact_;
  auto save = [&](std::size_t k) {
    const std::uint32_t j = c.body[k];
    c.x0[k] = x_[j], c.y0[k] = y_[j], c.vx0[k] = vx_[j], c.vy0[k] = vy_[j];
  };
  if (awake_.skip()) {  // a sleeper's start is not read (resolve_body_contacts)
    for_each_in_runs(awake_.colliders, save);
    return;
  }
  // By halves within the tick's run of the discs' second thread (each body's copy its own),
  // from DiscContacts::min_parallel_copies bodies.
  auto range = [&](std::size_t begin, std::size_t end, int /*half*/) {
    for (std::size_t k = begin; k < end; ++k) save(k);
  };
  if (discs_) {
    discs_->halves_from(c.body.size(), DiscContacts<Real>::min_parallel_copies, range);
  } else {
    range(0, c.body.size(), 0);
  }
}

/// One body's way through a tick's planes and segments (resolve_contacts): its motion, what
/// it met, and the surface (a segment's contact as a plane) it met last.
struct detail::PlaneWay {
  Motion m;
  Surfaces surfaces;
  Spin turn;
  Spin* spin = nullptr;  ///< &turn for a rolling disc
  PlaneDef local;        ///< a segment's contact as a plane (world_segments.cpp)
  Vec2 local_u;          ///< its velocity (a kinematic body's segment; 0 static)
  bool touched = false;  ///< some plane or segment acted on the body this tick
  double first = 0;      ///< when one first did, s
  V2 free_offset;        ///< the free motion's offset δ
  double free_w = 0;     ///< a rolling disc's spin before the planes turned it, rad/s
  bool bounced = false;  ///< some impact was a bounce (the disc phases start from it)
  Vec2 start;            ///< its centre at the tick's start (one-way segments), m
};

template <class Real>
std::size_t detail::WorldKernel<Real>::resolve_contacts() {
  const ContactScratch& c = contact_;
  PlaneTally tally;
  if (segments_.moves()) plane_work_.assign(body_count(), 0.0);
  segment_tests_ = polled_tests_ = 0;
  auto visit = [&](std::size_t k) {
    if (k % 1024 == 1023) {  // many planes: a tick of seconds
      ++plane_polls_;
      throw_if_stop_requested();
    }
    poll_segment_work();  // many segments: a disc may test every one
    resolve_body_contacts(k, tally);
  };
  if (awake_.skip()) {  // a sleeper's plane motion stays "none" (set when it was visited last)
    plane_visited_ = for_each_in_runs(awake_.colliders, visit);
  } else if (segments_.empty()) {
    // Most bodies are clear of every plane: one pass over all tells them from those near one,
    // and only those go the whole way (in order, so the cap's count is the same).
    find_near_planes();
    resolve_near_planes(tally);
    plane_visited_ = c.body.size();
  } else {
    for (std::size_t k = 0; k < c.body.size(); ++k) visit(k);
    plane_visited_ = c.body.size();
  }
  if (tally.out_of_range && !fault_) record_fault();
  return tally.capped;
}

template <class Real>
void detail::WorldKernel<Real>::resolve_body_contacts(std::size_t k, PlaneTally& tally) {
  const ContactScratch& c = contact_;
  const double dt = settings_.dt;
  const double rel = 8.0 * double(std::numeric_limits<Real>::epsilon());
  const std::uint32_t j = c.body[k];
  const double r = c.radius[k];
  contact_.after_t[k] = -1.0;
  if (sleep_ && asleep_[j] != 0) return;  // a sleeper stays where it is
  const V2 v0{double(c.vx0[k]), double(c.vy0[k])};
  const V2 v1{double(vx_[j]), double(vy_[j])};
  const V2 x0{double(c.x0[k]), double(c.y0[k])}, x1{double(x_[j]), double(y_[j])};
  if (segments_.empty() && clear_of_planes(planes_, x0, x1, v0, v1, r, dt, rel)) return;
  const V2 offset = (1.0 / dt) * (x1 - x0) - 0.5 * (v0 + v1);
  PlaneWay w;
  w.m = Motion{x0, v0 + offset, (1.0 / dt) * (v1 - v0), offset};
  w.surfaces = Surfaces{.a_free = w.m.a};
  w.free_offset = offset;
  w.start = Vec2{x0.x, x0.y};
  if (rolling_ && inv_inertia_[j] > 0.0) {
    w.turn = Spin{double(spin_[j]), mass_[j] * r * r * inv_inertia_[j]};
    w.spin = &w.turn;
    w.free_w = w.turn.w;
  }
  push_out_of_surfaces(w, r, rel);
  follow_plane_impacts(w, j, r, tally);
  if (tally.deferred) return;
  if (!w.touched && !touch_at_tick_end(w, x1, v1 + offset, offset, r)) return;
  store_plane_way(k, j, w, tally);
}

// A body that starts inside a plane is pushed out; its approaching velocity is dropped.
template <class Real>
void detail::WorldKernel<Real>::push_out_of_surfaces(PlaneWay& w, double r, double rel) {
  for (const PlaneDef& p : planes_) w.touched = push_out(w.m, p, r, rel) || w.touched;  // at 0
  for (int s = 0; s < 4 && !segments_.empty(); ++s) {
    const double tol = rel * (std::abs(w.m.x.x) + std::abs(w.m.x.y) + r);
    if (!segment_overlap(w.m.x.x, w.m.x.y, r, tol, w.m.t, w.start, w.local, w.local_u)) break;
    const V2 u{w.local_u.x, w.local_u.y};
    if (!push_out_moving(w.m, w.local, r, rel, u, w.surfaces.work)) break;
    w.touched = true;
  }
}

// The impacts of the tick in time order: the first plane or segment the motion meets, resolved
// there, until none is met before the tick's end.
template <class Real>
void detail::WorldKernel<Real>::follow_plane_impacts(PlaneWay& w, std::uint32_t j, double r,
                                                     PlaneTally& tally) {
  const double dt = settings_.dt;
  const double rel = 8.0 * double(std::numeric_limits<Real>::epsilon());
  Motion& m = w.m;
  for (int i = 0;; ++i) {
    poll_segment_work();
    const double horizon = dt - m.t;
    // Rounding of the offset (x1 - x0)/dt is up to about eps |x|/dt.
    const double vtol = rel * (norm(m.v) + norm(m.a) * dt + norm(m.x) / dt);
    double first = std::numeric_limits<double>::infinity();
    const PlaneDef* hit = nullptr;
    for (const PlaneDef& p : planes_) {
      const V2 n{p.normal.x, p.normal.y};
      const double nx = dot(n, m.x);
      const double g0 = nx - p.offset - r;
      const double tol = rel * (std::abs(nx) + std::abs(p.offset) + r);
      const double s = first_impact(g0, dot(n, m.v), dot(n, m.a), horizon, tol, vtol);
      if (s < first) first = s, hit = &p;
    }
    std::uint32_t segment = 0;
    std::uint64_t looked = 0;
    if (!segments_.empty()) {
      const detail::SegmentMotion sm{m.x.x, m.x.y, m.v.x, m.v.y, m.a.x, m.a.y};
      const double s = first_segment_hit(sm, m.t, r, horizon, rel, vtol, w.start, w.local,
                                         w.local_u, segment, looked);
      if (s < first) first = s, hit = &w.local;
    }
    if (!hit) return;
    const V2 u_hit = hit == &w.local ? V2{w.local_u.x, w.local_u.y} : V2{};  // surface's frame
    if (i >= max_impacts &&
        !keep_bouncing(w, j, *hit, first, planes_.size() + looked, segment, tally)) {
      return;
    }
    m.advance(first);
    if (!w.touched) w.first = m.t;
    const bool bounce = resolve_event(m, *hit, hit == &w.local, u_hit, r, dt, w.spin, w.surfaces);
    w.bounced = bounce || w.bounced;
    w.touched = true;
  }
}

// After a body's max_impacts-th event: only a bounce goes on (a body settling into a corner
// finishes in the next ticks), each further test counted against max_tick_predictions; past
// it the world records a StateFault naming the cap, the body and the plane or segment.
template <class Real>
bool detail::WorldKernel<Real>::keep_bouncing(const PlaneWay& w, std::uint32_t j,
                                              const PlaneDef& hit, double first,
                                              std::uint64_t tests, std::uint32_t segment,
                                              PlaneTally& tally) {
  if (tally.defer) {  // the count is the first half's and this one's (PlaneTally)
    tally.deferred = true;
    return false;
  }
  const bool on_segment = &hit == &w.local;
  Motion seen = w.m;  // from the surface's frame
  seen.v = seen.v - (on_segment ? V2{w.local_u.x, w.local_u.y} : V2{});
  if (!bounces(seen, first, hit, settings_.dt)) return false;  // settling into a corner
  tally.again += tests;
  const std::uint64_t cap = max_tick_predictions(contact_.body.size());
  if (tally.again <= cap) return true;
  if (!fault_) {  // cold: the bounce is unresolved
    record_cap_fault(j, "max_tick_predictions", cap,
                     fmt::format("{} (the bounce due at {:g} s into the tick)",
                                 on_segment ? fmt::format("segment[{}]", segment)
                                            : fmt::format("plane[{}]", &hit - planes_.data()),
                                 w.m.t + first));
  }
  tally.capped = 1;
  return false;
}

// The model found no impact; rounding may still leave the end state a hair inside: an impact
// at the end of the tick. Returns whether there was one.
template <class Real>
bool detail::WorldKernel<Real>::touch_at_tick_end(PlaneWay& w, V2 x1, V2 u1, V2 offset, double r) {
  const double dt = settings_.dt;
  Motion& m = w.m;
  if (!w.touched) w.first = dt;
  for (const PlaneDef& p : planes_) {
    const V2 n{p.normal.x, p.normal.y};
    if (dot(n, x1) - p.offset - r >= 0.0) continue;
    if (!w.touched) m = Motion{x1, u1, m.a, offset, dt, 0.0};
    w.bounced = impact(m, p, r, dt, w.spin) || w.bounced;
    w.touched = true;
  }
  if (!segments_.empty() && segment_overlap(x1.x, x1.y, r, 0.0, dt, w.start, w.local, w.local_u)) {
    if (!w.touched) m = Motion{x1, u1, m.a, offset, dt, 0.0};
    const V2 u{w.local_u.x, w.local_u.y};
    w.bounced = impact_moving(m, w.local, r, dt, w.spin, u, w.surfaces.work) || w.bounced;
    w.touched = true;
  }
  return w.touched;
}

// The body's state at the tick's end from its way through the planes, and its account.
template <class Real>
void detail::WorldKernel<Real>::store_plane_way(std::size_t k, std::uint32_t j, PlaneWay& w,
                                                PlaneTally& tally) {
  if (tally.defer && w.surfaces.work != 0.0) {  // external_work_ is summed in body order
    tally.deferred = true;
    return;
  }
  Motion& m = w.m;
  // Disc contacts continue from the motion after a bounce, or after a rest the body came to
  // within the tick (a body at rest on a plane from the tick's start keeps its integrated one).
  if (w.bounced || w.first > 0.0) {
    const V2 a = w.surfaces.a_free, d = w.free_offset;
    contact_.after_t[k] = m.t;
    contact_.after[k] =
        detail::PlaneMotion{m.x.x,      m.x.y,   m.v.x, m.v.y, m.a.x, m.a.y, m.offset.x,
                            m.offset.y, w.first, a.x,   a.y,   d.x,   d.y,   w.free_w};
  }
  m.advance(settings_.dt - m.t);
  x_[j] = static_cast<Real>(m.x.x), y_[j] = static_cast<Real>(m.x.y);
  vx_[j] = static_cast<Real>(m.v.x - m.offset.x), vy_[j] = static_cast<Real>(m.v.y - m.offset.y);
  if (w.spin) spin_[j] = static_cast<Real>(w.turn.w);
  if (settings_.track_dissipation) dissipated_body_[j] += static_cast<Real>(m.lost);
  if (w.surfaces.work != 0.0) external_work_ += mass_[j] * w.surfaces.work;
  if (!plane_work_.empty()) plane_work_[j] = w.surfaces.work;
  // The runtime guard, as in the sweep: a push-out beyond the range is a fault too.
  for (const Real value : {x_[j], y_[j], vx_[j], vy_[j]}) {
    tally.out_of_range = tally.out_of_range || !(std::abs(double(value)) <= max_state_magnitude);
  }
}

}  // namespace fixstep
