// Joints, part 1: each joint's geometry at the tick's start, its warm start and its velocity
// rows (joint_solver.hpp says what the solver is and whose it follows).
#include "joint_solver.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fixstep::detail {

namespace {

double inverse_or_zero(double k) {
  return k > 0.0 ? 1.0 / k : 0.0;
}

Softness softness(double frequency, double damping_ratio, double h) {
  if (!(frequency > 0.0)) return {};
  const double omega = 2.0 * std::numbers::pi * frequency;
  const double a1 = 2.0 * damping_ratio + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

Vec2 velocity(const JointSolver::End& e) {
  if (e.v) return {e.v->vx, e.v->vy};
  return e.s ? Vec2{e.s->vx, e.s->vy} : Vec2{};
}
double spin(const JointSolver::End& e) {
  if (e.v) return e.v->w;
  return e.s ? e.s->w : 0.0;
}

}  // namespace

[[gnu::always_inline]] inline void JointSolver::push(End e, Vec2 p, double l) const {
  if (e.b) {
    current_->given_b += p, current_->turned_b += l;
  } else {
    current_->given_a += p, current_->turned_a += l;
  }
  if (!e.s || (e.m == 0.0 && e.i == 0.0)) return;
  ShapeMotion& v = *e.v;  // (pushes are the velocity solve's)
  v.vx += e.m * p.x, v.vy += e.m * p.y, v.w += e.i * l;
}

void JointSolver::prepare_geometry(JointRecord& j) {
  const End a = end(j.a, false), b = end(j.b, true);
  const Rot qa = a.s ? a.s->q0 : Rot{}, qb = b.s ? b.s->q0 : Rot{};
  const Vec2 ca = a.s ? Vec2{a.s->x0, a.s->y0} : Vec2{}, cb = b.s ? Vec2{b.s->x0, b.s->y0} : Vec2{};
  const double angle = (b.s ? b.s->a0 : 0.0) - (a.s ? a.s->a0 : 0.0);
  const bool motor_joint = j.def.type == JointType::motor;
  j.ra = rotate(qa, motor_joint ? j.target : j.local_a);
  j.rb = motor_joint ? Vec2{} : rotate(qb, j.local_b);
  j.offset = (cb + j.rb) - (ca + j.ra);
  j.angle_mass = inverse_or_zero(a.i + b.i);
  j.value = wrap_angle(angle - (motor_joint ? j.target_angle : j.reference));
  j.angle0 = j.value;
  const double m = a.m + b.m;
  const PointMass k = point_mass(a.m, a.i, b.m, b.i, j.ra, j.rb);
  j.k11 = k.k11, j.k12 = k.k12, j.k22 = k.k22;
  j.axial_mass = j.angle_mass;
  switch (j.def.type) {
    case JointType::prismatic:
    case JointType::wheel: {
      j.axis = rotate(qa, j.axis_a), j.perp = joint_perp(j.axis);
      const Vec2 arm = j.offset + j.ra;
      j.a1 = cross(arm, j.axis), j.a2 = cross(j.rb, j.axis);
      j.s1 = cross(arm, j.perp), j.s2 = cross(j.rb, j.perp);
      j.axial_mass = inverse_or_zero(m + a.i * j.a1 * j.a1 + b.i * j.a2 * j.a2);
      j.value = dot(j.axis, j.offset);
      const double kp = m + a.i * j.s1 * j.s1 + b.i * j.s2 * j.s2;
      j.perp_mass = inverse_or_zero(kp);
      j.k11 = kp, j.k12 = a.i * j.s1 + b.i * j.s2, j.k22 = a.i + b.i;
      if (j.k22 == 0.0) j.k22 = 1.0;  // neither turns: the angle row is void
      break;
    }
    case JointType::distance: {
      const double length = std::sqrt(dot(j.offset, j.offset));
      j.axis = length > joint_linear_slop ? j.offset / length : Vec2{};
      j.a1 = cross(j.ra, j.axis), j.a2 = cross(j.rb, j.axis);
      j.axial_mass = inverse_or_zero(m + a.i * j.a1 * j.a1 + b.i * j.a2 * j.a2);
      j.value = length;
      break;
    }
    default:
      break;
  }
  j.soft = softness(j.def.frequency, j.def.damping_ratio, dt_);
}

void JointSolver::prepare(JointRecord& j) {
  current_ = &j;
  j.given_a = j.given_b = Vec2{}, j.turned_a = j.turned_b = 0.0;
  j.limit_row = false;
  const End a = end(j.a, false), b = end(j.b, true);
  j.va0 = velocity(a), j.vb0 = velocity(b), j.wa0 = spin(a), j.wb0 = spin(b);
  prepare_geometry(j);
  JointImpulses& im = j.impulses;
  const bool motor = j.motor_on && (j.max_torque > 0.0 || j.max_force > 0.0);
  if (!motor) im.motor = 0.0;
  if (!j.def.lower) im.lower = 0.0;
  if (!j.def.upper) im.upper = 0.0;
  if (!(j.def.frequency > 0.0)) im.spring = 0.0;
  warm_start(j);
}

void JointSolver::warm_start(JointRecord& j) {
  const End a = end(j.a, false), b = end(j.b, true);
  const JointImpulses& im = j.impulses;
  switch (j.def.type) {
    case JointType::revolute:
    case JointType::weld:
    case JointType::motor: {
      const double l = im.angular + im.motor + im.spring + im.lower - im.upper;
      push(a, -im.linear, -(cross(j.ra, im.linear) + l));
      push(b, im.linear, cross(j.rb, im.linear) + l);
      break;
    }
    case JointType::prismatic:
    case JointType::wheel: {
      const double axial =
          im.spring + im.lower - im.upper + (j.def.type == JointType::prismatic ? im.motor : 0.0);
      const double turn = im.angular + (j.def.type == JointType::wheel ? im.motor : 0.0);
      const Vec2 p = im.linear.x * j.perp + axial * j.axis;
      push(a, -p, -(im.linear.x * j.s1 + axial * j.a1 + turn));
      push(b, p, im.linear.x * j.s2 + axial * j.a2 + turn);
      break;
    }
    case JointType::distance: {
      const Vec2 p = (im.axial + im.spring + im.lower - im.upper) * j.axis;
      push(a, -p, -cross(j.ra, p));
      push(b, p, cross(j.rb, p));
      break;
    }
  }
}

void JointSolver::solve_velocity(JointRecord& j) {
  current_ = &j;
  const End a = end(j.a, false), b = end(j.b, true);
  const Vec2 given_a = j.given_a, given_b = j.given_b;  // what push() adds to, before
  const double turned_a = j.turned_a, turned_b = j.turned_b;
  solve_rows(j, a, b);
  // The ends' velocity changes from the rows' impulses together (a static end's mass is 0).
  auto most = [](const End& e, Vec2 p, double l) {
    return std::max({std::abs(e.m * p.x), std::abs(e.m * p.y), std::abs(e.i * l)});
  };
  velocity_change_ =
      std::max({velocity_change_, most(a, j.given_a - given_a, j.turned_a - turned_a),
                most(b, j.given_b - given_b, j.turned_b - turned_b)});
}

void JointSolver::solve_rows(JointRecord& j, const End& a, const End& b) {
  switch (j.def.type) {
    case JointType::revolute:
      solve_revolute(j, a, b);
      break;
    case JointType::prismatic:
      solve_prismatic(j, a, b);
      break;
    case JointType::weld:
      solve_weld(j, a, b);
      break;
    case JointType::distance:
      solve_distance(j, a, b);
      break;
    case JointType::wheel:
      solve_wheel(j, a, b);
      break;
    case JointType::motor:
      solve_motor(j, a, b);
      break;
  }
}

// The anchor kept one point of both bodies (revolute, and a soft weld's point): the 2×2 K
// from the arms, Ċ = v_b + ω_b × r_b − v_a − ω_a × r_a driven to zero.
void JointSolver::solve_point(JointRecord& j, const End& a, const End& b) {
  const Vec2 cdot =
      velocity(b) + joint_spin_cross(spin(b), j.rb) - velocity(a) - joint_spin_cross(spin(a), j.ra);
  const Vec2 p = joint_solve22(j.k11, j.k12, j.k22, -cdot);
  j.impulses.linear += p;
  push(a, -p, -cross(j.ra, p));
  push(b, p, cross(j.rb, p));
}

// The rows about the relative angle: the spring towards its target, the motor, and the lower
// and upper limits (speculative: a gap of C may close within the tick, C/dt).
void JointSolver::solve_angle_rows(JointRecord& j, const End& a, const End& b, bool motor_turns) {
  JointImpulses& im = j.impulses;
  auto turn = [&](double l) { push(a, {}, -l), push(b, {}, l); };
  const double mass = j.angle_mass;
  if (mass == 0.0) return;
  if (j.def.frequency > 0.0 && j.def.type == JointType::revolute) {
    const double c = wrap_angle(j.value - j.target.x);
    const double cdot = spin(b) - spin(a);
    const double l = -j.soft.mass_scale * mass * (cdot + j.soft.bias_rate * c) -
                     j.soft.impulse_scale * im.spring;
    im.spring += l;
    turn(l);
  }
  if (motor_turns && j.motor_on && j.max_torque > 0.0) {
    const double bound = j.max_torque * dt_;
    const double l = -mass * (spin(b) - spin(a) - j.motor_speed);
    turn(accumulate(im.motor, l, -bound, bound));
  }
  if (j.def.type != JointType::revolute) return;
  if (j.def.lower) {
    const double c = j.value - *j.def.lower;
    const double l = -mass * (spin(b) - spin(a) + std::max(c, 0.0) / dt_);
    turn(accumulate(im.lower, l, 0.0, INFINITY));
  }
  if (j.def.upper) {
    const double c = *j.def.upper - j.value;
    const double l = -mass * (spin(a) - spin(b) + std::max(c, 0.0) / dt_);
    turn(-accumulate(im.upper, l, 0.0, INFINITY));
  }
}

void JointSolver::solve_revolute(JointRecord& j, const End& a, const End& b) {
  solve_angle_rows(j, a, b, true);
  if (!j.direct) solve_point(j, a, b);
}

// The rows along the axis of a prismatic or wheel joint: spring, motor (prismatic), limits.
void JointSolver::solve_axis_rows(JointRecord& j, const End& a, const End& b) {
  JointImpulses& im = j.impulses;
  auto axial_speed = [&] {
    return dot(j.axis, velocity(b) - velocity(a)) + j.a2 * spin(b) - j.a1 * spin(a);
  };
  auto along = [&](double l) {
    const Vec2 p = l * j.axis;
    push(a, -p, -l * j.a1), push(b, p, l * j.a2);
  };
  const double mass = j.axial_mass;
  if (mass == 0.0) return;
  if (j.def.frequency > 0.0) {
    const double c = j.value - j.target.x;
    const double l = -j.soft.mass_scale * mass * (axial_speed() + j.soft.bias_rate * c) -
                     j.soft.impulse_scale * im.spring;
    im.spring += l;
    along(l);
  }
  if (j.def.type == JointType::prismatic && j.motor_on && j.max_force > 0.0) {
    const double bound = j.max_force * dt_;
    along(accumulate(im.motor, mass * (j.motor_speed - axial_speed()), -bound, bound));
  }
  if (j.def.lower) {
    const double c = j.value - *j.def.lower;
    const double l = -mass * (axial_speed() + std::max(c, 0.0) / dt_);
    along(accumulate(im.lower, l, 0.0, INFINITY));
  }
  if (j.def.upper) {
    const double c = *j.def.upper - j.value;
    const double l = -mass * (-axial_speed() + std::max(c, 0.0) / dt_);
    along(-accumulate(im.upper, l, 0.0, INFINITY));
  }
}

// A slider: the axis rows, then B kept on the axis and unturned against A as one 2×2 block.
void JointSolver::solve_prismatic(JointRecord& j, const End& a, const End& b) {
  solve_axis_rows(j, a, b);
  const Vec2 cdot{dot(j.perp, velocity(b) - velocity(a)) + j.s2 * spin(b) - j.s1 * spin(a),
                  spin(b) - spin(a)};
  const Vec2 d = joint_solve22(j.k11, j.k12, j.k22, -cdot);
  j.impulses.linear.x += d.x, j.impulses.angular += d.y;
  const Vec2 p = d.x * j.perp;
  push(a, -p, -(d.x * j.s1 + d.y));
  push(b, p, d.x * j.s2 + d.y);
}

// A weld: rigid, the point and the angle as one 3×3 block (exact for two bodies in one
// sweep); soft, the angle as a spring and then the point.
void JointSolver::solve_weld(JointRecord& j, const End& a, const End& b) {
  JointImpulses& im = j.impulses;
  if (j.def.frequency > 0.0) {
    if (j.angle_mass > 0.0) {
      const double l =
          -j.soft.mass_scale * j.angle_mass * (spin(b) - spin(a) + j.soft.bias_rate * j.value) -
          j.soft.impulse_scale * im.angular;
      im.angular += l;
      push(a, {}, -l), push(b, {}, l);
    }
    solve_point(j, a, b);
    return;
  }
  const Vec2 cdot =
      velocity(b) + joint_spin_cross(spin(b), j.rb) - velocity(a) - joint_spin_cross(spin(a), j.ra);
  const double cw = spin(b) - spin(a);
  Vec2 p;
  double l = 0.0;
  if (a.i + b.i == 0.0) {
    p = joint_solve22(j.k11, j.k12, j.k22, -cdot);
  } else {
    const auto x = joint_solve33(point_mass(a.m, a.i, b.m, b.i, j.ra, j.rb), -cdot.x, -cdot.y, -cw);
    p = {x[0], x[1]}, l = x[2];
  }
  im.linear += p, im.angular += l;
  push(a, -p, -(cross(j.ra, p) + l));
  push(b, p, cross(j.rb, p) + l);
}

// A distance joint: rigid at its length, or a spring towards it within its range (a rope:
// only an upper limit).
void JointSolver::solve_distance(JointRecord& j, const End& a, const End& b) {
  JointImpulses& im = j.impulses;
  auto axial_speed = [&] {
    const Vec2 vb = velocity(b) + joint_spin_cross(spin(b), j.rb);
    const Vec2 va = velocity(a) + joint_spin_cross(spin(a), j.ra);
    return dot(j.axis, vb - va);
  };
  auto along = [&](double l) {
    const Vec2 p = l * j.axis;
    push(a, -p, -cross(j.ra, p)), push(b, p, cross(j.rb, p));
  };
  const double mass = j.axial_mass;
  if (mass == 0.0) return;
  const bool rigid = !(j.def.frequency > 0.0) && !j.def.lower && !j.def.upper;
  if (rigid) {
    const double l = -mass * axial_speed();
    im.axial += l;
    along(l);
    return;
  }
  if (j.def.frequency > 0.0) {
    const double c = j.value - j.length;
    const double l = -j.soft.mass_scale * mass * (axial_speed() + j.soft.bias_rate * c) -
                     j.soft.impulse_scale * im.spring;
    im.spring += l;
    along(l);
  }
  if (j.def.lower) {
    const double c = j.value - *j.def.lower;
    along(accumulate(im.lower, -mass * (axial_speed() + std::max(c, 0.0) / dt_), 0.0, INFINITY));
  }
  if (j.def.upper) {
    const double c = *j.def.upper - j.value;
    along(-accumulate(im.upper, -mass * (-axial_speed() + std::max(c, 0.0) / dt_), 0.0, INFINITY));
  }
}

// A wheel: the suspension's rows along the axis, the motor turning B, B's anchor kept on the
// axis (one row along its perpendicular).
void JointSolver::solve_wheel(JointRecord& j, const End& a, const End& b) {
  solve_axis_rows(j, a, b);
  solve_angle_rows(j, a, b, true);
  if (j.perp_mass == 0.0) return;
  const double cdot = dot(j.perp, velocity(b) - velocity(a)) + j.s2 * spin(b) - j.s1 * spin(a);
  const double l = -j.perp_mass * cdot;
  j.impulses.linear.x += l;
  const Vec2 p = l * j.perp;
  push(a, -p, -l * j.s1);
  push(b, p, l * j.s2);
}

// A motor joint: B's angle and centre driven towards their targets in A's frame, the error
// removed at motor_joint_correction of itself a tick, within the maximum torque and force.
void JointSolver::solve_motor(JointRecord& j, const End& a, const End& b) {
  JointImpulses& im = j.impulses;
  const double correction = motor_joint_correction / dt_;
  if (j.angle_mass > 0.0) {
    const double bound = j.motor_on ? j.max_torque * dt_ : 0.0;
    const double cdot = spin(b) - spin(a) + correction * j.value;
    const double l = accumulate(im.angular, -j.angle_mass * cdot, -bound, bound);
    push(a, {}, -l), push(b, {}, l);
  }
  const Vec2 cdot = velocity(b) + joint_spin_cross(spin(b), j.rb) - velocity(a) -
                    joint_spin_cross(spin(a), j.ra) + correction * j.offset;
  const Vec2 old = im.linear;
  im.linear += joint_solve22(j.k11, j.k12, j.k22, -cdot);
  const double bound = j.motor_on ? j.max_force * dt_ : 0.0;
  const double size2 = dot(im.linear, im.linear);
  if (size2 > bound * bound) im.linear = (bound / std::sqrt(size2)) * im.linear;
  const Vec2 p = im.linear - old;
  push(a, -p, -cross(j.ra, p));
  push(b, p, cross(j.rb, p));
}

}  // namespace fixstep::detail
