// Shape contacts, part 3: the joints' sweeps as the shape phase runs them (shape_world.hpp has
// the whole tick; joint_solver.hpp the joints' rows).
#include "fixstep/core/stop_request.hpp"
#include "joint_solver.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

void ShapeWorld::prepare_joints() {
  JointSolver solver(bodies_, state_, dt_, velocity_);
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
  JointSolver solver(bodies_, state_, dt_, velocity_);
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

}  // namespace fixstep::detail
