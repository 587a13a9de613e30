// A vector of four doubles, GCC's generic vector, and the mask a comparison of two gives (all
// ones or all zeros a lane): what the code written four lanes at a time shares (the shape
// sweep's rows, shape_lanes.hpp; det's sin and cos, det_trig_lanes.cpp). GCC and Clang lower it
// to what the target has (two SSE2 registers, one AVX2 register, NEON pairs, scalars on
// wasm32), each operation element-wise and correctly rounded. Types only: the functions that
// take or return one are in lane_ops.hpp, which only sources built with -Wno-psabi include
// (GCC notes at every such function that AVX changes its calling convention). Internal: not
// installed.
#pragma once

namespace fixstep::detail::four_lanes {

inline constexpr int width = 4;
using Lane = double __attribute__((vector_size(width * sizeof(double))));
using Mask = decltype(Lane{} < Lane{});

}  // namespace fixstep::detail::four_lanes
