// SoftPiece::draw_shaded()'s loop over 2x2 quads, written once for any width of vector and
// included by the two files that compile it: soft_piece.cpp (Lanes4, soft_lanes.hpp: one quad a
// vector, the baseline instruction set) and soft_piece_avx2.cpp (Lanes8: two quads a vector,
// AVX2). Lane by lane both do the same IEEE operations on the same values, so the pixels do not
// depend on the width. Internal to fixstep::render (not installed).
//
// The including file defines FIXSTEP_QUADS_FN, the attributes of the functions here (none for
// the baseline; target("avx2") in soft_piece_avx2.cpp, which GCC needs on every function
// instantiated for its vectors), and includes this header once; the header undefines it. Its
// functions are in an unnamed namespace: each file compiles its own copy with its own attributes.
//
// A lanes type L has:
//   V, VI         vectors of 2 L::columns floats (int32s): two rows of L::columns pixels, lane k
//                 at row k / L::columns and column k % L::columns (a quad's lanes k and k ^ 1
//                 are its two columns)
//   columns       pixels of each row in a vector (2: one quad; 4: two)
//   splat, abs, max, min, clamp01, sqrt, to8, other_column, other_row
//                 lane by lane as Lanes4's (soft_lanes.hpp)
//   blend(top, bottom, r, g, b, a)
//                 lanes::blend() of the upper lanes over the row of pixels from `top` and of the
//                 lower lanes over the row from `bottom`
#pragma once

#ifndef FIXSTEP_QUADS_FN
#error "soft_quads.hpp: define FIXSTEP_QUADS_FN (the functions' attributes) before including it"
#endif

#include <cstddef>
#include <cstdint>

#include "soft_lanes.hpp"
#include "soft_piece.hpp"

// Helpers of the loop, inlined into it whatever the compiler's estimate.
#define FIXSTEP_QUADS_INLINE FIXSTEP_QUADS_FN __attribute__((always_inline)) inline

namespace fixstep::detail {

namespace {

/// Each lane's column (k % L::columns) and row (k / L::columns) within a vector's pixels.
template <class L>
struct QuadLanes {
  typename L::VI column_i{}, upper{};  ///< column; -1 in the lanes of the upper row, else 0
  typename L::V column{}, row{};
};

template <class L>
FIXSTEP_QUADS_INLINE QuadLanes<L> quad_lanes() {
  QuadLanes<L> k;
  for (int lane = 0; lane < 2 * L::columns; ++lane) {
    const bool upper = lane < L::columns;
    k.column_i[lane] = lane % L::columns;
    k.upper[lane] = upper ? -1 : 0;
    k.column[lane] = float(lane % L::columns);
    k.row[lane] = upper ? 0.0f : 1.0f;
  }
  return k;
}

/// A row of quads (SoftQuadRow) in lanes: each lane's span of pixels, and the shape coordinates
/// and colour at the centre of pixel (x_start, its row) with their steps per px.
template <class L>
struct QuadRowLanes {
  typename L::VI lo, hi;
  typename L::V u, v, c[4], c_step[4];
};

template <class L, bool line, bool flat>
FIXSTEP_QUADS_INLINE QuadRowLanes<L> row_lanes(const SoftPiece& p, const SoftQuadRow& q,
                                               const QuadLanes<L>& k) {
  using V = typename L::V;
  using VI = typename L::VI;
  QuadRowLanes<L> r;
  r.lo = ((VI{} + q.lo[0]) & k.upper) | ((VI{} + q.lo[1]) & ~k.upper);
  r.hi = ((VI{} + q.hi[0]) & k.upper) | ((VI{} + q.hi[1]) & ~k.upper);
  r.u = line ? V{} : L::splat(float(p.at(p.u, q.cx, q.cy))) + L::splat(float(p.u.dy)) * k.row;
  r.v = L::splat(float(p.at(p.v, q.cx, q.cy))) + L::splat(float(p.v.dy)) * k.row;
  for (int ch = 0; ch < 4; ++ch) {
    if constexpr (flat) {
      r.c[ch] = L::splat(float(p.color[ch].at));  // its planes are flat: at() is `at`, exactly
      r.c_step[ch] = V{};
    } else {
      r.c[ch] =
          L::splat(float(p.at(p.color[ch], q.cx, q.cy))) + L::splat(float(p.color[ch].dy)) * k.row;
      r.c_step[ch] = L::splat(float(p.color[ch].dx));
    }
  }
  return r;
}

/// Premultiplied 8-bit colour of each lane.
template <class L>
struct QuadColor {
  typename L::VI r, g, b, a;
};

/// The colour of the lanes `s` px right of x_start (s exact: small whole numbers): the coverage
/// of the shape (distance d from its centre line or centre, fwidth w as llvmpipe's derivatives
/// within each quad) times the interpolated colour.
template <class L, bool line, bool hole, bool flat>
FIXSTEP_QUADS_INLINE QuadColor<L> shade(const SoftPiece& p, const QuadRowLanes<L>& r,
                                        typename L::V u_step, typename L::V v_step,
                                        typename L::V s) {
  using V = typename L::V;
  const V vv = r.v + v_step * s;
  V d;
  if constexpr (line) {
    d = L::abs(vv);
  } else {
    const V uu = r.u + u_step * s;
    d = L::sqrt(uu * uu + vv * vv);
  }
  const V w = L::max(L::abs(d - L::other_column(d)) + L::abs(d - L::other_row(d)), L::splat(1e-6f));
  V coverage = L::clamp01((L::splat(1.0f) - d) / w + L::splat(0.5f));
  if constexpr (hole)
    coverage = L::max(coverage - L::clamp01((L::splat(p.fill) - d) / w + L::splat(0.5f)), V{});
  V c[4];  // the colour at each lane
  for (int ch = 0; ch < 4; ++ch) c[ch] = flat ? r.c[ch] : r.c[ch] + r.c_step[ch] * s;
  const V a = c[3] * coverage;
  return {L::to8(c[0] * a), L::to8(c[1] * a), L::to8(c[2] * a), L::to8(a)};
}

/// Blends the lanes of `px` that `drawn` has (-1) over the vector's pixels from column x of q's
/// rows. A vector with no lane drawn is blended too (a lane of alpha and colour 0 leaves its
/// pixel exactly as it is): no branch to mispredict.
template <class L>
FIXSTEP_QUADS_INLINE void blend_lanes(const SoftQuadRow& q, int x, int width,
                                      const QuadColor<L>& px, typename L::VI drawn) {
  if (x + L::columns - 1 < width && q.whole) {  // every lane's pixel is in the frame
    L::blend(q.rows[0] + std::size_t(x) * 4, q.rows[1] + std::size_t(x) * 4, px.r & drawn,
             px.g & drawn, px.b & drawn, px.a & drawn);
    return;
  }
  for (int lane = 0; lane < 2 * L::columns; ++lane) {  // the last columns, or row -1: pixels
    if (!drawn[lane]) continue;                        // beyond
    lanes::blend(q.rows[lane / L::columns] + std::size_t(x + lane % L::columns) * 4, px.r[lane],
                 px.g[lane], px.b[lane], px.a[lane]);
  }
}

/// SoftPiece::draw_shaded() for a line's coordinates (u = 0), a hole or not, one colour or not.
template <class L, bool line, bool hole, bool flat>
FIXSTEP_QUADS_FN void draw_quads(const SoftPiece& p, std::uint8_t* pixels, int width, int first,
                                 int last) {
  using V = typename L::V;
  const QuadLanes<L> k = quad_lanes<L>();
  const V u_step = L::splat(float(p.u.dx)), v_step = L::splat(float(p.v.dx));
  SoftQuadRow q;
  for (int top = first; top <= last; top += 2) {
    if (!p.quad_row(top, width, pixels, q)) continue;
    const QuadRowLanes<L> r = row_lanes<L, line, flat>(p, q, k);
    // Each lane's column from x_start, a small whole number: stepping it is exact.
    V s = L::splat(float(q.x_begin - q.x_start)) + k.column;
    for (int x = q.x_begin; x <= q.x_last; x += L::columns, s += float(L::columns)) {
      if (x >= q.skip_from && x < q.skip_to) {  // the vector's first quad is in the hole
        x = q.skip_to;
        s = L::splat(float(x - q.x_start)) + k.column;
        if (x > q.x_last) break;
      }
      const QuadColor<L> px = shade<L, line, hole, flat>(p, r, u_step, v_step, s);
      const typename L::VI xs = k.column_i + x;
      blend_lanes<L>(q, x, width, px, (xs >= r.lo) & (xs <= r.hi) & (px.a > 0));
    }
  }
}

/// SoftPiece::draw_shaded() in L's vectors: draw_quads() for the piece's kind.
template <class L>
FIXSTEP_QUADS_FN void draw_shaded_lanes(const SoftPiece& p, std::uint8_t* pixels, int width,
                                        int first, int last) {
  const bool line = p.is_line(), hole = p.has_hole(), flat = p.flat_color;
  if (line) {
    if (hole) {
      flat ? draw_quads<L, true, true, true>(p, pixels, width, first, last)
           : draw_quads<L, true, true, false>(p, pixels, width, first, last);
    } else {
      flat ? draw_quads<L, true, false, true>(p, pixels, width, first, last)
           : draw_quads<L, true, false, false>(p, pixels, width, first, last);
    }
  } else if (hole) {
    flat ? draw_quads<L, false, true, true>(p, pixels, width, first, last)
         : draw_quads<L, false, true, false>(p, pixels, width, first, last);
  } else {
    flat ? draw_quads<L, false, false, true>(p, pixels, width, first, last)
         : draw_quads<L, false, false, false>(p, pixels, width, first, last);
  }
}

}  // namespace

}  // namespace fixstep::detail

#undef FIXSTEP_QUADS_INLINE
#undef FIXSTEP_QUADS_FN
