// Pixel arithmetic of the CPU rasteriser (soft_shapes.hpp): llvmpipe's 8-bit blending, and
// the 4-lane vectors that hold one 2x2 quad of pixels (Lanes4). Lane by lane these are the same
// IEEE operations as scalar code, so the pixels do not depend on the vector unit (SSE, NEON or
// none). Internal to fixstep::render (not installed).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE__)
#include <immintrin.h>
#elif defined(__aarch64__)
#include <arm_neon.h>
#endif

namespace fixstep::detail::lanes {

/// d x / 255, rounded (llvmpipe's 8-bit multiplication).
inline int mul255(int d, int x) {
  const int t = d * x + 0x80;
  return (t + (t >> 8)) >> 8;
}

/// Blends premultiplied 8-bit colour (r, g, b, a) over pixel p.
inline void blend(std::uint8_t* p, int r, int g, int b, int a) {
  const int keep = 255 - a;
  p[0] = static_cast<std::uint8_t>(std::min(255, r + mul255(p[0], keep)));
  p[1] = static_cast<std::uint8_t>(std::min(255, g + mul255(p[1], keep)));
  p[2] = static_cast<std::uint8_t>(std::min(255, b + mul255(p[2], keep)));
}

/// Four floats (ints): one 2x2 quad of pixels, lanes (row 0, column 0), (0, 1), (1, 0), (1, 1).
using V4 = float __attribute__((vector_size(16)));
using V4I = std::int32_t __attribute__((vector_size(16)));

/// The 4-lane vectors of the quad loop (soft_quads.hpp): one 2x2 quad a vector, lanes (row 0,
/// column 0), (0, 1), (1, 0), (1, 1). The 8-lane ones are in soft_piece_avx2.cpp.
struct Lanes4 {
  using V = V4;
  using VI = V4I;
  static constexpr int columns = 2;  ///< pixels of each row in a vector

  static V splat(float x) { return V{x, x, x, x}; }
  /// |x| in every lane: the sign bit cleared (|-0| = +0).
  static V abs(V x) { return V(VI(x) & 0x7fffffff); }
  /// The larger (smaller) of a and b in every lane, for lanes that are not NaN (the
  /// rasteriser's never are); which zero a tie of -0 and +0 gives may differ, which no 8-bit
  /// value it feeds sees.
  static V max(V a, V b) {
#if defined(__SSE__)
    return _mm_max_ps(a, b);
#elif defined(__aarch64__)
    return vmaxq_f32(a, b);
#else
    return a < b ? b : a;
#endif
  }
  static V min(V a, V b) {
#if defined(__SSE__)
    return _mm_min_ps(a, b);
#elif defined(__aarch64__)
    return vminq_f32(a, b);
#else
    return a < b ? a : b;
#endif
  }
  static V clamp01(V x) {
    return max(min(x, splat(1.0f)), V{});
  }
  /// Each lane's neighbour in the other column (row) of its quad.
  static V other_column(V x) {
    return __builtin_shufflevector(x, x, 1, 0, 3, 2);
  }
  static V other_row(V x) {
    return __builtin_shufflevector(x, x, 2, 3, 0, 1);
  }
  /// Square roots, correctly rounded in every lane.
  static V sqrt(V x) {
#if defined(__SSE__)
    return _mm_sqrt_ps(x);
#elif defined(__aarch64__)
    return vsqrtq_f32(x);
#else
    for (int k = 0; k < 4; ++k) x[k] = std::sqrt(x[k]);
    return x;
#endif
  }
  /// 8-bit values of x in [0, 1]: x 255 + 0.5 truncated (round to nearest, as llvmpipe
  /// converts its fragments).
  static VI to8(V x) {
    return __builtin_convertvector(x * 255.0f + 0.5f, VI);
  }
  /// blend() over the quad's pixels: lanes 0, 1 over the two pixels from `top`, lanes 2, 3
  /// over the two from `bottom` (blend_quad()).
  static void blend(std::uint8_t* top, std::uint8_t* bottom, VI r, VI g, VI b, VI a);
};

/// Lanes4::to8() of one value (the vector's arithmetic, so that solid and shaded pixels round
/// alike).
inline int to8(float x) {
  return Lanes4::to8(Lanes4::splat(x))[0];
}

using V4U = std::uint32_t __attribute__((vector_size(16)));
using V8U16 = std::uint16_t __attribute__((vector_size(16)));

/// blend() of four pixels at once: premultiplied colour src (r | g << 8 | b << 16 | a << 24)
/// over each pixel of `pixels` with keep = 255 - a, channel by channel in 16-bit lanes (red and
/// blue in one, green and alpha in the other: every product fits), no lane crossing.
inline V4U over(V4U pixels, V4U src, V4U keep) {
  const V8U16 keep16 = V8U16(keep | keep << 16);
  auto scaled = [&](V4U two_channels) {  // mul255(channel, keep) for two 8-bit channels
    const V8U16 t = V8U16(two_channels) * keep16 + 0x80;
#if defined(__SSE2__)
    // (t + (t >> 8)) >> 8 == (257 t) >> 16 for every 16-bit t: 257 t = 256 t + t, and
    // t + t / 256 lies within one of the whole number t + floor(t / 256) below it, which
    // no multiple of 256 falls strictly between.
    return V4U(_mm_mulhi_epu16(__m128i(t), _mm_set1_epi16(257)));
#else
    return V4U((t + (t >> 8)) >> 8);
#endif
  };
  const V4U rb = scaled(pixels & 0x00ff00ffu), ga = scaled((pixels >> 8) & 0x00ff00ffu);
  return (rb | ga << 8) + src;  // each channel at most 255: no carry between them
}

/// blend() over the 2x2 quad of pixels whose left pixels are top and bottom (each followed by
/// its right neighbour), premultiplied 8-bit colour per lane (row 0 left, right, row 1 left,
/// right); a lane of alpha 0 and colour 0 leaves its pixel as it is, exactly.
inline void blend_quad(std::uint8_t* top, std::uint8_t* bottom, V4I r, V4I g, V4I b, V4I a) {
  using V2U64 = std::uint64_t __attribute__((vector_size(16)));
  // Four RGBA8 pixels, little-endian (r in the low byte); each row's two loaded straight into
  // its half of the register (a 16-byte load of two 8-byte stores would stall).
  std::uint64_t row[2];
  std::memcpy(&row[0], top, 8);
  std::memcpy(&row[1], bottom, 8);
  const V4U src = V4U(r) | V4U(g) << 8 | V4U(b) << 16 | V4U(a) << 24;
  const V2U64 out = V2U64(over(V4U(V2U64{row[0], row[1]}), src, V4U(255 - a)));
  row[0] = out[0];
  row[1] = out[1];
  std::memcpy(top, &row[0], 8);
  std::memcpy(bottom, &row[1], 8);
}

inline void Lanes4::blend(std::uint8_t* top, std::uint8_t* bottom, VI r, VI g, VI b, VI a) {
  blend_quad(top, bottom, r, g, b, a);
}

/// blend() of one colour over `count` pixels from p, four at a time.
inline void blend_span(std::uint8_t* p, int count, int r, int g, int b, int a) {
  const auto src = static_cast<std::uint32_t>(r | g << 8 | b << 16 | a << 24);
  const auto keep = static_cast<std::uint32_t>(255 - a);
  int i = 0;
  for (; i + 4 <= count; i += 4, p += 16) {  // four pixels a step
    V4U pixels;
    std::memcpy(&pixels, p, 16);
    pixels = over(pixels, V4U{} + src, V4U{} + keep);
    std::memcpy(p, &pixels, 16);
  }
  for (; i < count; ++i, p += 4) blend(p, r, g, b, a);
}

}  // namespace fixstep::detail::lanes
