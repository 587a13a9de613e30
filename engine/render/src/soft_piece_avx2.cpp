// SoftPiece::draw_shaded() two 2x2 quads at a time, in 8-lane vectors (AVX2; chosen at run time
// by soft_wide_lanes()). Lane by lane it does exactly what the 4-lane path of soft_piece.cpp
// does (the same IEEE operations on the same values, the same 16-bit blend), so the pixels are
// the same whichever path draws them (tested). Only these functions are compiled for AVX2
// (target attribute), so nothing shared with the rest of the library is.
#include "soft_piece.hpp"

#if FIXSTEP_SOFT_WIDE

#include <immintrin.h>

#include <cstdint>
#include <cstring>

#include "soft_lanes.hpp"

namespace fixstep::detail {

namespace {

#define FIXSTEP_WIDE __attribute__((target("avx2"), always_inline)) inline

// Lanes 0-3: columns x .. x + 3 of the upper row; lanes 4-7: the same columns of the lower row.
// Lanes (0, 1), (2, 3), (4, 5), (6, 7) are the upper and lower halves of the quads at columns x
// and x + 2.
using V8 = float __attribute__((vector_size(32)));
using V8I = std::int32_t __attribute__((vector_size(32)));
using V8U = std::uint32_t __attribute__((vector_size(32)));
using V16U16 = std::uint16_t __attribute__((vector_size(32)));
using V4U = std::uint32_t __attribute__((vector_size(16)));

FIXSTEP_WIDE V8 splat8(float x) {
  return V8{} + x;
}
FIXSTEP_WIDE V8 abs8(V8 x) {
  return V8(V8I(x) & 0x7fffffff);
}
// maxps/minps: the second operand where the lanes are equal or unordered, as max4()/min4().
FIXSTEP_WIDE V8 max8(V8 a, V8 b) {
  return _mm256_max_ps(a, b);
}
FIXSTEP_WIDE V8 min8(V8 a, V8 b) {
  return _mm256_min_ps(a, b);
}
FIXSTEP_WIDE V8 clamp01(V8 x) {
  return max8(min8(x, splat8(1.0f)), V8{});
}
FIXSTEP_WIDE V8 other_column(V8 x) {
  return __builtin_shufflevector(x, x, 1, 0, 3, 2, 5, 4, 7, 6);
}
FIXSTEP_WIDE V8 other_row(V8 x) {
  return __builtin_shufflevector(x, x, 4, 5, 6, 7, 0, 1, 2, 3);
}
FIXSTEP_WIDE V8 sqrt8(V8 x) {
  return _mm256_sqrt_ps(x);
}
FIXSTEP_WIDE V8I to8(V8 x) {  // lanes::to8()
  return __builtin_convertvector(x * 255.0f + 0.5f, V8I);
}

/// mul255(channel, keep) of two 8-bit channels a lane: (257 t) >> 16, see lanes::over().
FIXSTEP_WIDE V8U scaled(V8U two_channels, V16U16 keep16) {
  const V16U16 t = V16U16(two_channels) * keep16 + 0x80;
  return V8U(_mm256_mulhi_epu16(__m256i(t), _mm256_set1_epi16(257)));
}

/// lanes::over() of eight pixels.
FIXSTEP_WIDE V8U over(V8U pixels, V8U src, V8U keep) {
  const V16U16 keep16 = V16U16(keep | keep << 16);
  const V8U rb = scaled(pixels & 0x00ff00ffu, keep16);
  const V8U ga = scaled((pixels >> 8) & 0x00ff00ffu, keep16);
  return (rb | ga << 8) + src;
}

/// lanes::blend_quad() of the quads at columns x and x + 2: four pixels of each row from
/// `top` and `bottom`.
FIXSTEP_WIDE void blend_quads(std::uint8_t* top, std::uint8_t* bottom, V8I r, V8I g, V8I b, V8I a) {
  V4U upper, lower;
  std::memcpy(&upper, top, 16);
  std::memcpy(&lower, bottom, 16);
  const V8U src = V8U(r) | V8U(g) << 8 | V8U(b) << 16 | V8U(a) << 24;
  const V8U out =
      over(__builtin_shufflevector(upper, lower, 0, 1, 2, 3, 4, 5, 6, 7), src, V8U(255 - a));
  upper = __builtin_shufflevector(out, out, 0, 1, 2, 3);
  lower = __builtin_shufflevector(out, out, 4, 5, 6, 7);
  std::memcpy(top, &upper, 16);
  std::memcpy(bottom, &lower, 16);
}

template <bool line, bool hole, bool flat>
__attribute__((target("avx2"))) void draw_quads(const SoftPiece& p, std::uint8_t* pixels, int width,
                                                int first, int last) {
  const V8 column{0, 1, 2, 3, 0, 1, 2, 3}, row{0, 0, 0, 0, 1, 1, 1, 1};
  const V8 u_step = splat8(float(p.u.dx)), v_step = splat8(float(p.v.dx));
  const V8I columns{0, 1, 2, 3, 0, 1, 2, 3};
  SoftQuadRow q;
  for (int top = first; top <= last; top += 2) {
    if (!p.quad_row(top, width, pixels, q)) continue;
    const V8I lo8{q.lo[0], q.lo[0], q.lo[0], q.lo[0], q.lo[1], q.lo[1], q.lo[1], q.lo[1]};
    const V8I hi8{q.hi[0], q.hi[0], q.hi[0], q.hi[0], q.hi[1], q.hi[1], q.hi[1], q.hi[1]};
    const V8 u_quad =
        line ? V8{} : splat8(float(p.at(p.u, q.cx, q.cy))) + splat8(float(p.u.dy)) * row;
    const V8 v_quad = splat8(float(p.at(p.v, q.cx, q.cy))) + splat8(float(p.v.dy)) * row;
    V8 c_quad[4], c_step[4];
    for (int ch = 0; ch < 4; ++ch) {
      if constexpr (flat) {
        c_quad[ch] = splat8(float(p.color[ch].at));
        c_step[ch] = V8{};
      } else {
        c_quad[ch] =
            splat8(float(p.at(p.color[ch], q.cx, q.cy))) + splat8(float(p.color[ch].dy)) * row;
        c_step[ch] = splat8(float(p.color[ch].dx));
      }
    }
    V8 s = splat8(float(q.x_begin - q.x_start)) + column;
    for (int x = q.x_begin; x <= q.x_last; x += 4, s += 4.0f) {
      if (x >= q.skip_from && x < q.skip_to) {  // the first quad is in the hole
        x = q.skip_to;
        s = splat8(float(x - q.x_start)) + column;
        if (x > q.x_last) break;
      }
      const V8 vv = v_quad + v_step * s;
      V8 d;
      if constexpr (line) {
        d = abs8(vv);
      } else {
        const V8 uu = u_quad + u_step * s;
        d = sqrt8(uu * uu + vv * vv);
      }
      const V8 w = max8(abs8(d - other_column(d)) + abs8(d - other_row(d)), splat8(1e-6f));
      V8 coverage = clamp01((splat8(1.0f) - d) / w + splat8(0.5f));
      if constexpr (hole)
        coverage = max8(coverage - clamp01((splat8(p.fill) - d) / w + splat8(0.5f)), V8{});
      V8 c[4];
      for (int ch = 0; ch < 4; ++ch) c[ch] = flat ? c_quad[ch] : c_quad[ch] + c_step[ch] * s;
      const V8 a = c[3] * coverage;
      const V8I a8 = to8(a), r8 = to8(c[0] * a), g8 = to8(c[1] * a), b8 = to8(c[2] * a);
      const V8I xs = columns + x;
      const V8I drawn = (xs >= lo8) & (xs <= hi8) & (a8 > 0);
      if (x + 3 < width && q.whole) {
        blend_quads(q.rows[0] + std::size_t(x) * 4, q.rows[1] + std::size_t(x) * 4, r8 & drawn,
                    g8 & drawn, b8 & drawn, a8 & drawn);
        continue;
      }
      for (int lane = 0; lane < 8; ++lane) {  // the last columns, or row -1: pixels beyond
        if (!drawn[lane]) continue;
        lanes::blend(q.rows[lane >> 2] + std::size_t(x + (lane & 3)) * 4, r8[lane], g8[lane],
                     b8[lane], a8[lane]);
      }
    }
  }
}

}  // namespace

void draw_shaded_wide(const SoftPiece& p, std::uint8_t* pixels, int width, int first, int last) {
  const bool line = p.is_line(), hole = p.has_hole(), flat = p.flat_color;
  if (line) {
    if (hole) {
      flat ? draw_quads<true, true, true>(p, pixels, width, first, last)
           : draw_quads<true, true, false>(p, pixels, width, first, last);
    } else {
      flat ? draw_quads<true, false, true>(p, pixels, width, first, last)
           : draw_quads<true, false, false>(p, pixels, width, first, last);
    }
  } else if (hole) {
    flat ? draw_quads<false, true, true>(p, pixels, width, first, last)
         : draw_quads<false, true, false>(p, pixels, width, first, last);
  } else {
    flat ? draw_quads<false, false, true>(p, pixels, width, first, last)
         : draw_quads<false, false, false>(p, pixels, width, first, last);
  }
}

}  // namespace fixstep::detail

#endif  // FIXSTEP_SOFT_WIDE
