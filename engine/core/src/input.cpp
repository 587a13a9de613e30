// InputSampler's per-body input: forces held as levels, impulses and velocities as events.
#include "fixstep/core/input.hpp"

#include <algorithm>

namespace fixstep {

const char* body_input_kind_name(BodyInputKind kind) {
  switch (kind) {
    case BodyInputKind::force:
      return "force";
    case BodyInputKind::impulse:
      return "impulse";
    case BodyInputKind::velocity:
      return "velocity";
    case BodyInputKind::torque:
      return "torque";
    case BodyInputKind::angular_impulse:
      return "angular_impulse";
    case BodyInputKind::angular_velocity:
      return "angular_velocity";
    case BodyInputKind::target_angle:
      return "target_angle";
  }
  return "?";
}

void InputSampler::set_force(Entity body, Vec2 force) {
  const auto it = std::find_if(forces_.begin(), forces_.end(),
                               [&](const BodyInput& f) { return f.body == body; });
  const bool zero = force.x == 0.0 && force.y == 0.0;
  if (it == forces_.end()) {
    if (!zero) forces_.push_back({body, BodyInputKind::force, force});
  } else if (zero) {
    forces_.erase(it);
  } else {
    it->value = force;
  }
}

void InputSampler::sample(std::uint64_t tick, TickInput& out) {
  out.tick = tick;
  out.push = push_;
  out.held = held_;
  out.pressed = pressed_;
  out.released = released_;
  out.pointer = pointer_;
  out.axes = axes_;
  out.drag_body = drag_body_;
  out.bodies.assign(forces_.begin(), forces_.end());
  out.bodies.insert(out.bodies.end(), events_.begin(), events_.end());
  pressed_ = released_ = 0;
  events_.clear();
}

}  // namespace fixstep
