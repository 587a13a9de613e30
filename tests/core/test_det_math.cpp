// fixstep::det exp, expm1, hypot (det_math.hpp): accuracy against x86's 80-bit long
// double libm (64-bit significand, its own error about 2^-11 of a double ulp) over the ranges
// the engine uses, IEEE special values, and golden bit patterns that any platform computing
// differently (a libm call, an FMA contraction, FTZ) fails.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "det_golden_cases.hpp"
#include "fixstep/core/bits.hpp"
#include "fixstep/core/det_math.hpp"

namespace {

using fixstep::det::exp;
using fixstep::det::expm1;
using fixstep::det::hypot;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// |got - ref| in units of the double ulp at ref (subnormal ulp 2^-1074 below the normals).
double ulps(double got, long double ref) {
  if (static_cast<long double>(got) == ref) return 0.0;
  int e = 0;
  std::frexp(static_cast<double>(std::fabs(ref)), &e);  // |ref| in [2^(e-1), 2^e)
  const long double ulp = std::ldexp(1.0L, std::max(e - 53, -1074));
  return static_cast<double>(std::fabs(static_cast<long double>(got) - ref) / ulp);
}

using fixstep::bits_of;
using fixstep::double_from_bits;

/// Largest error in ulps of f against ref over n arguments drawn by draw(rng).
template <class F, class Ref, class Draw>
double worst(F f, Ref ref, Draw draw, int n = 300'000) {
  std::mt19937_64 rng(23);
  double w = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = draw(rng);
    w = std::max(w, ulps(f(x), ref(x)));
  }
  return w;
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// ±2^u with u uniform in [lo, hi): log-uniform magnitudes.
double log_uniform(std::mt19937_64& rng, double lo, double hi, bool negative) {
  const double m = std::exp2(uniform(rng, lo, hi));
  return negative ? -m : m;
}

auto exp_ref = [](double x) { return std::exp(static_cast<long double>(x)); };
auto expm1_ref = [](double x) { return std::expm1(static_cast<long double>(x)); };

// Damping-flow factors e^{-γτ} (world_step.cpp) and link flows expm1(-μτ) (world_coupled.cpp):
// γτ ≥ 0 of any size the guard lets through (tiny for light damping, up to hundreds when the
// damping is stiff; e^{-745} underflows). Measured max: exp 0.52 ulp (normal results), 0.75 ulp
// (subnormal results), expm1 0.58 ulp; asserted with a margin to the next representable bound.
TEST(DetMath, ExpIsWithinHalfAnUlpAndABitOverTheDampingRange) {
  auto f = [](double x) { return exp(x); };
  EXPECT_LE(worst(f, exp_ref, [](auto& r) { return uniform(r, -708.0, 709.7); }), 0.53);
  EXPECT_LE(worst(f, exp_ref, [](auto& r) { return uniform(r, -2.0, 0.0); }), 0.53);
  EXPECT_LE(worst(f, exp_ref, [](auto& r) { return log_uniform(r, -60.0, 9.0, true); }), 0.53);
  EXPECT_LE(worst(f, exp_ref, [](auto& r) { return log_uniform(r, -60.0, 0.0, false); }), 0.53);
  // Subnormal results: rounded twice (the reduced value, then its scaling).
  EXPECT_LE(worst(f, exp_ref, [](auto& r) { return uniform(r, -745.1, -708.4); }), 0.76);
}

TEST(DetMath, Expm1IsWithinAbout0_58UlpIncludingTinyArguments) {
  auto f = [](double x) { return expm1(x); };
  EXPECT_LE(worst(f, expm1_ref, [](auto& r) { return uniform(r, -3.0, 3.0); }), 0.6);
  EXPECT_LE(worst(f, expm1_ref, [](auto& r) { return uniform(r, -40.0, 709.7); }), 0.6);
  EXPECT_LE(worst(f, expm1_ref, [](auto& r) { return log_uniform(r, -1074, 3.0, true); }), 0.6);
  EXPECT_LE(worst(f, expm1_ref, [](auto& r) { return log_uniform(r, -1074, 3.0, false); }), 0.6);
}

// Rest lengths, plane normals, pick distances: spacings of metres, and the full range down to
// subnormals and up to the edge of overflow. Measured max 0.5005 ulp (normal), 0.75 (subnormal).
TEST(DetMath, HypotIsWithinHalfAnUlpAndABitOverWideMagnitudes) {
  std::mt19937_64 rng(23);
  double near = 0.0, wide = 0.0, tiny = 0.0;
  for (int i = 0; i < 300'000; ++i) {
    const double x = uniform(rng, -2.0, 2.0), y = uniform(rng, -2.0, 2.0);
    near = std::max(near, ulps(hypot(x, y), std::sqrt((long double)x * x + (long double)y * y)));
    // Normal results from 2^-1020 to just below overflow; ratios up to 2^40.
    const double a = log_uniform(rng, -1020.0, 1023.4, i % 2 == 0);
    const double b = a * std::exp2(uniform(rng, -40.0, 0.0));
    const long double ref = std::sqrt((long double)a * a + (long double)b * b);
    if (ref <= DBL_MAX) wide = std::max(wide, ulps(hypot(a, b), ref));
    const double s = log_uniform(rng, -1074.0, -1022.0, false);
    const double t = log_uniform(rng, -1074.0, -1022.0, true);
    tiny = std::max(tiny, ulps(hypot(s, t), std::sqrt((long double)s * s + (long double)t * t)));
  }
  EXPECT_LE(near, 0.501);
  EXPECT_LE(wide, 0.501);
  EXPECT_LE(tiny, 0.76);
  EXPECT_EQ(hypot(DBL_MAX, DBL_MAX), inf);                                   // overflows as it must
  EXPECT_EQ(hypot(DBL_MAX / 2, DBL_MAX / 2), DBL_MAX / 2 * std::sqrt(2.0));  // no spurious one
  EXPECT_EQ(hypot(3e-320, 4e-320), 5e-320);  // subnormals, no spurious underflow
  EXPECT_EQ(hypot(3.0, 4.0), 5.0);
}

TEST(DetMath, SpecialValuesFollowC99AnnexF) {
  EXPECT_TRUE(std::isnan(exp(nan)));
  EXPECT_EQ(exp(inf), inf);
  EXPECT_EQ(bits_of(exp(-inf)), bits_of(0.0));
  EXPECT_EQ(exp(0.0), 1.0);
  EXPECT_EQ(exp(-0.0), 1.0);
  EXPECT_EQ(exp(710.0), inf);
  EXPECT_LT(exp(709.78), inf);  // 1.7964e308, just below DBL_MAX
  EXPECT_EQ(exp(-746.0), 0.0);
  EXPECT_EQ(exp(-745.0), 4.9406564584124654e-324);  // the least subnormal
  EXPECT_TRUE(std::isnan(expm1(nan)));
  EXPECT_EQ(expm1(inf), inf);
  EXPECT_EQ(expm1(-inf), -1.0);
  EXPECT_EQ(bits_of(expm1(-0.0)), bits_of(-0.0));
  EXPECT_EQ(expm1(0x1p-1074), 0x1p-1074);
  EXPECT_EQ(expm1(-50.0), -1.0);
  EXPECT_EQ(expm1(710.0), inf);
  EXPECT_EQ(hypot(inf, nan), inf);
  EXPECT_EQ(hypot(nan, -inf), inf);
  EXPECT_TRUE(std::isnan(hypot(nan, 1.0)));
  EXPECT_EQ(bits_of(hypot(-0.0, 0.0)), bits_of(0.0));
  EXPECT_EQ(hypot(-5.0, 0.0), 5.0);
}

// Golden bits: input → output as computed here. A platform whose det functions compute
// differently (a libm call slipped in, an FMA contraction, FTZ/DAZ) fails this on its own.
// The first four are the causes: exp(-2.73/120) (tests/scenes/cross/damped_exp.toml),
// where glibc's FMA and non-FMA exp disagree; hypot(0.15, -0.25), where glibc's hypot is 1 ulp
// off the correctly rounded value; and the two shear diagonals of
// tests/scenes/cross/hypot_rest.toml (spacing 0.10 x -0.15 m): glibc aarch64 and musl
// (emscripten) round the first 1 ulp high (0x1.71355d04de19p-3), musl the second 1 ulp low
// (0x1.71355d04de18ep-3); glibc x86-64 rounds both correctly.
TEST(DetMath, GoldenBitPatterns) {
  int checked = 0;
  for (const fixstep::det_golden::Case& c : fixstep::det_golden::cases) {
    EXPECT_EQ(fixstep::det_golden::result_bits(c), c.out)
        << "f " << c.f << " x " << std::hexfloat << double_from_bits(c.x) << " y "
        << double_from_bits(c.y);
    ++checked;
  }
  EXPECT_GE(checked, 40);
}

}  // namespace
