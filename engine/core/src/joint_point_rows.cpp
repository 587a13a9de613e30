// The forest's point rows packed for the velocity sweeps (joint_point_rows.hpp).
#include "joint_point_rows.hpp"

#include <algorithm>
#include <cmath>

#include "copy_bytes.hpp"
#include "joint_solver.hpp"
#include "joint_tree.hpp"
#include "shape_records.hpp"

namespace fixstep::detail {

void JointPointRows::pack(int part, std::span<JointRecord> joints, const JointTree& tree,
                          std::span<const ShapedBody> bodies, std::uint32_t zero) {
  std::vector<Row>& rows = rows_[static_cast<std::size_t>(part)];
  rows.clear();
  const auto members = tree.members();
  for (const std::uint32_t k : tree.members_of(part)) {
    JointRecord& j = joints[members[k]];
    Row r{.joint = &j, .member = k, .tree = tree.tree_of(k), .a = zero, .b = zero};
    if (j.a != JointRecord::none) {
      r.a = j.a, r.ma = bodies[j.a].inv_mass, r.ia = bodies[j.a].inv_inertia;
      r.push_a = !(r.ma == 0.0 && r.ia == 0.0);
    }
    if (j.b != JointRecord::none) {
      r.b = j.b, r.mb = bodies[j.b].inv_mass, r.ib = bodies[j.b].inv_inertia;
      r.push_b = !(r.mb == 0.0 && r.ib == 0.0);
    }
    r.ra = j.ra, r.rb = j.rb;
    rows.push_back(r);
  }
}

// −(v_b + ω_b × r_b − v_a − ω_a × r_a), the world's end read from the zero slot (as
// JointSolver reads the world: a velocity (0, 0) and a spin 0).
double JointPointRows::errors(int part, std::span<const ShapeMotion> velocities,
                              std::span<Vec2> rhs, std::span<std::uint8_t> active,
                              double tolerance) const {
  const std::vector<Row>& rows = rows_[static_cast<std::size_t>(part)];
  for (const Row& r : rows) active[r.tree] = 0;
  double most = 0.0;
  for (const Row& r : rows) {
    const ShapeMotion &a = velocities[r.a], &b = velocities[r.b];
    Vec2& e = rhs[r.member];
    e = -(Vec2{b.vx, b.vy} + joint_spin_cross(b.w, r.rb) - Vec2{a.vx, a.vy} -
          joint_spin_cross(a.w, r.ra));
    const double error = std::max(std::abs(e.x), std::abs(e.y));
    most = std::max(most, error);
    if (error > tolerance) active[r.tree] = 1;
  }
  return most;
}

// Each end's given and turned impulses added up, and its velocity moved where an impulse moves
// it (as JointSolver::push).
void JointPointRows::apply(int part, std::span<ShapeMotion> velocities, std::span<const Vec2> rhs,
                           std::span<const std::uint8_t> active) const {
  for (const Row& r : rows_[static_cast<std::size_t>(part)]) {
    if (active[r.tree] == 0) continue;
    JointRecord& j = *r.joint;
    const Vec2 p = rhs[r.member];
    j.impulses.linear += p;
    const Vec2 pa = -p;
    const double la = -cross(r.ra, p), lb = cross(r.rb, p);
    j.given_a += pa, j.turned_a += la;
    if (r.push_a) {
      ShapeMotion& v = velocities[r.a];
      v.vx += r.ma * pa.x, v.vy += r.ma * pa.y, v.w += r.ia * la;
    }
    j.given_b += p, j.turned_b += lb;
    if (r.push_b) {
      ShapeMotion& v = velocities[r.b];
      v.vx += r.mb * p.x, v.vy += r.mb * p.y, v.w += r.ib * lb;
    }
  }
}

std::size_t JointPointRows::bytes() const {
  return copy_bytes(rows_[0], rows_[1], rows_[2]);
}

}  // namespace fixstep::detail
