// The bodies a tick's joints hold, numbered densely (joint_bodies.hpp).
#include "joint_bodies.hpp"

#include "copy_bytes.hpp"

namespace fixstep::detail {

void JointBodies::build(std::span<const JointRecord> joints, std::span<const std::uint32_t> listed,
                        std::size_t bodies) {
  if (local_of_.size() < bodies) local_of_.resize(bodies);
  bodies_.clear();
  auto number = [&](std::uint32_t body) {
    if (body == JointRecord::none) return;
    const std::uint32_t k = local_of_[body];
    if (k < bodies_.size() && bodies_[k] == body) return;
    local_of_[body] = static_cast<std::uint32_t>(bodies_.size());
    bodies_.push_back(body);
  };
  for (const std::uint32_t i : listed) {
    const JointRecord& j = joints[i];
    if (j.broken) continue;
    number(j.a), number(j.b);
  }
}

std::size_t JointBodies::bytes() const {
  return copy_bytes(local_of_, bodies_);
}

}  // namespace fixstep::detail
