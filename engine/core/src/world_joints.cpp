// Joints, the kernel's side: creating and destroying them (checked), their geometry fixed in
// their bodies' frames, a tick's input to their motors and targets, the shape phase's view of
// them (JointRecord's body indices, the pairs they keep apart), breaking, and what World reads
// of them. The solver is joint_solver.cpp. Included by kernel_instances.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fixstep/core/joint.hpp"
#include "joint_solver.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {

namespace {

Vec2 unit_vector(Vec2 v) {
  return v / std::sqrt(dot(v, v));
}

}  // namespace

// The centre of mass (m) and angle (rad) of a joint's end now; the world: (0, 0), 0.
template <class Real>
std::pair<Vec2, double> detail::WorldKernel<Real>::joint_end_pose(Entity e) const {
  if (e.is_null()) return {{}, 0.0};
  const std::size_t j = bodies_.index(e);
  return {{double(x_[j]), double(y_[j])}, shape_sets_.data[shape_sets_.set.index(e)].angle};
}

template <class Real>
Joint detail::WorldKernel<Real>::create_joint(const JointDef& def, const std::string& who) {
  const IeeeFloatMode ieee;  // a state never depends on the caller's FPU mode (float_mode.hpp)
  check_joint(def, who);
  JointRecord j;
  j.def = def;
  const auto [ca, ta] = joint_end_pose(def.body_a);
  const auto [cb, tb] = joint_end_pose(def.body_b);
  const Rot qa = rot_of(ta), qb = rot_of(tb);
  const Vec2 end_b = def.anchor_b.value_or(def.anchor);
  j.local_a = unrotate(qa, def.anchor - ca);
  j.local_b = unrotate(qb, (def.type == JointType::distance ? end_b : def.anchor) - cb);
  j.axis_a = unrotate(qa, unit_vector(def.axis));
  j.reference = tb - ta;
  j.length = def.length.value_or(std::sqrt(dot(end_b - def.anchor, end_b - def.anchor)));
  j.motor_speed = def.motor_speed;
  j.max_torque = def.max_motor_torque, j.max_force = def.max_motor_force;
  j.target = {def.target, 0.0};
  if (def.type == JointType::motor) {
    j.target = unrotate(qa, cb - ca), j.target_angle = tb - ta;
  }
  Entity key;
  if (!joint_free_slots_.empty()) {
    const std::uint32_t slot = joint_free_slots_.back();
    joint_free_slots_.pop_back();
    key = Entity{slot + 1, joint_generations_[slot]};
  } else {
    joint_generations_.push_back(1);
    key = Entity{static_cast<std::uint32_t>(joint_generations_.size()), 1};
  }
  joints_.insert(key);
  joint_records_.push_back(std::move(j));
  joint_handles_.push_back(Joint{key.index1, key.generation});
  wake_joint_bodies(def);
  terms_dirty_ = true;
  return joint_handles_.back();
}

template <class Real>
void detail::WorldKernel<Real>::wake_joint_bodies(const JointDef& def) {
  if (!sleep_) return;
  for (const Entity e : {def.body_a, def.body_b}) {
    if (!e.is_null() && bodies_.contains(e)) wake(bodies_.index(e));
  }
}

template <class Real>
std::size_t detail::WorldKernel<Real>::joint_index(Joint joint) const {
  const Entity key{joint.index1, joint.generation};
  if (!joints_.contains(key)) {
    throw std::invalid_argument(
        fmt::format("joint {}:{} is null or was destroyed", joint.index1, joint.generation));
  }
  return joints_.index(key);
}

template <class Real>
void detail::WorldKernel<Real>::destroy_joint(Joint joint) {
  const std::size_t i = joint_index(joint);
  wake_joint_bodies(joint_records_[i].def);
  const Entity key{joint.index1, joint.generation};
  joints_.erase(key);
  if (i + 1 != joint_records_.size()) {  // the last one into its place (as SparseSet::erase)
    joint_records_[i] = std::move(joint_records_.back());
    joint_handles_[i] = joint_handles_.back();
  }
  joint_records_.pop_back(), joint_handles_.pop_back();
  ++joint_generations_[key.slot()];
  joint_free_slots_.push_back(key.slot());
  terms_dirty_ = true;
}

template <class Real>
void detail::WorldKernel<Real>::destroy_joints_of(Entity e) {
  for (std::size_t i = joint_records_.size(); i-- > 0;) {
    const JointDef& d = joint_records_[i].def;
    if (d.body_a == e || d.body_b == e) destroy_joint(joint_handles_[i]);
  }
}

template <class Real>
Joint detail::WorldKernel<Real>::find_joint(std::string_view name) const {
  if (name.empty()) return {};
  for (std::size_t i = 0; i < joint_records_.size(); ++i) {
    if (joint_records_[i].def.name == name) return joint_handles_[i];
  }
  return {};
}

// The shape phase's view of the joints, after rebuild_shapes: each end's index in the shape
// world (a shape set's, which comes first there in set order) and the pairs of bodies a joint
// keeps from colliding.
template <class Real>
void detail::WorldKernel<Real>::rebuild_joints() {
  joint_unpaired_.clear();
  for (JointRecord& j : joint_records_) {
    auto index = [&](Entity e) {
      return e.is_null() ? JointRecord::none : static_cast<std::uint32_t>(shape_sets_.set.index(e));
    };
    j.a = index(j.def.body_a), j.b = index(j.def.body_b);
    if (j.a == JointRecord::none || j.b == JointRecord::none || j.def.collide_connected) continue;
    joint_unpaired_.push_back(std::uint64_t{std::min(j.a, j.b)} << 32 | std::max(j.a, j.b));
  }
  std::sort(joint_unpaired_.begin(), joint_unpaired_.end());
  joint_unpaired_.erase(std::unique(joint_unpaired_.begin(), joint_unpaired_.end()),
                        joint_unpaired_.end());
  // Each body's run of pairs it is the lower end of (the pairs are sorted by it).
  joint_unpaired_start_.assign(shape_sets_.set.dense.size() + 1, 0);
  for (const std::uint64_t key : joint_unpaired_) ++joint_unpaired_start_[(key >> 32) + 1];
  for (std::size_t a = 1; a < joint_unpaired_start_.size(); ++a) {
    joint_unpaired_start_[a] += joint_unpaired_start_[a - 1];
  }
}

// A tick's input to one joint (World::check_input refused what does not apply; its bodies
// were woken with the tick's other input: wake_for_input).
template <class Real>
void detail::WorldKernel<Real>::apply_joint_input(const JointInput& in) {
  const Entity key{in.joint.index1, in.joint.generation};
  if (!joints_.contains(key)) return;
  JointRecord& j = joint_records_[joints_.index(key)];
  const double v = in.value.x;
  switch (in.kind) {
    case JointInputKind::motor_speed:
      j.motor_speed = v;
      break;
    case JointInputKind::max_motor_torque:
      j.max_torque = v;
      break;
    case JointInputKind::max_motor_force:
      j.max_force = v;
      break;
    case JointInputKind::enable_motor:
      j.motor_on = v != 0.0;
      break;
    case JointInputKind::target:
      j.target = j.def.type == JointType::motor ? in.value - local_center_or_zero(j.def.body_a)
                                                : Vec2{v, 0.0};
      break;
    case JointInputKind::target_angle:
      j.target_angle = v;
      break;
  }
}

template <class Real>
Vec2 detail::WorldKernel<Real>::local_center_or_zero(Entity e) const {
  return e.is_null() ? Vec2{} : shape_sets_.data[shape_sets_.set.index(e)].center;
}

// After the shape phase: the joints whose reaction passed their bound break (JointBreak).
template <class Real>
void detail::WorldKernel<Real>::break_joints() {
  joints_broken_.clear();
  const double dt = settings_.dt;
  // The joints the tick visited: one whose ends rest keeps its last reaction, under its bound.
  for_shape_joints([&](JointRecord& j, std::size_t i) {
    if (!j.def.break_force && !j.def.break_torque) return;
    const Vec2 force = j.given_b / dt;
    const double torque = (j.turned_b - cross(j.rb, j.given_b)) / dt;
    const bool over = (j.def.break_force && std::sqrt(dot(force, force)) > *j.def.break_force) ||
                      (j.def.break_torque && std::abs(torque) > *j.def.break_torque);
    if (!over) return;
    j.broken = true;
    j.impulses = JointImpulses{};
    j.given_a = j.given_b = Vec2{}, j.turned_a = j.turned_b = 0.0;
    joints_broken_.push_back({joint_handles_[i], force, torque});
  });
}

template <class Real>
JointState detail::WorldKernel<Real>::joint_state(Joint joint) const {
  const JointRecord& j = joint_records_[joint_index(joint)];
  JointState s;
  const auto [ca, ta] = joint_end_pose(j.def.body_a);
  const auto [cb, tb] = joint_end_pose(j.def.body_b);
  const Rot qa = rot_of(ta), qb = rot_of(tb);
  const bool motor_joint = j.def.type == JointType::motor;
  s.anchor_a = ca + rotate(qa, motor_joint ? j.target : j.local_a);
  s.anchor_b = cb + rotate(qb, motor_joint ? Vec2{} : j.local_b);
  s.axis = rotate(qa, j.axis_a);
  auto velocity = [&](Entity e, Vec2 r) {
    if (e.is_null()) return Vec2{};
    const std::size_t k = bodies_.index(e);
    const double w = shape_sets_.data[shape_sets_.set.index(e)].spin;
    return Vec2{double(vx_[k]) - w * r.y, double(vy_[k]) + w * r.x};
  };
  auto spin = [&](Entity e) {
    return e.is_null() ? 0.0 : shape_sets_.data[shape_sets_.set.index(e)].spin;
  };
  const Vec2 d = s.anchor_b - s.anchor_a;
  const Vec2 rel =
      velocity(j.def.body_b, s.anchor_b - cb) - velocity(j.def.body_a, s.anchor_a - ca);
  s.value = detail::wrap_angle(tb - ta - j.reference);
  s.speed = s.spin = spin(j.def.body_b) - spin(j.def.body_a);
  if (j.def.type == JointType::prismatic || j.def.type == JointType::wheel) {
    s.value = dot(s.axis, d), s.speed = dot(s.axis, rel);
  }
  if (j.def.type == JointType::distance) {
    s.value = std::sqrt(dot(d, d));
    s.speed = s.value > 0.0 ? dot(d, rel) / s.value : 0.0;
  }
  const double dt = settings_.dt;
  s.force = j.given_b / dt;
  s.torque = (j.turned_b - cross(j.rb, j.given_b)) / dt;
  s.motor = j.impulses.motor / dt;
  s.broken = j.broken, s.motor_enabled = j.motor_on;
  s.motor_speed = j.motor_speed, s.max_motor_torque = j.max_torque, s.max_motor_force = j.max_force;
  s.target = motor_joint ? j.target + local_center_or_zero(j.def.body_a) : j.target;
  s.target_angle = j.target_angle;
  return s;
}

}  // namespace fixstep
