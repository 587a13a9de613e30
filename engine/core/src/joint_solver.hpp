// The joints' part of the shape phase (shape_world.hpp has the whole tick): each joint's lever
// arms and effective masses at the tick's start poses, its warm start, one velocity sweep and
// one position sweep at a time (interleaved with the contacts' by ShapeWorld), and its
// reaction at the end. Box2D v2.4's joint solver is the model (b2RevoluteJoint,
// b2PrismaticJoint, b2WeldJoint, b2DistanceJoint, b2WheelJoint, b2MotorJoint): velocity
// constraints with accumulated, clamped impulses; limits as speculative one-sided rows; motors
// as impulses bounded by the maximum torque or force times dt; springs as soft rows
// (joint_record.hpp's Softness); position errors removed on positions only (non-linear
// Gauss-Seidel), which adds no kinetic energy. A revolute joint of the forest
// (joint_tree.hpp, JointRecord::direct) leaves its point rows to the forest's direct solve.
#pragma once

#include <array>
#include <span>

#include "joint_record.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

/// The solver over one tick's states. Every impulse moves velocities only; the poses follow
/// by dt times the velocity change once the velocity solve is done (as the contacts' do:
/// semi-implicit Euler's x1 = x0 + dt v1; ShapeWorld::follow_velocities).
class JointSolver {
 public:
  /// `velocities`: each body's velocity through the velocity solve (ShapeWorld::velocity_),
  /// which prepare(), solve_velocity() and push() read and move; empty after it (the
  /// position sweeps and the account read and move state's).
  JointSolver(std::span<const ShapedBody> bodies, std::span<ShapeState> state, double dt,
              std::span<ShapeMotion> velocities = {})
      : bodies_(bodies), state_(state), velocities_(velocities), dt_(dt) {}

  /// Arms, axes, effective masses and spring factors at the tick's start poses (ShapeState
  /// x0, y0, a0, q0), then the warm start: last tick's impulses applied again.
  void prepare(JointRecord& j);
  /// One velocity sweep of the joint's rows.
  void solve_velocity(JointRecord& j);
  /// One position sweep of the joint's rigid rows at the current poses (ShapeState x, y, a).
  /// `keep`: the error the tick's motion made is removed, the start's kept, and each
  /// correction moves the velocities by itself over dt as well (a constraint impulse, as SHAKE
  /// takes it: Ryckaert, Ciccotti, Berendsen 1977), which keeps momentum, angular momentum and,
  /// over a swing, energy; otherwise: every error beyond the slop is removed on positions only
  /// (Box2D v2.4's non-linear Gauss-Seidel), which adds no kinetic energy, and the limits too.
  void solve_position(JointRecord& j, bool keep);
  /// After the velocity sweeps: the motors' and kinematic ends' work (JointRecord::work_a,
  /// work_b, J) at the tick's end velocities.
  void account(JointRecord& j) const;

  // (A joint's point row in the forest's direct solve, joint_tree.hpp: its velocity error
  // and impulse are joint_point_rows.hpp's.)
  /// A position correction p (kg·m) along the arms ra, rb (m), and l (kg·m²) about the
  /// relative angle, on positions only.
  void shift_point(JointRecord& j, const Vec2& p, const Vec2& ra, const Vec2& rb, double l = 0.0);
  /// The correction a revolute joint's limits ask of its relative angle at the poses now
  /// (rad; Box2D v2.4's: past a limit by more than the slop, the excess, within ± the largest
  /// correction; 0 within its limits or without any).
  [[nodiscard]] double limit_correction(const JointRecord& j) const;
  /// How far within its nearest limit a revolute joint's relative angle is at the poses now
  /// (rad; negative past it; infinite without limits).
  [[nodiscard]] double limit_margin(const JointRecord& j) const;
  /// The constraint impulse p/dt (N·s) at arms ra and rb (m): what a correction p (kg·m) of
  /// the tick's own error gives the velocities.
  void kick_point(JointRecord& j, Vec2 p, Vec2 ra, Vec2 rb);
  /// How far the joint's bodies have turned since the tick's start, the larger (rad).
  [[nodiscard]] double tick_turn(const JointRecord& j) const;
  /// Whether a position sweep has moved a body since this solver was made.
  [[nodiscard]] bool moved() const { return moved_; }
  /// The largest change of a body's velocity component (m/s, rad/s) that one joint's
  /// solve_velocity() made (its rows' impulses together), over those since this solver was
  /// made.
  [[nodiscard]] double velocity_change() const { return velocity_change_; }

  /// One end of a joint: inverse mass and inertia, and its state (null: the world).
  struct End {
    double m = 0.0, i = 0.0;
    ShapeState* s = nullptr;
    bool b = false;            ///< B's end (else A's)
    ShapeMotion* v = nullptr;  ///< its velocity in the velocity solve (null after it)
  };

 private:
  std::span<const ShapedBody> bodies_;
  std::span<ShapeState> state_;
  std::span<ShapeMotion> velocities_;
  double dt_;

  JointRecord* current_ = nullptr;  ///< the joint whose impulses push() adds up

  /// Defined here, so that every caller inlines it: a call in between made the caller keep its
  /// vectors on the stack in halves and load them back whole, a load that waited on the stores.
  [[nodiscard]] End end(std::uint32_t body, bool b) const {
    if (body == JointRecord::none) return {.b = b};
    const ShapedBody& d = bodies_[body];
    return {d.inv_mass, d.inv_inertia, &state_[body], b,
            velocities_.empty() ? nullptr : &velocities_[body]};
  }
  /// θ_B − θ_A − θ_ref at the poses now, wrapped into [−π, π) (rad).
  [[nodiscard]] double relative_angle(const JointRecord& j) const;
  /// An impulse p (N·s) and an angular impulse l (N·m·s) on e's velocity; added up in the
  /// current joint's given_ and turned_.
  void push(End e, Vec2 p, double l) const;
  /// A position correction: e moved by m p and turned by i l; while keep_, its velocity too by
  /// that over dt (and the impulse p/dt added up in the current joint's given_ and turned_).
  void shift(End e, Vec2 p, double l) const;
  bool keep_ = false;
  mutable bool moved_ = false;
  mutable double velocity_change_ = 0.0;

  void prepare_geometry(JointRecord& j);
  void warm_start(JointRecord& j);
  /// solve_velocity's rows, by joint type.
  void solve_rows(JointRecord& j, const End& a, const End& b);
  void solve_point(JointRecord& j, const End& a, const End& b);
  void solve_angle_rows(JointRecord& j, const End& a, const End& b, bool motor_turns);
  void solve_axis_rows(JointRecord& j, const End& a, const End& b);
  void solve_revolute(JointRecord& j, const End& a, const End& b);
  void solve_prismatic(JointRecord& j, const End& a, const End& b);
  void solve_weld(JointRecord& j, const End& a, const End& b);
  void solve_distance(JointRecord& j, const End& a, const End& b);
  void solve_wheel(JointRecord& j, const End& a, const End& b);
  void solve_motor(JointRecord& j, const End& a, const End& b);
  void correct_point(JointRecord& j, const End& a, const End& b);
  void correct_angle_limit(JointRecord& j, const End& a, const End& b);
  void correct_axis(JointRecord& j, const End& a, const End& b);
  void correct_weld(JointRecord& j, const End& a, const End& b);
  void correct_distance(JointRecord& j, const End& a, const End& b);
};

/// Box2D v2.4's position solver constants: the slop each error keeps (b2_linearSlop,
/// b2_angularSlop) and the largest correction of one sweep (b2_maxLinearCorrection,
/// b2_maxAngularCorrection).
inline constexpr double joint_linear_slop = 0.005;                                  ///< m
inline constexpr double joint_angular_slop = 2.0 / 180.0 * 3.14159265358979323846;  ///< rad
inline constexpr double joint_max_linear_correction = 0.2;                          ///< m
inline constexpr double joint_max_angular_correction = 8.0 / 180.0 * 3.14159265358979323846;
/// A turn within a tick (rad) past which the sweeps that keep give a joint's impulses along
/// the gradient at the poses now, not the start's (ShapeWorld::solve_tree_positions).
inline constexpr double fast_joint_turn = 0.2;
/// A motor joint's fraction of its position error a tick removes (b2MotorJoint's default).
inline constexpr double motor_joint_correction = 0.3;

/// JointSolver::limit_correction of a revolute joint whose ends' angles are angle_a and
/// angle_b (rad; the world's 0): the correction its limits ask of its relative angle
/// θ_B − θ_A − θ_ref wrapped into [−π, π) (rad; 0 without limits, or where nothing turns it).
[[nodiscard]] double revolute_limit_correction(const JointRecord& j, double angle_a,
                                               double angle_b);

/// v turned by +90°.
[[nodiscard]] inline Vec2 joint_perp(Vec2 v) {
  return {-v.y, v.x};
}
/// ω × r for a scalar angular velocity ω about z.
[[nodiscard]] inline Vec2 joint_spin_cross(double w, Vec2 r) {
  return {-w * r.y, w * r.x};
}
/// x of the 2×2 system [[k11, k12], [k12, k22]] x = b (0 when singular).
[[nodiscard]] inline Vec2 joint_solve22(double k11, double k12, double k22, Vec2 b) {
  double det = k11 * k22 - k12 * k12;
  if (det != 0.0) det = 1.0 / det;
  return {det * (k22 * b.x - k12 * b.y), det * (k11 * b.y - k12 * b.x)};
}

/// The effective mass matrix K of a point held by a joint with lever arms ra, rb (m) between
/// bodies of inverse masses ma, mb and inverse inertias ia, ib: the 2×2 block of the point
/// (k11, k12, k22) and the angle's row and column of the 3×3 one (k13, k23, k33).
struct PointMass {
  double k11 = 0, k12 = 0, k22 = 0, k13 = 0, k23 = 0, k33 = 0;
};
[[nodiscard]] inline PointMass point_mass(double ma, double ia, double mb, double ib, Vec2 ra,
                                          Vec2 rb) {
  const double m = ma + mb;
  return {m + ia * ra.y * ra.y + ib * rb.y * rb.y,
          -ia * ra.x * ra.y - ib * rb.x * rb.y,
          m + ia * ra.x * ra.x + ib * rb.x * rb.x,
          -ia * ra.y - ib * rb.y,
          ia * ra.x + ib * rb.x,
          ia + ib};
}
/// x of the symmetric 3×3 system K x = (bx, by, bz) by Cramer's rule (0 when singular): a
/// weld's point (x[0], x[1]) and angle (x[2]) as one block.
[[nodiscard]] inline std::array<double, 3> joint_solve33(const PointMass& k, double bx, double by,
                                                         double bz) {
  const double c0 = k.k22 * k.k33 - k.k23 * k.k23, c1 = k.k23 * k.k13 - k.k12 * k.k33,
               c2 = k.k12 * k.k23 - k.k22 * k.k13;
  double det = k.k11 * c0 + k.k12 * c1 + k.k13 * c2;
  if (det != 0.0) det = 1.0 / det;
  return {
      det * (bx * c0 + by * c1 + bz * c2),
      det * (bx * c1 + by * (k.k11 * k.k33 - k.k13 * k.k13) + bz * (k.k12 * k.k13 - k.k11 * k.k23)),
      det *
          (bx * c2 + by * (k.k12 * k.k13 - k.k11 * k.k23) + bz * (k.k11 * k.k22 - k.k12 * k.k12))};
}

}  // namespace fixstep::detail
