// Disc contacts, phase 2: resting contact of touching discs and of discs on planes, by
// sequential impulses (Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005: clamped
// accumulated impulses, warm starting, Coulomb friction bounded by μ times the normal
// impulse), each acting as a constant contact force over the tick, then a bounded push-out of
// what overlap is left (see disc_contacts.hpp).
#include <algorithm>
#include <cmath>

#include "disc_contacts.hpp"

namespace fixstep::detail {

namespace {}  // namespace

template <class Real>
void DiscContacts<Real>::gather_contacts(const Tick& tick) {
  contacts_.clear();
  const auto n = static_cast<std::uint32_t>(discs_.size());
  for (const DiscPair& p : pairs_) {
    const Disc &da = discs_[p.a], &db = discs_[p.b];
    const double dx = ex_[p.a] - ex_[p.b], dy = ey_[p.a] - ey_[p.b];
    const double dist = length(dx, dy);
    const double gap = dist - (da.radius + db.radius);
    if (gap > slop * std::min(da.radius, db.radius)) continue;
    RestContact c;
    c.nx = dist > 0.0 ? dx / dist : 0.0, c.ny = dist > 0.0 ? dy / dist : 1.0;
    // A pair still apart that closes faster than one tick of relative acceleration is an
    // impact of the next tick, not a resting contact.
    const double vn = (evx_[p.a] - evx_[p.b]) * c.nx + (evy_[p.a] - evy_[p.b]) * c.ny;
    const double cn =
        (motion_[p.a].ax - motion_[p.b].ax) * c.nx + (motion_[p.a].ay - motion_[p.b].ay) * c.ny;
    if (gap > 0.0 && -vn > std::abs(cn) * tick.dt) continue;
    c.key = (std::uint64_t(p.a) << 32) | p.b;
    c.a = p.a, c.b = p.b;
    c.inv_a = da.inv_mass, c.inv_b = db.inv_mass;
    c.kinematic_a = !da.dynamic && (motion_[p.a].ux != 0.0 || motion_[p.a].uy != 0.0);
    c.kinematic_b = !db.dynamic && (motion_[p.b].ux != 0.0 || motion_[p.b].uy != 0.0);
    c.mass = 1.0 / (da.inv_mass + db.inv_mass);
    c.friction = std::sqrt(da.friction * db.friction);
    contacts_.push_back(c);
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const Disc& d = discs_[k];
    if (!d.dynamic || d.sensor) continue;
    for (std::uint32_t i = 0; i < tick.planes.size(); ++i) {
      const PlaneDef& p = tick.planes[i];
      const double gap = p.normal.x * ex_[k] + p.normal.y * ey_[k] - p.offset - d.radius;
      if (gap > slop * d.radius) continue;
      RestContact c;
      c.key = (std::uint64_t(k) << 32) | (n + i);
      c.a = k, c.b = n + i;
      c.nx = p.normal.x, c.ny = p.normal.y;
      c.mass = 1.0 / d.inv_mass;
      c.inv_a = d.inv_mass;
      c.friction = p.friction;
      contacts_.push_back(c);
    }
  }
}

// Applies the impulse (jx, jy) to a and its opposite to b, moving each by κ dt Δv.
template <class Real>
[[gnu::always_inline]] inline void DiscContacts<Real>::apply(const RestContact& c, double jx,
                                                             double jy, double kdt) {
  if (c.kinematic_b) external_[c.a] += jx * evx_[c.b] + jy * evy_[c.b];
  if (c.kinematic_a) external_[c.b] -= jx * evx_[c.a] + jy * evy_[c.a];
  if (c.inv_a > 0.0) {
    const double dvx = c.inv_a * jx, dvy = c.inv_a * jy;
    evx_[c.a] += dvx, evy_[c.a] += dvy, ex_[c.a] += kdt * dvx, ey_[c.a] += kdt * dvy;
    changed_[c.a] |= 2;
  }
  if (c.inv_b > 0.0) {
    const double dvx = c.inv_b * jx, dvy = c.inv_b * jy;
    evx_[c.b] -= dvx, evy_[c.b] -= dvy, ex_[c.b] -= kdt * dvx, ey_[c.b] -= kdt * dvy;
    changed_[c.b] |= 2;
  }
}

template <class Real>
void DiscContacts<Real>::warm_start(const Tick& tick) {
  const double kdt = tick.kappa * tick.dt;
  for (RestContact& c : contacts_) {
    const auto it =
        std::lower_bound(warm_.begin(), warm_.end(), c.key,
                         [](const WarmImpulse& w, std::uint64_t k) { return w.key < k; });
    if (it == warm_.end() || it->key != c.key) continue;
    c.lambda_n = it->lambda_n, c.lambda_t = it->lambda_t;
    apply(c, c.lambda_n * c.nx - c.lambda_t * c.ny, c.lambda_n * c.ny + c.lambda_t * c.nx, kdt);
  }
}

template <class Real>
void DiscContacts<Real>::solve_velocities(const Tick& tick, ContactStats& stats) {
  const double kdt = tick.kappa * tick.dt;
  const std::size_t n = discs_.size();
  if (contacts_.empty()) return;
  stats.velocity_converged = false;
  for (int it = 0; it < velocity_iterations; ++it) {
    ++stats.velocity_sweeps;
    // A sweep that changes no impulse by more than 1e-9 of the largest has converged.
    double change = 0.0, largest = 0.0;
    for (RestContact& c : contacts_) {
      auto relative = [&](double& vx, double& vy) {
        vx = evx_[c.a], vy = evy_[c.a];
        if (c.b < n) vx -= evx_[c.b], vy -= evy_[c.b];
      };
      double vx = 0, vy = 0;
      relative(vx, vy);
      // Normal: no approach at the end of the tick; the accumulated impulse stays >= 0.
      const double vn = vx * c.nx + vy * c.ny;
      const double ln = std::max(c.lambda_n - vn * c.mass, 0.0);
      const double dn = ln - c.lambda_n;
      c.lambda_n = ln;
      if (dn != 0.0) apply(c, dn * c.nx, dn * c.ny, kdt);
      // Friction along t = (-n_y, n_x), within Coulomb's cone |λ_t| <= μ λ_n.
      relative(vx, vy);
      const double vt = -vx * c.ny + vy * c.nx;
      const double bound = c.friction * c.lambda_n;
      const double lt = std::clamp(c.lambda_t - vt * c.mass, -bound, bound);
      const double dt = lt - c.lambda_t;
      c.lambda_t = lt;
      if (dt != 0.0) apply(c, -dt * c.ny, dt * c.nx, kdt);
      change = std::max({change, std::abs(dn), std::abs(dt)});
      largest = std::max(largest, c.lambda_n);
    }
    if (change <= 1e-9 * largest) {
      stats.velocity_converged = true;
      break;
    }
  }
}

template <class Real>
void DiscContacts<Real>::push_out(const Tick& tick, ContactStats& stats) {
  const std::size_t n = discs_.size();
  auto overlap_of = [&](const RestContact& c, double& nx, double& ny, double& r_min) {
    const Disc& da = discs_[c.a];
    if (c.b >= n) {
      const PlaneDef& p = tick.planes[c.b - n];
      nx = p.normal.x, ny = p.normal.y, r_min = da.radius;
      return da.radius + p.offset - (nx * ex_[c.a] + ny * ey_[c.a]);
    }
    const Disc& db = discs_[c.b];
    const double dx = ex_[c.a] - ex_[c.b], dy = ey_[c.a] - ey_[c.b];
    const double dist = length(dx, dy);
    nx = dist > 0.0 ? dx / dist : c.nx, ny = dist > 0.0 ? dy / dist : c.ny;
    r_min = std::min(da.radius, db.radius);
    return da.radius + db.radius - dist;
  };
  for (int it = 0; it < position_iterations && !contacts_.empty(); ++it) {
    ++stats.position_sweeps;
    bool pushed = false;  // a sweep that pushes nothing ends the push-out
    for (const RestContact& c : contacts_) {
      double nx = 0, ny = 0, r_min = 0;
      const double depth = overlap_of(c, nx, ny, r_min);
      if (depth <= slop * r_min) continue;
      pushed = true;
      const double push = std::min(depth - slop * r_min, max_push_out * r_min);
      const double ia = discs_[c.a].inv_mass, ib = c.b < n ? discs_[c.b].inv_mass : 0.0;
      const double share = push / (ia + ib);
      ex_[c.a] += ia * share * nx, ey_[c.a] += ia * share * ny;
      if (ia > 0.0) changed_[c.a] |= 2;
      if (c.b < n && ib > 0.0) {
        ex_[c.b] -= ib * share * nx, ey_[c.b] -= ib * share * ny;
        changed_[c.b] |= 2;
      }
    }
    if (!pushed) break;
  }
  stats.touching = contacts_.size();
  for (const RestContact& c : contacts_) {
    double nx = 0, ny = 0, r_min = 0;
    const double depth = overlap_of(c, nx, ny, r_min);
    stats.max_overlap = std::max(stats.max_overlap, depth);
    if (std::isgreater(depth, slop * r_min)) stats.positions_settled = false;
  }
}

template <class Real>
void DiscContacts<Real>::keep_impulses() {
  warm_.clear();
  for (const RestContact& c : contacts_) {
    if (c.lambda_n > 0.0) warm_.push_back(WarmImpulse{c.key, c.lambda_n, c.lambda_t});
  }
  std::sort(warm_.begin(), warm_.end(),
            [](const WarmImpulse& l, const WarmImpulse& r) { return l.key < r.key; });
}

template <class Real>
void DiscContacts<Real>::finish(const Tick& tick) {
  for (std::size_t k = 0; k < discs_.size(); ++k) {
    if (!changed_[k]) continue;
    const Disc& d = discs_[k];
    const std::uint32_t j = d.body;
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
    const double since_start =
        e_begin_[k] - (tick.dissipated ? double(tick.dissipated[j]) - d_begin_[k] : 0.0);
    lost_[k] = ((changed_[k] & 2) ? since_start : e_start_[k]) - e_end + external_[k] * d.inv_mass;
  }
}

#define FIXSTEP_INSTANTIATE(Real)                                                      \
  template void DiscContacts<Real>::gather_contacts(const Tick&);                      \
  template void DiscContacts<Real>::apply(const RestContact&, double, double, double); \
  template void DiscContacts<Real>::warm_start(const Tick&);                           \
  template void DiscContacts<Real>::solve_velocities(const Tick&, ContactStats&);      \
  template void DiscContacts<Real>::push_out(const Tick&, ContactStats&);              \
  template void DiscContacts<Real>::keep_impulses();                                   \
  template void DiscContacts<Real>::finish(const Tick&);
FIXSTEP_INSTANTIATE(float)
FIXSTEP_INSTANTIATE(double)
#undef FIXSTEP_INSTANTIATE

}  // namespace fixstep::detail
