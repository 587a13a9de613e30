// The pieces of det_trig.cpp's sin and cos that det_trig_lanes.cpp shares: the reduction's
// constants and the kernels' polynomials, written once for a double and for a generic vector
// of doubles (each operation element-wise, in the same order: the same bits). Internal: not
// installed. The coefficients and the split constants of π/2 are fdlibm 5.3's (Sun
// Microsystems, 1993).
#pragma once

namespace fixstep::det::trig {

inline constexpr double pi_4 = 7.85398163397448278999e-01;  // π/4 rounded

// 2/π rounded, and π/2 = p1 + p2 + p3 + p3_tail with p1, p2, p3 of 33 significant bits each,
// so n·p1, n·p2 and n·p3 are exact for the n < 2^20 of |x| ≤ trig_max_argument.
inline constexpr double two_over_pi = 6.36619772367581382433e-01;
inline constexpr double p1 = 1.57079632673412561417e+00;
inline constexpr double p1_tail = 6.07710050650619224932e-11;  // π/2 - p1
inline constexpr double p2 = 6.07710050630396597660e-11;
inline constexpr double p2_tail = 2.02226624879595063154e-21;  // π/2 - (p1 + p2)
inline constexpr double p3 = 2.02226624871116645580e-21;
inline constexpr double p3_tail = 8.47842766036889956997e-32;  // π/2 - (p1 + p2 + p3)

// sin r ≈ r + S1 r³ + ... + S6 r¹³ and cos r ≈ 1 - r²/2 + C1 r⁴ + ... + C6 r¹⁴ on [-π/4, π/4]
// (fdlibm k_sin.c, k_cos.c: relative error of the polynomial < 2^-58).
inline constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                        S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                        S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
inline constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                        C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                        C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;

/// sin(x + y) for |x| ≤ about π/4, |y| ≤ ulp(x)/2 and |x| ≥ 2^-27 (below, sin is x): fdlibm
/// k_sin.c's polynomial with its correction for y.
template <class T>
T sin_poly(T x, T y) {
  const T z = x * x, v = z * x;
  const T r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
  return x - ((z * (0.5 * y - v * r) - y) - v * S1);
}

/// cos(x + y) for |x| ≤ about π/4 and |y| ≤ ulp(x)/2: 1 - x²/2 rounded apart from the rest
/// so that its rounding error is added back (fdlibm k_cos.c, 2004 revision).
template <class T>
T cos_poly(T x, T y) {
  const T z = x * x, w = z * z;
  const T r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
  const T hz = 0.5 * z, one_minus = 1.0 - hz;
  return one_minus + (((1.0 - one_minus) - hz) + (z * r - x * y));
}

}  // namespace fixstep::det::trig
