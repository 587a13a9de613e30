#include "fixstep/core/pointer_drag.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/input.hpp"

namespace fixstep {

Entity pick_body(const World& sim, Vec2 point, double tolerance) {
  Entity best = null_entity;
  double best_distance = 0.0;
  for (const Entity e : sim.bodies()) {
    const Vec2 p = sim.body(e).position;
    const double d = det::hypot(p.x - point.x, p.y - point.y);
    const std::optional<Appearance> a = sim.get<Appearance>(e);
    const double reach = std::max(a ? a->radius : 0.0, tolerance);
    if (d <= reach && (best == null_entity || d < best_distance)) {
      best = e;
      best_distance = d;
    }
  }
  return best;
}

PointerDrag::PointerDrag(double tolerance) : tolerance_(tolerance) {
  if (!std::isfinite(tolerance) || tolerance < 0.0) {
    throw std::invalid_argument(
        fmt::format("pointer drag: tolerance must be finite and >= 0 m (got {})", tolerance));
  }
}

void PointerDrag::apply(TickInput& input, const World& sim) {
  const IeeeFloatMode ieee;  // a state never depends on the caller's FPU mode (float_mode.hpp)
  const bool held = (input.held & button_pointer_primary) != 0;
  if ((input.pressed & button_pointer_primary) && held) {
    body_ = pick_body(sim, input.pointer, tolerance_);
  } else if (!held) {
    body_ = null_entity;
  }
  input.drag_body = body_;
}

}  // namespace fixstep
