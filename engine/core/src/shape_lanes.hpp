// The shape contact solver's manifolds four at a time (shape_sweep.cpp runs them): four
// two-point manifolds of one colour, which share no moving body, solved side by side in the
// lanes of a vector, each lane doing exactly the arithmetic shape_rows.hpp does for one
// manifold (friction of each point, then the two normal impulses as a block), in the same
// order. A vector here is GCC's generic vector of four doubles, which GCC and Clang lower to
// whatever the target has (two SSE2 registers, one AVX2 register, NEON pairs, scalars on
// wasm32): element-wise IEEE-754 operations, each correctly rounded, never fused
// (-ffp-contract=off), so every lane's result is the bits of the scalar row kernels on any
// target and vector width. A comparison gives a mask of all ones or zeros per lane, and a
// choice between two results is made by the mask with bitwise operations (no branch).
#pragma once

#include <array>
#include <cstdint>

#include "lane_types.hpp"

namespace fixstep::detail {

/// A body's velocity (m/s, m/s, rad/s) as the velocity solve carries it through a manifold's
/// rows; zero for a plane or segment.
struct ShapeMotion {
  double vx = 0.0, vy = 0.0, w = 0.0;
};

}  // namespace fixstep::detail

namespace fixstep::detail::shape_lanes {

/// For tests: whether the velocity sweeps solve manifolds four at a time (true, the default,
/// for every thread) or every one alone through shape_rows.hpp, the lanes' reference.
void set_lanes_enabled(bool on);
[[nodiscard]] bool lanes_enabled();

using four_lanes::Lane;
using four_lanes::Mask;
using four_lanes::width;

/// One manifold point's rows in each lane (ShapeSolveRow's fields of a point).
struct LanePoint {
  Lane rna{}, rnb{}, rta{}, rtb{}, kn{}, kt{}, normal_mass{}, tangent_mass{}, target{}, ln{}, lt{};
};

/// A lane's write index for a body it must not write.
inline constexpr std::uint32_t no_write = ~std::uint32_t{0};

/// Four manifolds' bodies, lane by lane: what their points share. A lane without a manifold
/// (the last group of a colour) has every mass 0, reads the zero velocity slot and writes
/// nothing.
struct LaneBodies {
  /// velocity_ indices: where a lane reads each body's velocity and where it writes it back
  /// (no_write for a body that does not move, a plane's or a static, kinematic or asleep
  /// body's: its velocity is unchanged, and lanes on two threads may read it).
  std::array<std::uint32_t, width> read_a{}, read_b{}, write_a{}, write_b{};
  std::array<std::uint32_t, width> row{};  ///< the manifold's first row in solve_ (padding: ~0)
  Lane nx{}, ny{}, ma{}, ia{}, mb{}, ib{}, friction{};
};

/// Four two-point manifolds solved as blocks (ShapeSolveRow::block_first), with the block's
/// coupling k12 and K⁻¹ = [[m11, m12], [m12, m22]].
struct alignas(32) BlockLanes : LaneBodies {
  Lane k12{}, m11{}, m12{}, m22{};
  std::array<LanePoint, 2> p{};
};

/// Four one-point manifolds.
struct alignas(32) PointLanes : LaneBodies {
  std::array<LanePoint, 1> p{};
};

/// Four bodies' velocities (m/s, m/s, rad/s).
struct Motion {
  Lane vx, vy, w;
};

}  // namespace fixstep::detail::shape_lanes
