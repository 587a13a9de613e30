// Shape contacts, part 2: the contact solver (shape_world.hpp has the whole tick): the impact
// pass (bounces), then sequential impulses with warm starting on the manifold points, then a
// push-out of the overlap left on positions only.
#include <algorithm>
#include <cmath>
#include <limits>

#include "fixstep/core/stop_request.hpp"
#include "joint_solver.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

namespace {

/// Box2D v2.4's position solver: the fraction of the overlap beyond the slop one iteration
/// removes (b2_baumgarte) and the largest push of one point (b2_maxLinearCorrection, m).
constexpr double push_fraction = 0.2;
constexpr double max_push = 0.2;

Vec2 perp(Vec2 n) {
  return {-n.y, n.x};
}
/// ω × r for a scalar angular velocity ω about z.
Vec2 spin_cross(double w, Vec2 r) {
  return {-w * r.y, w * r.x};
}

}  // namespace

void ShapeWorld::apply(const ShapeRow& r, double pn, double pt) {
  const Vec2 p = pn * r.n + pt * perp(r.n);
  const double move = dt_;
  if (r.a != none) {
    const ShapedBody& b = bodies_[r.a];
    ShapeState& s = state_[r.a];
    const double dw = b.inv_inertia * cross(r.ra, p);
    s.vx -= b.inv_mass * p.x, s.vy -= b.inv_mass * p.y, s.w -= dw;
    s.x -= move * b.inv_mass * p.x, s.y -= move * b.inv_mass * p.y, s.a -= move * dw;
  }
  const ShapedBody& b = bodies_[r.b];
  ShapeState& s = state_[r.b];
  const double dw = b.inv_inertia * cross(r.rb, p);
  s.vx += b.inv_mass * p.x, s.vy += b.inv_mass * p.y, s.w += dw;
  s.x += move * b.inv_mass * p.x, s.y += move * b.inv_mass * p.y, s.a += move * dw;
}

Vec2 ShapeWorld::relative_velocity(const ShapeRow& r) const {
  const ShapeState& sb = state_[r.b];
  Vec2 v = Vec2{sb.vx, sb.vy} + spin_cross(sb.w, r.rb);
  if (r.a != none) {
    const ShapeState& sa = state_[r.a];
    v = v - (Vec2{sa.vx, sa.vy} + spin_cross(sa.w, r.ra));
  }
  return v;
}

void ShapeWorld::prepare_rows(const ShapeTick& tick) {
  dt_ = tick.dt;
  for (ShapeRow& r : rows_) {
    const ShapedBody& bb = bodies_[r.b];
    double ma = 0.0, ia = 0.0;
    if (r.a != none) ma = bodies_[r.a].inv_mass, ia = bodies_[r.a].inv_inertia;
    const double rna = cross(r.ra, r.n), rnb = cross(r.rb, r.n);
    const Vec2 t = perp(r.n);
    const double rta = cross(r.ra, t), rtb = cross(r.rb, t);
    const double kn = ma + bb.inv_mass + ia * rna * rna + bb.inv_inertia * rnb * rnb;
    const double kt = ma + bb.inv_mass + ia * rta * rta + bb.inv_inertia * rtb * rtb;
    r.normal_mass = kn > 0.0 ? 1.0 / kn : 0.0;
    r.tangent_mass = kt > 0.0 ? 1.0 / kt : 0.0;
    r.rolling_mass =
        r.rolling > 0.0 && ia + bb.inv_inertia > 0.0 ? 1.0 / (ia + bb.inv_inertia) : 0.0;
    r.lr = 0.0;
    // The normal velocity the row asks for: a gap may close within the tick, a touching point
    // stops approaching (the bounces are the impact pass's).
    r.approach = std::max(-dot(relative_velocity(r), r.n), 0.0);
    r.target = r.separation > 0.0 ? -r.separation / tick.dt : 0.0;
    r.bn = 0.0, r.bt = 0.0;
  }
  prepare_blocks();
  for (int pass = 0; pass < max_impact_passes && impact_pass(tick); ++pass) {
  }
  // Warm starting, once every row's target is set from the free velocities.
  for (ShapeRow& r : rows_) {
    if (r.redundant) continue;
    const auto warm = std::lower_bound(warm_.begin(), warm_.end(), ShapeWarm{r.pair, r.id});
    if (warm != warm_.end() && warm->pair == r.pair && warm->id == r.id) {
      r.ln = warm->ln, r.lt = warm->lt;
      apply(r, r.ln, r.lt);
      if (r.rolling_mass > 0.0) r.lr = warm->lr, turn(r, r.lr);
    }
  }
}

// Impacts, before the resting solve: every point that meets within the tick faster than the
// restitution threshold, at the velocities the bounces before it left, gets the impulse that
// gives it −e times its normal velocity (Newton's law; a manifold's two points together), and
// the Coulomb-bounded tangential impulse that stops its sliding. Each bounce is a collision of
// two bodies at one point (or one edge) that keeps their momentum and angular momentum, and
// their energy when e = 1 and μ = 0: a body that meets two others within one tick bounces off
// both in turn, as Guendelman, Bridson and Fedkiw's collision pass does (SIGGRAPH 2003), where
// the resting solve alone would stop it at the second without a bounce. The passes end when no
// point meets (bounded by max_impact_passes; what is left is stopped by the resting solve).
bool ShapeWorld::impact_pass(const ShapeTick& tick) {
  bool any = false;
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    ShapeRow& r = rows_[i];
    if (r.pair_first) {
      any = bounce_block(r, rows_[i + 1], tick) || any;
      ++i;
    } else if (!r.redundant) {
      any = bounce(r, tick) || any;
    }
  }
  return any;
}

namespace {

/// Whether a point of separation s (m) and normal velocity vn (m/s) meets within the tick dt
/// fast enough to bounce.
bool meets(const ShapeRow& r, double vn, const ShapeTick& tick) {
  // (the threshold is >= 0, so a point that meets approaches)
  return r.restitution > 0.0 && vn < -tick.restitution_threshold &&
         r.separation + vn * tick.dt < 0.0;
}

}  // namespace

bool ShapeWorld::bounce(ShapeRow& r, const ShapeTick& tick) {
  const Vec2 v = relative_velocity(r);
  const double vn = dot(v, r.n);
  if (!meets(r, vn, tick)) return false;
  const double pn = -(1.0 + r.restitution) * vn * r.normal_mass;
  const double vt = dot(v, perp(r.n));
  const double pt = std::clamp(-vt * r.tangent_mass, -r.friction * pn, r.friction * pn);
  r.bn += pn, r.bt += pt;
  apply(r, pn, pt);
  return true;
}

// A manifold's two points meeting at once: the 2×2 problem K x = −(1 + e) vn for the points
// that meet (x >= 0; a point that would pull is left out and the other solved alone).
bool ShapeWorld::bounce_block(ShapeRow& r1, ShapeRow& r2, const ShapeTick& tick) {
  const double vn1 = dot(relative_velocity(r1), r1.n), vn2 = dot(relative_velocity(r2), r2.n);
  const bool m1 = meets(r1, vn1, tick), m2 = meets(r2, vn2, tick);
  if (!m1 && !m2) return false;
  const double k11 = 1.0 / r1.normal_mass, k22 = 1.0 / r2.normal_mass, k12 = r1.k12;
  const double d1 = m1 ? -(1.0 + r1.restitution) * vn1 : 0.0;
  const double d2 = m2 ? -(1.0 + r2.restitution) * vn2 : 0.0;
  double x1 = 0.0, x2 = 0.0;
  const double det = k11 * k22 - k12 * k12;
  if (m1 && m2) x1 = (k22 * d1 - k12 * d2) / det, x2 = (k11 * d2 - k12 * d1) / det;
  if (!(m1 && m2 && x1 >= 0.0 && x2 >= 0.0)) {  // one point alone: the one that meets
    const bool first = m1 && (!m2 || d1 / k11 >= d2 / k22);
    x1 = first ? d1 / k11 : 0.0, x2 = first ? 0.0 : d2 / k22;
  }
  r1.bn += x1, r2.bn += x2;
  if (x1 != 0.0) apply(r1, x1, 0.0);
  if (x2 != 0.0) apply(r2, x2, 0.0);
  for (ShapeRow* r : {&r1, &r2}) {  // sliding stopped within each point's Coulomb cone
    const double bound = r->friction * (r == &r1 ? x1 : x2);
    if (bound == 0.0) continue;
    const double pt =
        std::clamp(-dot(relative_velocity(*r), perp(r->n)) * r->tangent_mass, -bound, bound);
    r->bt += pt;
    apply(*r, 0.0, pt);
  }
  return true;
}

void ShapeWorld::solve_friction(ShapeRow& r) {
  const double vt = dot(relative_velocity(r), perp(r.n));
  const double bound = r.friction * r.ln;
  const double lt = std::clamp(r.lt - vt * r.tangent_mass, -bound, bound);
  const double d = lt - r.lt;
  r.lt = lt;
  if (d != 0.0) apply(r, 0.0, d);
}

void ShapeWorld::solve_normal(ShapeRow& r) {
  const double vn = dot(relative_velocity(r), r.n);
  const double ln = std::max(r.ln - (vn - r.target) * r.normal_mass, 0.0);
  const double d = ln - r.ln;
  r.ln = ln;
  if (d != 0.0) apply(r, d, 0.0);
}

// A manifold's two normal impulses at once (Catto's block solver, Box2D v2.4
// b2ContactSolver::SolveVelocityConstraints): the 2×2 linear complementarity problem
// vn = K x + b, x >= 0, vn >= 0, x·vn = 0 for the accumulated impulses x, by trying its four
// cases in turn. Solving the two points one after the other lets a box resting on its two
// corners rock (each point's impulse turns it against the other), which a tall stack amplifies.
void ShapeWorld::solve_block(ShapeRow& r1, ShapeRow& r2) {
  const double k11 = 1.0 / r1.normal_mass, k22 = 1.0 / r2.normal_mass, k12 = r1.k12;
  const double a1 = r1.ln, a2 = r2.ln;
  const double vn1 = dot(relative_velocity(r1), r1.n) - r1.target;
  const double vn2 = dot(relative_velocity(r2), r2.n) - r2.target;
  const double b1 = vn1 - (k11 * a1 + k12 * a2), b2 = vn2 - (k12 * a1 + k22 * a2);
  double x1 = 0.0, x2 = 0.0;
  const double det = k11 * k22 - k12 * k12;
  const double y1 = -(k22 * b1 - k12 * b2) / det, y2 = -(k11 * b2 - k12 * b1) / det;
  if (y1 >= 0.0 && y2 >= 0.0) {
    x1 = y1, x2 = y2;  // both points push
  } else if (-b1 / k11 >= 0.0 && k12 * (-b1 / k11) + b2 >= 0.0) {
    x1 = -b1 / k11;  // the first pushes, the second separates
  } else if (-b2 / k22 >= 0.0 && k12 * (-b2 / k22) + b1 >= 0.0) {
    x2 = -b2 / k22;                        // the second pushes
  } else if (!(b1 >= 0.0 && b2 >= 0.0)) {  // no case holds (rounding): one at a time
    solve_normal(r1);
    solve_normal(r2);
    return;
  }
  r1.ln = x1, r2.ln = x2;
  if (x1 != a1) apply(r1, x1 - a1, 0.0);
  if (x2 != a2) apply(r2, x2 - a2, 0.0);
}

void ShapeWorld::prepare_blocks() {
  for (ShapeRow& r : rows_) r.pair_first = false, r.redundant = false;
  for (std::size_t i = 0; i + 1 < rows_.size(); ++i) {
    ShapeRow& r1 = rows_[i];
    ShapeRow& r2 = rows_[i + 1];
    if (r1.pair != r2.pair || r1.a != r2.a || r1.b != r2.b) continue;
    if (r1.normal_mass == 0.0 || r2.normal_mass == 0.0) continue;
    double ma = 0.0, ia = 0.0;
    if (r1.a != none) ma = bodies_[r1.a].inv_mass, ia = bodies_[r1.a].inv_inertia;
    const ShapedBody& b = bodies_[r1.b];
    const double k12 = ma + b.inv_mass + ia * cross(r1.ra, r1.n) * cross(r2.ra, r2.n) +
                       b.inv_inertia * cross(r1.rb, r1.n) * cross(r2.rb, r2.n);
    const double k11 = 1.0 / r1.normal_mass, k22 = 1.0 / r2.normal_mass;
    // Box2D's condition number guard: a K this close to singular keeps one point (the deeper).
    if (k11 * k11 < 1000.0 * (k11 * k22 - k12 * k12)) {
      r1.pair_first = true, r1.k12 = k12;
    } else {
      (r2.separation < r1.separation ? r1 : r2).redundant = true;
    }
    ++i;
  }
}

// Rolling resistance (Box2D v3.1's b2SolveContact): an angular impulse that stops the two
// bodies' relative turning, within ± c r times the manifold's normal impulse.
void ShapeWorld::solve_rolling(ShapeRow& r, double normal_impulse) {
  const double wa = r.a != none ? state_[r.a].w : 0.0;
  const double bound = r.rolling * normal_impulse;
  const double lr = std::clamp(r.lr - r.rolling_mass * (state_[r.b].w - wa), -bound, bound);
  const double d = lr - r.lr;
  r.lr = lr;
  if (d != 0.0) turn(r, d);
}

void ShapeWorld::turn(const ShapeRow& r, double l) {
  if (r.a != none) {
    const double dw = bodies_[r.a].inv_inertia * l;
    state_[r.a].w -= dw, state_[r.a].a -= dt_ * dw;
  }
  const double dw = bodies_[r.b].inv_inertia * l;
  state_[r.b].w += dw, state_[r.b].a += dt_ * dw;
}

void ShapeWorld::solve_velocities(const ShapeTick& tick) {
  for (int it = 0; it < tick.velocity_iterations; ++it) {
    if (!joints_.empty()) solve_joint_velocities();
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      ShapeRow& r = rows_[i];
      if (r.pair_first) {  // friction first, bounded by this iteration's normal impulse
        solve_friction(r), solve_friction(rows_[i + 1]);
        solve_block(r, rows_[i + 1]);
        if (r.rolling_mass > 0.0) solve_rolling(r, r.ln + rows_[i + 1].ln);
        ++i;
      } else {
        if (!r.redundant) solve_friction(r), solve_normal(r);
        if (r.rolling_mass > 0.0) {  // a manifold's first row, maybe redundant: both its rows'
          const bool pair = i + 1 < rows_.size() && rows_[i + 1].pair == r.pair &&
                            rows_[i + 1].a == r.a && rows_[i + 1].b == r.b;
          solve_rolling(r, r.ln + (pair ? rows_[i + 1].ln : 0.0));
        }
      }
    }
  }
}

void ShapeWorld::solve_positions(const ShapeTick& tick, ShapeTally& tally) {
  // Each point's separation now: its manifold's (at the start poses) changed by how far each
  // body's copy of the point has moved since along the normal (the lever arm turned by the
  // body's turn since the start).
  auto moved = [&](std::uint32_t body, Vec2 r) {
    const ShapeState& s = state_[body];
    const Vec2 now = Vec2{s.x - s.x0, s.y - s.y0} + rotate(s.turn, r);
    return now - r;
  };
  auto separation = [&](const ShapeRow& r) {
    Vec2 d = moved(r.b, r.rb);
    if (r.a != none) d = d - moved(r.a, r.ra);
    return r.separation + dot(d, r.n);
  };
  // Each body's turn since the start, made again only where its angle has changed since
  // (turned_at_: the angle it was made at; NaN at first, unequal to any).
  turned_at_.assign(state_.size(), std::numeric_limits<double>::quiet_NaN());
  auto update_turns = [&] {
    for (std::size_t k = 0; k < state_.size(); ++k) {
      ShapeState& s = state_[k];
      if (s.a != turned_at_[k]) s.turn = rot_of(s.a - s.a0), turned_at_[k] = s.a;
    }
  };
  // The joints' errors of this tick's motion first, as constraint impulses (they move the
  // velocities too), then every error left, the contacts' and the joints', on positions only.
  for (int it = 0; it < tick.position_iterations && !joints_.empty(); ++it) {
    solve_joint_positions(true);
  }
  update_turns();
  for (int it = 0; it < tick.position_iterations; ++it) {
    bool pushed = false;
    for (const ShapeRow& r : rows_) {
      const double c = std::clamp(push_fraction * (separation(r) + slop), -max_push, 0.0);
      if (c == 0.0 || r.normal_mass == 0.0) continue;
      pushed = true;
      const Vec2 p = (-c * r.normal_mass) * r.n;
      if (r.a != none) {
        const ShapedBody& b = bodies_[r.a];
        ShapeState& s = state_[r.a];
        s.x -= b.inv_mass * p.x, s.y -= b.inv_mass * p.y, s.a -= b.inv_inertia * cross(r.ra, p);
      }
      const ShapedBody& b = bodies_[r.b];
      ShapeState& s = state_[r.b];
      s.x += b.inv_mass * p.x, s.y += b.inv_mass * p.y, s.a += b.inv_inertia * cross(r.rb, p);
    }
    // A sweep that pushes nothing leaves the poses as they were, and so would every sweep
    // after it: without joints (whose sweeps may still correct) the push-out has ended.
    if (!pushed && joints_.empty()) break;
    if (!joints_.empty()) solve_joint_positions(false);
    update_turns();
  }
  for (const ShapeRow& r : rows_) tally.deepest = std::max(tally.deepest, -separation(r));
  for (ShapeState& s : state_) s.q = rot_of(s.a);
}

void ShapeWorld::prepare_joints() {
  JointSolver solver(bodies_, state_, dt_);
  for (JointRecord& j : joints_) {
    if (!j.broken) solver.prepare(j);
  }
}

// Each joint sweep polls a stop request first (one relaxed atomic load): a sweep of
// max_joints joints is a fraction of a second, a tick of them tens of sweeps.
void ShapeWorld::poll_stop() {
  ++stop_polls_;
  throw_if_stop_requested();
}

void ShapeWorld::solve_joint_velocities() {
  poll_stop();
  JointSolver solver(bodies_, state_, dt_);
  for (JointRecord& j : joints_) {
    if (!j.broken) solver.solve_velocity(j);
  }
}

void ShapeWorld::solve_joint_positions(bool keep) {
  poll_stop();
  JointSolver solver(bodies_, state_, dt_);
  for (JointRecord& j : joints_) {
    if (!j.broken) solver.solve_position(j, keep);
  }
}

void ShapeWorld::account_joints() {
  JointSolver solver(bodies_, state_, dt_);
  for (JointRecord& j : joints_) {
    if (!j.broken) solver.account(j);
  }
}

void ShapeWorld::keep_impulses() {
  next_warm_.clear();
  for (const ShapeRow& r : rows_) {
    if (r.ln != 0.0 || r.lt != 0.0 || r.lr != 0.0) {
      next_warm_.push_back({r.pair, r.id, r.ln, r.lt, r.lr});
    }
  }
  std::sort(next_warm_.begin(), next_warm_.end());
  warm_.swap(next_warm_);
}

}  // namespace fixstep::detail
