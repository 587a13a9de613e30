// fixstep::det sin, cos, atan, atan2 (det_math.hpp) against the 80-bit long double libm
// (x86-64; its own error is about 2^-11 of a double ulp) over the angles game rules use, up to
// the largest accepted argument; C99 Annex F special values; Vec2's arithmetic. Their golden
// bit patterns, checked on aarch64 and wasm32 too, are in det_math_golden.inc.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/types.hpp"

// A named namespace: this file shares a unity build with test_det_math.cpp.
namespace det_trig_test {

namespace det = fixstep::det;
using fixstep::bits_of;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double pi = std::numbers::pi;

/// |got - ref| in units of the double ulp at ref.
double ulps(double got, long double ref) {
  if (static_cast<long double>(got) == ref) return 0.0;
  int e = 0;
  std::frexp(static_cast<double>(std::fabs(ref)), &e);
  const long double ulp = std::ldexp(1.0L, std::max(e - 53, -1074));
  return static_cast<double>(std::fabs(static_cast<long double>(got) - ref) / ulp);
}

/// Largest error in ulps of f against ref over n arguments drawn uniformly from [lo, hi].
template <class F, class Ref>
double worst(F f, Ref ref, double lo, double hi, int n = 200'000) {
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<double> draw(lo, hi);
  double w = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = draw(rng);
    w = std::max(w, ulps(f(x), ref(x)));
  }
  return w;
}

auto sin_ref = [](double x) { return std::sin(static_cast<long double>(x)); };
auto cos_ref = [](double x) { return std::cos(static_cast<long double>(x)); };
auto atan_ref = [](double x) { return std::atan(static_cast<long double>(x)); };
auto det_sin = [](double x) { return det::sin(x); };
auto det_cos = [](double x) { return det::cos(x); };
auto det_atan = [](double x) { return det::atan(x); };

// Angles of a turn or two (aiming, orbits), of minutes of spin at 100 rad/s, and up to the
// largest accepted argument. Measured max over 2·10⁶ arguments each: sin 0.78, cos 0.77 ulp
// (without the reduced argument's tail: 1.47).
TEST(DetTrig, SinAndCosAreWithinOneUlpUpToTheLargestAcceptedArgument) {
  for (const auto& [lo, hi] : {std::pair{-2 * pi, 2 * pi}, std::pair{-1e4, 1e4},
                               std::pair{-det::trig_max_argument, det::trig_max_argument}}) {
    EXPECT_LE(worst(det_sin, sin_ref, lo, hi), 1.0) << "[" << lo << ", " << hi << "]";
    EXPECT_LE(worst(det_cos, cos_ref, lo, hi), 1.0) << "[" << lo << ", " << hi << "]";
  }
  // Near multiples of π/2, where the reduction cancels most bits: 355/113-style neighbours.
  for (int n = 1; n < 200'000; n += 997) {
    const double x = std::nextafter(n * (pi / 2), 0.0);
    EXPECT_LE(ulps(det::sin(x), sin_ref(x)), 1.0) << x;
    EXPECT_LE(ulps(det::cos(x), cos_ref(x)), 1.0) << x;
  }
  // Tiny angles: sin x = x and cos x = 1 to the last bit.
  EXPECT_EQ(det::sin(1e-20), 1e-20);
  EXPECT_EQ(det::cos(1e-20), 1.0);
}

// sincos: one reduction for both, the same bits as sin and cos in every quadrant, near the
// multiples of π/2 where the reduction takes its second and third steps, at the special values,
// and the same refusal beyond the largest accepted argument.
TEST(DetTrig, SincosGivesTheBitsOfSinAndCos) {
  auto same = [](double x) {
    double s = 0.0, c = 0.0;
    det::sincos(x, s, c);
    return bits_of(s) == bits_of(det::sin(x)) && bits_of(c) == bits_of(det::cos(x));
  };
  std::mt19937_64 rng(7);
  for (const auto& [lo, hi] :
       {std::pair{-2 * pi, 2 * pi}, std::pair{-det::trig_max_argument, det::trig_max_argument}}) {
    std::uniform_real_distribution<double> draw(lo, hi);
    for (int i = 0; i < 100'000; ++i) {
      const double x = draw(rng);
      ASSERT_TRUE(same(x)) << x;
    }
  }
  for (int n = -200'000; n < 200'000; n += 997) {
    const double x = n * (pi / 2);
    ASSERT_TRUE(same(x) && same(std::nextafter(x, 0.0)) && same(std::nextafter(x, inf))) << x;
  }
  for (const double x : {0.0, -0.0, 1e-300, -5e-324, pi / 4, -pi / 4, inf, -inf, nan}) {
    double s = 0.0, c = 0.0;
    det::sincos(x, s, c);
    EXPECT_TRUE(bits_of(s) == bits_of(det::sin(x)) || (std::isnan(s) && std::isnan(det::sin(x))))
        << x;
    EXPECT_TRUE(bits_of(c) == bits_of(det::cos(x)) || (std::isnan(c) && std::isnan(det::cos(x))))
        << x;
  }
  double s = 7.0, c = 7.0;  // refused: neither written
  EXPECT_THROW(det::sincos(1e7, s, c), std::domain_error);
  EXPECT_EQ(s, 7.0);
  EXPECT_EQ(c, 7.0);
}

// Measured max over 2·10⁶ arguments: atan 0.75, atan2 1.42 ulp (directions at every magnitude).
TEST(DetTrig, AtanIsWithinOneUlpAndAtan2WithinTwoOverEveryMagnitude) {
  EXPECT_LE(worst(det_atan, atan_ref, -4.0, 4.0), 1.0);
  EXPECT_LE(worst(det_atan, atan_ref, -1e6, 1e6), 1.0);
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), scale(-60.0, 60.0);
  double w = 0.0;
  for (int i = 0; i < 200'000; ++i) {
    const double y = unit(rng) * std::exp2(scale(rng)), x = unit(rng) * std::exp2(scale(rng));
    w = std::max(w, ulps(det::atan2(y, x), std::atan2(static_cast<long double>(y), x)));
  }
  EXPECT_LE(w, 2.0);
}

TEST(DetTrig, SpecialValuesFollowC99AnnexF) {
  EXPECT_EQ(bits_of(det::sin(-0.0)), bits_of(-0.0));
  EXPECT_EQ(det::cos(-0.0), 1.0);
  EXPECT_TRUE(std::isnan(det::sin(inf)));
  EXPECT_TRUE(std::isnan(det::cos(-inf)));
  EXPECT_TRUE(std::isnan(det::sin(nan)));
  EXPECT_EQ(det::atan(inf), pi / 2);
  EXPECT_EQ(det::atan(-inf), -pi / 2);
  EXPECT_EQ(bits_of(det::atan(-0.0)), bits_of(-0.0));
  EXPECT_TRUE(std::isnan(det::atan(nan)));
  EXPECT_EQ(det::atan(1.0), pi / 4);
  EXPECT_EQ(bits_of(det::atan2(0.0, 0.0)), bits_of(0.0));
  EXPECT_EQ(bits_of(det::atan2(-0.0, 0.0)), bits_of(-0.0));
  EXPECT_EQ(det::atan2(0.0, -0.0), pi);
  EXPECT_EQ(det::atan2(-0.0, -1.0), -pi);
  EXPECT_EQ(det::atan2(1.0, 0.0), pi / 2);
  EXPECT_EQ(det::atan2(-1.0, -0.0), -pi / 2);
  EXPECT_EQ(det::atan2(inf, inf), pi / 4);
  EXPECT_EQ(det::atan2(-inf, -inf), -3 * pi / 4);
  EXPECT_EQ(bits_of(det::atan2(-1.0, inf)), bits_of(-0.0));
  EXPECT_EQ(det::atan2(1.0, -inf), pi);
  EXPECT_EQ(det::atan2(inf, 1.0), pi / 2);
  EXPECT_TRUE(std::isnan(det::atan2(nan, 1.0)));
  EXPECT_TRUE(std::isnan(det::atan2(1.0, nan)));
  EXPECT_EQ(det::atan2(1.0, 1.0), pi / 4);
  EXPECT_EQ(det::atan2(1.0, -1.0), 3 * pi / 4);
  EXPECT_EQ(det::atan2(1e300, 1e-300), pi / 2);  // |y/x| overflows: the angle is π/2
}

TEST(DetTrig, AnAngleBeyondTheLargestAcceptedArgumentIsRefusedNotGuessed) {
  EXPECT_NO_THROW((void)det::sin(det::trig_max_argument));
  EXPECT_NO_THROW((void)det::cos(-det::trig_max_argument));
  try {
    (void)det::sin(1e7);
    ADD_FAILURE() << "sin(1e7) returned";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("10000000"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)det::cos(-1e300), std::domain_error);
}

TEST(Vec2, ArithmeticIsComponentWiseAndLengthIsDetHypot) {
  using fixstep::Vec2;
  constexpr Vec2 a{3.0, -4.0}, b{0.5, 2.0};
  static_assert(a + b == Vec2{3.5, -2.0});
  static_assert(a - b == Vec2{2.5, -6.0});
  static_assert(-a == Vec2{-3.0, 4.0});
  static_assert(2.0 * a == Vec2{6.0, -8.0} && a * 2.0 == 2.0 * a);
  static_assert(a / 2.0 == Vec2{1.5, -2.0});
  static_assert(fixstep::dot(a, b) == 1.5 - 8.0);
  static_assert(fixstep::cross(a, b) == 6.0 + 2.0);
  static_assert(fixstep::cross(Vec2{1, 0}, Vec2{0, 1}) == 1.0);  // counter-clockwise: positive
  Vec2 c = a;
  c += b, c -= a, c *= 4.0;
  EXPECT_EQ(c, (Vec2{2.0, 8.0}));
  EXPECT_EQ(fixstep::length(a), 5.0);
  const Vec2 odd{0.1, -0.7};
  EXPECT_EQ(bits_of(fixstep::length(odd)), bits_of(det::hypot(0.1, -0.7)));
  EXPECT_EQ(fixstep::length(Vec2{1e300, 1e300}), det::hypot(1e300, 1e300));  // no overflow
}

}  // namespace det_trig_test
