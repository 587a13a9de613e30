// Joints: rigid and soft connections between two bodies with shapes (or a body and the world),
// solved with the shape contacts: hinges (revolute), sliders (prismatic), welds, distance joints
// and ropes, wheels and motor joints, with limits, motors, springs and breaking. Box2D's joints
// (b2RevoluteJointDef, b2PrismaticJointDef, ...) are the model; units are SI throughout.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "fixstep/core/entity.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

/// What a joint holds (each type's constraints, limits, motor and spring in JointDef).
enum class JointType : std::uint8_t {
  /// A hinge: the anchor stays one point of both bodies; they turn freely about it.
  revolute = 0,
  /// A slider: B moves only along the axis (fixed in A's frame) and does not turn against A.
  prismatic = 1,
  /// A weld: the anchor stays one point and the relative angle is fixed (rigid, or soft with a
  /// frequency).
  weld = 2,
  /// The distance between an anchor on A and one on B: rigid at `length`, a spring towards
  /// it, or a rope (free within [lower, upper]).
  distance = 3,
  /// A wheel: B's anchor moves only along the axis (fixed in A's frame) on a spring (the
  /// suspension), and turns freely, driven by the motor.
  wheel = 4,
  /// Drives B towards a target position and angle in A's frame, within a force and a torque:
  /// what a mouse drag or a character's carry uses.
  motor = 5,
};
inline constexpr JointType last_joint_type = JointType::motor;

/// "revolute", "prismatic", "weld", "distance", "wheel" or "motor" (the scene file's spelling).
[[nodiscard]] const char* joint_type_name(JointType type);

/// One joint: what World::create_joint and WorldDef::joints take. Bodies are handles (of live
/// bodies for create_joint; for a WorldDef, those WorldDef::add_body returned); a null handle
/// is the world (a fixed frame), and at most one of the two may be null. Both bodies, where
/// not the world, carry shapes (BodyDef::shapes). Geometry is given in world coordinates at
/// creation and kept in each body's frame from then on.
///
/// Per type (unused fields must keep their defaults; a set one is refused):
///   revolute:  anchor; lower/upper (rad, the relative angle θ_b − θ_a − θ_ref, within
///              [−π, π]); motor (rad/s, max_motor_torque N·m); spring towards `target` (rad).
///   prismatic: anchor, axis; lower/upper (m along the axis); motor (m/s, max_motor_force N);
///              spring towards `target` (m).
///   weld:      anchor; frequency/damping_ratio make it soft (0: rigid).
///   distance:  anchor (on A), anchor_b (on B); rigid at `length` (default the anchors'
///              distance) when neither a spring nor a limit is set; lower/upper (m) a range
///              (a rope: upper only); a spring towards `length` within it.
///   wheel:     anchor (on B, the wheel's hub), axis (the suspension's, in A the chassis);
///              spring along the axis towards `target` (m; frequency > 0 required);
///              lower/upper (m along the axis); motor turning B (rad/s, max_motor_torque).
///   motor:     drives B's centre of mass towards its place in A's frame at creation and its
///              angle to θ_ref, within max_motor_force (N) and max_motor_torque (N·m); the
///              target is moved by JointInput.
/// θ_ref (the reference angle) is θ_b − θ_a at creation.
struct JointDef {
  JointType type = JointType::revolute;
  Entity body_a{};  ///< null: the world
  Entity body_b{};  ///< null: the world (not both, and != body_a)
  Vec2 anchor{};    ///< m, world coordinates at creation
  /// m, world coordinates at creation: a distance joint's end on B (unset: `anchor`).
  std::optional<Vec2> anchor_b = std::nullopt;
  /// Prismatic and wheel: the axis in world coordinates at creation (any length > 0; kept as
  /// a unit vector in A's frame).
  Vec2 axis{1.0, 0.0};
  std::optional<double> length = std::nullopt;  ///< m, distance only: > 0
  /// The limits (rad for revolute, m otherwise), each optional; lower <= upper.
  std::optional<double> lower = std::nullopt, upper = std::nullopt;
  double motor_speed = 0.0;       ///< rad/s (revolute, wheel) or m/s (prismatic)
  double max_motor_torque = 0.0;  ///< N·m, >= 0; 0: no motor (revolute, wheel, motor)
  double max_motor_force = 0.0;   ///< N, >= 0; 0: no motor (prismatic, motor)
  /// The spring (Hz, > 0 turns it on; weld: soft) and its damping ratio ζ (>= 0): stiffness
  /// k = m ω² and damping b = 2 m ζ ω for ω = 2π f and m the constraint's effective mass
  /// (Box2D's parameterization), integrated implicitly (it adds no energy at any dt).
  double frequency = 0.0;
  double damping_ratio = 0.0;
  double target = 0.0;  ///< the spring's rest: rad (revolute) or m (prismatic, wheel)
  /// Breaks when the reaction force (N) or torque (N·m) of a tick exceeds it (unset: never).
  std::optional<double> break_force = std::nullopt, break_torque = std::nullopt;
  /// Whether the two bodies' shapes still collide (false: they do not).
  bool collide_connected = false;
  std::string name{};  ///< shown in messages and events; may be empty
  friend bool operator==(const JointDef&, const JointDef&) = default;
};

/// A joint's state after the last tick (World::joint_state). A joint whose two bodies are
/// asleep or static (ContactStats::joint_visited) reports the force, torque and motor of the
/// last tick that solved it.
struct JointState {
  /// Revolute: the relative angle θ_b − θ_a − θ_ref wrapped into [−π, π] (rad); prismatic and
  /// wheel: the translation along the axis (m; a wheel's suspension); distance: the anchors'
  /// distance (m); weld, motor: the relative angle (rad).
  double value = 0.0;
  /// Its rate: rad/s or m/s.
  double speed = 0.0;
  /// ω_b − ω_a (rad/s): a wheel's spin against its chassis.
  double spin = 0.0;
  Vec2 force{};         ///< N: the constraint's force on B at the anchor (−force on A)
  double torque = 0.0;  ///< N·m: the constraint's torque on B (−torque on A)
  double motor = 0.0;   ///< N·m or N: the motor's torque or force this tick
  bool broken = false;  ///< it broke (JointBreak) and no longer acts
  bool motor_enabled = true;
  double motor_speed = 0.0;                              ///< rad/s or m/s, as now set
  double max_motor_torque = 0.0, max_motor_force = 0.0;  ///< N·m, N, as now set
  Vec2 target{};  ///< spring target (x) or a motor joint's target position in A's frame (m)
  double target_angle = 0.0;  ///< a motor joint's target angle (rad)
  /// m, world coordinates: the anchor as carried by A and by B (apart by the joint's error;
  /// a distance joint's two ends), and the axis as carried by A (unit; prismatic, wheel).
  Vec2 anchor_a{}, anchor_b{}, axis{};
};

/// A joint that broke in the last tick (World::joints_broken()): its reaction exceeded
/// JointDef::break_force or break_torque. It stays (World::joint_state says broken) until
/// destroyed.
struct JointBreak {
  Joint joint{};
  Vec2 force{};         ///< N, the reaction that broke it
  double torque = 0.0;  ///< N·m
  friend constexpr bool operator==(const JointBreak&, const JointBreak&) = default;
};

/// What a tick's input may change of a joint (JointInput::kind).
enum class JointInputKind : std::uint8_t {
  motor_speed = 0,       ///< value.x: rad/s or m/s
  max_motor_torque = 1,  ///< value.x: N·m, >= 0
  max_motor_force = 2,   ///< value.x: N, >= 0
  enable_motor = 3,      ///< value.x: 1 on, 0 off
  /// value.x: a spring's target (rad or m); a motor joint's target position in A's frame (m,
  /// value.x and value.y)
  target = 4,
  target_angle = 5,  ///< value.x: a motor joint's target angle (rad)
};
inline constexpr JointInputKind last_joint_input_kind = JointInputKind::target_angle;
/// "motor_speed", "max_motor_torque", ... (a recording's and a script's spelling).
[[nodiscard]] const char* joint_input_kind_name(JointInputKind kind);

/// One joint's input for one tick (TickInput::joints), applied at the tick's start in order;
/// it wakes the joint's bodies. World::check_input refuses a stale joint, a value that is not
/// finite, a negative maximum, an enable value other than 0 or 1, and a kind the joint's type
/// does not have.
struct JointInput {
  Joint joint{};
  JointInputKind kind = JointInputKind::motor_speed;
  Vec2 value{};
  friend constexpr bool operator==(const JointInput&, const JointInput&) = default;
};

/// Most joints a world may hold (World::create_joint, WorldDef::joints).
inline constexpr std::size_t max_joints = 1'000'000;

/// Most JointInput entries one tick may carry.
inline constexpr std::size_t max_joint_inputs = 4096;

}  // namespace fixstep
