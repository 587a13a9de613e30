// The checks a joint's definition passes before World::create_joint makes it (joint.hpp says
// what each type uses), and those of a tick's joint input. Each failure names the joint and
// the field. Included by kernel_instances.cpp.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "fixstep/core/joint.hpp"
#include "value_checks.hpp"
#include "world_kernel.hpp"

namespace fixstep {

namespace {

bool uses(JointType t, std::initializer_list<JointType> types) {
  for (const JointType u : types) {
    if (t == u) return true;
  }
  return false;
}

/// The first field `def` sets that its type does not use, or nullptr.
const char* unused_field(const JointDef& def) {
  using T = JointType;
  const T t = def.type;
  if (def.anchor_b && t != T::distance) return "anchor_b";
  if (def.axis != Vec2{1.0, 0.0} && !uses(t, {T::prismatic, T::wheel})) return "axis";
  if (def.length && t != T::distance) return "length";
  const bool limits = uses(t, {T::revolute, T::prismatic, T::distance, T::wheel});
  if (def.lower && !limits) return "lower";
  if (def.upper && !limits) return "upper";
  if (def.motor_speed != 0.0 && !uses(t, {T::revolute, T::prismatic, T::wheel})) {
    return "motor_speed";
  }
  if (def.max_motor_torque != 0.0 && !uses(t, {T::revolute, T::wheel, T::motor})) {
    return "max_motor_torque";
  }
  if (def.max_motor_force != 0.0 && !uses(t, {T::prismatic, T::motor})) return "max_motor_force";
  if (def.frequency != 0.0 && t == T::motor) return "frequency";
  if (def.damping_ratio != 0.0 && t == T::motor) return "damping_ratio";
  if (def.target != 0.0 && !uses(t, {T::revolute, T::prismatic, T::wheel})) return "target";
  return nullptr;
}

}  // namespace

template <class Real>
void detail::WorldKernel<Real>::check_joint_body(Entity e, const std::string& who,
                                                 const char* field) const {
  if (e.is_null()) return;
  if (!bodies_.contains(e)) {
    throw std::invalid_argument(fmt::format("{}: {} is a destroyed body", who, field));
  }
  if (!shape_sets_.set.contains(e)) {
    throw std::invalid_argument(
        fmt::format("{}: {} (\"{}\") has no shapes: a joint's bodies carry shapes", who, field,
                    names_[bodies_.index(e)]));
  }
}

template <class Real>
void detail::WorldKernel<Real>::check_joint(const JointDef& def, const std::string& who) const {
  if (static_cast<unsigned>(def.type) > static_cast<unsigned>(last_joint_type)) {
    throw std::invalid_argument(fmt::format("{}: type is not a joint type", who));
  }
  if (joint_records_.size() >= max_joints) {
    throw std::invalid_argument(
        fmt::format("{}: more than max_joints = {} joints", who, max_joints));
  }
  if (def.body_a.is_null() && def.body_b.is_null()) {
    throw std::invalid_argument(fmt::format("{}: body_a and body_b are both the world", who));
  }
  if (def.body_a == def.body_b) {
    throw std::invalid_argument(fmt::format("{}: body_b is body_a: a joint joins two bodies", who));
  }
  check_joint_body(def.body_a, who, "body_a");
  check_joint_body(def.body_b, who, "body_b");
  if (const char* field = unused_field(def)) {
    throw std::invalid_argument(
        fmt::format("{}: a {} joint has no {}", who, joint_type_name(def.type), field));
  }
  check_vec<Real>(def.anchor, who, "anchor");
  if (def.anchor_b) check_vec<Real>(*def.anchor_b, who, "anchor_b");
  check_vec<Real>(def.axis, who, "axis");
  if (!(def.axis.x * def.axis.x + def.axis.y * def.axis.y > 1e-24)) {
    throw std::invalid_argument(
        fmt::format("{}: axis must not be zero (got ({}, {}))", who, def.axis.x, def.axis.y));
  }
  auto state = [&](std::optional<double> v, const char* field) {
    if (v) check_value<Real>(*v, within_state(*v), who, field, "finite with |value| <= 1e12");
  };
  auto nonnegative = [&](std::optional<double> v, const char* field, const char* unit) {
    if (!v) return;
    check_value<Real>(*v, nonnegative_coefficient(*v), who, field,
                      fmt::format("in [0, 1e100] {}", unit).c_str());
  };
  state(def.lower, "lower"), state(def.upper, "upper");
  state(def.motor_speed, "motor_speed"), state(def.target, "target");
  nonnegative(def.max_motor_torque, "max_motor_torque", "N·m");
  nonnegative(def.max_motor_force, "max_motor_force", "N");
  nonnegative(def.frequency, "frequency", "Hz");
  nonnegative(def.damping_ratio, "damping_ratio", "");
  nonnegative(def.break_force, "break_force", "N");
  nonnegative(def.break_torque, "break_torque", "N·m");
  check_joint_ranges(def, who);
}

template <class Real>
void detail::WorldKernel<Real>::check_joint_ranges(const JointDef& def,
                                                   const std::string& who) const {
  if (def.lower && def.upper && *def.lower > *def.upper) {
    throw std::invalid_argument(
        fmt::format("{}: lower ({}) is above upper ({})", who, *def.lower, *def.upper));
  }
  const double pi = std::numbers::pi;
  for (const auto& [v, field] : {std::pair{def.lower, "lower"}, std::pair{def.upper, "upper"}}) {
    if (!v) continue;
    if (def.type == JointType::revolute && std::abs(*v) > pi) {
      throw std::invalid_argument(
          fmt::format("{}: {} must be in [-pi, pi] rad (got {})", who, field, *v));
    }
    if (def.type == JointType::distance && *v < 0.0) {
      throw std::invalid_argument(fmt::format("{}: {} must be >= 0 m (got {})", who, field, *v));
    }
  }
  if (def.type == JointType::wheel && !(def.frequency > 0.0)) {
    throw std::invalid_argument(
        fmt::format("{}: a wheel joint's suspension needs frequency > 0 Hz", who));
  }
  if (def.type != JointType::distance) return;
  const Vec2 d = def.anchor_b.value_or(def.anchor) - def.anchor;
  const double length = def.length.value_or(std::sqrt(d.x * d.x + d.y * d.y));
  const bool needs_length = def.frequency > 0.0 || (!def.lower && !def.upper);
  if (def.length || needs_length) {
    check_value<Real>(length, within_state(length) && length > 0.0, who, "length",
                      "> 0 m (the anchors' distance when unset)");
  }
}

template <class Real>
void detail::WorldKernel<Real>::check_joint_input(const JointInput& in,
                                                  const std::string& who) const {
  const Entity key{in.joint.index1, in.joint.generation};
  if (!joints_.contains(key)) {
    throw std::invalid_argument(fmt::format("{}: joint {}:{} is null or was destroyed", who,
                                            in.joint.index1, in.joint.generation));
  }
  if (static_cast<unsigned>(in.kind) > static_cast<unsigned>(last_joint_input_kind)) {
    throw std::invalid_argument(fmt::format("{}: kind is not a joint input kind", who));
  }
  const JointRecord& j = joint_records_[joints_.index(key)];
  const char* kind = joint_input_kind_name(in.kind);
  check_vec<Real>(in.value, who, kind);
  using K = JointInputKind;
  using T = JointType;
  const T t = j.def.type;
  bool fits = true;
  switch (in.kind) {
    case K::motor_speed:
      fits = uses(t, {T::revolute, T::prismatic, T::wheel});
      break;
    case K::max_motor_torque:
      fits = uses(t, {T::revolute, T::wheel, T::motor});
      break;
    case K::max_motor_force:
      fits = uses(t, {T::prismatic, T::motor});
      break;
    case K::enable_motor:
      fits = uses(t, {T::revolute, T::prismatic, T::wheel, T::motor});
      break;
    case K::target:
      fits = t != T::weld && t != T::distance;
      break;
    case K::target_angle:
      fits = t == T::motor;
      break;
  }
  if (!fits) {
    throw std::invalid_argument(
        fmt::format("{}: a {} joint takes no {} input", who, joint_type_name(t), kind));
  }
  const double v = in.value.x;
  const bool scalar = !(in.kind == K::target && t == T::motor);
  if (scalar && in.value.y != 0.0) {
    throw std::invalid_argument(fmt::format("{}: {} takes value.x only (value.y 0)", who, kind));
  }
  if ((in.kind == K::max_motor_torque || in.kind == K::max_motor_force) && v < 0.0) {
    throw std::invalid_argument(fmt::format("{}: {} must be >= 0 (got {})", who, kind, v));
  }
  if (in.kind == K::enable_motor && v != 0.0 && v != 1.0) {
    throw std::invalid_argument(fmt::format("{}: enable_motor must be 0 or 1 (got {})", who, v));
  }
}

}  // namespace fixstep
