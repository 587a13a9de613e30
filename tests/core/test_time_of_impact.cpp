// The time of impact of two discs (engine/core/src/disc_toi.hpp, internal): the quadratic
// path taken without relative acceleration gives the quartic path's stationary points to the
// bit and its roots to within a few doubles, each a sign change of the gap, and both find the
// closed-form contact time of two discs in straight-line motion; the slope's root from its closed
// form has the bisection's bits.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "disc_toi.hpp"
#include "segment_set.hpp"

namespace fixstep::detail {
namespace {

/// Two discs in straight-line relative motion, aimed within `miss` radii of head-on, from a gap
/// of up to 3 R, over a window of up to 1/30 s; c = (±0, ±0) as the world's motions give it.
RelativeMotion straight_line_motion(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double radius = scale * (0.5 + unit(rng));
  const double angle = 6.283185307179586 * unit(rng);
  const double dist = radius * (1.0 + 3.0 * unit(rng));
  const double px = dist * std::cos(angle), py = dist * std::sin(angle);
  const double speed = scale * 200.0 * unit(rng);
  const double aim = angle + 3.141592653589793 + 1.2 * (unit(rng) - 0.5);  // some miss
  const double sign_x = unit(rng) < 0.5 ? -0.0 : 0.0, sign_y = unit(rng) < 0.5 ? -0.0 : 0.0;
  return RelativeMotion{px,     py,    speed * std::cos(aim), speed * std::sin(aim), sign_x,
                        sign_y, radius};
}

std::uint64_t bits(double x) {
  return std::bit_cast<std::uint64_t>(x);
}

TEST(TimeOfImpact, TheQuadraticPathMeetsWhereTheQuarticPathDoes) {
  std::mt19937_64 rng(20261126);
  int roots = 0, stationary = 0;
  for (int i = 0; i < 200000; ++i) {
    const RelativeMotion m = straight_line_motion(rng, std::ldexp(1.0, i % 24 - 12));
    const double horizon = (1.0 / 30.0) * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const Quartic q = gap_quartic(m);
    ASSERT_TRUE(q.k[3] == 0.0 && q.k[4] == 0.0);
    const Quadratic f{q.k[0], q.k[1], q.k[2]};
    double from_quartic[4] = {}, from_quadratic[4] = {};
    const int n = stationary_points(q, horizon, from_quartic);
    ASSERT_EQ(stationary_points(f, horizon, from_quadratic), n) << "case " << i;
    for (int k = 0; k < n; ++k) ASSERT_EQ(bits(from_quadratic[k]), bits(from_quartic[k]));
    stationary += n;
    // The root: the quartic's bisected, the quadratic's from its closed form (falling_root),
    // both where f changes sign: the same to within a few doubles, and each a sign change.
    const double t = first_root(q, horizon);
    const double tq = first_root(f, horizon);
    ASSERT_EQ(bits(first_contact(m, horizon)), bits(tq)) << "case " << i;
    ASSERT_EQ(t <= horizon, tq <= horizon) << "case " << i;
    if (tq <= horizon) {
      ASSERT_NEAR(tq, t, 1e-12 * horizon) << "case " << i;
      ASSERT_LE(f(tq), 0.0) << "case " << i;
      const double below = std::nextafter(tq, 0.0);
      ASSERT_TRUE(below <= 0.0 || f(below) > 0.0) << "case " << i;
    }
    roots += t <= horizon;
  }
  // Enough of the cases find both f' and f's roots for the comparison to mean something.
  EXPECT_GT(roots, 20000);
  EXPECT_GT(stationary, 20000);
}

TEST(TimeOfImpact, TheSlopesRootFromItsClosedFormHasTheBisectionsBits) {
  // Quadratics whose slope's root lies anywhere from 2^-140 of the window to its end, over
  // magnitudes from 2^-60 to 2^60: slope_root, where it answers, gives bisect_down's bits.
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int answered = 0;
  for (int i = 0; i < 200000; ++i) {
    const double horizon = std::ldexp(0.5 + unit(rng), i % 9 - 8);
    const double root = horizon * std::ldexp(unit(rng), -static_cast<int>(140 * unit(rng)));
    const double k2 = std::ldexp(0.5 + unit(rng), static_cast<int>(120 * unit(rng)) - 60);
    const Quadratic f{1.0, -2.0 * k2 * root, k2};
    if (!(f.slope(0.0) < 0.0 && f.slope(horizon) > 0.0)) continue;
    const double want = bisect_down([&](double t) { return -f.slope(t); }, 0.0, horizon);
    const double got = slope_root(f, horizon);
    if (std::isnan(got)) continue;
    ASSERT_EQ(bits(got), bits(want)) << "case " << i;
    ++answered;
  }
  EXPECT_GT(answered, 120000);  // the rest: roots below 2^-100 of the window
}

TEST(TimeOfImpact, StraightLineMotionMeetsAtTheClosedFormTime) {
  // |p + w t| = R: t = (-(p·w) - sqrt((p·w)² - |w|²(|p|² - R²))) / |w|², the earlier root.
  std::mt19937_64 rng(7);
  int met = 0;
  for (int i = 0; i < 20000; ++i) {
    const RelativeMotion m = straight_line_motion(rng, 0.05);
    const double horizon = 1.0 / 60.0;
    const double pw = m.px * m.wx + m.py * m.wy, ww = m.wx * m.wx + m.wy * m.wy;
    const double pp = m.px * m.px + m.py * m.py - m.radius * m.radius;
    const double disc = pw * pw - ww * pp;
    const double t = first_contact(m, horizon);
    // Clear of grazing passes (a double root), where the root is ill-conditioned.
    if (pw < 0.0 && disc > 1e-6 * pw * pw) {
      const double exact = (-pw - std::sqrt(disc)) / ww;
      if (exact <= horizon * (1.0 - 1e-9)) {
        ASSERT_NEAR(t, exact, 1e-12 * horizon) << "case " << i;
        ++met;
        continue;
      }
      if (exact < horizon * (1.0 + 1e-9)) continue;  // at the window's end: either answer
    }
    if (pw >= 0.0 || disc < -1e-6 * pw * pw) {
      EXPECT_TRUE(std::isinf(t)) << "case " << i;
    }
  }
  EXPECT_GT(met, 2000);
}

// A disc touching a segment, closing on it within the tolerances (b = -1e-16 m/s, |b| <= vtol)
// and pressed into it by less than the rounding of its acceleration (c = -1e-14 m/s² against a
// tangential 10 m/s²): resting contact, no event. The leave-and-fall-back root -2b/c is then a
// time before the present (-0.02 s), which segment_impact returned, and the plane pass moved the
// disc's motion back in time with it.
TEST(SegmentImpact, ADiscAtRestWithinTheTolerancesHasNoEventBeforeNow) {
  SegmentDef def{.a = {-1.0, 0.0}, .b = {1.0, 0.0}};
  SegmentSet set;
  set.add(def);
  const SegmentMotion m{0.0, 0.1, 0.0, -1e-16, 10.0, -1e-14};
  SegmentTouch at;
  const double s = segment_impact(set.shapes()[0], m, 0.1, 1.0 / 60.0, 1e-15, 1e-9, at);
  EXPECT_TRUE(!std::isfinite(s) || (s >= 0.0 && s <= 1.0 / 60.0)) << s;
}

}  // namespace
}  // namespace fixstep::detail
