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

void ShapeWorld::solve_velocities(const ShapeTick& tick) {
  for (int it = 0; it < tick.velocity_iterations; ++it) {
    for (ShapeRow& r : rows_) {
      // Friction first, bounded by μ times this iteration's normal impulse (Box2D's order).
      const double vt = dot(relative_velocity(r), perp(r.n));
      const double bound = r.friction * r.ln;
      const double lt = std::clamp(r.lt - vt * r.tangent_mass, -bound, bound);
      const double dt = lt - r.lt;
      r.lt = lt;
      if (dt != 0.0) apply(r, 0.0, dt);
      const double vn = dot(relative_velocity(r), r.n);
      const double ln = std::max(r.ln - (vn - r.target) * r.normal_mass, 0.0);
      const double dn = ln - r.ln;
      r.ln = ln;
      if (dn != 0.0) apply(r, dn, 0.0);
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
