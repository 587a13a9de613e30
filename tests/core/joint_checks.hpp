// Parts of the joints' tests (test_joint_tree.cpp, test_joint_limit_rows.cpp,
// test_joint_point_rows.cpp): a revolute joint's record, and bit-for-bit checks of the packed
// rows against their reference (a body's velocity and a joint's given and turned impulses, each
// double compared as bits, so that −0 and +0 differ).
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstddef>
#include <cstdint>

#include "joint_record.hpp"
#include "shape_lanes.hpp"

namespace fixstep::joint_checks {

/// A revolute joint of bodies a and b (JointRecord::none: the world), all else its defaults.
inline detail::JointRecord revolute(std::uint32_t a, std::uint32_t b) {
  detail::JointRecord j;
  j.def.type = JointType::revolute;
  j.a = a, j.b = b;
  return j;
}

inline std::uint64_t bits(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

inline void expect_same_motion(const detail::ShapeMotion& got, const detail::ShapeMotion& want,
                               std::size_t body) {
  EXPECT_EQ(bits(got.vx), bits(want.vx)) << "body " << body;
  EXPECT_EQ(bits(got.vy), bits(want.vy)) << "body " << body;
  EXPECT_EQ(bits(got.w), bits(want.w)) << "body " << body;
}

/// The impulses a joint gave each end (given_a, given_b, turned_a, turned_b).
inline void expect_same_given(const detail::JointRecord& got, const detail::JointRecord& want,
                              std::size_t joint) {
  EXPECT_EQ(bits(got.given_a.x), bits(want.given_a.x)) << "joint " << joint;
  EXPECT_EQ(bits(got.given_a.y), bits(want.given_a.y)) << "joint " << joint;
  EXPECT_EQ(bits(got.given_b.x), bits(want.given_b.x)) << "joint " << joint;
  EXPECT_EQ(bits(got.given_b.y), bits(want.given_b.y)) << "joint " << joint;
  EXPECT_EQ(bits(got.turned_a), bits(want.turned_a)) << "joint " << joint;
  EXPECT_EQ(bits(got.turned_b), bits(want.turned_b)) << "joint " << joint;
}

}  // namespace fixstep::joint_checks
