// The forest's point rows packed for the velocity sweeps (joint_point_rows.hpp): each member's
// velocity error and impulse, bit for bit, against Ċ = v_b + ω_b × r_b − v_a − ω_a × r_a and
// the impulse p on B, −p on A, written out joint by joint here; the world's end, a static end
// and a kinematic one; the trees left inactive untouched; the forest by halves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "joint_bodies.hpp"
#include "joint_checks.hpp"
#include "joint_point_rows.hpp"
#include "joint_tree.hpp"
#include "shape_records.hpp"

namespace fixstep::point_rows_test {
namespace {

using joint_checks::bits;
using joint_checks::revolute;

using detail::JointBodies;
using detail::JointPointRows;
using detail::JointRecord;
using detail::JointTree;
using detail::ShapedBody;
using detail::ShapeMotion;
constexpr std::uint32_t ground_end = JointRecord::none;

/// Three trees: bodies 0–3 hang from the world (a chain 0–1–2 and a branch 1–3); 4 and 7 from
/// kinematic body 6 (B's end of its joint); 8 from static body 5.
struct Hanging {
  std::vector<ShapedBody> bodies = std::vector<ShapedBody>(9);
  std::vector<JointRecord> joints = {revolute(ground_end, 0), revolute(0, 1), revolute(1, 2),
                                     revolute(3, 1),          revolute(4, 6), revolute(4, 7),
                                     revolute(8, 5)};
  JointTree tree;
  JointBodies numbered;
  /// Each body's velocity, and past them the zero slot the world's end reads.
  std::vector<ShapeMotion> velocity = std::vector<ShapeMotion>(10);

  Hanging() {
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> unit(0.2, 3.0), signed_unit(-2.0, 2.0);
    for (ShapedBody& b : bodies) b.inv_mass = unit(random), b.inv_inertia = unit(random);
    bodies[5].inv_mass = bodies[5].inv_inertia = 0.0;  // static
    bodies[6].inv_mass = bodies[6].inv_inertia = 0.0;  // kinematic: moves, never pushed
    for (std::size_t k = 0; k < bodies.size(); ++k) {
      velocity[k] = {signed_unit(random), signed_unit(random), signed_unit(random)};
    }
    velocity[5] = {};
    velocity[6] = {0.5, -0.0, 1.5};
    velocity[1].vx = -0.0, velocity[2].w = -0.0;
    for (JointRecord& j : joints) {
      j.ra = {signed_unit(random), signed_unit(random)};
      j.rb = {signed_unit(random), -0.0};
      j.impulses.linear = {signed_unit(random), -0.0};
      j.given_a = {-0.0, signed_unit(random)}, j.given_b = {signed_unit(random), -0.0};
      j.turned_a = signed_unit(random), j.turned_b = -0.0;
    }
    std::vector<std::uint32_t> all(joints.size());
    std::iota(all.begin(), all.end(), 0U);
    numbered.build(joints, all, bodies.size());
    tree.build(joints, all, bodies, numbered);
  }
};

/// A body's velocity as the rows read it: the world's is zero.
ShapeMotion motion(const std::vector<ShapeMotion>& velocity, std::uint32_t body) {
  return body == ground_end ? ShapeMotion{} : velocity[body];
}

TEST(JointPointRows, GiveEachMembersErrorAndImpulseBitForBit) {
  Hanging f;
  ASSERT_EQ(f.tree.members().size(), f.joints.size()) << "every joint a member";
  ASSERT_EQ(f.tree.trees(), 3U);
  const auto zero = static_cast<std::uint32_t>(f.bodies.size());
  JointPointRows rows;
  rows.pack(JointTree::whole, f.joints, f.tree, f.bodies, zero);

  // The errors: Ċ at the arms, negated, and the trees over the tolerance marked.
  std::vector<Vec2> rhs(f.joints.size());
  std::vector<std::uint8_t> active(f.tree.trees(), 1);
  f.velocity[8] = {};  // the tree of 8 and static 5 within the tolerance
  const double tolerance = 1e-9;
  const double most = rows.errors(JointTree::whole, f.velocity, rhs, active, tolerance);
  double expected_most = 0.0;
  std::vector<std::uint8_t> expected_active(f.tree.trees(), 0);
  for (std::size_t k = 0; k < f.joints.size(); ++k) {
    const JointRecord& j = f.joints[f.tree.members()[k]];
    const ShapeMotion a = motion(f.velocity, j.a), b = motion(f.velocity, j.b);
    const Vec2 cdot = Vec2{b.vx, b.vy} + Vec2{-b.w * j.rb.y, b.w * j.rb.x} - Vec2{a.vx, a.vy} -
                      Vec2{-a.w * j.ra.y, a.w * j.ra.x};
    EXPECT_EQ(bits(rhs[k].x), bits(-cdot.x)) << "member " << k;
    EXPECT_EQ(bits(rhs[k].y), bits(-cdot.y)) << "member " << k;
    const double error = std::max(std::abs(cdot.x), std::abs(cdot.y));
    expected_most = std::max(expected_most, error);
    if (error > tolerance) expected_active[f.tree.tree_of(k)] = 1;
  }
  EXPECT_EQ(bits(most), bits(expected_most));
  EXPECT_EQ(active, expected_active);
  EXPECT_EQ(active[f.tree.tree_of(6)], 0) << "the tree of 8 is within the tolerance";
  EXPECT_GT(most, 0.1) << "the velocities are far from the rows' own";

  // The impulses: p on B and −p on A, on the active trees only (the world's tree left out).
  std::vector<Vec2> impulses(f.joints.size());
  for (std::size_t k = 0; k < impulses.size(); ++k) {
    impulses[k] = {0.25 * static_cast<double>(k) - 0.6, k == 2 ? -0.0 : 0.5};
  }
  std::vector<std::uint8_t> some(f.tree.trees(), 1);
  some[f.tree.tree_of(0)] = 0;
  std::vector<JointRecord> expected_joints = f.joints;
  std::vector<ShapeMotion> expected_velocity = f.velocity;
  for (std::size_t k = 0; k < f.joints.size(); ++k) {
    if (some[f.tree.tree_of(k)] == 0) continue;
    JointRecord& j = expected_joints[f.tree.members()[k]];
    const Vec2 p = impulses[k];
    j.impulses.linear += p;
    j.given_a += -p, j.turned_a += -cross(j.ra, p);
    j.given_b += p, j.turned_b += cross(j.rb, p);
    auto push = [&](std::uint32_t body, Vec2 q, double l) {
      if (body == ground_end) return;
      const ShapedBody& d = f.bodies[body];
      if (d.inv_mass == 0.0 && d.inv_inertia == 0.0) return;
      ShapeMotion& v = expected_velocity[body];
      v.vx += d.inv_mass * q.x, v.vy += d.inv_mass * q.y, v.w += d.inv_inertia * l;
    };
    push(j.a, -p, -cross(j.ra, p));
    push(j.b, p, cross(j.rb, p));
  }
  rows.apply(JointTree::whole, f.velocity, impulses, some);
  for (std::size_t body = 0; body < f.velocity.size(); ++body) {
    joint_checks::expect_same_motion(f.velocity[body], expected_velocity[body], body);
  }
  for (std::size_t k = 0; k < f.joints.size(); ++k) {
    const JointRecord &p = f.joints[k], &e = expected_joints[k];
    EXPECT_EQ(bits(p.impulses.linear.x), bits(e.impulses.linear.x)) << "joint " << k;
    EXPECT_EQ(bits(p.impulses.linear.y), bits(e.impulses.linear.y)) << "joint " << k;
    joint_checks::expect_same_given(p, e, k);
  }
  EXPECT_EQ(bits(f.velocity[6].vy), bits(-0.0)) << "the kinematic body is never pushed";
  EXPECT_EQ(bits(f.velocity[zero].w), bits(0.0)) << "nor the world's zero slot";
}

// By halves: each half's rows are its trees' members, and the two halves give every member
// what the whole forest's rows give.
TEST(JointPointRows, ByHalvesGiveWhatTheWholeForestGives) {
  Hanging whole, halves;
  const auto zero = static_cast<std::uint32_t>(whole.bodies.size());
  // Bodies by the forest's numbering: the tree from the world in half 0, the others in half 1.
  std::vector<std::uint8_t> half(halves.numbered.size(), 1);
  for (const std::uint32_t body : {0U, 1U, 2U, 3U}) half[halves.numbered.local(body)] = 0;
  halves.tree.split(half, halves.numbered);
  JointPointRows whole_rows, half_rows;
  whole_rows.pack(JointTree::whole, whole.joints, whole.tree, whole.bodies, zero);
  for (int h = 0; h < 2; ++h) half_rows.pack(h, halves.joints, halves.tree, halves.bodies, zero);
  std::vector<Vec2> rhs_whole(whole.joints.size()), rhs_halves(halves.joints.size());
  std::vector<std::uint8_t> active_whole(whole.tree.trees()), active_halves(halves.tree.trees());
  const double most =
      whole_rows.errors(JointTree::whole, whole.velocity, rhs_whole, active_whole, 1e-9);
  const double most_0 = half_rows.errors(0, halves.velocity, rhs_halves, active_halves, 1e-9);
  const double most_1 = half_rows.errors(1, halves.velocity, rhs_halves, active_halves, 1e-9);
  EXPECT_EQ(bits(std::max(most_0, most_1)), bits(most));
  EXPECT_EQ(active_halves, active_whole);
  for (std::size_t k = 0; k < rhs_whole.size(); ++k) {
    EXPECT_EQ(bits(rhs_halves[k].x), bits(rhs_whole[k].x)) << "member " << k;
    EXPECT_EQ(bits(rhs_halves[k].y), bits(rhs_whole[k].y)) << "member " << k;
  }
  whole_rows.apply(JointTree::whole, whole.velocity, rhs_whole, active_whole);
  half_rows.apply(1, halves.velocity, rhs_halves, active_halves);
  half_rows.apply(0, halves.velocity, rhs_halves, active_halves);
  for (std::size_t body = 0; body < whole.velocity.size(); ++body) {
    joint_checks::expect_same_motion(halves.velocity[body], whole.velocity[body], body);
  }
}

}  // namespace
}  // namespace fixstep::point_rows_test
