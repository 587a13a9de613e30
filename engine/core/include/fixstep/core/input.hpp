// The input a tick receives, and the sampler that turns a stream of window events into exactly
// one TickInput per tick, so a run can be recorded as (tick, input) pairs and replayed bit for
// bit.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fixstep/core/entity.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep {

/// fixstep's default actions: bits of TickInput::held, pressed and released. A program that
/// declares no actions of its own has the arrow keys, Enter and the mouse buttons bound to
/// them (default_input_map, fixstep/render/input_map.hpp); what they mean is the program's
/// (fixstep view pushes with the arrows and drags with the primary pointer button). A game
/// declares its own actions, any of the 32 bits (app::Settings::actions).
enum InputButton : std::uint32_t {
  button_left = 1u << 0,
  button_right = 1u << 1,
  button_up = 1u << 2,
  button_down = 1u << 3,
  button_action = 1u << 4,           ///< Enter
  button_pointer_primary = 1u << 8,  ///< left mouse button
  button_pointer_secondary = 1u << 9,
};
/// Every bit of the default actions: what a recording without rules (physics alone) may carry
/// (a recording with others is refused). A recording with rules may carry all 32 bits: they are
/// the game's actions.
inline constexpr std::uint32_t all_buttons = 0x31fu;

/// How many analogue axes a TickInput carries (TickInput::axes).
inline constexpr std::size_t max_axes = 4;

/// The drag spring: the one of Box2D's samples (their mouse joint: 5 Hz, damping ratio 0.7),
/// per unit mass, so light and heavy bodies follow the pointer alike. World::step applies it to
/// the dragged body's velocity with implicit Euler (stable at any dt; see World::step).
inline constexpr double drag_frequency = 5.0;      ///< Hz
inline constexpr double drag_damping_ratio = 0.7;  ///< ζ

/// What a BodyInput does to its body during the tick it is given to (World::step).
enum class BodyInputKind : std::uint8_t {
  /// A force, N, acting through the whole tick as a ConstantForce would (each integrator's
  /// stages see it); dynamic bodies only.
  force = 0,
  /// An impulse J, N·s, at the tick's start: Δv = J/m before the integrator runs; dynamic
  /// bodies only.
  impulse = 1,
  /// The velocity, m/s, a kinematic body moves at from this tick on (it keeps it until
  /// changed); kinematic bodies only.
  velocity = 2,
  /// A torque τ, N·m, in value.x (value.y 0), acting through the whole tick: Δω = τ dt / I
  /// over the tick, the angle stepped as the integrator steps a constant acceleration; dynamic
  /// bodies with shapes only.
  torque = 3,
  /// An angular impulse L, N·m·s, in value.x (value.y 0), at the tick's start: Δω = L / I;
  /// dynamic bodies with shapes only.
  angular_impulse = 4,
  /// The angular velocity ω, rad/s, in value.x (value.y 0), a kinematic body with shapes turns
  /// at from this tick on (it keeps it until changed).
  angular_velocity = 5,
  /// The angle θ, rad, in value.x (value.y 0), a kinematic body with shapes reaches at this
  /// tick's end: its angular velocity becomes (θ − θ_now)/dt, the shorter way round, and stays
  /// (Box2D's b2Body_SetTargetTransform): a flipper driven towards its stop, a door swung.
  target_angle = 6,
};

/// The last BodyInputKind (recordings and packets refuse larger values).
inline constexpr BodyInputKind last_body_input_kind = BodyInputKind::target_angle;

/// "force", "impulse", "velocity", "torque", "angular_impulse", "angular_velocity" or
/// "target_angle" (the spelling of scripts and recordings).
[[nodiscard]] const char* body_input_kind_name(BodyInputKind kind);

/// Input addressed to one body by its handle (so it follows the body when others are
/// destroyed), recorded and replayed with the rest of the tick's input. World::step ignores an
/// entry whose handle is stale, whose value is not finite or whose body has the wrong type
/// (World::check_input names them); a program or a script refuses them before.
struct BodyInput {
  Entity body{};
  BodyInputKind kind = BodyInputKind::force;
  /// N (force), N·s (impulse), m/s (velocity); the angular kinds' value in x (N·m, N·m·s,
  /// rad/s, rad), y 0
  Vec2 value{};
  friend constexpr bool operator==(const BodyInput&, const BodyInput&) = default;
};

/// Most BodyInput entries one tick may carry (a recording with more is refused).
inline constexpr std::size_t max_body_inputs = 4096;

struct TickInput {
  std::uint64_t tick = 0;  ///< index of the tick this input is for (0 = the first tick)
  /// An extra acceleration applied to every body during this tick (m/s², like gravity, so it
  /// moves light and heavy bodies alike); (0, 0) costs nothing. fixstep view maps the arrow
  /// keys to it.
  Vec2 push{};
  std::uint32_t held = 0;      ///< action bits (InputButton by default) down during this tick
  std::uint32_t pressed = 0;   ///< bits that went down since the previous tick's sample
  std::uint32_t released = 0;  ///< bits that went up since the previous tick's sample
  Vec2 pointer{};              ///< pointer position in world coordinates, m
  /// The program's analogue axes this tick (a stick, a trigger, or a pair of keys as -1 / +1),
  /// each finite and in [-1, 1]; levels (every tick carries the latest), 0 unless bound.
  std::array<double, max_axes> axes{};
  /// The body the pointer drags (a spring from `pointer` to it; see drag_frequency), or
  /// null_entity. A stale handle, or a body that is not dynamic, drags nothing.
  Entity drag_body = null_entity;
  /// Per-body forces, impulses and kinematic velocities of this tick, applied in this order
  /// (at most max_body_inputs). Empty costs nothing.
  std::vector<BodyInput> bodies{};
  /// Joint motors' speeds and limits, springs' and motor joints' targets of this tick, applied
  /// in order after `bodies` (at most max_joint_inputs). Empty costs nothing.
  std::vector<JointInput> joints{};
  friend bool operator==(const TickInput&, const TickInput&) = default;
};

/// Collects input events as they happen and hands each tick its TickInput (sample()). A press
/// or release between two samples is reported by exactly one tick, the next one sampled,
/// however many ticks a frame runs: with 0 ticks it waits for the next frame's first tick, with
/// many only the first sees it. Several presses of one button between two ticks read as one
/// (pressed is a set of bits, not a count); a press and release between two ticks sets both
/// bits with the button not held, so a tap is never lost. Pointer, push and drag body are
/// levels: every tick sees their latest value. Per-body input: impulses, velocities and
/// apply_force are events (the next tick sampled carries them, once); set_force is a level
/// (every tick carries it until set to zero), so a thruster held over a frame of three ticks
/// pushes in all three. A tick lists the held forces first, then the events in order.
class InputSampler {
 public:
  /// Buttons (InputButton bits) went down; a button already held is not pressed again (key
  /// repeat).
  void press(std::uint32_t buttons) {
    pressed_ |= buttons & ~held_;
    held_ |= buttons;
  }
  /// Buttons went up; releasing a button that is not held does nothing.
  void release(std::uint32_t buttons) {
    released_ |= buttons & held_;
    held_ &= ~buttons;
  }
  void set_pointer(Vec2 position) { pointer_ = position; }    ///< m, world coordinates
  void set_push(Vec2 acceleration) { push_ = acceleration; }  ///< m/s²
  /// Axis `index` (< max_axes; others are ignored) reads `value` (in [-1, 1]) in every
  /// following tick, until set again.
  void set_axis(std::size_t index, double value) {
    if (index < max_axes) axes_[index] = value == 0.0 ? 0.0 : value;  // -0 reads as 0
  }
  /// The body every following tick drags (TickInput::drag_body), or null_entity; for programs that
  /// decide the drag outside the ticks (fixstep's own use PointerDrag at the tick).
  void set_drag_body(Entity body) { drag_body_ = body; }
  /// An impulse J (N·s) on `body` in the next tick sampled (an event: once).
  void apply_impulse(Entity body, Vec2 impulse) {
    events_.push_back({body, BodyInputKind::impulse, impulse});
  }
  /// The velocity (m/s) kinematic `body` moves at from the next tick sampled on (an event: the
  /// body keeps it until changed).
  void set_velocity(Entity body, Vec2 velocity) {
    events_.push_back({body, BodyInputKind::velocity, velocity});
  }
  /// A force (N) on `body` in the next tick sampled only (an event: once; a script's `force`).
  void apply_force(Entity body, Vec2 force) {
    events_.push_back({body, BodyInputKind::force, force});
  }
  /// A force (N) on `body` in every tick sampled from now on, until set again; (0, 0) ends it
  /// (a thruster held down).
  void set_force(Entity body, Vec2 force);
  /// A torque (N·m) on `body` in the next tick sampled only (an event: once).
  void apply_torque(Entity body, double torque) {
    events_.push_back({body, BodyInputKind::torque, {torque, 0.0}});
  }
  /// An angular impulse (N·m·s) on `body` in the next tick sampled (an event: once).
  void apply_angular_impulse(Entity body, double impulse) {
    events_.push_back({body, BodyInputKind::angular_impulse, {impulse, 0.0}});
  }
  /// The angular velocity (rad/s) kinematic `body` turns at from the next tick sampled on.
  void set_angular_velocity(Entity body, double omega) {
    events_.push_back({body, BodyInputKind::angular_velocity, {omega, 0.0}});
  }
  /// The angle (rad) kinematic `body` reaches at the end of the next tick sampled.
  void set_target_angle(Entity body, double angle) {
    events_.push_back({body, BodyInputKind::target_angle, {angle, 0.0}});
  }
  [[nodiscard]] std::uint32_t held() const { return held_; }
  [[nodiscard]] Entity drag_body() const { return drag_body_; }
  [[nodiscard]] Vec2 pointer() const { return pointer_; }  ///< m

  /// The input of tick `tick`; clears the pending presses, releases and per-body events.
  TickInput sample(std::uint64_t tick) {
    TickInput in;
    sample(tick, in);
    return in;
  }
  /// sample(tick) into `out`, reusing its storage (no allocation once it has grown).
  void sample(std::uint64_t tick, TickInput& out);

 private:
  std::uint32_t held_ = 0, pressed_ = 0, released_ = 0;
  Vec2 pointer_{}, push_{};
  std::array<double, max_axes> axes_{};
  Entity drag_body_ = null_entity;
  std::vector<BodyInput> forces_;  ///< levels, in the order first set
  std::vector<BodyInput> events_;  ///< one-tick inputs, in the order given
};

}  // namespace fixstep
