// Shape contacts, part 3: the joints' sweeps as the shape phase runs them (shape_world.hpp has
// the whole tick): each joint's own rows (joint_solver.hpp), then the point rows of the
// revolute joints that form a forest, all at once (joint_tree.hpp). With two threads and
// enough joints, each pass runs by halves (joint_halves.hpp: each thread its half's joints and
// trees), with what decides a sweep (its largest error, whether it moved) taken over both.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "fixstep/core/stop_request.hpp"
#include "joint_solver.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

void ShapeWorld::prepare_joints() {
  JointSolver solver(bodies_, state_, dt_, velocity_);
  for_joints(JointTree::whole, [&](JointRecord& j) { solver.prepare(j); });
  const std::span<const std::uint32_t> live = rest_.live_joints;
  joint_bodies_.build(joints_, live, bodies_.size());
  tree_.build(joints_, live, bodies_, joint_bodies_);
  joints_halved_ = joint_thread_ != nullptr && live.size() >= min_split_joints &&
                   halves_.split(joints_, live, joint_bodies_);
  if (joints_halved_ && !tree_.empty()) tree_.split(halves_.half_of_body(), joint_bodies_);
  joint_rows_ = false, indirect_ = false, direct_limits_ = false, searches_ = true;
  bool packable = true;  // every joint's own rows ones JointLimitRows packs
  for (const std::uint32_t i : live) {
    const JointRecord& j = joints_[i];
    if (j.broken) continue;
    ++joints_visited_;
    indirect_ = indirect_ || !j.direct;
    // (A joint outside the forest that holds a forest body corrects it in the sweeps that
    // keep, which taking a forest step back would undo.)
    if (!j.direct && searches_) searches_ = !in_forest(j.a) && !in_forest(j.b);
    // A revolute joint of the forest: its angle's Gauss-Seidel rows beside the direct solve.
    const bool rows = !j.direct || j.angle_rows();
    joint_rows_ = joint_rows_ || rows;
    packable = packable && (!rows || JointLimitRows::serves(j));
    direct_limits_ = direct_limits_ || (j.direct && (j.def.lower || j.def.upper));
  }
  packed_limits_ = joint_rows_ && packable;
  if (packed_limits_ && joints_halved_) {
    for (int h = 0; h < 2; ++h) {
      limit_rows_.pack(h, joints_, halves_.joints(h), bodies_, dt_, zero_slot());
      limit_shifts_.pack(h, joints_, halves_.joints(h), bodies_);
    }
  } else if (packed_limits_) {
    limit_rows_.pack(JointTree::whole, joints_, live, bodies_, dt_, zero_slot());
    limit_shifts_.pack(JointTree::whole, joints_, live, bodies_);
  }
  if (tree_.empty()) return;
  const auto members = tree_.members();
  const auto arms = tree_.arms();
  for (std::size_t k = 0; k < members.size(); ++k) {
    const JointRecord& j = joints_[members[k]];
    arms[k] = {j.ra, j.rb};
  }
  tree_.factor();
  tree_active_.assign(tree_.trees(), 1);
  if (joints_halved_) {
    for (int h = 0; h < 2; ++h) point_rows_.pack(h, joints_, tree_, bodies_, zero_slot());
  } else {
    point_rows_.pack(JointTree::whole, joints_, tree_, bodies_, zero_slot());
  }
  rest_factored_ = false;
  step_error_ = no_step, step_keeps_ = false;
}

bool ShapeWorld::in_forest(std::uint32_t body) const {
  return body != JointRecord::none && tree_.holds(joint_bodies_.local(body));
}

void ShapeWorld::clear_active(int part) {
  for (const std::uint32_t k : tree_.members_of(part)) tree_active_[tree_.tree_of(k)] = 0;
}

// The forest's point errors now into tree_.rhs() (m: while keeping, the error the tick's
// motion made, the start's kept; else all of it) and each member's arms now into fresh_arms_;
// and each member's angle row (a limit the joint is past, or, at the first sweep on positions
// only, within the largest correction of: a row of the forest's solve in each sweep after,
// holding the angle within the limits).
ShapeWorld::TreeErrors ShapeWorld::measure_tree_errors(bool keep, const JointSolver& solver,
                                                       int part) {
  const auto members = tree_.members();
  const auto rhs = tree_.rhs();
  rot_of_each(
      tree_.bodies_of(part), [&](std::uint32_t body) { return state_[body].a; },
      [&](std::uint32_t body, Rot q) { turned_[body] = q; });
  // An end's centre and rotation now: the world's origin, a forest body's (made once a sweep:
  // every end that translates is one), or a static or kinematic body's.
  // (Each end's arm turned in its own branch: a pose chosen whole went through the stack in
  // narrow stores and one wide load, which waited for the stores to retire.)
  auto centre = [&](std::uint32_t body) {
    return body == JointRecord::none ? Vec2{} : Vec2{state_[body].x, state_[body].y};
  };
  auto arm = [&](std::uint32_t body, Vec2 local) {
    if (body == JointRecord::none) return rotate(Rot{}, local);
    if (!(bodies_[body].inv_mass > 0.0)) return rotate(rot_of(state_[body].a), local);
    return rotate(turned_[body], local);
  };
  const auto angle_rows = tree_.angle_rows();
  const auto angle_rhs = tree_.angle_rhs();
  TreeErrors out;
  clear_active(part);
  for (const std::uint32_t k : tree_.members_of(part)) {
    const JointRecord& j = joints_[members[k]];
    const Vec2 ra = arm(j.a, j.local_a), rb = arm(j.b, j.local_b);
    const Vec2 c = (centre(j.b) + rb) - (centre(j.a) + ra);
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
    const double error = std::max(std::abs(rhs[k].x), std::abs(rhs[k].y));
    out.error = std::max(out.error, error);
    if (error > direct_position_tolerance || limit != 0.0) tree_active_[tree_.tree_of(k)] = 1;
  }
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
// along the gradient at the step's poses (kick). Where no joint outside the forest holds a
// forest body (searches_), a step gives that impulse only once the next measure shows it
// shrank the error (or the sweeps reach their count), and one that did not is made again
// shorter (cut_kept_step); otherwise these sweeps end when the error did not shrink. On
// positions only, the steps are chord steps (the factors of the first such sweep: these
// sweeps move the poses little), made at the poses now again after a step that did not shrink
// the error (the contacts' push-out moves bodies between these sweeps). A tree whose errors
// are within direct_position_tolerance (and past no limit) is left: the step moves none of it.
bool ShapeWorld::step_tree_positions(bool keep, const TreeErrors& now) {
  if (now.past_limit == 0.0 && now.error <= direct_position_tolerance) return false;
  const bool stalled = step_error_ < no_step && !(now.error < step_error_);
  if (stalled && keep) return searches_ && cut_kept_step();  // else these sweeps have ended
  const bool arms_now = keep || !rest_factored_ || stalled;
  const bool refactor = arms_now || now.rows_changed;
  const bool scaled = now.error > joint_max_linear_correction;
  const double scale = scaled ? joint_max_linear_correction / now.error : 1.0;
  if (refactor) tree_.factor_angles();
  const bool search = keep && searches_;
  const bool give = search && keep_search_.pending;  // the last step shrank the error
  auto step = [&](int part) {
    const auto members = tree_.members();
    const auto rhs = tree_.rhs();
    const auto arms = tree_.arms();
    const auto angle_rows = tree_.angle_rows();
    const auto angle_rhs = tree_.angle_rhs();
    const auto own = tree_.members_of(part);
    if (give) give_kept_step(part);  // at its own arms, before they are made again
    if (search) keep_search_.save(tree_.bodies_of(part), state_, joint_bodies_);
    for (const std::uint32_t k : own) {
      if (scaled) rhs[k] = scale * rhs[k];
      if (arms_now) arms[k] = fresh_arms_[k];
    }
    if (refactor) {
      tree_.factor_part(part);
      for (const std::uint32_t k : own) joints_[members[k]].limit_row = tree_.angle_row_kept(k);
    }
    tree_.solve(rhs, angle_rhs, part, tree_active_);
    JointSolver solver(bodies_, state_, dt_);
    for (const std::uint32_t k : own) {
      if (tree_active_[tree_.tree_of(k)] == 0) {  // a tree within tolerance: no step
        if (search) keep_search_.step[k] = {};
        continue;
      }
      JointRecord& j = joints_[members[k]];
      solver.shift_point(j, rhs[k], arms[k][0], arms[k][1], angle_rows[k] ? angle_rhs[k] : 0.0);
      if (search) {
        keep_search_.step[k] = rhs[k];
      } else if (keep) {
        kick(solver, k, rhs[k]);
      }
    }
  };
  run_joint_parts(step);
  keep_search_.pending = search, keep_search_.cuts = 0;
  rest_factored_ = !keep;
  // Only a step without angle rows is checked (a limit's row is one-sided).
  step_error_ = now.error;
  if (now.any_row) step_error_ = no_step;
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
  std::array<double, 3> change{}, error{};  // by part (0, 1, or JointTree::whole)
  auto rows = [&](int part) {
    JointSolver solver(bodies_, state_, dt_, velocity_);
    if (packed_limits_) {
      change[part] = limit_rows_.sweep(part, velocity_);
    } else {
      if (joint_rows_) for_joints(part, [&](JointRecord& j) { solver.solve_velocity(j); });
      change[part] = solver.velocity_change();
    }
    // The forest's point rows: each member's velocity error, Ċ at the start's arms.
    if (!tree_.empty()) {
      error[part] =
          point_rows_.errors(part, velocity_, tree_.rhs(), tree_active_, direct_velocity_tolerance);
    }
  };
  run_joint_parts(rows);
  // The forest's point rows at once: the impulses that make every one's Ċ zero together, at
  // the start's arms. A tree whose velocity errors are within direct_velocity_tolerance is
  // left (tree_active_): the solve moves none of it.
  const bool direct = std::max({error[0], error[1], error[2]}) > direct_velocity_tolerance;
  if (direct) {
    auto solve = [&](int part) {
      tree_.solve(tree_.rhs(), {}, part, tree_active_);
      point_rows_.apply(part, velocity_, tree_.rhs(), tree_active_);
    };
    run_joint_parts(solve);
  }
  return std::max({change[0], change[1], change[2]}) > direct_velocity_tolerance || direct;
}

// The step waiting (keep_search_) given as impulses by `part`'s members, at the arms it was
// made at.
void ShapeWorld::give_kept_step(int part) {
  JointSolver solver(bodies_, state_, dt_);
  for (const std::uint32_t k : tree_.members_of(part)) kick(solver, k, keep_search_.step[k]);
}

// A step that did not shrink the error taken back: made again at half its length from the
// poses before it (the same arms and direction), or, after JointKeepSearch::most_cuts
// halvings, not at all; then the sweeps that keep end (returns false).
bool ShapeWorld::cut_kept_step() {
  if (!keep_search_.pending) return false;
  const bool again = keep_search_.cuts < JointKeepSearch::most_cuts;
  auto cut = [&](int part) {
    keep_search_.take_back(tree_.bodies_of(part), state_, joint_bodies_);
    if (!again) return;
    const auto members = tree_.members();
    const auto arms = tree_.arms();
    JointSolver solver(bodies_, state_, dt_);
    for (const std::uint32_t k : tree_.members_of(part)) {
      Vec2& p = keep_search_.step[k];
      p = 0.5 * p;
      solver.shift_point(joints_[members[k]], p, arms[k][0], arms[k][1]);
    }
  };
  run_joint_parts(cut);
  keep_search_.pending = again;
  keep_search_.cuts += 1, keep_search_.cuts_made += 1;
  return again;
}

void ShapeWorld::end_keeping() {
  if (!keep_search_.pending) return;
  auto give = [&](int part) { give_kept_step(part); };
  run_joint_parts(give);
  keep_search_.pending = false;
}

bool ShapeWorld::solve_joint_positions(bool keep) {
  const bool rows = indirect_ || (!keep && direct_limits_);
  const bool tree = !tree_.empty();
  const bool phase = tree && keep != step_keeps_;  // a phase begins: its first step unchecked
  if (phase) step_error_ = no_step, step_keeps_ = keep;
  if (tree) {
    turned_.resize(state_.size());
    fresh_arms_.resize(tree_.members().size());
    fast_.resize(tree_.members().size());
  }
  if (phase && keep && searches_) {
    keep_search_.size(tree_.members().size(), joint_bodies_.size());
  }
  std::array<std::uint8_t, 3> moved{};  // by part
  std::array<TreeErrors, 3> errors{};
  auto measure = [&](int part) {
    JointSolver solver(bodies_, state_, dt_);
    if (rows && packed_limits_) {  // (every joint a forest's revolute joint: its limits alone)
      moved[part] = limit_shifts_.correct(part, state_) ? 1 : 0;
    } else {
      if (rows) for_joints(part, [&](JointRecord& j) { solver.solve_position(j, keep); });
      moved[part] = solver.moved() ? 1 : 0;
    }
    if (!tree) return;
    if (phase && keep) {  // while keeping, which joints turn fast
      const auto members = tree_.members();
      for (const std::uint32_t k : tree_.members_of(part)) {
        fast_[k] = solver.tick_turn(joints_[members[k]]) > fast_joint_turn ? 1 : 0;
      }
    }
    errors[part] = measure_tree_errors(keep, solver, part);
  };
  run_joint_parts(measure);
  TreeErrors now;
  for (const TreeErrors& e : errors) {  // the parts' together (a part not run: all zero)
    now.error = std::max(now.error, e.error);
    now.past_limit = std::max(now.past_limit, e.past_limit);
    now.rows_changed = now.rows_changed || e.rows_changed;
    now.any_row = now.any_row || e.any_row;
  }
  const bool direct = tree && step_tree_positions(keep, now);
  return moved[0] != 0 || moved[1] != 0 || moved[2] != 0 || direct;
}

void ShapeWorld::account_joints() {
  JointSolver solver(bodies_, state_, dt_);
  for_joints(JointTree::whole, [&](JointRecord& j) { solver.account(j); });
}

}  // namespace fixstep::detail
