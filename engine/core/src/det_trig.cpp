// Deterministic sin, cos, atan and atan2 (det_math.hpp): IEEE-754 double +, -, ×, ÷ only,
// compiled with -ffp-contract=off, so every operation rounds once, the same on every target.
// The methods, their sources and the measured errors are in det_math.hpp; the polynomial
// coefficients and the split constants of π/2 are fdlibm 5.3's (Sun Microsystems, 1993).
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "binary_exponent.hpp"
#include "det_trig_kernels.hpp"
#include "fixstep/core/det_math.hpp"

namespace fixstep::det {
namespace {

constexpr double pi = 3.14159265358979311600e+00;     // π rounded
constexpr double pi_lo = 1.22464679914735317720e-16;  // π - pi
constexpr double pi_2 = 1.57079632679489655800e+00;   // π/2 rounded
using namespace trig;  // π/4, the reduction's constants and the kernels' polynomials

// atan c as a double-double for the reduction points c = 1/2, 1, 3/2, ∞, and the odd
// polynomial's coefficients: atan t ≈ t - t³(a0 + a1 t² + ... + a10 t²⁰) on [0, 7/16]
// (fdlibm s_atan.c).
constexpr double atan_hi[] = {4.63647609000806093515e-01, 7.85398163397448278999e-01,
                              9.82793723247329054082e-01, 1.57079632679489655800e+00};
constexpr double atan_lo[] = {2.26987774529616870924e-17, 3.06161699786838301793e-17,
                              1.39033110312309984516e-17, 6.12323399573676603587e-17};
constexpr double aT[] = {
    3.33333333333329318027e-01,  -1.99999999998764832476e-01, 1.42857142725034663711e-01,
    -1.11111104054623557880e-01, 9.09088713343650656196e-02,  -7.69187620504482999495e-02,
    6.66107313738753120669e-02,  -5.83357013379057348645e-02, 4.97687799461593236017e-02,
    -3.65315727442169155270e-02, 1.62858201153657823623e-02};

/// sin(x + y) for |x| ≤ about π/4 and |y| ≤ ulp(x)/2 (y: the tail of a reduced argument).
double sin_kernel(double x, double y) {
  if (std::fabs(x) < 0x1p-27) return x;  // x³/6 < half an ulp of x
  return sin_poly(x, y);
}

/// cos(x + y) for |x| ≤ about π/4 and |y| ≤ ulp(x)/2.
double cos_kernel(double x, double y) {
  return cos_poly(x, y);
}

/// n and x - nπ/2 = y0 + y1 (|y0| ≤ about π/4, |y1| ≤ ulp(y0)/2) for finite |x| ≤
/// trig_max_argument; throws std::domain_error beyond it.
int reduce_half_pi(double x, double& y0, double& y1) {
  const double t = std::fabs(x);
  if (t <= pi_4) {
    y0 = x, y1 = 0.0;
    return 0;
  }
  if (t > trig_max_argument) {
    throw std::domain_error("det::sin/cos: |x| = " + std::to_string(t) +
                            " rad is beyond trig_max_argument (823549.66 rad); reduce the angle "
                            "first (it is periodic in 2π)");
  }
  const double fn = std::floor(t * two_over_pi + 0.5);
  const int n = static_cast<int>(fn);
  // t - fn·p1 is exact (Sterbenz); fn·(π/2 - p1) is good to 85 bits. When x lies close to a
  // multiple of π/2 the difference cancels: then p2 and p3 replace the tail, each step keeping
  // the rounding error of its subtraction in w (fdlibm e_rem_pio2.c's medium case). The
  // branches depend on exponents only, the same everywhere.
  double r = t - fn * p1;
  double w = fn * p1_tail;
  y0 = r - w;
  const int e = binary_exponent(t);
  auto lost_bits = [e](double y) { return y == 0.0 ? 1000 : e - binary_exponent(y); };
  if (lost_bits(y0) > 16) {  // a second step: good to 118 bits
    double s = r;
    w = fn * p2;
    r = s - w;
    w = fn * p2_tail - ((s - r) - w);
    y0 = r - w;
    if (lost_bits(y0) > 49) {  // a third: 151 bits, enough for every double below the limit
      s = r;
      w = fn * p3;
      r = s - w;
      w = fn * p3_tail - ((s - r) - w);
      y0 = r - w;
    }
  }
  y1 = (r - y0) - w;
  if (x < 0.0) y0 = -y0, y1 = -y1;
  return x < 0.0 ? -n : n;
}

/// atan x for x ≥ 0 (finite or +inf), by fdlibm's reduction.
double atan_nonnegative(double x) {
  if (x >= 0x1p66) return atan_hi[3] + atan_lo[3];  // π/2 rounded (also for +inf)
  int id = -1;
  if (x >= 0.4375) {
    if (x < 0.6875) {
      id = 0, x = (2.0 * x - 1.0) / (2.0 + x);
    } else if (x < 1.1875) {
      id = 1, x = (x - 1.0) / (x + 1.0);
    } else if (x < 2.4375) {
      id = 2, x = (x - 1.5) / (1.0 + 1.5 * x);
    } else {
      id = 3, x = -1.0 / x;
    }
  } else if (x < 0x1p-27) {
    return x;  // x³/3 < half an ulp of x
  }
  const double z = x * x, w = z * z;
  const double s1 =
      z * (aT[0] + w * (aT[2] + w * (aT[4] + w * (aT[6] + w * (aT[8] + w * aT[10])))));
  const double s2 = w * (aT[1] + w * (aT[3] + w * (aT[5] + w * (aT[7] + w * aT[9]))));
  if (id < 0) return x - x * (s1 + s2);
  return atan_hi[id] - ((x * (s1 + s2) - atan_lo[id]) - x);
}

}  // namespace

double sin(double x) {
  if (x != x) return x + x;                                            // NaN (quieted)
  if (std::isinf(x)) return std::numeric_limits<double>::quiet_NaN();  // raising no flag
  double y0, y1;
  switch (reduce_half_pi(x, y0, y1) & 3) {
    case 0:
      return sin_kernel(y0, y1);
    case 1:
      return cos_kernel(y0, y1);
    case 2:
      return -sin_kernel(y0, y1);
    default:
      return -cos_kernel(y0, y1);
  }
}

double cos(double x) {
  if (x != x) return x + x;
  if (std::isinf(x)) return std::numeric_limits<double>::quiet_NaN();
  double y0, y1;
  switch (reduce_half_pi(x, y0, y1) & 3) {
    case 0:
      return cos_kernel(y0, y1);
    case 1:
      return -sin_kernel(y0, y1);
    case 2:
      return -cos_kernel(y0, y1);
    default:
      return sin_kernel(y0, y1);
  }
}

void sincos(double x, double& sine, double& cosine) {
  if (x != x || std::isinf(x)) {
    sine = sin(x), cosine = cos(x);
    return;
  }
  double y0, y1;
  const int n = reduce_half_pi(x, y0, y1) & 3;
  const double s = sin_kernel(y0, y1), c = cos_kernel(y0, y1);
  sine = n == 0 ? s : n == 1 ? c : n == 2 ? -s : -c;
  cosine = n == 0 ? c : n == 1 ? -s : n == 2 ? -c : s;
}

double atan(double x) {
  if (x != x) return x + x;
  return std::signbit(x) ? -atan_nonnegative(-x) : atan_nonnegative(x);
}

double atan2(double y, double x) {
  if (x != x || y != y) return x + y;
  const bool y_negative = std::signbit(y), x_negative = std::signbit(x);
  const double sign = y_negative ? -1.0 : 1.0;
  if (y == 0.0) return x_negative ? sign * pi : y;  // ±0 or ±π
  if (x == 0.0) return sign * pi_2;
  if (std::isinf(x)) {
    if (std::isinf(y)) return sign * (x_negative ? 3.0 * pi_4 : pi_4);
    return x_negative ? sign * pi : sign * 0.0;
  }
  if (std::isinf(y)) return sign * pi_2;
  // |y/x| > 2^60: the angle rounds to ±π/2; x < 0 and |y/x| < 2^-60: to ±π.
  const int k = std::ilogb(y) - std::ilogb(x);
  if (k > 60) return sign * (pi_2 + 0.5 * pi_lo);
  const double z = x_negative && k < -60 ? 0.0 : atan_nonnegative(std::fabs(y / x));
  return x_negative ? sign * (pi - (z - pi_lo)) : sign * z;
}

}  // namespace fixstep::det
