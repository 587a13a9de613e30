// The boxes a disc's motion sweeps (disc_records.hpp's motions): over a span of the tick, and
// with the plane pass's motion after its last plane event; and the length of a vector by the
// correctly rounded sqrt. Shared by the broadphase's boxes, the impacts and reach().
#pragma once

#include <algorithm>
#include <cmath>

#include "disc_records.hpp"
#include "grid_broadphase.hpp"
#include "world_kernel.hpp"

namespace fixstep::detail {

/// |(x, y)|, m, by the correctly rounded sqrt (std::hypot's result differs between libms).
inline double length(double x, double y) {
  return std::sqrt(x * x + y * y);
}

/// The box of motion m over [from, to] (s, from >= m.t), widened by pad (m).
inline SweptBox path_box(const DiscMotion& m, double from, double to, double pad) {
  const double s = from - m.t;
  SweptBox b;
  motion_extent(m.px(from), m.ux + s * m.ax, m.ax, to - from, pad, b.min_x, b.max_x);
  motion_extent(m.py(from), m.uy + s * m.ay, m.ay, to - from, pad, b.min_y, b.max_y);
  return b;
}

/// Widens b (m) to hold the plane pass's motion after its last plane event p (at time t, s)
/// over [from, to] (s), extrapolated back from t (the disc pass follows it from the disc's first
/// plane event on), widened by pad (m).
inline void add_plane_motion(const PlaneMotion& p, double t, double from, double to, double pad,
                             SweptBox& b) {
  const double back = from - t;  // <= 0
  double lo = 0, hi = 0;
  motion_extent(p.x + back * (p.ux + 0.5 * back * p.ax), p.ux + back * p.ax, p.ax, to - from, pad,
                lo, hi);
  b.min_x = std::min(b.min_x, lo), b.max_x = std::max(b.max_x, hi);
  motion_extent(p.y + back * (p.uy + 0.5 * back * p.ay), p.uy + back * p.ay, p.ay, to - from, pad,
                lo, hi);
  b.min_y = std::min(b.min_y, lo), b.max_y = std::max(b.max_y, hi);
}

/// A disc whose box grew within a tick (disc_reach.cpp), and its box as the broadphase paired it.
struct GrownBox {
  static constexpr std::uint32_t none = 0xffffffffu;
  std::uint32_t disc = 0;
  SweptBox first{};
};

}  // namespace fixstep::detail
