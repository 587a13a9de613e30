// The forest's sweeps that keep (ShapeWorld::step_tree_positions) as a backtracking line
// search: each damped Newton step on positions waits to give its impulse until the next
// measure shows that it shrank the largest point error. A step that did not is taken back
// (the forest bodies' poses as they were before it) and made again at half its length, up to
// `most_cuts` times; then the sweeps end at the poses before it. (A step made as the sweeps
// reach their count is kept unmeasured, as before the search.) A step may fail to shrink the
// error where the linearization is poor: a chain that whips, nearly straight, is near a
// singular Jacobian, where a full Newton step overshoots (Nocedal and Wright, Numerical
// Optimization, 2nd ed., section 3.1 and chapter 11: backtracking on a merit function, here the
// largest error). Internal to the engine: not installed.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "copy_bytes.hpp"
#include "fixstep/core/types.hpp"
#include "joint_bodies.hpp"
#include "shape_records.hpp"

namespace fixstep::detail {

struct JointKeepSearch {
  /// Halvings of one step before the sweeps end: its last try is 1/16 of the step.
  static constexpr int most_cuts = 4;
  /// Each member's step not yet given as an impulse (kg·m: the position change times the
  /// effective mass, JointTree::solve's solution), by member index.
  std::vector<Vec2> step;
  /// Each forest body's pose (x m, y m, a rad) before that step, by its JointBodies number
  /// (so sized by the bodies the joints hold, not by the world).
  std::vector<std::array<double, 3>> from;
  bool pending = false;         ///< a step waits in `step`
  int cuts = 0;                 ///< halvings of the step waiting
  std::uint64_t cuts_made = 0;  ///< steps taken back so far (the tests')

  /// Sizes for `members` and the `bodies` numbered (allocates only while the world grows).
  void size(std::size_t members, std::size_t bodies) {
    step.resize(members);
    from.resize(bodies);
  }
  /// Keeps the poses of `part_bodies` (body indices, each numbered by `numbered`) before a
  /// step.
  void save(std::span<const std::uint32_t> part_bodies, std::span<const ShapeState> state,
            const JointBodies& numbered) {
    for (const std::uint32_t b : part_bodies) {
      from[numbered.local(b)] = {state[b].x, state[b].y, state[b].a};
    }
  }
  /// Puts the poses of `part_bodies` back as save() found them.
  void take_back(std::span<const std::uint32_t> part_bodies, std::span<ShapeState> state,
                 const JointBodies& numbered) const {
    for (const std::uint32_t b : part_bodies) {
      const auto& p = from[numbered.local(b)];
      state[b].x = p[0], state[b].y = p[1], state[b].a = p[2];
    }
  }
  [[nodiscard]] std::size_t bytes() const { return copy_bytes(step, from); }
};

}  // namespace fixstep::detail
