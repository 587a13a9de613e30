// A joint as the kernel keeps it (JointRecord): its definition, its geometry fixed in each
// body's frame, what a tick's input set of its motor and targets, its accumulated impulses
// (warm starting: state, copied by snapshots), and the solver's scratch of one tick.
// Internal; the kernel's side is world_joints.cpp, the solver's joint_solver.cpp.
#pragma once

#include <algorithm>
#include <cstdint>

#include "fixstep/core/joint.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep::detail {

/// The impulses a joint has accumulated over the tick (N·s, N·m·s): the warm start of the
/// next tick and the reaction it reports. Which terms a type uses:
///   linear:  the point constraint (revolute, weld, motor), (perp, 0) for prismatic and wheel
///   angular: the relative angle (prismatic, weld, motor)
///   spring, motor, lower, upper: along the axis or the angle; the limits >= 0
///   axial: a rigid distance joint's
struct JointImpulses {
  Vec2 linear{};
  double angular = 0.0;
  double spring = 0.0, motor = 0.0, lower = 0.0, upper = 0.0, axial = 0.0;
};

/// Soft constraint factors of an implicit spring for one tick (Box2D v3's b2Softness, from
/// frequency f, damping ratio ζ and step h: ω = 2π f, a1 = 2ζ + hω, a2 = hω a1, a3 = 1/(1+a2);
/// bias_rate = ω/a1, mass_scale = a2 a3, impulse_scale = a3). An impulse
/// −mass_scale·m·(Ċ + bias_rate·C) − impulse_scale·λ integrates the spring k = m ω², damper
/// b = 2 m ζ ω implicitly (Catto, "Solver2D: Soft Step", 2024).
struct Softness {
  double bias_rate = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
};

struct JointRecord {
  static constexpr std::uint32_t none = ~std::uint32_t{0};
  JointDef def;
  // Geometry in each body's frame about its centre of mass (the world: world coordinates).
  Vec2 local_a{}, local_b{};  ///< m, the anchor on A and on B
  Vec2 axis_a{};              ///< unit, in A's frame (prismatic, wheel)
  double reference = 0.0;     ///< rad, θ_b − θ_a at creation
  double length = 0.0;        ///< m, a distance joint's rest length
  // What input set (joint.hpp JointInput), starting from the definition.
  double motor_speed = 0.0, max_torque = 0.0, max_force = 0.0;
  bool motor_on = true;
  bool broken = false;
  Vec2 target{};              ///< spring target (x); a motor joint's: B's centre in A's (m)
  double target_angle = 0.0;  ///< a motor joint's target relative angle (rad)
  JointImpulses impulses;     ///< accumulated this tick, kept for the next (state)
  /// The motor's and the kinematic bodies' work on each dynamic end this tick (J), for the
  /// energy account (kinematic and motor work is external).
  double work_a = 0.0, work_b = 0.0;

  // --- the solver's scratch for one tick (joint_solver.cpp) ---------------------------------
  std::uint32_t a = none, b = none;  ///< ShapeWorld::bodies_ indices (none: the world)
  Vec2 ra{}, rb{};                   ///< lever arms from each centre of mass, m (world)
  Vec2 axis{}, perp{};               ///< unit axis and its perpendicular (world)
  Vec2 offset{};                     ///< (c_b + r_b) − (c_a + r_a) at the tick's start, m
  double value = 0.0;   ///< the angle (rad) or translation / distance (m) at the tick's start
  double angle0 = 0.0;  ///< θ_b − θ_a − θ_ref at the tick's start (rad)
  double a1 = 0.0, a2 = 0.0, s1 = 0.0, s2 = 0.0;  ///< the axis' and perp's angular arms
  double axial_mass = 0.0;                 ///< the effective mass along the axis or about the angle
  double perp_mass = 0.0;                  ///< a wheel's point-on-line effective mass
  double angle_mass = 0.0;                 ///< 1/(1/I_a + 1/I_b) (0 when neither turns)
  double k11 = 0.0, k12 = 0.0, k22 = 0.0;  ///< a 2×2 effective mass matrix K
  Softness soft{};
  /// Its point rows are the direct solve's (joint_tree.hpp), not its own sweep's.
  bool direct = false;
  /// Its limit's row is the direct solve's too, on positions only, in the rest of this tick's
  /// position sweeps (JointTree::angle_row_kept), not its own correction's.
  bool limit_row = false;
  /// Everything the joint gave each end this tick: impulse (N·s) and angular impulse about
  /// its centre of mass (N·m·s), warm start included (the kinematic ends' work).
  Vec2 given_a{}, given_b{};
  double turned_a = 0.0, turned_b = 0.0;
  /// Each end's velocity (m/s) and angular velocity (rad/s) before the joints' solve: the
  /// work of an impulse is taken at the mean of its end's velocities before and after.
  Vec2 va0{}, vb0{};
  double wa0 = 0.0, wb0 = 0.0;

  /// Whether its motor acts: on, with a torque (N·m) or force (N) bound above 0.
  [[nodiscard]] bool motor_acts() const {
    return motor_on && (max_torque > 0.0 || max_force > 0.0);
  }
  /// Whether it has velocity rows about its angle or axis: a spring, a motor or a limit
  /// (a revolute joint of the forest has none else of its own).
  [[nodiscard]] bool angle_rows() const {
    return motor_acts() || def.frequency > 0.0 || def.lower || def.upper;
  }
};

/// An impulse (a limit's or a motor's) added to its accumulated `acc` and the sum clamped to
/// [lo, hi]; returns the change of `acc`, the impulse to apply (Box2D's accumulated impulses).
inline double accumulate(double& acc, double impulse, double lo, double hi) {
  const double old = acc;
  acc = std::clamp(old + impulse, lo, hi);
  return acc - old;
}

}  // namespace fixstep::detail
