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
    if (j.a != none) r.ma = bodies[j.a].inv_mass, r.ia = bodies[j.a].inv_inertia;
    if (j.b != none) r.mb = bodies[j.b].inv_mass, r.ib = bodies[j.b].inv_inertia;
    r.push_a = j.a != none && !(r.ma == 0.0 && r.ia == 0.0);
    r.push_b = j.b != none && !(r.mb == 0.0 && r.ib == 0.0);
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
double JointLimitRows::sweep(int part, std::span<ShapeMotion> velocities) const {
  double change = 0.0;
  auto spin = [&](std::uint32_t slot) { return velocities[slot].w; };
  auto push = [&](Vec2& given, double& turned, bool moves, std::uint32_t body, double i, double l) {
    given += Vec2{};
    turned += l;
    if (!moves) return;
    ShapeMotion& v = velocities[body];
    v.vx += 0.0, v.vy += 0.0, v.w += i * l;
  };
  for (const Row& r : rows_[static_cast<std::size_t>(part)]) {
    JointRecord& j = *r.joint;
    const Vec2 given_a = j.given_a, given_b = j.given_b;
    const double turned_a = j.turned_a, turned_b = j.turned_b;
    auto turn = [&](double l) {
      push(j.given_a, j.turned_a, r.push_a, r.a, r.ia, -l);
      push(j.given_b, j.turned_b, r.push_b, r.b, r.ib, l);
    };
    constexpr double unbounded = std::numeric_limits<double>::infinity();
    if (r.lower) {
      const double l = -r.mass * (spin(r.b) - spin(r.a) + r.lower_bias);
      turn(accumulate(j.impulses.lower, l, 0.0, unbounded));
    }
    if (r.upper) {
      const double l = -r.mass * (spin(r.a) - spin(r.b) + r.upper_bias);
      turn(-accumulate(j.impulses.upper, l, 0.0, unbounded));
    }
    auto most = [](double m, double i, Vec2 p, double l) {
      return std::max({std::abs(m * p.x), std::abs(m * p.y), std::abs(i * l)});
    };
    change = std::max({change, most(r.ma, r.ia, j.given_a - given_a, j.turned_a - turned_a),
                       most(r.mb, r.ib, j.given_b - given_b, j.turned_b - turned_b)});
  }
  return change;
}

std::size_t JointLimitRows::bytes() const {
  return copy_bytes(rows_[0], rows_[1], rows_[2]);
}

}  // namespace fixstep::detail
