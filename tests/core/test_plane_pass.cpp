// The plane pass's first look (world_contacts.cpp, find_near_planes): the bodies clear of every
// plane are told apart in blocks, plane by plane (by halves on two threads), and only the others
// go the whole way. The reference is a world that sends every body the whole way: the same
// world with one segment far from every body (the pass then tests every body against planes
// and segments together, and a body nothing touches keeps its integrated state).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "fixstep/core/segment.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

struct Box {
  double width = 0.0;
  bool far_segment = false;  ///< the reference: every body tested the whole way
};

/// n discs of radius 5 cm with gravity, 0.5-4 m/s in random directions, in a box of four walls
/// (restitution 0.8) with a fifth, tilted wall across one corner, on `threads` threads.
template <class Real>
std::unique_ptr<detail::WorldKernel<Real>> box_of_discs(std::size_t n, int threads,
                                                        const Box& box) {
  WorldSettings s{.dt = 1.0 / 60.0, .threads = threads};
  s.contacts = ContactSettings{.restitution = 0.9, .friction = 0.2};
  auto w = std::make_unique<detail::WorldKernel<Real>>(s);
  const double r = 0.05, cell = 0.3;
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(double(n))));
  const double width = cell * double(side);
  auto wall = [&](Vec2 normal, double offset) {
    w->add_plane({.normal = normal, .offset = offset, .restitution = 0.8, .friction = 0.2});
  };
  wall({0.0, 1.0}, 0.0), wall({1.0, 0.0}, 0.0), wall({-1.0, 0.0}, -width),
      wall({0.0, -1.0}, -width);
  wall({-0.6, -0.8}, -0.95 * (0.6 + 0.8) * width);  // across the top right corner
  if (box.far_segment) {
    (void)w->add_segment(SegmentDef{.a = {1e4, 1e4}, .b = {1e4 + 1.0, 1e4}});
  }
  std::uint64_t seed = n;
  auto unit = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return double(seed >> 11) * 0x1p-53;
  };
  for (std::size_t i = 0; i < n; ++i) {
    // Every fourth disc starts a hair from a wall: the blocks' test sees it near or clear.
    double x = (double(i % side) + 0.5) * cell, y = (double(i / side) + 0.5) * cell;
    if (i % 4 == 0) x = r * (1.0 + 1e-9 * double(i % 7)), y += 0.1 * (unit() - 0.5);
    const double speed = 0.5 + 3.5 * unit(), angle = 6.283185307179586 * unit();
    BodyDef d;
    d.body = {.mass = 1.0,
              .position = {x, y},
              .velocity = {speed * std::cos(angle), speed * std::sin(angle)}};
    d.gravity = Gravity{{0.0, -9.81}};
    d.collider = Collider{.radius = r};
    (void)w->create_body(d);
  }
  return w;
}

template <class Real>
void same_as_every_body_tested(int threads, const std::string& what) {
  const std::size_t n = 1500;
  auto blocks = box_of_discs<Real>(n, threads, Box{});
  auto whole = box_of_discs<Real>(n, threads, Box{.far_segment = true});
  std::uint64_t wall_impacts = 0;
  for (int t = 0; t < 60; ++t) {
    blocks->step(), whole->step();
    for (const auto& [a, b] : {std::pair{blocks->x(), whole->x()},
                               {blocks->y(), whole->y()},
                               {blocks->vx(), whole->vx()},
                               {blocks->vy(), whole->vy()}}) {
      ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()))
          << what << ": the state differs after tick " << t + 1;
    }
    ASSERT_EQ(blocks->contact_stats().wall_impacts, whole->contact_stats().wall_impacts)
        << what << ", tick " << t + 1;
    wall_impacts += blocks->contact_stats().wall_impacts;
  }
  EXPECT_FALSE(blocks->fault().has_value()) << what;
  // The walls did work: about 2000 wall impacts in 60 ticks (a pass that never found a body near
  // a wall would have none, and the discs would leave the box).
  EXPECT_GT(wall_impacts, 1000u) << what;
  const double top = *std::max_element(blocks->y().begin(), blocks->y().end());
  EXPECT_LT(top, 0.3 * std::ceil(std::sqrt(double(n)))) << what;
}

// Deliberate bugs checked: the blocks' end position read as the start position (a disc that
// reaches a wall from afar within a tick passes through: differs after tick 1), and the blocks
// telling every body clear (differs after tick 1).
TEST(PlanePass, TestingInBlocksGivesTheBitsOfTestingEveryBodyWhole) {
  same_as_every_body_tested<double>(1, "f64, one thread");
  same_as_every_body_tested<double>(2, "f64, two threads");
  same_as_every_body_tested<float>(1, "f32, one thread");
  same_as_every_body_tested<float>(2, "f32, two threads");
}

// A stop request is seen every 1024 colliders of the first look, on this thread (the bodies'
// half the second thread takes is as long as this thread's). Deliberate bug checked: no poll
// in the blocks' pass (0 polls).
TEST(PlanePass, TheFirstLookPollsAStopRequestEvery1024Colliders) {
  auto w = box_of_discs<double>(8192, 1, Box{});
  const std::uint64_t before = w->plane_polls();
  w->step();
  EXPECT_GE(w->plane_polls() - before, 8192u / 1024u - 1u);
}

}  // namespace
}  // namespace fixstep
