// The forest's limit rows packed for the velocity sweeps (joint_limit_rows.hpp): which worlds
// they serve, and a sweep of them against JointSolver::solve_velocity, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <optional>
#include <random>
#include <vector>

#include "joint_checks.hpp"
#include "joint_limit_rows.hpp"
#include "joint_limit_shifts.hpp"
#include "joint_solver.hpp"
#include "joint_tree.hpp"

namespace fixstep::limit_rows_test {
namespace {

using joint_checks::bits;

using detail::JointLimitRows;
using detail::JointRecord;
using detail::ShapedBody;
using detail::ShapeMotion;
using detail::ShapeState;
constexpr std::uint32_t the_world = JointRecord::none;

JointRecord limited(std::uint32_t a, std::uint32_t b, std::optional<double> lower,
                    std::optional<double> upper) {
  JointRecord j;
  j.def.type = JointType::revolute;
  j.def.lower = lower, j.def.upper = upper;
  j.a = a, j.b = b;
  j.direct = true;
  return j;
}

std::vector<std::uint32_t> every(const std::vector<JointRecord>& j) {
  std::vector<std::uint32_t> all(j.size());
  std::iota(all.begin(), all.end(), 0U);
  return all;
}

// Which joints' rows these are (a world packs its rows only when every joint with rows of its
// own is one: JointHalves' heaps check both kinds of world).
TEST(JointLimitRows, ServeRevoluteJointsOfTheForestWithoutMotorOrSpring) {
  EXPECT_TRUE(JointLimitRows::serves(limited(0, 1, -0.5, 0.5)));
  EXPECT_TRUE(JointLimitRows::serves(limited(0, 1, {}, 0.5)));
  EXPECT_TRUE(JointLimitRows::serves(limited(1, 2, {}, {}))) << "no rows of its own";
  JointRecord motor = limited(2, 3, -0.5, 0.5);
  motor.max_torque = 1.0;
  EXPECT_FALSE(JointLimitRows::serves(motor)) << "a motor";
  motor.motor_on = false;
  EXPECT_TRUE(JointLimitRows::serves(motor)) << "a motor turned off";
  JointRecord spring = limited(2, 3, -0.5, 0.5);
  spring.def.frequency = 2.0;
  EXPECT_FALSE(JointLimitRows::serves(spring)) << "a spring";
  JointRecord loop = limited(2, 3, -0.5, 0.5);
  loop.direct = false;
  EXPECT_FALSE(JointLimitRows::serves(loop)) << "a joint closing a loop (its point rows its own)";
  JointRecord prismatic = limited(2, 3, -1.0, 1.0);
  prismatic.def.type = JointType::prismatic;
  EXPECT_FALSE(JointLimitRows::serves(prismatic)) << "a prismatic joint";
}

// Ends of every kind (the world, a static body, a body that spins but neither translates nor
// is pushed, dynamic ones), each limit alone and both, angles within, at and past them, the
// impulses and velocities starting from values that include −0 (on ends first swept as B and
// as A, where the first push makes it +0): six sweeps of the packed rows and of JointSolver
// over copies of one state move every velocity, impulse and given and turned impulse, and
// report the change, to the same bits.
TEST(JointLimitRows, SweepAsJointSolverDoesBitForBit) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(0.2, 3.0), signed_unit(-2.0, 2.0);
  std::vector<ShapedBody> bodies(9);
  for (std::size_t k = 0; k < 7; ++k) {
    bodies[k].inv_mass = unit(random), bodies[k].inv_inertia = unit(random);
  }
  bodies[7].inv_mass = 0.5, bodies[7].inv_inertia = 2.0;  // turning into its limit to the world
  bodies[8].inv_mass = 1.5, bodies[8].inv_inertia = 0.8;  // an A end first: its −0 made +0 there
  bodies[4].inv_mass = bodies[4].inv_inertia = 0.0;       // static
  bodies[5].inv_mass = bodies[5].inv_inertia = 0.0;       // kinematic: spins, never pushed
  bodies[6].inv_mass = 0.0;                               // turns only
  std::vector<ShapeState> state(bodies.size());
  std::vector<ShapeMotion> velocity(bodies.size() + 1);  // and past them the zero slot
  for (std::size_t k = 0; k < 7; ++k) {
    velocity[k] = {signed_unit(random), signed_unit(random), signed_unit(random)};
  }
  velocity[7] = {0.25, -0.0, -1.5};
  velocity[8] = {-0.0, -0.0, 0.75};
  velocity[4] = {};
  velocity[5] = {0.0, 0.0, 1.5};
  velocity[1].vx = -0.0, velocity[2].vy = -0.0;
  std::vector<JointRecord> joints = {limited(the_world, 0, -0.3, {}),
                                     limited(0, 1, -0.4, 0.4),
                                     limited(1, 2, {}, 0.2),
                                     limited(2, 4, -0.1, 0.1),
                                     limited(5, 3, -0.6, 0.6),
                                     limited(3, the_world, -1.0, 1.0),
                                     limited(1, 3, {}, {}),
                                     limited(2, 6, -0.2, 0.3),
                                     limited(4, the_world, -0.5, 0.5),
                                     limited(the_world, 7, -0.3, {}),
                                     limited(8, the_world, -0.2, 0.2)};
  for (JointRecord& j : joints) {
    const double ia = j.a == the_world ? 0.0 : bodies[j.a].inv_inertia;
    const double ib = j.b == the_world ? 0.0 : bodies[j.b].inv_inertia;
    j.angle_mass = ia + ib > 0.0 ? 1.0 / (ia + ib) : 0.0;
    j.value = signed_unit(random) * 0.5;
    j.impulses.lower = unit(random) - 1.0 > 0.0 ? unit(random) : 0.0;
    j.impulses.upper = unit(random) - 1.0 > 0.0 ? unit(random) : 0.0;
    j.given_a = {-0.0, signed_unit(random)}, j.given_b = {signed_unit(random), -0.0};
    j.turned_a = signed_unit(random), j.turned_b = -0.0;
  }
  joints[1].value = 0.4, joints[3].value = -0.35;          // at a limit, and past one
  joints[9].value = -0.3, joints[9].impulses.lower = 0.0;  // at its limit, no impulse yet
  const double dt = 1.0 / 60.0;
  const std::vector<std::uint32_t> all = every(joints);
  ASSERT_TRUE(std::all_of(joints.begin(), joints.end(), JointLimitRows::serves));

  std::vector<JointRecord> packed_joints = joints;
  std::vector<ShapeMotion> packed_velocity = velocity;
  JointLimitRows rows;
  rows.pack(detail::JointTree::whole, packed_joints, all, bodies, dt,
            static_cast<std::uint32_t>(bodies.size()));
  for (int sweep = 0; sweep < 6; ++sweep) {
    detail::JointSolver solver(bodies, state, dt, velocity);
    for (JointRecord& j : joints) solver.solve_velocity(j);
    const double change = rows.sweep(detail::JointTree::whole, packed_velocity);
    EXPECT_EQ(bits(change), bits(solver.velocity_change())) << "sweep " << sweep;
    for (std::size_t k = 0; k < velocity.size(); ++k) {
      joint_checks::expect_same_motion(packed_velocity[k], velocity[k], k);
    }
    for (std::size_t k = 0; k < joints.size(); ++k) {
      const JointRecord &p = packed_joints[k], &j = joints[k];
      EXPECT_EQ(bits(p.impulses.lower), bits(j.impulses.lower)) << "joint " << k;
      EXPECT_EQ(bits(p.impulses.upper), bits(j.impulses.upper)) << "joint " << k;
      joint_checks::expect_same_given(p, j, k);
    }
  }
  // The rows did something: some limit pushed in every sweep or the test proves nothing.
  EXPECT_GT(joints[3].impulses.lower + joints[1].impulses.upper, 0.0);
  EXPECT_GT(joints[9].impulses.lower, 0.0) << "the joint to the world, A's end";
}

// The same worlds' limits on positions (a push-out sweep): each joint's correction as
// JointSolver::solve_position makes it, bit for bit, over sweeps that move the angles; a
// joint whose limit the forest holds (limit_row) left alone; one without limits adding its +0.
TEST(JointLimitShifts, CorrectAsJointSolverDoesBitForBit) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(0.2, 3.0), signed_unit(-2.0, 2.0);
  std::vector<ShapedBody> bodies(7);
  for (ShapedBody& b : bodies) b.inv_mass = unit(random), b.inv_inertia = unit(random);
  bodies[4].inv_mass = bodies[4].inv_inertia = 0.0;  // static
  bodies[6].inv_mass = 0.0;                          // turns only
  std::vector<ShapeState> state(bodies.size());
  for (ShapeState& s : state) s.x = signed_unit(random), s.y = signed_unit(random), s.a = 0.0;
  state[1].x = -0.0, state[2].y = -0.0;  // a +0 added shows (and body 3's angle is −0)
  std::vector<JointRecord> joints = {
      limited(the_world, 0, -0.3, {}), limited(0, 1, -0.4, 0.4), limited(1, 2, {}, 0.2),
      limited(2, 4, -0.1, 0.1),        limited(1, 3, {}, {}),    limited(3, the_world, -1.0, 1.0),
      limited(2, 6, -0.2, 0.3),        limited(5, 6, 0.1, 0.1)};
  for (JointRecord& j : joints) {
    const double ia = j.a == the_world ? 0.0 : bodies[j.a].inv_inertia;
    const double ib = j.b == the_world ? 0.0 : bodies[j.b].inv_inertia;
    j.angle_mass = ia + ib > 0.0 ? 1.0 / (ia + ib) : 0.0;
    j.reference = signed_unit(random) * 0.1;
  }
  joints[5].limit_row = true;  // held by the forest's solve
  // Angles past the limits: 0 below joint 0's lower, 1 past joint 1's upper, 2 past 2's, ...
  const double angles[] = {-0.9, 0.2, 0.8, -0.0, 3.1, 0.4, 1.2};
  for (std::size_t k = 0; k < state.size(); ++k) state[k].a = angles[k];
  const std::vector<std::uint32_t> all = every(joints);
  std::vector<JointRecord> packed_joints = joints;
  std::vector<ShapeState> packed_state = state;
  detail::JointLimitShifts shifts;
  shifts.pack(detail::JointTree::whole, packed_joints, all, bodies);
  bool moved_any = false;
  for (int sweep = 0; sweep < 4; ++sweep) {
    detail::JointSolver solver(bodies, state, 1.0 / 60.0);
    for (JointRecord& j : joints) solver.solve_position(j, false);
    const bool moved = shifts.correct(detail::JointTree::whole, packed_state);
    EXPECT_EQ(moved, solver.moved()) << "sweep " << sweep;
    moved_any = moved_any || moved;
    for (std::size_t k = 0; k < state.size(); ++k) {
      EXPECT_EQ(bits(packed_state[k].x), bits(state[k].x)) << "body " << k;
      EXPECT_EQ(bits(packed_state[k].y), bits(state[k].y)) << "body " << k;
      EXPECT_EQ(bits(packed_state[k].a), bits(state[k].a)) << "body " << k;
    }
  }
  EXPECT_TRUE(moved_any) << "some limit corrected or the test proves nothing";
  EXPECT_EQ(bits(state[1].x), bits(0.0)) << "a moving end's position given +0";
}

}  // namespace
}  // namespace fixstep::limit_rows_test
