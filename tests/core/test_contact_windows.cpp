// A tick's disc impacts in windows (disc_windows.cpp): fast discs through a crowd, whose boxes
// swept over the whole tick overlap in hundreds of pairs a disc, are paired window by window.
// What must hold is what holds for one window: elastic impacts keep energy and momentum, no two
// discs end a tick overlapping, no disc leaves a box of elastic walls, one and two threads give
// the same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

constexpr double radius = 0.05;

WorldSettings elastic_world(int threads) {
  WorldSettings s{.dt = 1.0 / 60.0};
  s.contacts = ContactSettings{.restitution = 1.0, .friction = 0.0};
  s.threads = threads;
  return s;
}

BodyDef small_disc(Vec2 x, Vec2 v) {
  BodyDef b;
  b.body = Body{.mass = 1.0, .position = x, .velocity = v};
  b.collider = Collider{.radius = radius};
  return b;
}

// The crossing: two 40 x 40 grids of discs 0.5 m apart crossing at right angles at
// 1000 m/s, 16.7 m (333 radii) a tick at dt = 1/60 s. Its first tick scatters the discs in every
// direction at up to 1000 m/s; over the whole tick their boxes then overlapped in more than
// max_candidate_pairs pairs at tick 2 (a located fault, and before that a 4.8 s first tick).
void add_crossing(detail::WorldKernel<double>& w) {
  for (int side = 0; side < 2; ++side) {
    for (int i = 0; i < 40; ++i) {
      for (int j = 0; j < 40; ++j) {
        const Vec2 x = side == 0 ? Vec2{-20.0 + 0.5 * i, 0.5 * j} : Vec2{0.5 * i, -20.0 + 0.5 * j};
        (void)w.create_body(small_disc(x, side == 0 ? Vec2{1000.0, 0.0} : Vec2{0.0, 1000.0}));
      }
    }
  }
}

/// The deepest overlap of any two discs, m (brute force over every pair: an independent check of
/// the broadphase's).
double deepest_overlap(const detail::WorldKernel<double>& w) {
  const auto x = w.x(), y = w.y();
  double deepest = 0.0;
  for (std::size_t a = 0; a < x.size(); ++a) {
    for (std::size_t b = a + 1; b < x.size(); ++b) {
      const double d = std::sqrt((x[a] - x[b]) * (x[a] - x[b]) + (y[a] - y[b]) * (y[a] - y[b]));
      deepest = std::max(deepest, 2.0 * radius - d);
    }
  }
  return deepest;
}

double kinetic(const detail::WorldKernel<double>& w) {
  double e = 0.0;
  for (std::size_t k = 0; k < w.vx().size(); ++k) {
    e += 0.5 * (w.vx()[k] * w.vx()[k] + w.vy()[k] * w.vy()[k]);
  }
  return e;
}

// Six ticks of the crossing, elastic: energy and momentum kept to rounding, no two discs end a
// tick deeper than the slop (0.5 % of a radius), and the ticks ran in windows.
TEST(ContactWindows, TwoStreamsCrossingAtRightAnglesScatterWithNothingLost) {
  detail::WorldKernel<double> w(elastic_world(1));
  add_crossing(w);
  const double e0 = kinetic(w);
  std::size_t impacts = 0;
  for (int tick = 1; tick <= 6; ++tick) {
    w.step();
    ASSERT_FALSE(w.fault().has_value()) << "tick " << tick << ": " << w.fault()->cap;
    EXPECT_GT(w.contact_stats().windows, 1u) << tick;
    impacts += w.contact_stats().impacts;
    EXPECT_NEAR(kinetic(w), e0, 1e-12 * e0) << tick;
    double px = 0.0, py = 0.0;
    for (std::size_t k = 0; k < w.vx().size(); ++k) px += w.vx()[k], py += w.vy()[k];
    EXPECT_NEAR(px, 1.6e6, 1e-9 * 1.6e6) << tick;
    EXPECT_NEAR(py, 1.6e6, 1e-9 * 1.6e6) << tick;
    EXPECT_LE(deepest_overlap(w), 0.005 * radius) << tick;
  }
  EXPECT_GT(impacts, 1000u);  // they did meet
}

// The crossing inside a square of four elastic planes: the discs meet the walls among their
// impacts in every window (a wall event found in one window is resolved in a later one), none
// leaves the square (a disc resting on a wall may overlap it by the slop, 0.5 % of its radius),
// and the energy account balances with next to nothing dissipated (discs that end a tick
// touching a wall or each other are the resting solver's, whose impulses are not elastic).
TEST(ContactWindows, TheCrossingInsideElasticWallsStaysInside) {
  WorldSettings s = elastic_world(1);
  s.track_dissipation = true;
  detail::WorldKernel<double> w(s);
  add_crossing(w);
  constexpr double half = 21.0;  // the square [-21, 21]^2
  for (const Vec2 n : {Vec2{1.0, 0.0}, Vec2{-1.0, 0.0}, Vec2{0.0, 1.0}, Vec2{0.0, -1.0}}) {
    (void)w.add_plane(PlaneDef{.normal = n, .offset = -half, .restitution = 1.0});
  }
  const double e0 = w.energy().total();
  std::size_t walls = 0;
  for (int tick = 1; tick <= 6; ++tick) {
    w.step();
    ASSERT_FALSE(w.fault().has_value()) << "tick " << tick << ": " << w.fault()->cap;
    walls += w.contact_stats().wall_impacts;
    EXPECT_NEAR(w.energy().total() + w.dissipated_energy(), e0, 1e-12 * e0) << tick;
    EXPECT_LE(std::abs(w.dissipated_energy()), 1e-7 * e0) << tick;
    const double inside = half - radius + 0.005 * radius * (1.0 + 1e-6);
    for (std::size_t k = 0; k < w.x().size(); ++k) {
      ASSERT_LE(std::abs(w.x()[k]), inside) << "disc " << k << " tick " << tick;
      ASSERT_LE(std::abs(w.y()[k]), inside) << "disc " << k << " tick " << tick;
    }
    EXPECT_LE(deepest_overlap(w), 0.005 * radius) << tick;
  }
  EXPECT_GT(walls, 0u);
}

// A disc the plane pass bounced moves on its free motion until its first plane event and on the
// plane pass's motion from there: a window's box covers both. A formation far away (discs of
// 2 cm at 500 m/s, 417 radii a tick) makes 64 windows of 0.26 ms. Disc A comes at 500 m/s an
// axis diagonally at the wall x = 0 and bounces off it 0.02 ms into a window; disc B rests on
// A's way out, 0.15 m from where A bounces (met 0.07 ms later, in the same window), beyond the box
// of A's free motion in that window. Head-on, elastic and equal in mass: A stops and B leaves at
// A's velocity. With the box of the free motion alone, A went through B.
TEST(ContactWindows, AWindowsBoxCoversTheBounceOffAWall) {
  WorldSettings s = elastic_world(1);
  detail::WorldKernel<double> w(s);
  (void)w.add_plane(PlaneDef{.normal = {1.0, 0.0}, .offset = 0.0, .restitution = 1.0});
  for (int i = 0; i < 100; ++i) {  // rows of 100 whose boxes overlap 84 others each
    for (int j = 0; j < 4; ++j) {
      BodyDef d = small_disc({100.0 + 0.1 * i, 0.2 * j}, {500.0, 0.0});
      d.collider->radius = 0.02;
      (void)w.create_body(d);
    }
  }
  const double v = 500.0, r = radius, hit = 5.0 * s.dt / 64.0 + 0.02e-3;  // A meets the wall
  const Entity a = w.create_body(small_disc({r + v * hit, -v * hit}, {-v, v}));
  const double d = 0.15 / std::sqrt(2.0);  // B's centre from where A's meets the wall, each axis
  const Entity b = w.create_body(small_disc({r + d, d}, {0.0, 0.0}));
  w.step();
  ASSERT_FALSE(w.fault().has_value());
  EXPECT_EQ(w.contact_stats().windows, 64u);
  EXPECT_NEAR(w.body(a).velocity.x, 0.0, 1e-6);
  EXPECT_NEAR(w.body(a).velocity.y, 0.0, 1e-6);
  EXPECT_NEAR(w.body(b).velocity.x, v, 1e-6);
  EXPECT_NEAR(w.body(b).velocity.y, v, 1e-6);
}

// The windows split their boxes, the broadphase and the first predictions over two threads: the
// same bits as one.
TEST(ContactWindows, OneAndTwoThreadsGiveTheSameBits) {
  std::vector<std::uint64_t> hashes;
  for (const int threads : {1, 2}) {
    detail::WorldKernel<double> w(elastic_world(threads));
    add_crossing(w);
    for (int tick = 0; tick < 3; ++tick) w.step();
    ASSERT_FALSE(w.fault().has_value());
    hashes.push_back(w.state_hash());
  }
  EXPECT_EQ(hashes[0], hashes[1]);
}

}  // namespace
}  // namespace fixstep
