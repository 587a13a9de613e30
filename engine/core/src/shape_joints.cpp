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
  step_error_ = no_step, step_keeps_ = false;
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

// The forest's point errors now into tree_.rhs() (m: while keeping, the error the tick's
// motion made, the start's kept; else all of it) and each member's arms now into fresh_arms_;
// and each member's angle row (a limit the joint is past, or, at the first sweep on positions
// only, within the largest correction of: a row of the forest's solve in each sweep after,
// holding the angle within the limits).
ShapeWorld::TreeErrors ShapeWorld::measure_tree_errors(bool keep, const JointSolver& solver) {
  const auto members = tree_.members();
  const auto rhs = tree_.rhs();
  turned_.resize(state_.size());
  for (const std::uint32_t body : tree_.bodies()) turned_[body] = rot_of(state_[body].a);
  fresh_arms_.resize(members.size());
  // An end's centre and rotation now: the world's origin, a forest body's (made once a sweep:
  // every end that translates is one), or a static or kinematic body's.
  auto pose = [&](std::uint32_t body) -> std::pair<Vec2, Rot> {
    if (body == JointRecord::none) return {};
    const ShapeState& s = state_[body];
    return {{s.x, s.y}, bodies_[body].inv_mass > 0.0 ? turned_[body] : rot_of(s.a)};
  };
  const auto angle_rows = tree_.angle_rows();
  const auto angle_rhs = tree_.angle_rhs();
  TreeErrors out;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const JointRecord& j = joints_[members[k]];
    const auto [ca, qa] = pose(j.a);
    const auto [cb, qb] = pose(j.b);
    const Vec2 ra = rotate(qa, j.local_a), rb = rotate(qb, j.local_b);
    const Vec2 c = (cb + rb) - (ca + ra);
    rhs[k] = keep ? j.offset - c : -c;
    fresh_arms_[k] = {ra, rb};
    const double limit = !keep && direct_limits_ ? solver.limit_correction(j) : 0.0;
    const bool near = !keep && !rest_factored_ && direct_limits_ &&
                      solver.limit_margin(j) < joint_max_angular_correction;
    const std::uint8_t row = keep ? 0 : (limit != 0.0 || near || angle_rows[k] ? 1 : 0);
    out.rows_changed = out.rows_changed || angle_rows[k] != row;
    out.any_row = out.any_row || row != 0;
    angle_rows[k] = row, angle_rhs[k] = -limit;
    out.past_limit = std::max(out.past_limit, std::abs(limit));
  }
  out.error = largest(rhs);
  return out;
}

// The forest's point errors at once, a Newton step of the projection onto C = target: the
// error measured, and the positions moved, along the gradient at the poses now; a step whose
// largest point error is over joint_max_linear_correction is scaled down as a whole to it (a
// damped Newton step: its direction kept, where clamping each error alone turns it, and the
// error measured before it, so that a sweep sees whether it shrinks). While keeping, the same
// correction over dt also goes in as a constraint impulse along the start's gradient (the one
// the velocity sweeps made the motion tangent to, so it takes nearly nothing from the motion
// along it), or, for a joint whose bodies turned more than fast_joint_turn within the tick,
// along the gradient at the step's poses (kick); these sweeps end when the error did not
// shrink. On positions only, the steps are chord steps (the factors of the first such sweep:
// these sweeps move the poses little), made at the poses now again after a step that did not
// shrink the error (the contacts' push-out moves bodies between these sweeps). An error within
// direct_position_tolerance is left: such a sweep moves nothing.
bool ShapeWorld::solve_tree_positions(bool keep) {
  JointSolver solver(bodies_, state_, dt_);
  if (keep != step_keeps_) {  // a phase begins: while keeping, which joints turn fast
    step_error_ = no_step, step_keeps_ = keep;
    const auto members = tree_.members();
    if (keep) fast_.resize(members.size());
    for (std::size_t k = 0; keep && k < members.size(); ++k) {
      fast_[k] = solver.tick_turn(joints_[members[k]]) > fast_joint_turn ? 1 : 0;
    }
  }
  const TreeErrors now = measure_tree_errors(keep, solver);
  if (now.past_limit == 0.0 && now.error <= direct_position_tolerance) return false;
  const bool stalled = step_error_ < no_step && !(now.error < step_error_);
  if (stalled && keep) return false;  // the sweeps that keep have ended
  const auto members = tree_.members();
  const auto rhs = tree_.rhs();
  const auto arms = tree_.arms();
  const auto angle_rows = tree_.angle_rows();
  const auto angle_rhs = tree_.angle_rhs();
  const bool arms_now = keep || !rest_factored_ || stalled;
  if (now.error > joint_max_linear_correction) {
    const double scale = joint_max_linear_correction / now.error;
    for (Vec2& e : rhs) e = scale * e;
  }
  if (arms_now) std::copy(fresh_arms_.begin(), fresh_arms_.end(), arms.begin());
  if (arms_now || now.rows_changed) {
    tree_.factor();
    for (std::size_t k = 0; k < members.size(); ++k) {
      joints_[members[k]].limit_row = tree_.angle_row_kept(k);
    }
  }
  rest_factored_ = !keep;
  tree_.solve(rhs, angle_rhs);
  // Only a step without angle rows is checked (a limit's row is one-sided).
  step_error_ = now.error;
  if (now.any_row) step_error_ = no_step;
  for (std::size_t k = 0; k < members.size(); ++k) {
    JointRecord& j = joints_[members[k]];
    solver.shift_point(j, rhs[k], arms[k][0], arms[k][1], angle_rows[k] ? angle_rhs[k] : 0.0);
    if (keep) kick(solver, k, rhs[k]);
  }
  return true;
}

// Member k's share of a step that keeps, p (kg·m), as a constraint impulse p/dt: at the
// start's arms, or, for a joint that turns fast, at the arms the step was made at. Along the
// start's gradient, a link that turned a radian in the tick gained energy: a whipping chain
// rose by half its kinetic energy for a few ticks, and a 100-link one came apart. Along now's
// gradient for every joint, a pendulum lost 42 % of its energy over 100 periods: the start's is
// what the velocity sweeps made the motion tangent to.
void ShapeWorld::kick(JointSolver& solver, std::size_t k, Vec2 p) {
  JointRecord& j = joints_[tree_.members()[k]];
  const auto arms = tree_.arms();
  if (fast_[k]) {
    solver.kick_point(j, p, arms[k][0], arms[k][1]);
  } else {
    solver.kick_point(j, p, j.ra, j.rb);
  }
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
