// The velocity rows of a world whose joints with rows are all revolute joints of the forest
// (joint_tree.hpp) with angle limits alone (no spring, no motor: a ragdoll's): each joint's
// lower and upper limit rows packed in one record, made once a tick, so that a velocity
// sweep reads that record and the impulses it accumulates instead of the whole JointRecord.
// The arithmetic is JointSolver::solve_velocity's for such a joint, operation for operation
// (so the same bits): Box2D v2.4's speculative one-sided rows, λ accumulated and clamped to
// [0, ∞). Internal to the engine: not installed.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "joint_record.hpp"
#include "shape_lanes.hpp"
#include "shape_records.hpp"

namespace fixstep::detail {

class JointLimitRows {
 public:
  /// Whether a joint's own velocity rows (if any) are these: a revolute joint of the forest
  /// (JointRecord::direct, after JointTree::build) without a motor or a spring. A tick packs
  /// its rows only when every joint with rows of its own is one.
  [[nodiscard]] static bool serves(const JointRecord& j) {
    return j.def.type == JointType::revolute && j.direct && !j.motor_acts() &&
           !(j.def.frequency > 0.0);
  }
  /// Packs the rows of `part`'s joints (`listed`, in the order JointSolver would sweep them;
  /// part 0, 1 or 2, JointTree's parts) at the tick's start, after JointSolver::prepare (each
  /// joint's effective mass and angle), `dt` the tick (s). `zero`: a slot of the velocities
  /// the sweeps are given that holds zero, read for the world's end. Allocates only while the
  /// world grows.
  void pack(int part, std::span<JointRecord> joints, std::span<const std::uint32_t> listed,
            std::span<const ShapedBody> bodies, double dt, std::uint32_t zero);
  /// One sweep of `part`'s rows over `velocities` (each body's, m/s and rad/s); returns the
  /// largest change of a body's velocity component that one joint's rows made (as
  /// JointSolver::velocity_change()).
  double sweep(int part, std::span<ShapeMotion> velocities) const;
  /// Heap bytes a copy holds (World::snapshot_bytes).
  [[nodiscard]] std::size_t bytes() const;

 private:
  static constexpr std::uint32_t none = JointRecord::none;
  /// One joint's limit rows (64 bytes): whether an impulse moves each end's velocity (a body
  /// with a non-zero inverse mass or inertia), its ends' inverse inertia (1/(kg·m²)), its
  /// effective mass about the angle (kg·m²) and each limit's speculative bias max(C, 0)/dt
  /// (rad/s).
  struct Row {
    JointRecord* joint = nullptr;
    std::uint32_t a = none, b = none;  ///< the ends' velocity slots (the world's: the zero slot)
    bool push_a = false, push_b = false, lower = false, upper = false;
    double ia = 0.0, ib = 0.0;
    double mass = 0.0;
    double lower_bias = 0.0, upper_bias = 0.0;
  };
  std::array<std::vector<Row>, 3> rows_;
};

}  // namespace fixstep::detail
