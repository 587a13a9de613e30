// The joints by halves on two threads: a world's joints split between two threads by the bodies
// they join, so that each thread's sweeps move bodies the other's never touch. Internal to the
// engine: not installed.
//
// Two joints share a group when they share a body, of any type (a static or kinematic end is
// written by a position sweep too, by zero: two threads must not both write it); the world (no
// body) joins nothing. Each group goes whole to one half, in the order of its first joint, the
// first half taking groups until it holds half of the joints. A sweep of each half's joints in
// joint order then moves every body by the same impulses in the same order as one sweep of all
// of them does: the same bits on one thread and two. The forest's trees (joint_tree.hpp) lie
// each within one group.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "joint_bodies.hpp"
#include "joint_record.hpp"

namespace fixstep::detail {

class JointHalves {
 public:
  /// Groups the `listed` joints (indices into `joints`, ascending; those not broken) as above,
  /// over the bodies `numbered` numbers (built from the same list): O(listed joints). Returns
  /// whether both halves have joints (false: one group, or none; the halves then unset).
  /// Allocates only while the world grows.
  bool split(std::span<const JointRecord> joints, std::span<const std::uint32_t> listed,
             const JointBodies& numbered);
  /// Half h's joints (indices into split's span, not broken), in joint order.
  [[nodiscard]] std::span<const std::uint32_t> joints(int h) const { return joints_[h]; }
  /// Each numbered body's half (0 or 1), by its number in split's `numbered`.
  [[nodiscard]] std::span<const std::uint8_t> half_of_body() const { return half_of_body_; }
  /// Heap bytes a copy holds (World::snapshot_bytes).
  [[nodiscard]] std::size_t bytes() const;

 private:
  static constexpr std::uint32_t unset = ~std::uint32_t{0};
  std::vector<std::uint32_t> root_;     ///< union-find over the numbered bodies (island_union.hpp)
  std::vector<std::uint32_t> count_;    ///< per group root: its joints
  std::vector<std::uint32_t> half_of_;  ///< per group root: its half, or unset
  std::vector<std::uint8_t> half_of_body_;
  std::array<std::vector<std::uint32_t>, 2> joints_;
};

}  // namespace fixstep::detail
