// The shape contact solver's row kernels four lanes at a time (shape_lanes.hpp says how; the
// velocity sweep, shape_sweep.cpp, runs them): shape_rows.hpp's arithmetic, lane by lane.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "lane_ops.hpp"
#include "shape_lanes.hpp"

namespace fixstep::detail::shape_lanes {

using four_lanes::any;
using four_lanes::choose;

/// std::max(x, lo) and std::clamp(x, lo, hi) as libstdc++ defines them ((x < lo) ? lo : x, and
/// (x < lo) ? lo : (hi < x) ? hi : x): the same result for every x, a signed zero and a NaN
/// included.
[[gnu::always_inline]] inline Lane max_of(Lane x, Lane lo) {
  return choose(x < lo, lo, x);
}
[[gnu::always_inline]] inline Lane clamp_of(Lane x, Lane lo, Lane hi) {
  return choose(x < lo, lo, choose(hi < x, hi, x));
}

using Point = LanePoint;

// The row kernels of shape_rows.hpp, four lanes at once, each expression in the same order.
[[gnu::always_inline]] inline Lane normal_of(const LaneBodies& g, const Point& h, const Motion& a,
                                             const Motion& b) {
  return (b.vx - a.vx) * g.nx + (b.vy - a.vy) * g.ny + b.w * h.rnb - a.w * h.rna;
}

[[gnu::always_inline]] inline Lane tangent_of(const LaneBodies& g, const Point& h, const Motion& a,
                                              const Motion& b) {
  return (b.vy - a.vy) * g.nx - (b.vx - a.vx) * g.ny + b.w * h.rtb - a.w * h.rta;
}

[[gnu::always_inline]] inline void push_normal(const LaneBodies& g, const Point& h, Lane pn,
                                               Motion& a, Motion& b) {
  const Lane px = pn * g.nx, py = pn * g.ny;
  a.vx -= g.ma * px, a.vy -= g.ma * py, a.w -= g.ia * (pn * h.rna);
  b.vx += g.mb * px, b.vy += g.mb * py, b.w += g.ib * (pn * h.rnb);
}

[[gnu::always_inline]] inline void push_tangent(const LaneBodies& g, const Point& h, Lane pt,
                                                Motion& a, Motion& b) {
  const Lane px = -pt * g.ny, py = pt * g.nx;
  a.vx -= g.ma * px, a.vy -= g.ma * py, a.w -= g.ia * (pt * h.rta);
  b.vx += g.mb * px, b.vy += g.mb * py, b.w += g.ib * (pt * h.rtb);
}

[[gnu::always_inline]] inline void solve_friction(const LaneBodies& g, Point& h, Motion& a,
                                                  Motion& b) {
  const Lane bound = max_of(g.friction * h.ln, Lane{});  // shape_rows::solve_friction's
  const Lane lt = clamp_of(h.lt - tangent_of(g, h, a, b) * h.tangent_mass, -bound, bound);
  const Lane d = lt - h.lt;
  h.lt = lt;
  push_tangent(g, h, d, a, b);
}

// shape_rows::solve_block: the four cases of the 2×2 problem chosen lane by lane; a lane where
// none holds (rounding) takes the two points one after the other, as solve_block does, which
// is computed only when some lane needs it.
[[gnu::always_inline]] inline void solve_block(BlockLanes& g, Motion& a, Motion& b) {
  Point &h1 = g.p[0], &h2 = g.p[1];
  const Lane zero{};
  const Lane a1 = h1.ln, a2 = h2.ln;
  const Lane vn1 = normal_of(g, h1, a, b) - h1.target;
  const Lane vn2 = normal_of(g, h2, a, b) - h2.target;
  const Lane b1 = vn1 - (h1.kn * a1 + g.k12 * a2), b2 = vn2 - (g.k12 * a1 + h2.kn * a2);
  const Lane y1 = -(g.m11 * b1 + g.m12 * b2);
  const Lane y2 = -(g.m12 * b1 + g.m22 * b2);
  const Lane z1 = -b1 * h1.normal_mass, z2 = -b2 * h2.normal_mass;
  const Mask both = (y1 >= zero) & (y2 >= zero);
  const Mask first = ~both & (z1 >= zero) & (g.k12 * z1 + b2 >= zero);
  const Mask second = ~both & ~first & (z2 >= zero) & (g.k12 * z2 + b1 >= zero);
  const Mask none = ~both & ~first & ~second & ~((b1 >= zero) & (b2 >= zero));
  const Lane x1 = choose(both, y1, choose(first, z1, zero));
  const Lane x2 = choose(both, y2, choose(second, z2, zero));
  if (!any(none)) {
    h1.ln = x1, h2.ln = x2;
    push_normal(g, h1, x1 - a1, a, b);
    push_normal(g, h2, x2 - a2, a, b);
    return;
  }
  Motion sa = a, sb = b;  // the lanes where no case holds: one point after the other
  const Lane s1 = max_of(a1 - vn1 * h1.normal_mass, zero);
  push_normal(g, h1, s1 - a1, sa, sb);
  const Lane s2 = max_of(a2 - (normal_of(g, h2, sa, sb) - h2.target) * h2.normal_mass, zero);
  push_normal(g, h2, s2 - a2, sa, sb);
  push_normal(g, h1, x1 - a1, a, b);
  push_normal(g, h2, x2 - a2, a, b);
  h1.ln = choose(none, s1, x1), h2.ln = choose(none, s2, x2);
  a.vx = choose(none, sa.vx, a.vx), a.vy = choose(none, sa.vy, a.vy);
  a.w = choose(none, sa.w, a.w);
  b.vx = choose(none, sb.vx, b.vx), b.vy = choose(none, sb.vy, b.vy);
  b.w = choose(none, sb.w, b.w);
}

// shape_rows::solve_normal.
[[gnu::always_inline]] inline void solve_normal(const LaneBodies& g, Point& h, Motion& a,
                                                Motion& b) {
  const Lane ln = max_of(h.ln - (normal_of(g, h, a, b) - h.target) * h.normal_mass, Lane{});
  const Lane d = ln - h.ln;
  h.ln = ln;
  push_normal(g, h, d, a, b);
}

// GCC 12 at -O3 warns that the vectors gather() fills "may be used uninitialized" in the AVX2
// clone of the sweep (shape_sweep.cpp), whether they are filled lane by lane or made whole from
// four values, and even when they start zeroed. Every lane is written before any is read, so the
// warning is switched off for gather() alone.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
/// A group's bodies' velocities, gathered lane by lane.
[[gnu::always_inline]] inline void gather(const LaneBodies& g, const ShapeMotion* v, Motion& a,
                                          Motion& b) {
  for (int l = 0; l < width; ++l) {
    const ShapeMotion& va = v[g.read_a[l]];
    const ShapeMotion& vb = v[g.read_b[l]];
    a.vx[l] = va.vx, a.vy[l] = va.vy, a.w[l] = va.w;
    b.vx[l] = vb.vx, b.vy[l] = vb.vy, b.w[l] = vb.w;
  }
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

[[gnu::always_inline]] inline void scatter(const LaneBodies& g, const Motion& a, const Motion& b,
                                           ShapeMotion* v) {
  for (int l = 0; l < width; ++l) {
    if (g.write_a[l] != no_write) v[g.write_a[l]] = {a.vx[l], a.vy[l], a.w[l]};
    if (g.write_b[l] != no_write) v[g.write_b[l]] = {b.vx[l], b.vy[l], b.w[l]};
  }
}

/// A point's impulses before its rows are solved.
struct Before {
  Lane ln, lt;
};

/// `change` raised to the change of the point's own normal and tangent velocity its impulses'
/// change since `was` made (|Δλ| K, m/s), lane by lane.
[[gnu::always_inline]] inline void note_change(const Point& h, const Before& was, Lane& change) {
  const Lane dn = h.ln - was.ln, dt = h.lt - was.lt;
  change = max_of(change, max_of(dn, -dn) * h.kn);
  change = max_of(change, max_of(dt, -dt) * h.kt);
}

// A group's normal impulses after its friction: a block's two together, a point's alone.
[[gnu::always_inline]] inline void solve_normals(BlockLanes& g, Motion& a, Motion& b) {
  solve_block(g, a, b);
}
[[gnu::always_inline]] inline void solve_normals(PointLanes& g, Motion& a, Motion& b) {
  solve_normal(g, g.p[0], a, b);
}

/// Four manifolds: each point's friction, then the normal impulses (a block's two together);
/// `change` as note_change.
template <class Group>
[[gnu::always_inline]] inline void solve_group(Group& g, ShapeMotion* v, Lane& change) {
  constexpr std::size_t points = std::tuple_size_v<decltype(g.p)>;
  std::array<Before, points> was;
  for (std::size_t i = 0; i < points; ++i) was[i] = {g.p[i].ln, g.p[i].lt};
  Motion a, b;
  gather(g, v, a, b);
  for (std::size_t i = 0; i < points; ++i) solve_friction(g, g.p[i], a, b);
  solve_normals(g, a, b);
  scatter(g, a, b, v);
  for (std::size_t i = 0; i < points; ++i) note_change(g.p[i], was[i], change);
}

/// Two groups of one colour (they move no body in common), their steps interleaved so that the
/// processor overlaps their two chains of dependent arithmetic: the same results as
/// solve_group on `g`, then on `k`, `change` raised in that order.
template <class Group>
[[gnu::always_inline]] inline void solve_two(Group& g, Group& k, ShapeMotion* v, Lane& change) {
  constexpr std::size_t points = std::tuple_size_v<decltype(g.p)>;
  std::array<Before, points> gw, kw;
  for (std::size_t i = 0; i < points; ++i) gw[i] = {g.p[i].ln, g.p[i].lt};
  for (std::size_t i = 0; i < points; ++i) kw[i] = {k.p[i].ln, k.p[i].lt};
  Motion ga, gb, ka, kb;
  gather(g, v, ga, gb);
  gather(k, v, ka, kb);
  for (std::size_t i = 0; i < points; ++i) {
    solve_friction(g, g.p[i], ga, gb);
    solve_friction(k, k.p[i], ka, kb);
  }
  solve_normals(g, ga, gb);
  solve_normals(k, ka, kb);
  scatter(g, ga, gb, v);
  scatter(k, ka, kb, v);
  for (std::size_t i = 0; i < points; ++i) note_change(g.p[i], gw[i], change);
  for (std::size_t i = 0; i < points; ++i) note_change(k.p[i], kw[i], change);
}

/// The largest of a lane's values.
[[gnu::always_inline]] inline double largest(const Lane& x) {
  double most = x[0];
  for (int l = 1; l < width; ++l) most = most < x[l] ? x[l] : most;
  return most;
}

/// A colour's groups [first, last), two at a time, the last alone when their count is odd;
/// the largest change of a row's own velocity (note_change).
template <class Group>
[[gnu::always_inline]] inline double solve_groups(Group* first, Group* last, ShapeMotion* v) {
  Lane change{};
  for (; last - first >= 2; first += 2) solve_two(first[0], first[1], v, change);
  if (first != last) solve_group(*first, v, change);
  return largest(change);
}

}  // namespace fixstep::detail::shape_lanes
