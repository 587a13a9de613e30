// The bodies a tick's joints hold, numbered densely: the joints' forest (joint_tree.hpp) and
// their halves (joint_halves.hpp) keep their per-body tables over these numbers, so that a
// tick costs what its listed joints hold, not what the world holds (a world asleep but for a
// few joints pays for those). Internal to the engine: not installed.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "joint_record.hpp"

namespace fixstep::detail {

class JointBodies {
 public:
  /// Numbers the bodies held by the `listed` joints (indices into `joints`; the broken ones
  /// left out) 0, 1, 2, ... in the order the joints name them, A's end before B's; the world
  /// (JointRecord::none) is no body. `bodies` is the number of bodies the joints' ends index.
  /// O(listed joints): the table by body is never cleared, an entry counting only where the
  /// numbered body it names is that body (a sparse set). Allocates only while the world grows.
  void build(std::span<const JointRecord> joints, std::span<const std::uint32_t> listed,
             std::size_t bodies);
  /// A numbered body's number (precondition: one of the listed joints holds `body`).
  [[nodiscard]] std::uint32_t local(std::uint32_t body) const { return local_of_[body]; }
  /// How many bodies are numbered.
  [[nodiscard]] std::size_t size() const { return bodies_.size(); }
  /// Heap bytes a copy holds (World::snapshot_bytes).
  [[nodiscard]] std::size_t bytes() const;

 private:
  std::vector<std::uint32_t> local_of_;  ///< by body: its number, where bodies_ names it back
  std::vector<std::uint32_t> bodies_;    ///< by number: the body
};

}  // namespace fixstep::detail
