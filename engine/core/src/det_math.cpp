// Deterministic exp, expm1 and hypot (det_math.hpp): IEEE-754 double +, -, ×, ÷, sqrt and
// exact power-of-two scaling only. The library is compiled with -ffp-contract=off, so no a·b + c
// below is fused into an FMA on any target; every operation rounds once, the same everywhere.
// Constants are hex literals (exact); the method and its sources are in det_math.hpp.
#include "fixstep/core/det_math.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "binary_exponent.hpp"
#include "fixstep/core/bits.hpp"
#include "fixstep/core/types.hpp"

namespace fixstep::det {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// ln 2 = ln2_hi + ln2_lo: ln2_hi has 32 significant bits, so k·ln2_hi is exact for |k| < 2^21
// and x - k·ln2_hi is exact (fdlibm e_exp.c's split). 1/ln 2 rounded.
constexpr double ln2_hi = 0x1.62e42feep-1;
constexpr double ln2_lo = 0x1.a39ef35793c76p-33;
constexpr double inv_ln2 = 0x1.71547652b82fep+0;
constexpr double half_ln2 = 0x1.62e42fefa39efp-2;  // ln 2 / 2 rounded
// Beyond these e^x overflows (709.78) or underflows below half the least subnormal (-745.13).
constexpr double overflow_above = 0x1.62e42fefa39efp+9;
constexpr double underflow_below = -0x1.74910d52d3051p+9;
// 1/n! for n = 2..14, each correctly rounded (computed exactly with rational arithmetic).
constexpr double taylor[] = {0x1.0000000000000p-1,  0x1.5555555555555p-3,  0x1.5555555555555p-5,
                             0x1.1111111111111p-7,  0x1.6c16c16c16c17p-10, 0x1.a01a01a01a01ap-13,
                             0x1.a01a01a01a01ap-16, 0x1.71de3a556c734p-19, 0x1.27e4fb7789f5cp-22,
                             0x1.ae64567f544e4p-26, 0x1.1eed8eff8d898p-29, 0x1.6124613a86d09p-33,
                             0x1.93974a8c07c9dp-37};

/// 2^k for -1022 ≤ k ≤ 1023, built from its bits (exact).
double pow2(int k) {
  return double_from_bits(static_cast<std::uint64_t>(k + 1023) << 52);
}

/// y·2^k for y in [0.5, 4) and -1080 ≤ k ≤ 1024, rounded once (overflow → inf, subnormal
/// results rounded from the exact product).
double scale(double y, int k) {
  if (k > 1023) return y * 2.0 * pow2(k - 1);
  if (k >= -1021) return y * pow2(k);
  return y * pow2(k + 1000) * pow2(-1000);  // the first product is exact, the second rounds
}

/// k = round(x / ln 2) (ties away from zero) and x - k ln2 = hi - lo, for |x| ≤ 746.
int reduce(double x, double& hi, double& lo) {
  const double kd = x * inv_ln2;
  const int k = static_cast<int>(kd < 0.0 ? kd - 0.5 : kd + 0.5);
  hi = x - k * ln2_hi;
  lo = k * ln2_lo;
  return k;
}

/// p = a·b and the exact error e = a·b - p (Dekker's product with Veltkamp's split; needs
/// round to nearest, no FMA contraction and no overflow: |a|, |b| < 2^996).
void two_product(double a, double b, double& p, double& e) {
  constexpr double split = 0x1p27 + 1.0;
  const double ca = split * a, cb = split * b;
  const double ah = ca - (ca - a), al = a - ah;
  const double bh = cb - (cb - b), bl = b - bh;
  p = a * b;
  e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

/// s = a + b and the exact error e = a + b - s (Knuth's two-sum; round to nearest).
void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

/// e^r - 1 = hi + lo for |r| ≤ ln2/2 (a double-double, |lo| ≤ ulp(hi)), by Taylor's series to
/// r^14/14!: r + r²/2 with r² exact (Dekker), the tail r³(1/6 + r/24 + ...) by Horner. The sum
/// hi + lo is within about 0.51 ulp of e^r - 1, so callers that add it to more terms round once.
void expm1_reduced(double r, double& hi, double& lo) {
  double p = taylor[12];
  for (int i = 11; i >= 1; --i) p = taylor[i] + r * p;
  double sq, sq_err;
  two_product(r, r, sq, sq_err);
  two_sum(r, 0.5 * sq, hi, lo);
  lo += 0.5 * sq_err + r * sq * p;
}

}  // namespace

double exp(double x) {
  if (x != x) return x + x;  // NaN (quieted)
  if (x > overflow_above) return infinity;
  if (x < underflow_below) return 0.0;
  if (std::fabs(x) < 0x1p-54) return 1.0 + x;  // e^x - 1 - x < 2^-109: 1 + x rounds right
  double r = x, c = 0.0;
  int k = 0;
  if (std::fabs(x) > half_ln2) {
    double r_hi, r_lo;
    k = reduce(x, r_hi, r_lo);
    r = r_hi - r_lo, c = (r_hi - r) - r_lo;  // x - k ln2 = r + c (to ~2^-100)
  }
  double hi, lo, y, y_err;
  expm1_reduced(r, hi, lo);
  lo += c + c * hi;  // e^(r + c) - 1 to first order in c
  two_sum(1.0, hi, y, y_err);
  y += y_err + lo;  // e^r in (0.7, 1.42), rounded once
  return k == 0 ? y : scale(y, k);
}

double expm1(double x) {
  if (x != x) return x + x;
  if (x > overflow_above) return infinity;
  if (x < -38.9) return -1.0;            // e^x < 2^-56: e^x - 1 rounds to -1
  if (std::fabs(x) < 0x1p-54) return x;  // x²/2 is below half an ulp of x (or x is 0)
  double hi, lo;
  if (std::fabs(x) <= half_ln2) {
    expm1_reduced(x, hi, lo);
    return hi + lo;
  }
  double r_hi, r_lo;
  const int k = reduce(x, r_hi, r_lo);
  const double r = r_hi - r_lo, c = (r_hi - r) - r_lo;
  expm1_reduced(r, hi, lo);
  lo += c + c * hi;
  if (k > 56) {  // the -1 is below half an ulp: e^x rounded
    double y, y_err;
    two_sum(1.0, hi, y, y_err);
    return scale(y + (y_err + lo), k);
  }
  // (2^k - 1) + 2^k (hi + lo) with -56 ≤ k ≤ 56: every product by 2^k is exact.
  const double t = pow2(k);
  double m, m_err, s, s_err;
  two_sum(t, -1.0, m, m_err);
  two_sum(m, t * hi, s, s_err);
  return s + (s_err + (m_err + t * lo));
}

double hypot(double x, double y) {
  double a = std::fabs(x), b = std::fabs(y);
  if (a == infinity || b == infinity) return infinity;
  if (a != a || b != b) return a + b;  // NaN
  if (a < b) std::swap(a, b);
  if (b == 0.0) return a;
  const int e = binary_exponent(a);
  // b/a < 2^-30: √(a² + b²) = a (1 + (b/a)²/2 + ...) rounds to a.
  if (e - binary_exponent(b) > 30) return a;
  // Scale by 2^-e in two exact steps (e may be -1074 or 1023): a into [1, 2), b ≥ 2^-31.
  const int e1 = e / 2, e2 = e - e1;
  a = a * pow2(-e1) * pow2(-e2), b = b * pow2(-e1) * pow2(-e2);
  double h = std::sqrt(a * a + b * b);
  // Borges' correction: h² - a² - b² exactly (to rounding of the small sum), then one Newton
  // step. h² - a² is exact (Sterbenz: a² ≤ h² ≤ 2a² up to rounding).
  double hh, hh_err, aa, aa_err, bb, bb_err;
  two_product(h, h, hh, hh_err);
  two_product(a, a, aa, aa_err);
  two_product(b, b, bb, bb_err);
  const double delta = ((hh - aa) - bb) + ((hh_err - aa_err) - bb_err);
  h -= delta / (2.0 * h);
  return h * pow2(e1) * pow2(e2);
}

}  // namespace fixstep::det

namespace fixstep {
double length(Vec2 a) {
  return det::hypot(a.x, a.y);
}
}  // namespace fixstep
