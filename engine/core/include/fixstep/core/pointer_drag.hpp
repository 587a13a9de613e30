// Pick and drag with the pointer, as a rule on tick inputs (the mouse joint of Box2D's
// samples): which body the pointer holds is decided at a tick, from that tick's state, and
// written into the tick's input, so a recording carries it and a replay needs no picking.
#pragma once

#include <cstdint>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world.hpp"

namespace fixstep {

/// The body nearest to `point` (m) whose distance is within its reach: its Appearance radius,
/// or `tolerance` (m) if that is larger; null_entity (the null handle) if none. O(bodies).
[[nodiscard]] Entity pick_body(const World& sim, Vec2 point, double tolerance);

/// Applies the pick-and-drag rule to the inputs of successive ticks: a tick whose input
/// presses button_pointer_primary (with the button still held) picks the body under the
/// pointer (pick_body); that body stays dragged until a tick releases the button. The drag is
/// written into TickInput::drag_body; World::step pulls the body towards TickInput::pointer.
class PointerDrag {
 public:
  /// tolerance: the pick reach of bodies smaller than it, m (e.g. a few pixels in metres);
  /// finite and >= 0, else std::invalid_argument.
  explicit PointerDrag(double tolerance);
  /// Updates the drag from `input`'s presses and releases and sets input.drag_body.
  void apply(TickInput& input, const World& sim);
  [[nodiscard]] Entity body() const { return body_; }  ///< dragged body, or null_entity
  void reset() { body_ = null_entity; }

 private:
  double tolerance_;
  Entity body_ = null_entity;
};

}  // namespace fixstep
