// det::sincos four angles at a time (det_trig_lanes.hpp). Each lane does sincos's arithmetic
// for one angle (det_trig.cpp: the first step of its reduction, then the shared kernels of
// det_trig_kernels.hpp) in the same order, on GCC's generic vectors of four doubles:
// element-wise IEEE-754 operations, each correctly rounded, never fused (-ffp-contract=off),
// so each lane holds the bits sincos gives. A choice between two results is made by a
// comparison's mask with bitwise operations, never a branch.
#include "det_trig_lanes.hpp"

#include <cstdint>
#include <cstring>

#include "det_trig_kernels.hpp"
#include "fixstep/core/bits.hpp"
#include "fixstep/core/det_math.hpp"
#include "lane_ops.hpp"
#include "simd_targets.hpp"

namespace fixstep::det {
namespace {

void one_by_one(std::span<const double> x, double* sine, double* cosine) {
  for (std::size_t i = 0; i < x.size(); ++i) sincos(x[i], sine[i], cosine[i]);
}

// The lanes: on x86-64, for the AVX2 clone (elsewhere every angle goes one by one).
#if FIXSTEP_HAS_SIMD_CLONES
using detail::four_lanes::any;
using detail::four_lanes::choose;
using detail::four_lanes::Lane;
using detail::four_lanes::Mask;

[[gnu::always_inline]] inline Lane magnitude(Lane x) {
  return reinterpret_cast<Lane>(reinterpret_cast<Mask>(x) & INT64_MAX);
}

// floor of each lane, for |v| < 2^51: the nearest integer (adding and taking away 1.5·2^52,
// exact where the sum's unit is 1), less one where that is above v.
[[gnu::always_inline]] inline Lane floor_of(Lane v) {
  const Lane nearest = (v + 0x1.8p52) - 0x1.8p52;
  return choose(nearest > v, nearest - 1.0, nearest);
}

// Four angles' sine and cosine, or false (nothing written) where one needs more than the
// lanes do. First, without an FP operation that could raise a flag (an integer comparison of
// the magnitudes' bits, in the order of non-negative doubles), that each is finite and within
// trig_max_argument. Then reduce_half_pi's first step, n = floor(|x|·2/π + 0.5); sincos takes
// a second where x − nπ/2 lost more than 16 bits of |x|'s exponent, which |y0| < |x|·2^-15
// covers (with a few it does not need: those go one by one too).
[[gnu::always_inline]] inline bool sincos_four(const double* in, double* sine, double* cosine) {
  using namespace trig;
  Lane x;
  std::memcpy(&x, in, sizeof x);
  const Lane t = magnitude(x);
  const Mask beyond =
      reinterpret_cast<Mask>(t) > static_cast<std::int64_t>(bits_of(trig_max_argument));
  if (any(beyond)) return false;
  const Lane n = floor_of(t * two_over_pi + 0.5);
  const Lane r = t - n * p1;
  const Lane w = n * p1_tail;
  const Lane y0_reduced = r - w;
  const Mask small = t <= pi_4;
  const Mask cancelled = ~small & (magnitude(y0_reduced) < t * 0x1p-15);
  if (any(cancelled)) return false;
  const Mask negative = x < 0.0;
  const Lane y1_reduced = (r - y0_reduced) - w;
  const Lane y0 = choose(small, x, choose(negative, -y0_reduced, y0_reduced));
  const Lane y1 = choose(small, Lane{}, choose(negative, -y1_reduced, y1_reduced));
  // The quadrant, n mod 4 of the signed n (0 where small), exact in doubles below 2^20.
  const Lane signed_n = choose(small, Lane{}, choose(negative, -n, n));
  const Lane quadrant = signed_n - 4.0 * floor_of(signed_n * 0.25);
  const Lane s = choose(magnitude(y0) < 0x1p-27, y0, sin_poly(y0, y1));
  const Lane c = cos_poly(y0, y1);
  const Mask q0 = quadrant == 0.0, q1 = quadrant == 1.0, q2 = quadrant == 2.0;
  const Lane sin_x = choose(q0, s, choose(q1, c, choose(q2, -s, -c)));
  const Lane cos_x = choose(q0, c, choose(q1, -s, choose(q2, -c, s)));
  std::memcpy(sine, &sin_x, sizeof sin_x);
  std::memcpy(cosine, &cos_x, sizeof cos_x);
  return true;
}

FIXSTEP_TARGET_AVX2 void fours_avx2(std::span<const double> x, double* sine, double* cosine) {
  std::size_t i = 0;
  for (; i + 4 <= x.size(); i += 4) {
    if (!sincos_four(&x[i], sine + i, cosine + i))
      one_by_one(x.subspan(i, 4), sine + i, cosine + i);
  }
  one_by_one(x.subspan(i), sine + i, cosine + i);
}
#endif

}  // namespace

void sincos_each(std::span<const double> x, std::span<double> sine, std::span<double> cosine,
                 SimdLevel level) {
#if FIXSTEP_HAS_SIMD_CLONES
  if (level != SimdLevel::baseline) {
    fours_avx2(x, sine.data(), cosine.data());
    return;
  }
#endif
  (void)level;
  one_by_one(x, sine.data(), cosine.data());
}

}  // namespace fixstep::det
