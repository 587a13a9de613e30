// SoftPiece::draw_shaded() two 2x2 quads at a time, in 8-lane vectors (AVX2; chosen at run time
// by soft_wide_lanes()): soft_quads.hpp's loop, the one soft_piece.cpp compiles for 4 lanes,
// instantiated here for Lanes8. Lane by lane it does exactly what the 4-lane path does (the same
// IEEE operations on the same values, the same 16-bit blend), so the pixels are the same
// whichever path draws them (tested). Only these functions are compiled for AVX2 (target
// attribute), so nothing shared with the rest of the library is; this file stays out of unity
// batches (engine/CMakeLists.txt).
#include "soft_piece.hpp"

#if FIXSTEP_SOFT_WIDE

#include <immintrin.h>

#include <cstdint>
#include <cstring>

#include "soft_lanes.hpp"
#define FIXSTEP_QUADS_FN __attribute__((target("avx2")))
#include "soft_quads.hpp"

namespace fixstep::detail {

namespace {

#define FIXSTEP_WIDE __attribute__((target("avx2"), always_inline))

using V4U = std::uint32_t __attribute__((vector_size(16)));
using V8U = std::uint32_t __attribute__((vector_size(32)));
using V16U16 = std::uint16_t __attribute__((vector_size(32)));

/// The 8-lane vectors of the quad loop (soft_quads.hpp): lanes 0-3 are columns x .. x + 3 of the
/// upper row, lanes 4-7 the same columns of the lower row; lanes (0, 1), (4, 5) are the quad at
/// column x and (2, 3), (6, 7) the one at x + 2. Each operation is lanes::Lanes4's, 8 lanes wide.
struct Lanes8 {
  using V = float __attribute__((vector_size(32)));
  using VI = std::int32_t __attribute__((vector_size(32)));
  static constexpr int columns = 4;

  FIXSTEP_WIDE static V splat(float x) { return V{} + x; }
  FIXSTEP_WIDE static V abs(V x) { return V(VI(x) & 0x7fffffff); }
  // maxps/minps: the second operand where the lanes are equal or unordered, as Lanes4's.
  FIXSTEP_WIDE static V max(V a, V b) { return _mm256_max_ps(a, b); }
  FIXSTEP_WIDE static V min(V a, V b) { return _mm256_min_ps(a, b); }
  FIXSTEP_WIDE static V clamp01(V x) { return max(min(x, splat(1.0f)), V{}); }
  FIXSTEP_WIDE static V other_column(V x) {
    return __builtin_shufflevector(x, x, 1, 0, 3, 2, 5, 4, 7, 6);
  }
  FIXSTEP_WIDE static V other_row(V x) {
    return __builtin_shufflevector(x, x, 4, 5, 6, 7, 0, 1, 2, 3);
  }
  FIXSTEP_WIDE static V sqrt(V x) { return _mm256_sqrt_ps(x); }
  FIXSTEP_WIDE static VI to8(V x) { return __builtin_convertvector(x * 255.0f + 0.5f, VI); }
  /// lanes::blend_quad() of the quads at columns x and x + 2: four pixels of each row from
  /// `top` and `bottom`.
  FIXSTEP_WIDE static void blend(std::uint8_t* top, std::uint8_t* bottom, VI r, VI g, VI b, VI a);
};

/// mul255(channel, keep) of two 8-bit channels a lane: (257 t) >> 16, see lanes::over().
FIXSTEP_WIDE inline V8U scaled(V8U two_channels, V16U16 keep16) {
  const V16U16 t = V16U16(two_channels) * keep16 + 0x80;
  return V8U(_mm256_mulhi_epu16(__m256i(t), _mm256_set1_epi16(257)));
}

/// lanes::over() of eight pixels.
FIXSTEP_WIDE inline V8U over(V8U pixels, V8U src, V8U keep) {
  const V16U16 keep16 = V16U16(keep | keep << 16);
  const V8U rb = scaled(pixels & 0x00ff00ffu, keep16);
  const V8U ga = scaled((pixels >> 8) & 0x00ff00ffu, keep16);
  return (rb | ga << 8) + src;
}

FIXSTEP_WIDE inline void Lanes8::blend(std::uint8_t* top, std::uint8_t* bottom, VI r, VI g, VI b,
                                       VI a) {
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

#undef FIXSTEP_WIDE

}  // namespace

void draw_shaded_wide(const SoftPiece& p, std::uint8_t* pixels, int width, int first, int last) {
  draw_shaded_lanes<Lanes8>(p, pixels, width, first, last);
}

}  // namespace fixstep::detail

#endif  // FIXSTEP_SOFT_WIDE
