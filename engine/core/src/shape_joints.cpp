// Shape contacts, part 3: the joints' sweeps as the shape phase runs them (shape_world.hpp has
// the whole tick): each joint's own rows (joint_solver.hpp), then the point rows of the
// revolute joints that form a forest, all at once (joint_tree.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "fixstep/core/stop_request.hpp"
#include "joint_solver.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

namespace {

/// Whether a revolute joint has rows about its angle (a spring, a motor or a limit): Gauss-
/// Seidel rows beside its point's direct solve.
bool angle_rows(const JointRecord& j) {
  const bool motor = j.motor_on && (j.max_torque > 0.0 || j.max_force > 0.0);
  return motor || j.def.frequency > 0.0 || j.def.lower || j.def.upper;
}

double largest(std::span<const Vec2> v) {
  double most = 0.0;
  for (const Vec2 e : v) most = std::max({most, std::abs(e.x), std::abs(e.y)});
  return most;
}

}  // namespace

void ShapeWorld::prepare_joints() {
  JointSolver solver(bodies_, state_, dt_, velocity_);
  for (JointRecord& j : joints_) {
    if (!j.broken) solver.prepare(j);
  }
  tree_.build(joints_, bodies_);
  joint_rows_ = false, indirect_ = false, direct_limits_ = false;
  for (const JointRecord& j : joints_) {
    if (j.broken) continue;
    indirect_ = indirect_ || !j.direct;
    joint_rows_ = joint_rows_ || !j.direct || angle_rows(j);
    direct_limits_ = direct_limits_ || (j.direct && (j.def.lower || j.def.upper));
  }
  if (tree_.empty()) return;
  const auto members = tree_.members();
  const auto arms = tree_.arms();
  for (std::size_t k = 0; k < members.size(); ++k) {
    const JointRecord& j = joints_[members[k]];
    arms[k] = {j.ra, j.rb};
  }
  tree_.factor();
  rest_factored_ = false;
  kept_error_ = std::numeric_limits<double>::infinity();
}

// The forest's point rows at once: the impulses that make every one's Ċ zero together, at the
// start's arms (the velocity rows' own). A velocity error within direct_velocity_tolerance is
// left: such a sweep moves nothing.
bool ShapeWorld::solve_tree_velocities() {
  JointSolver solver(bodies_, state_, dt_, velocity_);
  const auto members = tree_.members();
  const auto rhs = tree_.rhs();
  for (std::size_t k = 0; k < members.size(); ++k) {
    rhs[k] = -solver.point_velocity(joints_[members[k]]);
  }
  if (largest(rhs) <= direct_velocity_tolerance) return false;
  tree_.solve(rhs);
  for (std::size_t k = 0; k < members.size(); ++k) solver.apply_point(joints_[members[k]], rhs[k]);
  return true;
}

// The forest's point errors at once, a Newton step of the projection onto C = target: the
// error measured, and the positions moved, along the gradient at the poses now, each point's
// error by at most joint_max_linear_correction a sweep. While keeping: the error the tick's
// motion made (the start's kept), and the same correction over dt as a constraint impulse
// along the start's gradient (the one the velocity sweeps made the motion tangent to, so it
// takes nearly nothing from the motion along it); these sweeps go on only while that error
// shrinks. Else all of it, on positions only, along the gradient of the first such sweep (a
// chord step: these sweeps move the poses little, and factor once). An error within
// direct_position_tolerance is left: such a sweep moves nothing.
bool ShapeWorld::solve_tree_positions(bool keep) {
  JointSolver solver(bodies_, state_, dt_);
  const auto members = tree_.members();
  const auto rhs = tree_.rhs();
  const auto arms = tree_.arms();
  turned_.resize(state_.size());
  for (const std::uint32_t body : tree_.bodies()) turned_[body] = rot_of(state_[body].a);
  // An end's centre and rotation now: the world's origin, a forest body's (made once a sweep:
  // every end that translates is one), or a static or kinematic body's.
  auto pose = [&](std::uint32_t body) -> std::pair<Vec2, Rot> {
    if (body == JointRecord::none) return {};
    const ShapeState& s = state_[body];
    return {{s.x, s.y}, bodies_[body].inv_mass > 0.0 ? turned_[body] : rot_of(s.a)};
  };
  const auto angle_rows = tree_.angle_rows();
  const auto angle_rhs = tree_.angle_rhs();
  bool rows_changed = false;  // whether a member's angle row came or went
  double past_limit = 0.0;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const JointRecord& j = joints_[members[k]];
    const auto [ca, qa] = pose(j.a);
    const auto [cb, qb] = pose(j.b);
    const Vec2 ra = rotate(qa, j.local_a), rb = rotate(qb, j.local_b);
    const Vec2 c = (cb + rb) - (ca + ra);
    constexpr double most = joint_max_linear_correction;
    const Vec2 e = keep ? j.offset - c : -c;
    rhs[k] = {std::clamp(e.x, -most, most), std::clamp(e.y, -most, most)};
    if (keep || !rest_factored_) arms[k] = {ra, rb};
    // A limit the joint is past, or within the largest correction of at the first sweep on
    // positions only: a row of the forest's solve in each sweep after (holding the angle
    // within the limits).
    const double limit = !keep && direct_limits_ ? solver.limit_correction(j) : 0.0;
    const bool near = !keep && !rest_factored_ && direct_limits_ &&
                      solver.limit_margin(j) < joint_max_angular_correction;
    const std::uint8_t row = keep ? 0 : (limit != 0.0 || near || angle_rows[k] ? 1 : 0);
    rows_changed = rows_changed || angle_rows[k] != row;
    angle_rows[k] = row, angle_rhs[k] = -limit;
    past_limit = std::max(past_limit, std::abs(limit));
  }
  const double error = largest(rhs);
  if (past_limit == 0.0 &&
      (error <= direct_position_tolerance || (keep && !(error < kept_error_)))) {
    return false;
  }
  if (keep) kept_error_ = error;
  if (keep || !rest_factored_ || rows_changed) {
    tree_.factor();
    for (std::size_t k = 0; k < members.size(); ++k) {
      joints_[members[k]].limit_row = tree_.angle_row_kept(k);
    }
  }
  rest_factored_ = !keep;
  tree_.solve(rhs, angle_rhs);
  for (std::size_t k = 0; k < members.size(); ++k) {
    JointRecord& j = joints_[members[k]];
    solver.shift_point(j, rhs[k], arms[k][0], arms[k][1], angle_rows[k] ? angle_rhs[k] : 0.0);
    if (keep) solver.kick_point(j, rhs[k]);
  }
  return true;
}

// Each sweep, velocity or position, with or without joints, polls a stop request first (one
// relaxed atomic load, in the sweeps' loops): a sweep of max_joints joints, or of a large world's
// contacts, is a fraction of a second; a tick is tens of sweeps (up to ContactSettings' largest
// iteration counts).
void ShapeWorld::poll_stop() {
  ++stop_polls_;
  throw_if_stop_requested();
}

bool ShapeWorld::solve_joint_velocities() {
  JointSolver solver(bodies_, state_, dt_, velocity_);
  if (joint_rows_) {
    for (JointRecord& j : joints_) {
      if (!j.broken) solver.solve_velocity(j);
    }
  }
  const bool direct = !tree_.empty() && solve_tree_velocities();
  return solver.velocity_change() > velocity_sweep_tolerance || direct;
}

bool ShapeWorld::solve_joint_positions(bool keep) {
  JointSolver solver(bodies_, state_, dt_);
  if (indirect_ || (!keep && direct_limits_)) {
    for (JointRecord& j : joints_) {
      if (!j.broken) solver.solve_position(j, keep);
    }
  }
  const bool direct = !tree_.empty() && solve_tree_positions(keep);
  return solver.moved() || direct;
}

void ShapeWorld::account_joints() {
  JointSolver solver(bodies_, state_, dt_);
  for (JointRecord& j : joints_) {
    if (!j.broken) solver.account(j);
  }
}

}  // namespace fixstep::detail
