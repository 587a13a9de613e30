// The forest's point rows (joint_tree.hpp) packed for the velocity sweeps: each member's ends,
// their inverse masses and its lever arms in one record, made once a tick, so that a sweep's
// two passes over the members (their velocity errors before the forest's solve, its impulses
// after) read that record instead of the whole JointRecord and each body's. An impulse is
// added up and moves its ends as JointSolver's rows push theirs (joint_solver.hpp), in the
// same order, so the sweeps give the same bits as when each member was a JointSolver call.
// Internal to the engine: not installed.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "joint_record.hpp"
#include "shape_lanes.hpp"

namespace fixstep::detail {

class JointTree;
struct ShapedBody;

class JointPointRows {
 public:
  /// Packs the point rows of `tree`'s members in `part` (JointTree's parts: 0, 1 or whole), in
  /// the order of tree.members_of(part), after JointSolver::prepare (each joint's arms at the
  /// tick's start). `zero`: a slot of the velocities the sweeps are given that holds zero,
  /// read for the world's end. Allocates only while the forest grows.
  void pack(int part, std::span<JointRecord> joints, const JointTree& tree,
            std::span<const ShapedBody> bodies, std::uint32_t zero);
  /// Each member's velocity error Ċ = v_b + ω_b × r_b − v_a − ω_a × r_a (m/s) at the start's
  /// arms, negated, into rhs[k] (k its member index); each of the part's trees marked in
  /// `active` (one entry per tree) 1 where some member's component is over `tolerance`, else
  /// 0. Returns the largest component (m/s).
  double errors(int part, std::span<const ShapeMotion> velocities, std::span<Vec2> rhs,
                std::span<std::uint8_t> active, double tolerance) const;
  /// The impulse rhs[k] (N·s) on B's end of each member of the part's active trees, and −rhs[k]
  /// on A's: added to its accumulated impulse and its given and turned impulses, and moving
  /// its ends' velocities (an end that does not move, or the world, is left as it is).
  void apply(int part, std::span<ShapeMotion> velocities, std::span<const Vec2> rhs,
             std::span<const std::uint8_t> active) const;
  /// Heap bytes a copy holds (World::snapshot_bytes).
  [[nodiscard]] std::size_t bytes() const;

 private:
  /// One member's point row: its joint, member index and tree; the velocity slots of its ends
  /// (the zero slot for the world), whether an impulse moves each (a body with a non-zero
  /// inverse mass or inertia), their inverse masses and inertias (1/kg, 1/(kg·m²)) and the
  /// lever arms at the tick's start (m, world frame).
  struct Row {
    JointRecord* joint = nullptr;
    std::uint32_t member = 0, tree = 0;
    std::uint32_t a = 0, b = 0;
    bool push_a = false, push_b = false;
    double ma = 0.0, ia = 0.0, mb = 0.0, ib = 0.0;
    Vec2 ra{}, rb{};
  };
  std::array<std::vector<Row>, 3> rows_;
};

}  // namespace fixstep::detail
