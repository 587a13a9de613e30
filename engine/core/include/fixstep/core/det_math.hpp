// Deterministic elementary functions: the transcendental and root functions a state or a
// game's rules depend on, computed in-tree from IEEE-754 double +, -, ×, ÷ and sqrt (all
// correctly rounded) and exact scaling by powers of two, compiled with -ffp-contract=off. They
// give the same bits on every platform, libm and CPU, and under any FTZ/DAZ setting of the
// caller for normal results (see docs/ROBUSTNESS.md, "Deterministic arithmetic").
//
// The libm's exp and hypot do not: glibc x86-64 picks an FMA variant of exp on CPUs with FMA
// (1 ulp apart from its non-FMA variant and from musl on ~0.07 % of arguments), and glibc
// x86-64, glibc aarch64 and musl round hypot differently on ~13 % of random inputs.
//
// Only double is provided: float callers compute in double and round once (static_cast).
// sqrt needs no copy: IEEE-754 requires it correctly rounded, so std::sqrt is the same
// everywhere. Accuracy against long double: tests/core/test_det_math.cpp (max errors stated there
// and in docs/ROBUSTNESS.md).
#pragma once

namespace fixstep::det {

/// e^x for any double x, dimensionless. Error ≤ 0.52 ulp for normal results, ≤ 0.75 ulp
/// for subnormal ones (measured against long double, tests/core/test_det_math.cpp).
/// NaN → NaN, +inf → +inf, -inf → +0, x > 709.78 → +inf (overflow), x < -745.13 → +0.
/// Never raises or sets errno.
/// Method: Cody–Waite reduction x = k ln2 + r + c, |r| ≤ ln2/2, with ln2 split in a 32-bit
/// head (k·head exact) and a tail as in fdlibm e_exp.c (W. J. Cody, W. Waite, "Software Manual
/// for the Elementary Functions", 1980); e^r - 1 by its Taylor series to r^14/14! (truncation
/// < 2^-62 relative) carried as a double-double, r² exact by Dekker's product; e^r = 1 + that,
/// rounded once; e^x = 2^k e^r by exact exponent arithmetic (one more rounding only for a
/// subnormal result).
double exp(double x);

/// e^x - 1 for any double x, dimensionless, with full relative precision near 0.
/// Error ≤ 0.58 ulp (measured, see the test). NaN → NaN, +inf → +inf, -inf → -1,
/// x > 709.78 → +inf, x < -38.9 → -1 (the exact value rounds to -1), |x| < 2^-54 → x.
/// Method: exp's reduction and series, then expm1(x) = (2^k - 1) + 2^k (e^(r+c) - 1) summed
/// with Knuth's two-sum (TAOCP vol. 2, 4.2.2) and rounded once.
double expm1(double x);

/// √(x² + y²) for any doubles, in the unit of x and y, without spurious overflow or
/// underflow. Error ≤ 0.501 ulp for normal results, ≤ 0.75 ulp for subnormal ones (measured,
/// see the test).
/// ±inf in either argument → +inf (even with a NaN), else NaN → NaN.
/// Method: both scaled by the same exact power of two so the larger lies in [1, 2), then
/// h = sqrt(x² + y²) with one Newton correction h -= (h² - x² - y²)/(2h) whose residual is
/// computed exactly with Dekker's product (Veltkamp splitting) instead of an FMA: C. F. Borges,
/// "An Improved Algorithm for hypot(a, b)", ACM TOMS 47(1), 2021, arXiv:1904.09481 (algorithm
/// "corrected"); T. J. Dekker, "A floating-point technique for extending the available
/// precision", Numer. Math. 18, 1971.
double hypot(double x, double y);

/// The largest |x| (rad) sin and cos accept: 2^19·π/2 ≈ 823 549.66 rad, where x - nπ/2 is
/// still computed to 151 bits with a 20-bit n (a spinning body at 100 rad/s reaches it after
/// more than two hours).
inline constexpr double trig_max_argument = 0x1.921fb54442d18p+19;

/// sin x for x in rad, |x| ≤ trig_max_argument. Error ≤ 1 ulp (measured against long double,
/// tests/core/test_det_trig.cpp). NaN → NaN, ±inf → NaN, ±0 → ±0; never raises an FP
/// exception flag (±inf too); |x| > trig_max_argument (finite) throws std::domain_error
/// naming x.
/// Method: x = nπ/2 + r, |r| ≤ π/4 (about), by Cody–Waite reduction with π/2 in three 33-bit
/// parts and a 53-bit tail, the remainder kept as a double-double (the "medium" case of
/// fdlibm's e_rem_pio2.c, always to 151 bits); then sin or cos of r by fdlibm's k_sin.c and
/// k_cos.c minimax polynomials (degree 13 and 14 on [-π/4, π/4], relative error < 2^-58) with
/// their first-order correction for r's tail, chosen and signed by n mod 4. Sun Microsystems'
/// fdlibm 5.3 (1993); W. J. Cody, W. Waite, "Software Manual for the Elementary Functions", 1980.
double sin(double x);

/// cos x for x in rad, |x| ≤ trig_max_argument. Error ≤ 1 ulp (measured, see sin). NaN → NaN,
/// ±inf → NaN, cos(±0) = 1; |x| > trig_max_argument (finite) throws std::domain_error.
/// Method: as sin.
double cos(double x);

/// sin x and cos x for x in rad, |x| ≤ trig_max_argument, into `sine` and `cosine`: the same
/// bits as sin(x) and cos(x), from one reduction of x. NaN or ±inf → NaN in both (no FP
/// exception flag raised); |x| > trig_max_argument (finite) throws std::domain_error naming x,
/// with neither output written. Method: as sin.
void sincos(double x, double& sine, double& cosine);

/// arctan x in rad, in [-π/2, π/2], for any double x. Error ≤ 1 ulp (measured, see sin).
/// NaN → NaN, ±inf → ±π/2, ±0 → ±0.
/// Method: fdlibm's s_atan.c: |x| reduced to [0, 7/16] by atan x = atan c + atan((x - c)/(1 + cx))
/// for c = 1/2, 1, 3/2 or ∞ (atan c as a double-double), then an odd polynomial of degree 23.
double atan(double x);

/// The angle of the vector (x, y) in rad, in [-π, π]: atan(y/x) put in its quadrant. Error ≤ 2
/// ulp (measured, see sin). Follows C99 Annex F for zeros, infinities and NaN:
/// atan2(±0, +0) = ±0, atan2(±0, -0) = ±π, atan2(±0, x < 0) = ±π, atan2(y > 0, ±0) = π/2,
/// atan2(±inf, +inf) = ±π/4, atan2(±inf, -inf) = ±3π/4; NaN in either → NaN.
/// Method: fdlibm's e_atan2.c: atan(|y/x|), then π - (z - π_lo) and its reflections, with π as a
/// double-double.
double atan2(double y, double x);

}  // namespace fixstep::det
