// The forest's limit rows packed for the velocity sweeps (joint_limit_rows.hpp).
#include "joint_limit_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "copy_bytes.hpp"

namespace fixstep::detail {

void JointLimitRows::pack(int part, std::span<JointRecord> joints,
                          std::span<const std::uint32_t> listed, std::span<const ShapedBody> bodies,
                          double dt, std::uint32_t zero) {
  std::vector<Row>& rows = rows_[static_cast<std::size_t>(part)];
  rows.clear();
  for (const std::uint32_t i : listed) {
    JointRecord& j = joints[i];
    // A joint without a limit, or whose angle nothing turns, has no row that moves anything.
    if (j.broken || !(j.def.lower || j.def.upper) || j.angle_mass == 0.0) continue;
    Row r{.joint = &j,
          .a = j.a != none ? j.a : zero,
          .b = j.b != none ? j.b : zero,
          .mass = j.angle_mass};
    const double ma = j.a != none ? bodies[j.a].inv_mass : 0.0;
    const double mb = j.b != none ? bodies[j.b].inv_mass : 0.0;
    if (j.a != none) r.ia = bodies[j.a].inv_inertia;
    if (j.b != none) r.ib = bodies[j.b].inv_inertia;
    r.push_a = j.a != none && !(ma == 0.0 && r.ia == 0.0);
    r.push_b = j.b != none && !(mb == 0.0 && r.ib == 0.0);
    r.lower = j.def.lower.has_value(), r.upper = j.def.upper.has_value();
    if (r.lower) r.lower_bias = std::max(j.value - *j.def.lower, 0.0) / dt;
    if (r.upper) r.upper_bias = std::max(*j.def.upper - j.value, 0.0) / dt;
    rows.push_back(r);
  }
}

// JointSolver::solve_velocity for a revolute joint of the forest with limits alone: each
// limit's λ = −m (ω_b − ω_a + bias) (upper: ω_a − ω_b), accumulated into [0, ∞); the ends
// turned by ∓λ (a pure turn: (0, 0) added to their linear velocity and impulse, as push()
// does: m · 0 is +0 for an inverse mass m, finite and not negative), the joint's given and
// turned impulses added up; the change is the largest of |m Δp| and |i Δl| over both ends.
// The world's end reads the zero slot (a spin of 0, as JointSolver reads the world).
//
// The same bits with less work: adding +0 to a linear velocity or a given impulse a second
// time changes nothing (the first turns −0 into +0; x + 0 is x after that), so each end's
// takes it once a row; and a finite given impulse's change is then +0, so |m Δp| adds nothing
// to the change beside |i Δl| (≥ +0). (With a given impulse not finite, JointSolver's change
// would be NaN or another end's; the change decides only whether the sweeps go on.)
double JointLimitRows::sweep(int part, std::span<ShapeMotion> velocities) const {
  double change = 0.0;
  for (const Row& r : rows_[static_cast<std::size_t>(part)]) {
    JointRecord& j = *r.joint;
    const double turned_a = j.turned_a, turned_b = j.turned_b;
    j.given_a += Vec2{}, j.given_b += Vec2{};
    ShapeMotion& va = velocities[r.a];
    ShapeMotion& vb = velocities[r.b];
    if (r.push_a) va.vx += 0.0, va.vy += 0.0;
    if (r.push_b) vb.vx += 0.0, vb.vy += 0.0;
    auto turn = [&](double l) {
      j.turned_a += -l;
      if (r.push_a) va.w += r.ia * -l;
      j.turned_b += l;
      if (r.push_b) vb.w += r.ib * l;
    };
    constexpr double unbounded = std::numeric_limits<double>::infinity();
    if (r.lower) {
      const double l = -r.mass * (vb.w - va.w + r.lower_bias);
      turn(accumulate(j.impulses.lower, l, 0.0, unbounded));
    }
    if (r.upper) {
      const double l = -r.mass * (va.w - vb.w + r.upper_bias);
      turn(-accumulate(j.impulses.upper, l, 0.0, unbounded));
    }
    change = std::max({change, std::abs(r.ia * (j.turned_a - turned_a)),
                       std::abs(r.ib * (j.turned_b - turned_b))});
  }
  return change;
}

std::size_t JointLimitRows::bytes() const {
  return copy_bytes(rows_[0], rows_[1], rows_[2]);
}

}  // namespace fixstep::detail
