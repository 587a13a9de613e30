// The position sweeps' corrections of the forest's angle limits, packed: in a world whose
// joints' rows are all JointLimitRows' (revolute joints of the forest, without motor or spring),
// each push-out sweep's pass over the joints does for each one only what
// JointSolver::solve_position does for it there: the turn its limits ask of its relative angle
// (Box2D v2.4's, within the largest correction), shared by its ends by their inverse inertias,
// unless the forest's solve holds the limit (JointRecord::limit_row). One record per joint, made
// once a tick, read instead of the JointRecord's ends and each body's record. The arithmetic is
// solve_position's, operation for operation (so the same bits, including the +0 a correction of
// none adds to a moving end's position and angle). Internal to the engine: not installed.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "joint_record.hpp"
#include "shape_records.hpp"

namespace fixstep::detail {

class JointLimitShifts {
 public:
  /// Packs `part`'s joints (`listed`, indices into `joints`, in the order the sweeps take them;
  /// the broken left out; JointTree's parts: 0, 1 or whole) after JointSolver::prepare.
  /// Allocates only while the world grows.
  void pack(int part, std::span<JointRecord> joints, std::span<const std::uint32_t> listed,
            std::span<const ShapedBody> bodies);
  /// One position sweep of `part`'s limits on `state` (positions only: ShapeState x, y, a);
  /// returns whether it turned any body (a correction other than 0).
  bool correct(int part, std::span<ShapeState> state) const;
  /// Heap bytes a copy holds (World::snapshot_bytes).
  [[nodiscard]] std::size_t bytes() const;

 private:
  static constexpr std::uint32_t none = JointRecord::none;
  /// One joint: its ends' bodies (none: the world), whether a correction moves each (a body
  /// with a non-zero inverse mass or inertia) and their inverse inertias (1/(kg·m²)).
  struct Row {
    JointRecord* joint = nullptr;
    std::uint32_t a = none, b = none;
    bool move_a = false, move_b = false;
    double ia = 0.0, ib = 0.0;
  };
  std::array<std::vector<Row>, 3> rows_;
};

}  // namespace fixstep::detail
