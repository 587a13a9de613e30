// Joints, part 2: the position sweeps (the error each rigid row has left, removed on positions
// only, Box2D v2.4's SolvePositionConstraints) and the work motors and kinematic ends did.
#include <algorithm>
#include <cmath>

#include "joint_solver.hpp"

namespace fixstep::detail {

namespace {

/// An end's pose now: its centre of mass, angle and rotation (the world's: 0, 0, identity).
struct Now {
  Vec2 c{};
  double angle = 0.0;
  Rot q{};
};
Now now(const JointSolver::End& e) {
  if (!e.s) return {};
  return {{e.s->x, e.s->y}, e.s->a, rot_of(e.s->a)};
}
/// An end's angle now (rad; the world's 0).
double angle_now(const JointSolver::End& e) {
  return e.s ? e.s->a : 0.0;
}

/// The correction of a one-sided error past a limit (Box2D v2.4's): past lower by more than
/// the slop, the error less the slop; equal limits, the whole error; each within ± most.
double limit_error(double value, double lower, double upper, bool has_lower, bool has_upper,
                   double slop, double most) {
  if (has_lower && has_upper && std::abs(upper - lower) < 2.0 * slop) {
    return std::clamp(value - lower, -most, most);
  }
  if (has_lower && value <= lower) return std::clamp(value - lower + slop, -most, 0.0);
  if (has_upper && value >= upper) return std::clamp(value - upper - slop, 0.0, most);
  return 0.0;
}

}  // namespace

[[gnu::always_inline]] inline void JointSolver::shift(End e, Vec2 p, double l) const {
  if (keep_) {
    if (e.b) {
      current_->given_b += p / dt_, current_->turned_b += l / dt_;
    } else {
      current_->given_a += p / dt_, current_->turned_a += l / dt_;
    }
  }
  if (!e.s) return;
  moved_ = moved_ || p.x != 0.0 || p.y != 0.0 || l != 0.0;
  if (e.m == 0.0 && e.i == 0.0) return;  // an end that does not move keeps its state as it is
  e.s->x += e.m * p.x, e.s->y += e.m * p.y, e.s->a += e.i * l;
  if (keep_) e.s->vx += e.m * p.x / dt_, e.s->vy += e.m * p.y / dt_, e.s->w += e.i * l / dt_;
}

void JointSolver::solve_position(JointRecord& j, bool keep) {
  keep_ = keep, current_ = &j;
  const End a = end(j.a, false), b = end(j.b, true);
  switch (j.def.type) {
    case JointType::revolute:
      correct_angle_limit(j, a, b);
      if (!j.direct) correct_point(j, a, b);
      break;
    case JointType::prismatic:
    case JointType::wheel:
      correct_axis(j, a, b);
      break;
    case JointType::weld:
      correct_weld(j, a, b);
      break;
    case JointType::distance:
      correct_distance(j, a, b);
      break;
    case JointType::motor:
      break;  // its error is its motor's to remove, within its force
  }
}

void JointSolver::shift_point(JointRecord& j, const Vec2& p, const Vec2& ra, const Vec2& rb,
                              double l) {
  keep_ = false, current_ = &j;
  const End a = end(j.a, false), b = end(j.b, true);
  shift(a, -p, -cross(ra, p) - l);
  shift(b, p, cross(rb, p) + l);
}

namespace {

/// θ_B − θ_A − θ_ref wrapped into [−π, π) (rad).
double relative_angle_of(const JointRecord& j, double angle_a, double angle_b) {
  return wrap_angle(angle_b - angle_a - j.reference);
}

}  // namespace

double JointSolver::relative_angle(const JointRecord& j) const {
  const End a = end(j.a, false), b = end(j.b, true);
  return relative_angle_of(j, angle_now(a), angle_now(b));
}

double JointSolver::limit_margin(const JointRecord& j) const {
  const double angle = relative_angle(j);
  double margin = INFINITY;
  if (j.def.lower) margin = angle - *j.def.lower;
  if (j.def.upper) margin = std::min(margin, *j.def.upper - angle);
  return margin;
}

double revolute_limit_correction(const JointRecord& j, double angle_a, double angle_b) {
  if ((!j.def.lower && !j.def.upper) || j.angle_mass == 0.0) return 0.0;
  return limit_error(relative_angle_of(j, angle_a, angle_b), j.def.lower.value_or(0.0),
                     j.def.upper.value_or(0.0), j.def.lower.has_value(), j.def.upper.has_value(),
                     joint_angular_slop, joint_max_angular_correction);
}

double JointSolver::limit_correction(const JointRecord& j) const {
  const End a = end(j.a, false), b = end(j.b, true);
  return revolute_limit_correction(j, angle_now(a), angle_now(b));
}

double JointSolver::tick_turn(const JointRecord& j) const {
  const End a = end(j.a, false), b = end(j.b, true);
  auto turn = [](const End& e) { return e.s ? std::abs(e.s->a - e.s->a0) : 0.0; };
  return std::max(turn(a), turn(b));
}

void JointSolver::kick_point(JointRecord& j, Vec2 p, Vec2 ra, Vec2 rb) {
  current_ = &j;
  const End a = end(j.a, false), b = end(j.b, true);
  const Vec2 q = p / dt_;
  const double la = -cross(ra, q), lb = cross(rb, q);
  j.given_a -= q, j.turned_a += la;
  j.given_b += q, j.turned_b += lb;
  if (a.s) a.s->vx -= a.m * q.x, a.s->vy -= a.m * q.y, a.s->w += a.i * la;
  if (b.s) b.s->vx += b.m * q.x, b.s->vy += b.m * q.y, b.s->w += b.i * lb;
}

// (A joint whose limit row is the forest's has it corrected with its point.)
void JointSolver::correct_angle_limit(JointRecord& j, const End& a, const End& b) {
  if (keep_ || j.limit_row) return;
  const double c = limit_correction(j);
  const double l = -j.angle_mass * c;
  shift(a, {}, -l), shift(b, {}, l);
}

void JointSolver::correct_point(JointRecord& j, const End& a, const End& b) {
  const Now pa = now(a), pb = now(b);
  const Vec2 ra = rotate(pa.q, j.local_a), rb = rotate(pb.q, j.local_b);
  const Vec2 c = (pb.c + rb) - (pa.c + ra) - (keep_ ? j.offset : Vec2{});
  if (keep_) {  // along the start's gradient (SHAKE's): its K and arms
    const Vec2 p = joint_solve22(j.k11, j.k12, j.k22, -c);
    shift(a, -p, -cross(j.ra, p));
    shift(b, p, cross(j.rb, p));
    return;
  }
  const PointMass k = point_mass(a.m, a.i, b.m, b.i, ra, rb);
  const Vec2 p = joint_solve22(k.k11, k.k12, k.k22, -c);
  shift(a, -p, -cross(ra, p));
  shift(b, p, cross(rb, p));
}

// A prismatic joint's perpendicular and angle errors (one 2×2 block) and a wheel's
// perpendicular one, then the limits along the axis.
void JointSolver::correct_axis(JointRecord& j, const End& a, const End& b) {
  const Now pa = now(a), pb = now(b);
  const Vec2 ra = rotate(pa.q, j.local_a), rb = rotate(pb.q, j.local_b);
  const Vec2 d = (pb.c + rb) - (pa.c + ra);
  const Vec2 axis = rotate(pa.q, j.axis_a);
  // The gradient: the start's while keeping (SHAKE's), else now's.
  const Vec2 perp = keep_ ? j.perp : joint_perp(axis);
  const double a1 = cross(d + ra, axis), a2 = cross(rb, axis);
  const double s1 = keep_ ? j.s1 : cross(d + ra, perp), s2 = keep_ ? j.s2 : cross(rb, perp);
  const double m = a.m + b.m;
  const double kp = m + a.i * s1 * s1 + b.i * s2 * s2;
  if (j.def.type == JointType::prismatic) {
    const Vec2 c{dot(joint_perp(axis), d) - (keep_ ? dot(j.perp, j.offset) : 0.0),
                 wrap_angle(pb.angle - pa.angle - j.reference) - (keep_ ? j.angle0 : 0.0)};
    double k22 = a.i + b.i;
    if (k22 == 0.0) k22 = 1.0;
    const Vec2 x = joint_solve22(kp, a.i * s1 + b.i * s2, k22, -c);
    const Vec2 p = x.x * perp;
    shift(a, -p, -(x.x * s1 + x.y));
    shift(b, p, x.x * s2 + x.y);
  } else if (kp > 0.0) {
    const double l = -(dot(joint_perp(axis), d) - (keep_ ? dot(j.perp, j.offset) : 0.0)) / kp;
    shift(a, -l * perp, -l * s1);
    shift(b, l * perp, l * s2);
  }
  const double ka = m + a.i * a1 * a1 + b.i * a2 * a2;
  if (keep_ || (!j.def.lower && !j.def.upper) || ka == 0.0) return;
  const double c = limit_error(dot(axis, d), j.def.lower.value_or(0.0), j.def.upper.value_or(0.0),
                               j.def.lower.has_value(), j.def.upper.has_value(), joint_linear_slop,
                               joint_max_linear_correction);
  const double l = -c / ka;
  shift(a, -l * axis, -l * a1);
  shift(b, l * axis, l * a2);
}

// A weld's point and angle errors as one 3×3 block (rigid), or its point alone (soft: the
// angle is the spring's).
void JointSolver::correct_weld(JointRecord& j, const End& a, const End& b) {
  if (j.def.frequency > 0.0 || a.i + b.i == 0.0) {
    correct_point(j, a, b);
    return;
  }
  const Now pa = now(a), pb = now(b);
  const Vec2 now_ra = rotate(pa.q, j.local_a), now_rb = rotate(pb.q, j.local_b);
  const Vec2 c = (pb.c + now_rb) - (pa.c + now_ra) - (keep_ ? j.offset : Vec2{});
  const double cw = wrap_angle(pb.angle - pa.angle - j.reference) - (keep_ ? j.angle0 : 0.0);
  // The gradient: the start's while keeping (SHAKE's), else now's.
  const Vec2 ra = keep_ ? j.ra : now_ra, rb = keep_ ? j.rb : now_rb;
  const auto x = joint_solve33(point_mass(a.m, a.i, b.m, b.i, ra, rb), -c.x, -c.y, -cw);
  const Vec2 p{x[0], x[1]};
  const double l = x[2];
  shift(a, -p, -(cross(ra, p) + l));
  shift(b, p, cross(rb, p) + l);
}

void JointSolver::correct_distance(JointRecord& j, const End& a, const End& b) {
  const bool rigid = !(j.def.frequency > 0.0) && !j.def.lower && !j.def.upper;
  if (!rigid && (keep_ || (!j.def.lower && !j.def.upper))) return;  // no rigid row
  const Now pa = now(a), pb = now(b);
  const Vec2 ra = rotate(pa.q, j.local_a), rb = rotate(pb.q, j.local_b);
  const Vec2 d = (pb.c + rb) - (pa.c + ra);
  const double length = std::sqrt(dot(d, d));
  if (!(length > joint_linear_slop) || (keep_ && j.axial_mass == 0.0)) return;
  const Vec2 u = keep_ ? j.axis : d / length;  // the gradient: the start's while keeping
  double c = 0.0;
  if (rigid) {
    c = std::clamp(length - (keep_ ? j.value : j.length), -joint_max_linear_correction,
                   joint_max_linear_correction);
  } else {
    c = limit_error(length, j.def.lower.value_or(0.0), j.def.upper.value_or(0.0),
                    j.def.lower.has_value(), j.def.upper.has_value(), 0.0,
                    joint_max_linear_correction);
  }
  const Vec2 arm_a = keep_ ? j.ra : ra, arm_b = keep_ ? j.rb : rb;
  const double ca = cross(arm_a, u), cb = cross(arm_b, u);
  const double k = a.m + b.m + a.i * ca * ca + b.i * cb * cb;
  if (c == 0.0 || k == 0.0) return;
  const Vec2 p = (-c / k) * u;
  shift(a, -p, -cross(arm_a, p));
  shift(b, p, cross(arm_b, p));
}

// The work the motor did on each dynamic end, and everything the joint did on a dynamic end
// whose other end is kinematic (the kinematic body's work), each impulse at the mean of its
// end's velocities before and after the solve (exact for one impulse on a free body): what
// the energy account enters as external work.
void JointSolver::account(JointRecord& j) const {
  j.work_a = j.work_b = 0.0;
  const End a = end(j.a, false), b = end(j.b, true);
  const JointImpulses& im = j.impulses;
  auto mean_velocity = [](const End& e, Vec2 before) {
    return e.s ? 0.5 * (Vec2{e.s->vx, e.s->vy} + before) : Vec2{};
  };
  const Vec2 va = mean_velocity(a, j.va0), vb = mean_velocity(b, j.vb0);
  const double wa = a.s ? 0.5 * (a.s->w + j.wa0) : 0.0, wb = b.s ? 0.5 * (b.s->w + j.wb0) : 0.0;
  const auto kinematic = [&](std::uint32_t body) {
    return body != JointRecord::none && bodies_[body].type == BodyType::kinematic;
  };
  if (kinematic(j.a) != kinematic(j.b)) {  // the kinematic end's work: all the joint gave
    if (kinematic(j.a)) j.work_b = dot(j.given_b, vb) + j.turned_b * wb;
    if (kinematic(j.b)) j.work_a = dot(j.given_a, va) + j.turned_a * wa;
    return;
  }
  switch (j.def.type) {  // the motor's: a torque about the angle, a force along the axis
    case JointType::revolute:
    case JointType::wheel:
      j.work_a = -im.motor * wa, j.work_b = im.motor * wb;
      break;
    case JointType::prismatic:
      j.work_a = -im.motor * (dot(j.axis, va) + j.a1 * wa);
      j.work_b = im.motor * (dot(j.axis, vb) + j.a2 * wb);
      break;
    case JointType::motor:  // a motor joint is all motor
      j.work_a = dot(j.given_a, va) + j.turned_a * wa;
      j.work_b = dot(j.given_b, vb) + j.turned_b * wb;
      break;
    default:
      break;
  }
}

}  // namespace fixstep::detail
