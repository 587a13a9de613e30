// mover_problem (mover.hpp): a MoverDef's own checks; those against its capsule are the
// kernel's (world_movers.cpp).
#include "fixstep/core/mover.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "fixstep/core/value_ranges.hpp"

namespace fixstep {

std::optional<std::string> mover_problem(const MoverDef& def) {
  const double a = def.max_floor_angle;
  if (!(a > 0.0 && a < 0.5 * std::numbers::pi)) {
    return fmt::format("max_floor_angle must be in (0, pi/2) rad (got {})", a);
  }
  auto range = [](double v, const char* name) -> std::optional<std::string> {
    if (!(v >= 0.0 && v <= max_state_magnitude)) {
      return fmt::format("{} must be finite and >= 0 (got {})", name, v);
    }
    return std::nullopt;
  };
  if (auto p = range(def.step_height, "step_height")) return p;
  if (auto p = range(def.snap_distance, "snap_distance")) return p;
  if (!(def.push_force >= 0.0 && def.push_force <= 1e100)) {
    return fmt::format("push_force must be finite and >= 0 N (got {})", def.push_force);
  }
  if (!(def.skin > 0.0 && def.skin <= max_state_magnitude)) {
    return fmt::format("skin must be finite and > 0 (got {})", def.skin);
  }
  return std::nullopt;
}

}  // namespace fixstep
