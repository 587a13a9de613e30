// World's joint calls (joint.hpp), forwarded to the kernel (world_joints.cpp), and the joints
// of a WorldDef made by World(def).
#include <fmt/format.h>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/world_def.hpp"
#include "world_state.hpp"

namespace fixstep {

namespace {

std::string joint_who(const JointDef& def, std::optional<std::size_t> index) {
  std::string who = index ? fmt::format("joint[{}]", *index) : std::string("joint");
  if (!def.name.empty()) who += fmt::format(" (\"{}\")", def.name);
  return who;
}

}  // namespace

Joint World::create_joint(const JointDef& def) {
  const Joint j = visit([&](auto& w) { return w.create_joint(def, joint_who(def, {})); });
  queries_changed();
  return j;
}
void World::destroy_joint(Joint joint) {
  visit([&](auto& w) { w.destroy_joint(joint); });
}
bool World::contains(Joint joint) const {
  return visit([&](const auto& w) { return w.contains(joint); });
}
JointDef World::joint(Joint joint) const {
  return visit([&](const auto& w) { return w.joint(joint); });
}
JointState World::joint_state(Joint joint) const {
  return visit([&](const auto& w) { return w.joint_state(joint); });
}
std::size_t World::joint_count() const {
  return visit([](const auto& w) { return w.joint_count(); });
}
std::span<const Joint> World::joints() const {
  return visit([](const auto& w) { return w.joint_handles(); });
}
std::span<const Joint> World::defined_joints() const {
  return state_->defined_joints;
}
Joint World::find_joint(std::string_view name) const {
  return visit([&](const auto& w) { return w.find_joint(name); });
}
std::span<const JointBreak> World::joints_broken() const {
  return visit([](const auto& w) { return w.joints_broken(); });
}

// The definition's joints, their bodies the ones World(def) made from def.bodies.
void World::build_joints(const WorldDef& def) {
  std::vector<Joint>& defined = state_->defined_joints;
  defined.reserve(def.joints.size());
  for (std::size_t i = 0; i < def.joints.size(); ++i) {
    JointDef j = def.joints[i];
    const std::string who = joint_who(j, i);
    for (auto [body, field] : {std::pair{&j.body_a, "body_a"}, std::pair{&j.body_b, "body_b"}}) {
      if (body->is_null()) continue;
      const std::optional<std::size_t> at = fixstep::defined_index(*body, def.bodies.size());
      if (!at) {
        throw std::invalid_argument(
            fmt::format("{}: {} {}:{} is not one of the definition's {} bodies (use the handles "
                        "WorldDef::add_body returns)",
                        who, field, body->index1, body->generation, def.bodies.size()));
      }
      *body = state_->defined[*at];
    }
    defined.push_back(visit([&](auto& w) { return w.create_joint(j, who); }));
  }
}

void World::check_joint_inputs(const TickInput& input) const {
  if (input.joints.size() > max_joint_inputs) {
    throw std::invalid_argument(fmt::format("tick {}: {} joint inputs; at most {} per tick",
                                            input.tick, input.joints.size(), max_joint_inputs));
  }
  for (const JointInput& in : input.joints) {
    const std::string who =
        fmt::format("tick {}: {} on joint {}:{}", input.tick, joint_input_kind_name(in.kind),
                    in.joint.index1, in.joint.generation);
    visit([&](const auto& w) { w.check_joint_input(in, who); });
  }
}

}  // namespace fixstep
