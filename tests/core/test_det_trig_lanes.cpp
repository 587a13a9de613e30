// det::sincos_each (four angles in the lanes of a vector) and RotBatch (the shape phase's
// rotations in batches) against det::sincos and rot_of, one angle at a time: the same bits for
// every angle, at every SIMD level this CPU runs.
#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "det_trig_lanes.hpp"
#include "fixstep/core/bits.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/simd.hpp"
#include "rot_batch.hpp"

// A named namespace: this file shares a unity build with test_det_math.cpp.
namespace det_trig_lanes_test {

namespace det = fixstep::det;
using fixstep::bits_of;
using fixstep::SimdLevel;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double pi = std::numbers::pi;

/// Whether a and b are the same bits, or both NaN.
bool same(double a, double b) {
  return bits_of(a) == bits_of(b) || (std::isnan(a) && std::isnan(b));
}

/// Angles the lanes take (most) and angles that send their four one by one, mixed so that
/// fours of each kind and fours with one of the second among three of the first occur.
std::vector<double> angles() {
  std::vector<double> x;
  std::mt19937_64 rng(11);
  for (const auto& [lo, hi] : {std::pair{-2 * pi, 2 * pi}, std::pair{-1e4, 1e4},
                               std::pair{-det::trig_max_argument, det::trig_max_argument}}) {
    std::uniform_real_distribution<double> draw(lo, hi);
    for (int i = 0; i < 40'000; ++i) x.push_back(draw(rng));
  }
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int e = -60; e <= 19; ++e) {  // every magnitude, around 2^-27 (sin x = x) too
    for (int i = 0; i < 400; ++i) x.push_back(std::ldexp(unit(rng), e));
  }
  for (int n = -200'000; n < 200'000; n += 997) {  // near multiples of π/2: the second step
    const double m = n * (pi / 2);
    x.insert(x.end(), {m, std::nextafter(m, 0.0), std::nextafter(m, inf), 0.5, -1.25});
  }
  for (const double q : {pi / 4, -pi / 4, 0x1p-27, -0x1p-27}) {  // the reduction's edges
    x.insert(x.end(), {q, std::nextafter(q, 0.0), std::nextafter(q, inf), 2.0});
  }
  x.insert(x.end(), {0.0, -0.0, 1e-300, -5e-324, 3.0, inf, 1.0, -inf, 2.0, 3.0, nan, 4.0, 5.0});
  x.insert(x.end(), {det::trig_max_argument, -det::trig_max_argument, 6.0});  // 3 left over
  return x;
}

std::vector<SimdLevel> levels() {
  std::vector<SimdLevel> out;
  for (const SimdLevel l : {SimdLevel::baseline, SimdLevel::avx2, SimdLevel::avx512}) {
    if (fixstep::simd_supported(l)) out.push_back(l);
  }
  return out;
}

TEST(DetTrigLanes, EachAngleGetsTheBitsOfSincosAtEveryLevel) {
  const std::vector<double> x = angles();
  std::vector<double> want_sin(x.size()), want_cos(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) det::sincos(x[i], want_sin[i], want_cos[i]);
  for (const SimdLevel level : levels()) {
    std::vector<double> s(x.size(), 7.0), c(x.size(), 7.0);
    det::sincos_each(x, s, c, level);
    for (std::size_t i = 0; i < x.size(); ++i) {
      ASSERT_TRUE(same(s[i], want_sin[i]) && same(c[i], want_cos[i]))
          << std::hexfloat << "x = " << x[i] << " (" << i << ") at "
          << fixstep::simd_level_name(level) << ": " << s[i] << ", " << c[i] << " against "
          << want_sin[i] << ", " << want_cos[i];
    }
  }
}

// As sincos: NaN and ±inf give NaN without raising the invalid-operation flag, and a finite
// angle beyond trig_max_argument is refused.
TEST(DetTrigLanes, SpecialAnglesRaiseNoFlagAndTooLargeOnesAreRefused) {
  const std::vector<double> x{1.0, inf, 2.0, 3.0, -inf, nan, 0.5, 0.25};
  for (const SimdLevel level : levels()) {
    std::vector<double> s(x.size()), c(x.size());
    std::feclearexcept(FE_INVALID);
    det::sincos_each(x, s, c, level);
    EXPECT_FALSE(std::fetestexcept(FE_INVALID)) << fixstep::simd_level_name(level);
    EXPECT_TRUE(std::isnan(s[1]) && std::isnan(c[4]) && std::isnan(s[5]));
    const std::vector<double> beyond{1.0, 2.0, 1e7, 3.0};
    EXPECT_THROW(det::sincos_each(beyond, s, c, level), std::domain_error);
  }
}

// The shape phase's batches: rot_of's bits for each angle, beyond det's trig range too (rot_of
// reduces by 2π first), in the order added, across a flush when the batch fills.
TEST(RotBatch, GivesRotOfEachAngleInTheOrderAdded) {
  std::vector<double> x = angles();
  x.insert(x.end(), {1e7, -3e11, 1e12, 0.1});
  std::vector<std::uint32_t> order;
  std::vector<fixstep::detail::Rot> got(x.size());
  fixstep::detail::RotBatch batch;
  auto store = [&](std::uint32_t id, fixstep::detail::Rot q) { order.push_back(id), got[id] = q; };
  for (std::uint32_t i = 0; i < x.size(); ++i) batch.add(i, x[i], store);
  batch.flush(store);
  ASSERT_EQ(order.size(), x.size());
  for (std::uint32_t i = 0; i < x.size(); ++i) {
    ASSERT_EQ(order[i], i);
    const fixstep::detail::Rot want = fixstep::detail::rot_of(x[i]);
    ASSERT_TRUE(same(got[i].c, want.c) && same(got[i].s, want.s)) << std::hexfloat << x[i];
  }
}

}  // namespace det_trig_lanes_test
