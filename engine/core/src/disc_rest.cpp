// Disc contacts, phase 2: resting contact of touching discs and of discs on planes, by
// sequential impulses (Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005: clamped
// accumulated impulses, warm starting, Coulomb friction bounded by μ times the normal
// impulse), each acting as a constant contact force over the tick, then a bounded push-out of
// what overlap is left (see disc_contacts.hpp). A large pile's iterations run over its two
// halves at once on two threads, then over the contacts across the cut (disc_halves.cpp), with
// the same result on one thread or two.
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "disc_contacts.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"

namespace fixstep::detail {

/// What a velocity iteration's share found: the largest change of an accumulated impulse and
/// the largest normal impulse (N·s). (Not file-local: the solver's lambdas, members of a class
/// template, hold it.)
struct RestSweep {
  double change = 0.0, largest = 0.0;
};

// Applies the impulse λ_n n + λ_t t (N·s; t = (-n_y, n_x)) to row i's body a and its opposite
// to b, each as the impulse's components times the row's 1/m n (so that the chain of one row's
// arithmetic through a disc's velocity is short); with kinematic rows, a moving kinematic
// partner's work on the other disc goes to external_.
template <class Real>
template <int Kind>
[[gnu::always_inline]] inline void DiscContacts<Real>::push_row(std::uint32_t i, const SolveRow& r,
                                                                SolveVelocity& va,
                                                                SolveVelocity& vb, double ln,
                                                                double lt) {
  if constexpr ((Kind & kinematic_rows) != 0) {
    // A moving kinematic partner has a slot past the discs' (build_rows()).
    const PushRow& d = push_rows_[i];
    const std::uint32_t fixed_slots = 3 + std::uint32_t(discs_.size());
    const double jx = ln * r.nx - lt * r.ny, jy = ln * r.ny + lt * r.nx;
    if (r.b >= fixed_slots) external_[d.a] += jx * vb.x + jy * vb.y;
    if (r.a >= fixed_slots) external_[d.b] -= jx * va.x + jy * va.y;
  }
  const double ax = r.inv_a * r.nx, ay = r.inv_a * r.ny, bx = r.inv_b * r.nx, by = r.inv_b * r.ny;
  va.x += ln * ax - lt * ay, va.y += ln * ay + lt * ax;
  vb.x -= ln * bx - lt * by, vb.y -= ln * by + lt * bx;
}

template <class Real>
void DiscContacts<Real>::solve_resting(const Tick& tick, ContactStats& stats) {
  const auto& p = part_start_;
  team_on_ = sharing() && p[1] > p[0] && p[2] > p[1];
  match_warm();
  build_rows(tick);  // and the warm start
  solve_velocities(stats);
  scatter_rows(tick.kappa * tick.dt);
  push_out(tick, stats);
  // The discs the passes moved: their slots' marks, by disc (build_rows() cleared every live
  // disc's; only a disc a row moves, 1/m > 0, is marked).
  halves_from(live_count(), min_parallel_copies, [&](std::size_t begin, std::size_t end, int) {
    live_range(begin, end, [&](std::uint32_t k) {
      if (slot_moved_[3 + k] != 0) changed_[k] |= 2;
    });
  });
}

template <class Real>
void DiscContacts<Real>::match_warm() {
  // contacts_ and warm_ are each two runs in key order (disc pairs, then planes and segments),
  // so each run is matched against its like in one walk (each half of it in one, from its
  // first key on). In a large world the disc pairs were matched as they were gathered
  // (pair_contact, gather_warm_pairs()).
  const std::size_t bounds[3] = {0, plane_contacts_, contacts_.size()};
  const std::size_t warm_bounds[3] = {0, warm_pairs_, warm_.size()};
  for (int run = warm_gathered_ ? 1 : 0; run < 2; ++run) {
    const std::size_t first = bounds[run];
    const WarmImpulse* const from = warm_.data() + warm_bounds[run];
    const WarmImpulse* const last = warm_.data() + warm_bounds[run + 1];
    const std::size_t n = bounds[run + 1] - first;
    halves_from(n, min_split_contacts, [&](std::size_t begin, std::size_t end, int /*half*/) {
      if (begin == end) return;
      const WarmImpulse* w = first_warm_from(from, last, contacts_[first + begin].key());
      for (std::size_t i = first + begin; i < first + end; ++i) {
        RestContact& c = contacts_[i];
        const std::uint64_t key = c.key();
        while (w != last && w->key < key) ++w;
        if (w != last && w->key == key && w->lambda_n > 0.0) {
          c.lambda_n = w->lambda_n, c.lambda_t = w->lambda_t;
        }
      }
    });
  }
}

template <class Real>
template <class F>
void DiscContacts<Real>::with_row_kind(F&& f) {
  switch (row_kind_) {
    case 0:
      f(std::integral_constant<int, 0>{});
      break;
    case kinematic_rows:
      f(std::integral_constant<int, kinematic_rows>{});
      break;
    case rolling_rows:
      f(std::integral_constant<int, rolling_rows>{});
      break;
    default:
      f(std::integral_constant<int, kinematic_rows | rolling_rows>{});
      break;
  }
}

// One row's normal and friction impulses, a Gauss–Seidel step: no approach at the end of the
// tick (the accumulated normal impulse stays >= 0), and friction along t = (-n_y, n_x) within
// Coulomb's cone |λ_t| <= μ λ_n. A normal impulse changes no tangential velocity (t · n = 0;
// nor any turn: it acts through the centres), so both are found from the velocities as loaded
// and applied as one impulse: the same step as normal then friction, with a dependency chain
// through the discs' velocities half as long. The impulse is applied even when it is 0, so
// that a sweep has no branch. The sweep's arrays come as pointers held in registers and its
// running maxima as locals (RestSweep): the byte stored in row_moved_ may alias anything in
// memory, which made every row load them again through `this`.
template <class Real>
template <int Kind>
[[gnu::always_inline]] inline void DiscContacts<Real>::solve_row(std::uint32_t i, SolveRow& r,
                                                                 SolveVelocity* sv,
                                                                 std::uint8_t& moved,
                                                                 RestSweep& out) {
  SolveVelocity va = sv[r.a], vb = sv[r.b];
  // x - 0 is x, so a plane's relative velocity is a's own.
  const double rx = va.x - vb.x, ry = va.y - vb.y;
  const double vn = rx * r.nx + ry * r.ny;
  // With rolling discs, the contact point's velocity less the turn's ω r of each disc.
  double vt = -rx * r.ny + ry * r.nx;
  if constexpr ((Kind & rolling_rows) != 0) vt -= turn_slip(i);
  const double ln = std::max(r.lambda_n - vn * r.mass, 0.0);
  const double bound = r.friction * ln;
  double mass_t = r.mass;
  if constexpr ((Kind & rolling_rows) != 0) mass_t = roll_rows_[i].mass_t;
  const double lt = std::clamp(r.lambda_t - vt * mass_t, -bound, bound);
  const double dn = ln - r.lambda_n, dt = lt - r.lambda_t;
  r.lambda_n = ln, r.lambda_t = lt;
  push_row<Kind>(i, r, va, vb, dn, dt);
  if constexpr ((Kind & rolling_rows) != 0) turn(i, dt);
  sv[r.a] = va, sv[r.b] = vb;
  moved |= std::uint8_t((dn != 0.0) | (dt != 0.0));
  out.change = std::max({out.change, std::abs(dn), std::abs(dt)});
  out.largest = std::max(out.largest, ln);
}

template <class Real>
void DiscContacts<Real>::solve_velocities(ContactStats& stats) {
  if (contacts_.empty()) return;
  stats.velocity_converged = false;
  RestSweep sweep[2];
  auto range = [&](std::uint32_t begin, std::uint32_t end, int thread) {
    // Written to sweep[thread] once: the two threads' entries share a line.
    with_row_kind([&](auto kind) {
      RestSweep out;
      SolveRow* const rows = rows_.data();
      SolveVelocity* const sv = sv_.data();
      std::uint8_t* const moved = row_moved_.data();
      for (std::uint32_t i = begin; i < end; ++i) solve_row<kind()>(i, rows[i], sv, moved[i], out);
      sweep[thread].change = std::max(sweep[thread].change, out.change);
      sweep[thread].largest = std::max(sweep[thread].largest, out.largest);
    });
  };
  for (int it = 0; it < settings_.velocity_iterations; ++it) {
    if (it % 16 == 15) throw_if_stop_requested();  // up to 1000 iterations: a long tick
    ++stats.velocity_sweeps;
    sweep[0] = sweep[1] = RestSweep{};
    parts_pass(range);
    // An iteration that changes no impulse by more than 1e-9 of the largest has converged.
    if (std::max(sweep[0].change, sweep[1].change) <=
        1e-9 * std::max(sweep[0].largest, sweep[1].largest)) {
      stats.velocity_converged = true;
      break;
    }
  }
}

template <class Real>
double DiscContacts<Real>::overlap_of(const Tick& tick, std::uint32_t i, const PushRow& r,
                                      const double* ex, const double* ey, double& nx,
                                      double& ny) const {
  const std::size_t n = discs_.size();
  if (r.b >= n + tick.planes.size()) return segment_overlap_of(tick, contacts_[order_[i]], nx, ny);
  if (r.b >= n) {
    const PlaneDef& p = tick.planes[r.b - n];
    nx = p.normal.x, ny = p.normal.y;
    return r.radii + p.offset - (nx * ex[r.a] + ny * ey[r.a]);
  }
  const double dx = ex[r.a] - ex[r.b], dy = ey[r.a] - ey[r.b];
  const double dist = length(dx, dy);
  if (dist > 0.0) {
    nx = dx / dist, ny = dy / dist;
  } else {
    nx = contacts_[order_[i]].nx, ny = contacts_[order_[i]].ny;
  }
  return r.radii - dist;
}

template <class Real>
void DiscContacts<Real>::push_out(const Tick& tick, ContactStats& stats) {
  bool pushed[2] = {false, false};  // an iteration that pushes nothing ends the push-out
  double deepest[2] = {0.0, 0.0};   // and its deepest overlap is the tick's last
  auto range = [&](std::uint32_t begin, std::uint32_t end, int thread) {
    bool any = false;  // written to pushed[thread] once (see solve_velocities)
    double most = deepest[thread];
    // Pointers in registers: the bytes stored in slot_moved_ may alias anything in memory.
    const PushRow* const rows = push_rows_.data();
    double *const ex = ex_.data(), *const ey = ey_.data();
    std::uint8_t* const moved = slot_moved_.data() + 3;  // by disc
    for (std::uint32_t i = begin; i < end; ++i) {
      const PushRow& r = rows[i];
      double nx = 0, ny = 0;
      const double depth = overlap_of(tick, i, r, ex, ey, nx, ny);
      most = std::max(most, depth);
      if (depth <= (slop + push_out_tolerance) * r.r_min + storage_rounding(r)) continue;
      any = true;
      const double push = std::min(depth - push_target * slop * r.r_min, max_push_out * r.r_min);
      const double pa = r.w_a * push, pb = r.w_b * push;
      ex[r.a] += pa * nx, ey[r.a] += pa * ny;
      if (r.w_a > 0.0) moved[r.a] = 1;
      if (pb > 0.0) ex[r.b] -= pb * nx, ey[r.b] -= pb * ny;
      if (r.w_b > 0.0) moved[r.b] = 1;
    }
    if (any) pushed[thread] = true;
    deepest[thread] = most;
  };
  bool settled = false;
  for (int it = 0; it < settings_.position_iterations && !contacts_.empty(); ++it) {
    if (it % 16 == 15) throw_if_stop_requested();
    ++stats.position_sweeps;
    pushed[0] = pushed[1] = false;
    deepest[0] = deepest[1] = 0.0;
    parts_pass(range);
    if (!pushed[0] && !pushed[1]) {
      settled = true;
      break;
    }
  }
  stats.touching = contacts_.size();
  if (settled) {  // the last sweep moved nothing: its overlaps are the tick's
    stats.max_overlap = std::max({stats.max_overlap, deepest[0], deepest[1]});
    return;
  }
  for (std::uint32_t i = 0; i < push_rows_.size(); ++i) {
    double nx = 0, ny = 0;
    const PushRow& r = push_rows_[i];
    const double depth = overlap_of(tick, i, r, ex_.data(), ey_.data(), nx, ny);
    stats.max_overlap = std::max(stats.max_overlap, depth);
    if (std::isgreater(depth, (slop + push_out_tolerance) * r.r_min + storage_rounding(r))) {
      stats.positions_settled = false;
    }
  }
}

template <class Real>
void DiscContacts<Real>::finish(const Tick& tick) {
  halves(live_count(), [&](std::size_t begin, std::size_t end, int) {
    live_range(begin, end, [&](std::uint32_t k) { finish(tick, k); });
  });
}

template <class Real>
void DiscContacts<Real>::finish(const Tick& tick, std::uint32_t k) {
  {
    if (!changed_[k]) return;
    const Disc& d = discs_[k];
    const std::uint32_t j = d.body;
    // Kinetic plus potential energy per unit mass (J/kg) of the state (m, m/s): at the tick's
    // start (x0_ ...) or after its free step (the body's state until it is written below).
    const auto energy = [&d](double x, double y, double vx, double vy) {
      return 0.5 * (vx * vx + vy * vy) - (d.accel_x * x + d.accel_y * y);
    };
    const bool from_start = (changed_[k] & 2) != 0;
    const double e_ref = from_start ? energy(x0_[k], y0_[k], vx0_[k], vy0_[k])
                                    : energy(double(tick.x[j]), double(tick.y[j]),
                                             double(tick.vx[j]), double(tick.vy[j]));
    tick.x[j] = static_cast<Real>(ex_[k]), tick.y[j] = static_cast<Real>(ey_[k]);
    tick.vx[j] = static_cast<Real>(evx_[k]), tick.vy[j] = static_cast<Real>(evy_[k]);
    const double vx = double(tick.vx[j]), vy = double(tick.vy[j]);
    const double e_end =
        0.5 * (vx * vx + vy * vy) - (d.accel_x * double(tick.x[j]) + d.accel_y * double(tick.y[j]));
    // What an impact takes is measured against the free step's end; a disc the resting solver
    // moved is measured against the tick's start (less what damping took this tick), since
    // resting contact undoes the free step's own energy error every tick (a semi-implicit
    // Euler step from rest under gravity loses ½ g² dt², which would otherwise pile up in
    // the account of a body at rest).
    const double since_start = e_ref -
                               (tick.dissipated ? double(tick.dissipated[j]) - d_begin_[k] : 0.0) +
                               (tick.plane_work ? tick.plane_work[j] : 0.0);
    lost_[k] = (from_start ? since_start : e_ref) - e_end + external_[k] * d.inv_mass;
    if (rolling_ && d.inv_inertia > 0.0) {  // the turn's ½ (I/m) ω², against the same start
      const double w_ref = from_start ? ew0_[k] : double(tick.spin[j]);  // not yet set
      const auto w = static_cast<Real>(ew_[k]);
      tick.spin[j] = w;
      lost_[k] += 0.5 * d.inv_mass / d.inv_inertia * (w_ref * w_ref - double(w) * double(w));
    }
  }
}

}  // namespace fixstep::detail
