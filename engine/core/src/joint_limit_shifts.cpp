// The position sweeps' corrections of the forest's angle limits, packed (joint_limit_shifts.hpp).
#include "joint_limit_shifts.hpp"

#include "copy_bytes.hpp"
#include "joint_solver.hpp"

namespace fixstep::detail {

void JointLimitShifts::pack(int part, std::span<JointRecord> joints,
                            std::span<const std::uint32_t> listed,
                            std::span<const ShapedBody> bodies) {
  std::vector<Row>& rows = rows_[static_cast<std::size_t>(part)];
  rows.clear();
  for (const std::uint32_t i : listed) {
    JointRecord& j = joints[i];
    if (j.broken) continue;
    Row r{.joint = &j, .a = j.a, .b = j.b};
    if (j.a != none) {
      r.ia = bodies[j.a].inv_inertia;
      r.move_a = !(bodies[j.a].inv_mass == 0.0 && r.ia == 0.0);
    }
    if (j.b != none) {
      r.ib = bodies[j.b].inv_inertia;
      r.move_b = !(bodies[j.b].inv_mass == 0.0 && r.ib == 0.0);
    }
    rows.push_back(r);
  }
}

// JointSolver::correct_angle_limit on positions only: l = −m c, A turned by −l and B by l,
// each moving end's position given m · 0 = +0 (its shift along no direction).
bool JointLimitShifts::correct(int part, std::span<ShapeState> state) const {
  bool moved = false;
  auto shift = [&](std::uint32_t body, bool moves, double i, double l) {
    if (body == none) return;
    moved = moved || l != 0.0;
    if (!moves) return;
    ShapeState& s = state[body];
    s.x += 0.0, s.y += 0.0, s.a += i * l;
  };
  for (const Row& r : rows_[static_cast<std::size_t>(part)]) {
    const JointRecord& j = *r.joint;
    if (j.limit_row) continue;  // the forest's solve holds it
    const double angle_a = r.a != none ? state[r.a].a : 0.0;
    const double angle_b = r.b != none ? state[r.b].a : 0.0;
    const double l = -j.angle_mass * revolute_limit_correction(j, angle_a, angle_b);
    shift(r.a, r.move_a, r.ia, -l);
    shift(r.b, r.move_b, r.ib, l);
  }
  return moved;
}

std::size_t JointLimitShifts::bytes() const {
  return copy_bytes(rows_[0], rows_[1], rows_[2]);
}

}  // namespace fixstep::detail
