// A tick's disc impacts in two lanes on two threads (disc_lanes.cpp) against one lane: the same
// state, impacts and contact counts after every tick, for gases with elastic and inelastic
// walls, rolling discs and a kinematic disc ploughing through, with the lanes used and, where
// a path crosses the cut, run again in one lane. And which worlds share their disc passes
// with a second thread at all: from 256 awake discs, on threads = 2 always, on 0 (automatic)
// in the ticks its trials of two threads and one give two.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "disc_contacts.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "gather_warm.hpp"
#include "workers.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

using Kernel = detail::WorldKernel<double>;

struct GasOptions {
  std::size_t n = 6000;
  double wall_restitution = 1.0;
  bool rolling = false;
  bool plough = false;  ///< a kinematic disc crossing the box
  double speed = 1.0;   ///< the speeds' scale: 1-3 m/s times it
  double spread = 1.0;  ///< the cells' side's scale (1: 10 % of the area covered)
};

/// n discs of radius 5 cm at 10 % of a square box's area, one a cell, 1-3 m/s in random
/// directions (the benchmark's gas), on `threads` threads.
std::unique_ptr<Kernel> gas(const GasOptions& o, int threads) {
  WorldSettings s{.dt = 1.0 / 60.0, .threads = threads};
  s.contacts = ContactSettings{.restitution = 1.0, .friction = o.rolling ? 0.3 : 0.0};
  s.contacts->rolling = o.rolling;
  auto w = std::make_unique<Kernel>(s);
  const double r = 0.05, cell = o.spread * r * std::sqrt(3.14159265358979 / 0.1);
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(double(o.n))));
  const double width = cell * double(side);
  auto wall = [&](Vec2 normal, double offset) {
    w->add_plane({.normal = normal,
                  .offset = offset,
                  .restitution = o.wall_restitution,
                  .friction = o.rolling ? 0.3 : 0.0});
  };
  wall({0.0, 1.0}, 0.0), wall({1.0, 0.0}, 0.0), wall({-1.0, 0.0}, -width),
      wall({0.0, -1.0}, -width);
  std::uint64_t seed = o.n;
  auto unit = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return double(seed >> 11) * 0x1p-53;
  };
  for (std::size_t i = 0; i < o.n; ++i) {
    const double x = (double(i % side) + 0.5) * cell + (unit() - 0.5) * (cell - 2.2 * r);
    const double y = (double(i / side) + 0.5) * cell + (unit() - 0.5) * (cell - 2.2 * r);
    const double speed = o.speed * (1.0 + 2.0 * unit()), angle = 6.283185307179586 * unit();
    BodyDef d;
    d.body = {.mass = 1.0,
              .position = {x, y},
              .velocity = {speed * std::cos(angle), speed * std::sin(angle)}};
    d.collider = Collider{.radius = r};
    w->create_body(d);
  }
  if (o.plough) {
    BodyDef d;
    d.type = BodyType::kinematic;
    d.body = {.mass = 1.0, .position = {0.3 * width, 0.5 * width}, .velocity = {4.0, 0.5}};
    d.collider = Collider{.radius = 0.3};
    w->create_body(d);
  }
  return w;
}

/// Steps both `ticks` ticks: the same state hash, impacts (time, bodies, speed) and contact
/// counts after each; then the lanes' counts of the two-thread world.
void same_as_one_lane(const GasOptions& o, int ticks, const std::string& what,
                      std::uint64_t& lane_ticks, std::uint64_t& undone) {
  auto one = gas(o, 1), two = gas(o, 2);
  for (int t = 0; t < ticks; ++t) {
    one->step(), two->step();
    ASSERT_EQ(one->state_hash(), two->state_hash()) << what << ": differs after tick " << t + 1;
    const auto a = one->impacts(), b = two->impacts();
    ASSERT_EQ(a.size(), b.size()) << what << ", tick " << t + 1;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_TRUE(a[i].a == b[i].a && a[i].b == b[i].b && a[i].time == b[i].time &&
                  a[i].normal_speed == b[i].normal_speed)
          << what << ", tick " << t + 1 << ", impact " << i;
    }
    const ContactStats &p = one->contact_stats(), &q = two->contact_stats();
    ASSERT_EQ(p.touching, q.touching) << what << ", tick " << t + 1;
    ASSERT_EQ(p.wall_impacts, q.wall_impacts) << what << ", tick " << t + 1;
    ASSERT_EQ(p.held, q.held) << what << ", tick " << t + 1;
  }
  EXPECT_EQ(one->disc_contacts()->lane_ticks(), 0u) << what;  // one thread: one lane
  lane_ticks = two->disc_contacts()->lane_ticks();
  undone = two->disc_contacts()->lanes_undone();
}

TEST(ImpactLanes, AGasInTwoLanesStepsToTheBitsOfOne) {
  std::uint64_t lanes = 0, undone = 0;
  same_as_one_lane(GasOptions{}, 120, "gas of 6000", lanes, undone);
  // 1100 pairs a tick or so, far over min_lane_pairs: most ticks in two lanes, some run again
  // where a disc's new path crossed the cut.
  EXPECT_GT(lanes, 60u);
  EXPECT_GT(undone, 0u);
}

TEST(ImpactLanes, AThousandDiscGasInTwoLanesStepsToTheBitsOfOne) {
  // The benchmark's smallest gas: about 190 pairs a tick, over min_lane_pairs.
  std::uint64_t lanes = 0, undone = 0;
  GasOptions o;
  o.n = 1000;
  same_as_one_lane(o, 240, "gas of 1000", lanes, undone);
  EXPECT_GT(lanes, 120u);
}

TEST(ImpactLanes, InelasticWallsRollingDiscsAndAKinematicPloughStepToTheBitsOfOneLane) {
  std::uint64_t lanes = 0, undone = 0;
  GasOptions o;
  o.wall_restitution = 0.5, o.rolling = true;
  same_as_one_lane(o, 90, "rolling gas, inelastic walls", lanes, undone);
  EXPECT_GT(lanes, 10u);
  o = GasOptions{}, o.plough = true;
  same_as_one_lane(o, 90, "gas with a plough", lanes, undone);
  EXPECT_GT(lanes, 10u);
}

TEST(ImpactLanes, AFastSparseGasStepsToTheBitsOfOneLane) {
  // Paths of 13-40 cm a tick (8-24 m/s) in a gas at a quarter of the density: discs sent far
  // across the cut, where the lanes meet.
  std::uint64_t lanes = 0, undone = 0;
  GasOptions o;
  o.n = 8000, o.speed = 8.0, o.spread = 2.0;
  same_as_one_lane(o, 60, "fast sparse gas", lanes, undone);
  EXPECT_GT(lanes, 0u);
  EXPECT_GT(undone, 0u);
}

TEST(ImpactLanes, AGasOfMoreDiscsThanMinParallelCopiesStepsToTheBitsOfOneThread) {
  // From DiscContacts::min_parallel_copies discs (8192) the tick's start copies (the discs'
  // and the walls' contacts') go by halves on two threads: 9000 discs, the same state,
  // impacts and contact counts after every tick as on one.
  std::uint64_t lanes = 0, undone = 0;
  GasOptions o;
  o.n = 9000;
  ASSERT_GE(o.n, detail::DiscContacts<double>::min_parallel_copies);
  same_as_one_lane(o, 30, "gas of 9000", lanes, undone);
  EXPECT_GT(lanes, 0u);
}

/// 1200 touching discs of radius 5 cm, 30 rows of 40, resting on the ground (y = 0).
void resting_block(Kernel& k) {
  k.add_plane({.normal = {0.0, 1.0}, .offset = 0.0});
  const double r = 0.05;
  for (int row = 0; row < 30; ++row) {
    for (int col = 0; col < 40; ++col) {
      BodyDef d;
      d.body = {.mass = 1.0, .position = {r + 2.0 * r * col, r + 2.0 * r * row}};
      d.collider = Collider{.radius = r};
      d.gravity = Gravity{};
      k.create_body(d);
    }
  }
}

TEST(ImpactLanes, APileIsNotCutIntoLanesEveryTick) {
  // 1200 touching discs resting on the ground: their pairs (over 1024) make one group, which no
  // cut splits. Finding that costs a union-find over every pair: after four ticks in a row
  // without lanes they rest 16 ticks, then 32, then 64. Tried in 200 ticks at ticks 1-4, 21,
  // 54, 119 and 184: 8 (every tick without the rest).
  WorldSettings s{.dt = 1.0 / 60.0, .threads = 2};
  s.contacts = ContactSettings{.restitution = 0.0, .friction = 0.5};
  Kernel w(s);
  s.threads = 1;
  Kernel one(s);
  for (Kernel* k : {&w, &one}) resting_block(*k);
  for (int t = 0; t < 200; ++t) {
    w.step(), one.step();
    ASSERT_EQ(w.state_hash(), one.state_hash()) << "tick " << t + 1;
  }
  EXPECT_GE(w.contact_stats().candidate_pairs, 1024u);
  EXPECT_EQ(w.disc_contacts()->lane_ticks(), 0u);
  EXPECT_EQ(w.disc_contacts()->lane_cuts(), 8u);
}

TEST(ImpactLanes, AGasOfFewRestingContactsIsNotCutInHalves) {
  // Every world matching its warm start in the gather (as one of min_gather_warm_pairs
  // candidate pairs does), a gas of 2000 discs, whose resting contacts stay under the 1024 a
  // split takes, is never cut: not after the gather, nor before it (where the cut went unused,
  // a pass over every disc and a median a tick). The resting block, with more, is cut every
  // tick (before its gather from the second on; the same bits as after it: ContactSweeps).
  struct Restore {
    ~Restore() { detail::set_gather_warm_pairs(detail::min_gather_warm_pairs); }
  } restore;
  detail::set_gather_warm_pairs(0);
  GasOptions o;
  o.n = 2000;
  auto w = gas(o, 1);
  std::size_t touching = 0;
  for (int t = 0; t < 60; ++t) {
    w->step();
    touching = std::max(touching, w->contact_stats().touching);
  }
  EXPECT_GT(touching, 0u);
  EXPECT_LT(touching, 1024u);
  EXPECT_EQ(w->disc_contacts()->pile_cuts(), 0u);
  // A pile whose every tick has contacts enough to split.
  WorldSettings s{.dt = 1.0 / 60.0, .threads = 1};
  s.contacts = ContactSettings{.restitution = 0.0, .friction = 0.5};
  Kernel pile(s);
  resting_block(pile);
  for (int t = 0; t < 30; ++t) {
    pile.step();
    ASSERT_GE(pile.contact_stats().touching, 1024u) << "tick " << t + 1;
  }
  EXPECT_EQ(pile.disc_contacts()->pile_cuts(), 30u);
}

TEST(DiscThreadChoice, WorldsShareTheirDiscPassesFromMinParallelDiscs) {
  // Below 256 busy discs one thread on any setting (the same bits as threads = 1); from there
  // threads = 2 shares, and an automatic world's first tick is its trial's first, on two.
  const bool two_cores = detail::threads_for(0) == 2;
  constexpr std::size_t least = detail::DiscContacts<double>::min_parallel_discs;
  struct Case {
    std::size_t n;
    int threads;
    bool shares;
  };
  for (const Case c : {Case{least - 1, 0, false}, Case{least - 1, 2, false},
                       Case{least, 0, two_cores}, Case{300, 2, detail::threads_for(2) == 2}}) {
    GasOptions o;
    o.n = c.n;
    auto w = gas(o, c.threads), one = gas(o, 1);
    for (int t = 0; t < 5; ++t) {
      w->step(), one->step();
      ASSERT_EQ(w->state_hash(), one->state_hash()) << c.n << " discs, tick " << t + 1;
    }
    EXPECT_EQ(w->disc_contacts()->second_thread_started(), c.shares)
        << c.n << " discs, threads = " << c.threads;
    EXPECT_FALSE(one->disc_contacts()->second_thread_started());
  }
}

TEST(DiscThreadChoice, AnAutomaticWorldStepsItsTrialsToTheSameBitsAsOneThread) {
  // threads = 0 with 1000 discs: the world tries two threads and one, two ticks each
  // (thread_choice.hpp), then holds its choice and tries again; 60 ticks hold two trials (ticks
  // 1-12 and 29-40). Every tick the state hash and the number of impacts of one thread,
  // and over the ticks both counts used.
  GasOptions o;
  o.n = 1000;
  auto one = gas(o, 1), automatic = gas(o, 0);
  int on_two = 0, on_one = 0;
  for (int t = 0; t < 60; ++t) {
    one->step(), automatic->step();
    ASSERT_EQ(one->state_hash(), automatic->state_hash()) << "first differs after tick " << t + 1;
    ASSERT_EQ(one->impacts().size(), automatic->impacts().size()) << "tick " << t + 1;
    ++(automatic->disc_phase_count() == 2 ? on_two : on_one);
  }
  if (detail::threads_for(0) < 2) GTEST_SKIP() << "one core: an automatic world runs one thread";
  // Each trial's twelve ticks are six on each count; two trials end within the 60 ticks.
  EXPECT_GE(on_two, 12);
  EXPECT_GE(on_one, 12);
  EXPECT_TRUE(automatic->disc_contacts()->second_thread_started());
  EXPECT_FALSE(automatic->fault().has_value());
}

}  // namespace
}  // namespace fixstep
