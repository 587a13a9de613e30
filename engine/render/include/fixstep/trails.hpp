// The trails behind the bodies: each body's recent positions, kept per handle (Entity), so that
// creating and destroying bodies in any order never joins two unrelated bodies' positions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fixstep/frame_data.hpp"

namespace fixstep {

/// One ring of recent positions per body handle: what Renderer::draw draws behind the bodies.
///
/// A trail belongs to its body's Entity, not to its dense index (which destroy() changes) nor to
/// its slot (which a later body may reuse with a new generation). A body that was not in the
/// previous record (just created, or a reused slot with a new generation) starts an empty trail;
/// the trail of a body missing from a record (destroyed) is dropped.
///
/// Cost: record() is O(bodies), with no allocation once every slot seen has storage (a steady
/// body set, or one whose slots are reused); memory is 2 * capacity floats per slot (360 bytes).
class Trails {
 public:
  /// Samples a trail holds: the last `capacity` records (frames).
  static constexpr int capacity = 45;

  /// Appends each body's position (frame.x[j], frame.y[j]), m, to the trail of frame.ids[j]. A
  /// frame without ids (filled by hand) keys body j by the handle World(def) gives def.bodies[j],
  /// as if no body were ever created or destroyed. Throws std::invalid_argument if ids is neither
  /// empty nor as long as x, or holds a null handle; handles within one frame must be distinct.
  void record(const RenderFrame& frame);
  /// Forgets every trail: each body starts an empty one at the next record() (after a restart,
  /// a rewind or a jump of the camera).
  void clear();
  /// Bodies in the last record().
  [[nodiscard]] std::size_t size() const { return slot_of_.size(); }
  /// The trail of body j < size() of the last record(), oldest first: its samples' positions
  /// (m) are written to xs and ys; returns their number, 1 to capacity (1: the body is new).
  int samples(std::size_t j, std::span<float, capacity> xs, std::span<float, capacity> ys) const;

 private:
  /// Makes room for slot `slot` (new slots were never seen).
  void grow(std::uint32_t slot);

  std::vector<std::uint32_t> slot_of_;  ///< body j of the last record -> its slot
  // Per slot: the generation its trail belongs to, the record it was last seen in, the ring's
  // next write position and sample count, and capacity samples (x_, y_: m).
  std::vector<std::uint32_t> generation_, seen_;
  std::vector<std::uint8_t> head_, count_;
  std::vector<float> x_, y_;
  std::uint32_t stamp_ = 1;  ///< the last record's number; seen_ starts at 0, never stamp_ - 1
};

}  // namespace fixstep
