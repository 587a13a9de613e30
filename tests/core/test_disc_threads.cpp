// Disc worlds step to the same bits on one thread and on two, tick by tick, at sizes on both
// sides of every split: the broadphase (from 512 discs), the second thread's run and the
// passes by halves (from 256 discs), the shared first impact predictions (from 128 candidate
// pairs), the resting solver's halves (cut from 1024 touching pairs, and on two threads
// from there), and the fat boxes' pairs and each disc's list of pairs by halves (from 8192
// pairs). Each world here crosses the split it is there for (the counts of discs by
// construction, those of pairs asserted): a gas of elastic impacts, a pile of rolling discs on
// a polyline floor, a pile that falls asleep, a pile ploughed by a kinematic disc, a pile
// settling in its fat boxes; f64 and f32.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "disc_contacts.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "unchecked_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace disc_thread_tests {

/// SplitMix64 (Steele, Lea & Flood, 2014): the same numbers on every standard library.
struct Stream {
  std::uint64_t s;
  double unit() {  // in [0, 1)
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
};

BodyDef disc(Vec2 x, Vec2 v, double r, bool gravity) {
  BodyDef b;
  b.body = Body{.mass = 1.0, .position = x, .velocity = v};
  b.collider = Collider{.radius = r};
  if (gravity) b.gravity = Gravity{};
  return b;
}

void box_walls(WorldDef& def, double half, double e, double mu) {
  for (const Vec2 n : {Vec2{1, 0}, Vec2{-1, 0}, Vec2{0, 1}, Vec2{0, -1}}) {
    def.planes.push_back(PlaneDef{.normal = n, .offset = -half, .restitution = e, .friction = mu});
  }
}

/// n elastic discs (r = 5 cm) at 10 % area fraction in a closed box, 1-3 m/s.
WorldDef gas(std::size_t n) {
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{.restitution = 1.0, .friction = 0.0};
  const double r = 0.05, cell = r * std::sqrt(3.14159265358979 / 0.1);
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(double(n))));
  box_walls(def, 0.5 * cell * double(side), 1.0, 0.0);
  Stream rng{n};
  for (std::size_t i = 0; i < n; ++i) {
    const double x = (double(i % side) + 0.5 - 0.5 * double(side)) * cell;
    const double y = (double(i / side) + 0.5 - 0.5 * double(side)) * cell;
    const double jx = (rng.unit() - 0.5) * (cell - 2.2 * r),
                 jy = (rng.unit() - 0.5) * (cell - 2.2 * r);
    const double speed = 1.0 + 2.0 * rng.unit(), angle = 6.283185307179586 * rng.unit();
    def.bodies.push_back(
        disc({x + jx, y + jy}, {speed * std::cos(angle), speed * std::sin(angle)}, r, false));
  }
  return def;
}

/// n discs (r = 5 cm, a little jitter) dropped in rows into a box `width` wide with a floor.
WorldDef pile(std::size_t n, std::size_t per_row) {
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{.restitution = 0.0, .friction = 0.4};
  const double r = 0.05, half = 0.5 * 2.0 * r * double(per_row) + 0.01;
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .friction = 0.4});
  def.planes.push_back(PlaneDef{.normal = {1, 0}, .offset = -half, .friction = 0.4});
  def.planes.push_back(PlaneDef{.normal = {-1, 0}, .offset = -half, .friction = 0.4});
  Stream rng{n + 1};
  for (std::size_t i = 0; i < n; ++i) {
    const double x = -half + r + 0.005 + 2.0 * r * double(i % per_row) + 0.004 * rng.unit();
    const double y = r + 0.001 + 2.02 * r * double(i / per_row);
    def.bodies.push_back(disc({x, y}, {0.0, 0.0}, 0.98 * r, true));
  }
  return def;
}

/// Steps the world built at one thread and at two, `ticks` ticks, comparing the state hash
/// and the contact statistics on every tick; returns the largest statistics seen (of one).
ContactStats same_bits(const WorldDef& def, int ticks, const std::string& what) {
  WorldDef one_def = def, two_def = def;
  one_def.settings.threads = 1, two_def.settings.threads = 2;
  // Random piles start a hair overlapped (pushed apart in the first ticks): no check_overlaps.
  World one = test::unchecked_world(one_def), two = test::unchecked_world(two_def);
  ContactStats most;
  for (int t = 0; t < ticks; ++t) {
    one.step(), two.step();
    EXPECT_EQ(one.state_hash(), two.state_hash()) << what << ", tick " << t;
    const ContactStats &a = one.contact_stats(), &b = two.contact_stats();
    EXPECT_EQ(a.impacts, b.impacts) << what << ", tick " << t;
    EXPECT_EQ(a.touching, b.touching) << what << ", tick " << t;
    EXPECT_EQ(a.sleeping, b.sleeping) << what << ", tick " << t;
    EXPECT_EQ(a.woken, b.woken) << what << ", tick " << t;
    if (one.state_hash() != two.state_hash()) break;  // one message, not one a tick
    most.candidate_pairs = std::max(most.candidate_pairs, a.candidate_pairs);
    most.impacts = std::max(most.impacts, a.impacts);
    most.touching = std::max(most.touching, a.touching);
    most.sleeping = std::max(most.sleeping, a.sleeping);
    most.woken = std::max(most.woken, a.woken);
  }
  return most;
}

TEST(DiscThreads, AGasStepsToTheSameBitsOnTwoThreads) {
  // 400 discs: the second thread's run, without the broadphase's split or the shared
  // predictions; 1500: with the predictions shared and the impacts in two lanes.
  for (const std::size_t n : {std::size_t{400}, std::size_t{1500}, std::size_t{6000}}) {
    const ContactStats most = same_bits(gas(n), 30, "gas of " + std::to_string(n));
    EXPECT_GT(most.impacts, n / 20) << n;  // impacts resolved at their time, many a tick
    constexpr std::size_t shared = detail::DiscContacts<double>::min_parallel_pairs;
    if (n > 1000) {
      EXPECT_GT(most.candidate_pairs, shared) << n;  // the predictions shared
    } else {
      EXPECT_LT(most.candidate_pairs, shared) << n;
    }
  }
}

TEST(DiscThreads, AFloatGasStepsToTheSameBitsOnTwoThreads) {
  WorldDef def = gas(5000);
  def.precision = Precision::f32;
  EXPECT_GT(same_bits(def, 20, "f32 gas").impacts, 100u);
}

TEST(DiscThreads, RollingDiscsOnAPolylineStepToTheSameBitsOnTwoThreads) {
  WorldDef def = pile(4000, 80);
  def.settings.contacts->rolling = true;
  def.planes.erase(def.planes.begin());  // the floor: a polyline of gentle slopes instead
  std::vector<Vec2> floor;
  for (int i = 0; i <= 16; ++i) floor.push_back({-4.4 + 0.55 * i, i % 2 == 0 ? -0.02 : 0.02});
  def.add_polyline(floor, 0.0, 0.4);
  const ContactStats most = same_bits(def, 50, "rolling pile");
  EXPECT_GT(most.touching, 1024u);  // the resting solver's halves on two threads
}

TEST(DiscThreads, ASmallPileStepsToTheSameBitsOnTwoThreads) {
  // Just past the cut: the resting solver's halves on two threads, the broadphase split.
  const ContactStats most = same_bits(pile(600, 30), 60, "pile of 600");
  EXPECT_GT(most.touching, 1024u);
}

TEST(DiscThreads, APileThatFallsAsleepStepsToTheSameBitsOnTwoThreads) {
  WorldDef def = pile(1800, 45);
  def.settings.contacts->sleep = true;
  def.settings.contacts->sleep_speed = 0.5;  // the whole pile asleep within the test
  def.settings.contacts->sleep_time = 0.1;
  def.bodies.push_back(disc({0.0, 14.0}, {0.0, 0.0}, 0.1, true));  // wakes it, later
  const ContactStats most = same_bits(def, 150, "sleeping pile");
  EXPECT_GT(most.sleeping, 900u);
  EXPECT_GT(most.woken, 0u);
  EXPECT_GT(most.touching, 1024u);
}

TEST(DiscThreads, APilePloughedByAKinematicDiscStepsToTheSameBitsOnTwoThreads) {
  WorldDef def = pile(4000, 80);
  BodyDef plough = disc({0.3, 5.6}, {0.0, -3.0}, 0.25, false);  // down into the pile
  plough.type = BodyType::kinematic;
  def.bodies.push_back(plough);
  const ContactStats most = same_bits(def, 50, "ploughed pile");
  EXPECT_GT(most.touching, 1024u);
}

TEST(DiscThreads, ASettlingPileRecyclesItsPairsToTheSameBitsOnTwoThreads) {
  // Past DiscContacts::min_parallel_copies fat pairs the two threads filter the fat boxes'
  // pairs by halves (disc_fat.cpp), and past as many candidate pairs they build each disc's
  // list of pairs by halves (incident_lists()): the same pairs, in the same order.
  using Kernel = detail::WorldKernel<double>;
  const WorldDef def = pile(4000, 80);
  auto world = [&](int threads) {
    WorldSettings s = def.settings;
    s.threads = threads;
    auto w = std::make_unique<Kernel>(s);
    for (const PlaneDef& p : def.planes) w->add_plane(p);
    for (const BodyDef& b : def.bodies) w->create_body(b);
    return w;
  };
  auto one = world(1), two = world(2);
  std::size_t most_fat = 0, most_pairs = 0;
  for (int t = 0; t < 40; ++t) {
    one->step(), two->step();
    ASSERT_EQ(one->state_hash(), two->state_hash()) << "settling pile, tick " << t + 1;
    const auto a = one->disc_contacts()->candidate_pairs(),
               b = two->disc_contacts()->candidate_pairs();
    ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()))
        << "settling pile, tick " << t + 1 << ": " << a.size() << " and " << b.size() << " pairs";
    most_fat = std::max(most_fat, two->disc_contacts()->fat_pairs());
    most_pairs = std::max(most_pairs, two->disc_contacts()->candidate_pairs().size());
  }
  EXPECT_GE(most_fat, detail::DiscContacts<double>::min_parallel_copies) << most_fat;
  EXPECT_GE(most_pairs, detail::DiscContacts<double>::min_parallel_copies);
}

TEST(DiscThreads, ThreadsUsedSaysWhetherATickSharedItsPasses) {
  // From 256 awake discs a tick on two threads shares its disc passes with the second thread;
  // below that, and on one thread, it runs them all on the stepping thread.
  struct Case {
    std::size_t discs;
    int threads, used;
  };
  for (const Case c : {Case{400, 2, 2}, Case{400, 1, 1}, Case{100, 2, 1}}) {
    WorldDef def = gas(c.discs);
    def.settings.threads = c.threads;
    World w = test::unchecked_world(def);
    for (int t = 0; t < 3; ++t) {
      w.step();
      EXPECT_EQ(w.threads_used(), c.used) << c.discs << " discs on " << c.threads << ", tick " << t;
    }
  }
}

}  // namespace disc_thread_tests
}  // namespace fixstep
