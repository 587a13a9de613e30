// The shape contact solver's row kernels (shape_solver.cpp runs them): one manifold point's
// friction and normal rows and a manifold's two normal rows as one block, on the velocities of
// its two bodies as a sweep carries them (ShapeMotion; A's zero for a plane or segment).
// Inline: a sweep calls them for every row, tens of times a tick.
#pragma once

#include <algorithm>

#include "shape_world.hpp"

namespace fixstep::detail::shape_rows {

// (ω × r)·n = ω (r × n): a body's spin adds ω (r × n) to its point's normal velocity.
[[gnu::always_inline]] inline double normal_of(const ShapeSolveRow& h, const ShapeMotion& a,
                                               const ShapeMotion& b) {
  return (b.vx - a.vx) * h.nx + (b.vy - a.vy) * h.ny + b.w * h.rnb - a.w * h.rna;
}

[[gnu::always_inline]] inline double tangent_of(const ShapeSolveRow& h, const ShapeMotion& a,
                                                const ShapeMotion& b) {
  return (b.vy - a.vy) * h.nx - (b.vx - a.vx) * h.ny + b.w * h.rtb - a.w * h.rta;
}

/// Impulses pn along n and pt along t = perp(n) (N·s) on b, their opposite on a.
[[gnu::always_inline]] inline void push(const ShapeSolveRow& h, double pn, double pt,
                                        ShapeMotion& a, ShapeMotion& b) {
  const double px = pn * h.nx - pt * h.ny, py = pn * h.ny + pt * h.nx;
  a.vx -= h.ma * px, a.vy -= h.ma * py, a.w -= h.ia * (pn * h.rna + pt * h.rta);
  b.vx += h.mb * px, b.vy += h.mb * py, b.w += h.ib * (pn * h.rnb + pt * h.rtb);
}

[[gnu::always_inline]] inline void push_normal(const ShapeSolveRow& h, double pn, ShapeMotion& a,
                                               ShapeMotion& b) {
  const double px = pn * h.nx, py = pn * h.ny;
  a.vx -= h.ma * px, a.vy -= h.ma * py, a.w -= h.ia * (pn * h.rna);
  b.vx += h.mb * px, b.vy += h.mb * py, b.w += h.ib * (pn * h.rnb);
}

[[gnu::always_inline]] inline void push_tangent(const ShapeSolveRow& h, double pt, ShapeMotion& a,
                                                ShapeMotion& b) {
  const double px = -pt * h.ny, py = pt * h.nx;
  a.vx -= h.ma * px, a.vy -= h.ma * py, a.w -= h.ia * (pt * h.rta);
  b.vx += h.mb * px, b.vy += h.mb * py, b.w += h.ib * (pt * h.rtb);
}

[[gnu::always_inline]] inline void solve_friction(ShapeSolveRow& h, ShapeMotion& a,
                                                  ShapeMotion& b) {
  // (A normal impulse a conjugate step left below 0 bounds the friction at 0: std::clamp's
  // bounds must be ordered.)
  const double bound = std::max(h.friction * h.ln, 0.0);
  const double lt = std::clamp(h.lt - tangent_of(h, a, b) * h.tangent_mass, -bound, bound);
  const double d = lt - h.lt;
  h.lt = lt;
  push_tangent(h, d, a, b);
}

[[gnu::always_inline]] inline void solve_normal(ShapeSolveRow& h, ShapeMotion& a, ShapeMotion& b) {
  const double ln = std::max(h.ln - (normal_of(h, a, b) - h.target) * h.normal_mass, 0.0);
  const double d = ln - h.ln;
  h.ln = ln;
  push_normal(h, d, a, b);
}

// A manifold's two normal impulses at once (Catto's block solver, Box2D v2.4
// b2ContactSolver::SolveVelocityConstraints): the 2×2 linear complementarity problem
// vn = K x + b, x >= 0, vn >= 0, x·vn = 0 for the accumulated impulses x, by trying its four
// cases in turn. Solving the two points one after the other lets a box resting on its two
// corners rock (each point's impulse turns it against the other), which a tall stack amplifies.
[[gnu::always_inline]] inline void solve_block(ShapeSolveRow& h1, ShapeSolveRow& h2, ShapeMotion& a,
                                               ShapeMotion& b) {
  const double k11 = h1.kn, k22 = h2.kn, k12 = h1.k12;
  const double a1 = h1.ln, a2 = h2.ln;
  const double vn1 = normal_of(h1, a, b) - h1.target;
  const double vn2 = normal_of(h2, a, b) - h2.target;
  const double b1 = vn1 - (k11 * a1 + k12 * a2), b2 = vn2 - (k12 * a1 + k22 * a2);
  double x1 = 0.0, x2 = 0.0;
  // K⁻¹ (ShapeSolveRow::block_mass, made once a tick) times −b.
  const double y1 = -(h1.block_mass[0] * b1 + h1.block_mass[1] * b2);
  const double y2 = -(h1.block_mass[1] * b1 + h1.block_mass[2] * b2);
  const double z1 = -b1 * h1.normal_mass, z2 = -b2 * h2.normal_mass;
  if (y1 >= 0.0 && y2 >= 0.0) {
    x1 = y1, x2 = y2;  // both points push
  } else if (z1 >= 0.0 && k12 * z1 + b2 >= 0.0) {
    x1 = z1;  // the first pushes, the second separates
  } else if (z2 >= 0.0 && k12 * z2 + b1 >= 0.0) {
    x2 = z2;                               // the second pushes
  } else if (!(b1 >= 0.0 && b2 >= 0.0)) {  // no case holds (rounding): one at a time
    solve_normal(h1, a, b);
    solve_normal(h2, a, b);
    return;
  }
  h1.ln = x1, h2.ln = x2;
  push_normal(h1, x1 - a1, a, b);
  push_normal(h2, x2 - a2, a, b);
}

}  // namespace fixstep::detail::shape_rows
