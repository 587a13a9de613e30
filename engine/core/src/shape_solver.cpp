// Shape contacts, part 2: the contact solver (shape_world.hpp has the whole tick): sequential
// impulses with warm starting on the manifold points, then a push-out of the overlap left on
// positions only.
#include <algorithm>
#include <cmath>

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
  const double move = kappa_ * dt_;
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
  dt_ = tick.dt, kappa_ = tick.kappa;
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
    // The normal velocity the row asks for: a gap may close within the tick, a touching point
    // stops approaching, and one that meets fast enough bounces back (Newton's law).
    const double e = r.restitution;
    const double vn = dot(relative_velocity(r), r.n);
    r.target = r.separation > 0.0 ? -r.separation / tick.dt : 0.0;
    if (e > 0.0 && vn < -restitution_threshold && r.separation + vn * tick.dt < 0.0) {
      r.target = std::max(r.target, -e * vn);
    }
    const auto warm = std::lower_bound(warm_.begin(), warm_.end(), ShapeWarm{r.pair, r.id});
    if (warm != warm_.end() && warm->pair == r.pair && warm->id == r.id) {
      r.ln = warm->ln, r.lt = warm->lt;
      apply(r, r.ln, r.lt);
    }
  }
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
  for (std::size_t i = 0; i + 1 < rows_.size(); ++i) {
    ShapeRow& r1 = rows_[i];
    const ShapeRow& r2 = rows_[i + 1];
    r1.pair_first = false;
    if (r1.pair != r2.pair || r1.a != r2.a || r1.b != r2.b) continue;
    if (r1.normal_mass == 0.0 || r2.normal_mass == 0.0) continue;
    double ma = 0.0, ia = 0.0;
    if (r1.a != none) ma = bodies_[r1.a].inv_mass, ia = bodies_[r1.a].inv_inertia;
    const ShapedBody& b = bodies_[r1.b];
    const double k12 = ma + b.inv_mass + ia * cross(r1.ra, r1.n) * cross(r2.ra, r2.n) +
                       b.inv_inertia * cross(r1.rb, r1.n) * cross(r2.rb, r2.n);
    const double k11 = 1.0 / r1.normal_mass, k22 = 1.0 / r2.normal_mass;
    // Box2D's condition number guard: a K this close to singular is solved point by point.
    if (k11 * k11 < 1000.0 * (k11 * k22 - k12 * k12)) r1.pair_first = true, r1.k12 = k12;
    ++i;
  }
}

void ShapeWorld::solve_velocities(const ShapeTick& tick) {
  prepare_blocks();
  for (int it = 0; it < tick.velocity_iterations; ++it) {
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      ShapeRow& r = rows_[i];
      if (r.pair_first) {  // friction first, bounded by this iteration's normal impulse
        solve_friction(r), solve_friction(rows_[i + 1]);
        solve_block(r, rows_[i + 1]);
        ++i;
      } else {
        solve_friction(r), solve_normal(r);
      }
    }
  }
}

void ShapeWorld::solve_positions(const ShapeTick& tick, ShapeTally& tally) {
  // Each point's separation now, linearised about the poses its manifold was found at: the
  // bodies' moves since (held in dx_, dy_, da_ from the poses kept at collect()) along n.
  auto separation = [&](const ShapeRow& r) {
    Vec2 d = Vec2{state_[r.b].x - at_x_[r.b], state_[r.b].y - at_y_[r.b]} +
             spin_cross(state_[r.b].a - at_a_[r.b], r.rb);
    if (r.a != none) {
      d = d - (Vec2{state_[r.a].x - at_x_[r.a], state_[r.a].y - at_y_[r.a]} +
               spin_cross(state_[r.a].a - at_a_[r.a], r.ra));
    }
    return r.separation + dot(d, r.n);
  };
  for (int it = 0; it < tick.position_iterations; ++it) {
    for (const ShapeRow& r : rows_) {
      const double c = std::clamp(push_fraction * (separation(r) + slop), -max_push, 0.0);
      if (c == 0.0 || r.normal_mass == 0.0) continue;
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
  }
  for (const ShapeRow& r : rows_) tally.deepest = std::max(tally.deepest, -separation(r));
  for (ShapeState& s : state_) s.q = rot_of(s.a);
}

void ShapeWorld::keep_impulses() {
  next_warm_.clear();
  for (const ShapeRow& r : rows_) {
    if (r.ln != 0.0 || r.lt != 0.0) next_warm_.push_back({r.pair, r.id, r.ln, r.lt});
  }
  std::sort(next_warm_.begin(), next_warm_.end());
  warm_.swap(next_warm_);
}

}  // namespace fixstep::detail
