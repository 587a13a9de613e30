// What the resting solver reports of its own work (ContactStats: velocity and push-out
// iterations, whether they finished early) and where a tick's time went (World::profile(),
// StepProfile): a resting disc converges in an iteration or two, a column that the iterations
// cannot settle in one tick says so and settles over the next ticks, a world without touching
// discs runs none, the profile is measured only with disc contacts; the iteration counts are
// settings (checked), a pile split in halves for two threads steps to the same bits on one, the
// warm start matched as the contacts are gathered or by a pass after it gives the same bits, and
// so does the cut's median sought near the last one or among every coordinate.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "gather_warm.hpp"
#include "median_window.hpp"

namespace fixstep {
namespace contact_profile_tests {

WorldDef ground_world() {
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{.restitution = 0.0, .friction = 0.3};
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .friction = 0.3});
  return def;
}

BodyDef falling_disc(Vec2 x, double r) {
  BodyDef b;
  b.body = Body{.mass = 1.0, .position = x, .velocity = {}};
  b.collider = Collider{.radius = r};
  b.gravity = Gravity{};
  return b;
}

/// `rows` rows of `columns` discs (r = 4.9 cm, 10 cm apart, each shifted by up to 4 mm) on the
/// ground between two walls 10 cm a column apart: a pile that settles within two seconds.
WorldDef walled_pile(int rows, int columns) {
  WorldDef def = ground_world();
  const double half_width = 0.05 * columns;
  def.planes.push_back(PlaneDef{.normal = {1, 0}, .offset = -half_width, .friction = 0.3});
  def.planes.push_back(PlaneDef{.normal = {-1, 0}, .offset = -half_width, .friction = 0.3});
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) {
      const double jitter = 0.001 * double((i * 7 + j * 3) % 5);
      const double x = -half_width + 0.05 + 0.1 * j + jitter;
      def.bodies.push_back(falling_disc({x, 0.05 + 0.1 * i}, 0.049));
    }
  }
  return def;
}

// One disc resting on the ground: a single contact, warm started, is solved by the first sweep
// and the second finds nothing left to change (converged at 2, or at 1 when the warm start was
// already exact); nothing is deeper than the slop.
TEST(ContactSweeps, ADiscRestingOnTheGroundConvergesInTwoSweeps) {
  WorldDef def = ground_world();
  def.bodies.push_back(falling_disc({0.0, 0.1}, 0.1));
  World w(def);
  for (int i = 0; i < 120; ++i) w.step();
  const ContactStats& s = w.contact_stats();
  ASSERT_EQ(s.touching, 1u);
  EXPECT_TRUE(s.velocity_converged);
  EXPECT_GE(s.velocity_sweeps, 1);
  EXPECT_LE(s.velocity_sweeps, 2);
  EXPECT_GE(s.position_sweeps, 1);
  EXPECT_TRUE(s.positions_settled);
}

// A column of 40 discs dropped onto the ground at once: Gauss–Seidel passes an impulse one disc
// further per iteration, so the first ticks cannot converge within the tick's iterations, and
// the stats say so (iterations at the setting, converged false) instead of passing for a solved
// tick. Warm starting carries the rest on: ten seconds later (five were measured to be nearly
// enough: the top disc still at 1.3 mm/s) the column stands still where it should, each disc's
// centre within the slop of r + 2 r i.
TEST(ContactSweeps, AColumnBeyondOneTicksIterationsSaysSoAndSettlesLater) {
  WorldDef def = ground_world();
  const double r = 0.1;
  for (int i = 0; i < 40; ++i) def.bodies.push_back(falling_disc({0.0, r + 2 * r * i}, r));
  World w(def);
  const int iterations = def.settings.contacts->velocity_iterations;
  bool hit_bound = false;
  for (int i = 0; i < 600; ++i) {
    w.step();
    const ContactStats& s = w.contact_stats();
    ASSERT_GE(s.velocity_sweeps, 1) << "tick " << i;
    ASSERT_LE(s.velocity_sweeps, iterations) << "tick " << i;
    ASSERT_LE(s.position_sweeps, def.settings.contacts->position_iterations) << "tick " << i;
    // Converged exactly when the iterations stopped before the setting.
    if (s.velocity_sweeps < iterations) {
      EXPECT_TRUE(s.velocity_converged) << "tick " << i;
    }
    if (!s.velocity_converged) {
      EXPECT_EQ(s.velocity_sweeps, iterations) << "tick " << i;
      hit_bound = true;
    }
  }
  EXPECT_TRUE(hit_bound);
  const auto bodies = w.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body b = w.body(bodies[i]);
    // Each contact below it may be up to the slop (0.5 % of r) deep.
    EXPECT_NEAR(b.position.y, r + 2 * r * double(i), 0.005 * r * double(i + 1) + 1e-12)
        << "disc " << i;
    EXPECT_LT(std::abs(b.velocity.y), 1e-3) << "disc " << i;
  }
}

// The iteration counts are settings of the method: outside their ranges a world refuses them,
// naming the field.
TEST(ContactSweeps, IterationCountsOutOfRangeAreRefused) {
  for (const auto& [v, p] :
       {std::pair{0, 3}, std::pair{8, -1}, std::pair{1001, 3}, std::pair{8, 1001}}) {
    WorldDef def = ground_world();
    def.settings.contacts->velocity_iterations = v;
    def.settings.contacts->position_iterations = p;
    def.bodies.push_back(falling_disc({0.0, 0.1}, 0.1));
    try {
      World w(def);
      ADD_FAILURE() << v << ", " << p << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(v < 1 || v > 1000 ? "velocity_iterations"
                                                             : "position_iterations"),
                std::string::npos)
          << e.what();
    }
  }
}

// A pile large enough to be split in halves for two threads (contacts across the cut solved
// after them) and to share the first impact predictions between them: one thread and two step
// it to the same bits, tick after tick, while it falls, collides and settles (1.5 s: its discs
// pressed against the walls are held within their ticks, and it passes 8192 touching pairs
// after the first second).
TEST(ContactSweeps, APileSplitForTwoThreadsStepsToTheSameBitsOnOne) {
  auto make = [](int threads) {
    WorldDef def = walled_pile(90, 40);
    def.settings.threads = threads;
    return std::make_unique<World>(def);
  };
  auto one = make(1), two = make(2);
  std::size_t across = 0, touching = 0;
  for (int t = 0; t < 90; ++t) {
    one->step(), two->step();
    ASSERT_EQ(one->state_hash(), two->state_hash()) << "tick " << t;
    across = std::max(across, one->contact_stats().across);
    touching = std::max(touching, one->contact_stats().touching);
    ASSERT_EQ(one->contact_stats().across, two->contact_stats().across) << "tick " << t;
  }
  EXPECT_GT(touching, 8192u);                              // split, on two threads
  EXPECT_GT(one->contact_stats().candidate_pairs, 4096u);  // predictions shared
  EXPECT_GT(across, 0u);
}

// The disc pairs' warm start is matched, and their parts of the split pile found, as they are
// gathered in a large world and by passes of their own after the gather in a small one
// (gather_warm.hpp): the same pile, stepped both ways side by side on one thread and on two,
// keeps the same bits and the same contacts across the cut on every tick.
TEST(ContactSweeps, TheWarmStartAndThePartsFoundInTheGatherOrAfterItGiveTheSameBits) {
  struct Restore {
    ~Restore() { detail::set_gather_warm_pairs(detail::min_gather_warm_pairs); }
  } restore;
  for (const int threads : {1, 2}) {
    WorldDef def = walled_pile(30, 20);
    def.settings.threads = threads;
    World gathered(def), after(def);
    std::size_t touching = 0, across = 0;
    for (int t = 0; t < 90; ++t) {
      detail::set_gather_warm_pairs(0);
      gathered.step();
      detail::set_gather_warm_pairs(std::numeric_limits<std::size_t>::max());
      after.step();
      ASSERT_EQ(gathered.state_hash(), after.state_hash())
          << "threads " << threads << ", tick " << t;
      ASSERT_EQ(gathered.contact_stats().across, after.contact_stats().across)
          << "threads " << threads << ", tick " << t;
      touching = std::max(touching, gathered.contact_stats().touching);
      across = std::max(across, gathered.contact_stats().across);
    }
    EXPECT_GT(touching, 1024u);  // a pile whose warm start carries it, split in halves
    EXPECT_GT(across, 0u);
  }
}

// The cut's median sought first near the last tick's (DiscContacts::cut_pile()) is the median
// of every coordinate: the same pile stepped both ways side by side keeps the same bits and
// the same contacts across the cut on every tick, while it settles (the median near the last)
// and after a shove sideways moves it past the window in one tick (every coordinate again).
TEST(ContactSweeps, TheMedianSoughtNearTheLastOneIsTheMedianOfThemAll) {
  struct Restore {
    ~Restore() { detail::set_median_window(true); }
  } restore;
  WorldDef def = walled_pile(30, 20);
  // Room to the right for the shove: the pile spreads from its left wall.
  def.planes.back().offset = -4.0;
  World windowed(def), whole(def);
  std::size_t across = 0;
  for (int t = 0; t < 120; ++t) {
    if (t == 60) {
      for (World* w : {&windowed, &whole}) {
        for (const Entity e : w->bodies()) w->set_velocity(e, w->body(e).velocity + Vec2{6.0, 0.0});
      }
    }
    detail::set_median_window(true);
    windowed.step();
    detail::set_median_window(false);
    whole.step();
    ASSERT_EQ(windowed.state_hash(), whole.state_hash()) << "tick " << t;
    ASSERT_EQ(windowed.contact_stats().across, whole.contact_stats().across) << "tick " << t;
    across = std::max(across, windowed.contact_stats().across);
  }
  EXPECT_GT(across, 0u);  // a pile split in halves
}

// A stop request (SIGINT) reaches a long resting solve (up to 1000 iterations a tick) on two
// threads: the tick throws StopRequested within it, and the world steps on once the request is
// cleared (the worker that served the passes was released, nothing hangs).
TEST(ContactSweeps, AStopRequestEndsALongRestingSolveOnTwoThreads) {
  WorldDef def = ground_world();
  def.settings.threads = 2;
  def.settings.contacts->velocity_iterations = 1000;
  def.planes.push_back(PlaneDef{.normal = {1, 0}, .offset = -2.0, .friction = 0.3});
  def.planes.push_back(PlaneDef{.normal = {-1, 0}, .offset = -2.0, .friction = 0.3});
  const double r = 0.049;
  for (int i = 0; i < 110; ++i) {  // a touching grid: about 8700 pairs from the first tick
    for (int j = 0; j < 40; ++j)
      def.bodies.push_back(falling_disc({-1.911 + 2 * r * j, r + 2 * r * i}, r));
  }
  World w(def);
  // The first tick's resting solve runs its 1000 iterations (a 110-row grid does not converge
  // from no warm start), about 0.1 s or more; the request comes 30 ms into the tick, after the
  // step's own poll at its start and the tick's earlier phases.
  clear_stop_request();
  std::atomic<bool> started{false};
  std::thread stopper([&] {
    while (!started.load()) std::this_thread::yield();
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    request_stop(2);
  });
  started.store(true);
  try {
    w.step();
    ADD_FAILURE() << "the tick ran to its end despite the stop request";
  } catch (const StopRequested& e) {
    EXPECT_EQ(e.signal(), 2);
  }
  stopper.join();
  const std::uint64_t torn = w.tick();
  clear_stop_request();
  w.step();
  EXPECT_EQ(w.tick(), torn + 1);
  EXPECT_GT(w.contact_stats().touching, 8192u);  // the passes ran on two threads
}

// Discs apart, with contacts on: no pair touches, no sweep runs, and nothing is unconverged.
TEST(ContactSweeps, NoTouchingPairsRunNoSweeps) {
  WorldDef def = ground_world();
  def.planes.clear();
  def.bodies.push_back(falling_disc({0.0, 0.0}, 0.1));
  def.bodies.push_back(falling_disc({1.0, 0.0}, 0.1));
  World w(def);
  w.step();
  const ContactStats& s = w.contact_stats();
  EXPECT_EQ(s.touching, 0u);
  EXPECT_EQ(s.velocity_sweeps, 0);
  EXPECT_EQ(s.position_sweeps, 0);
  EXPECT_TRUE(s.velocity_converged);
  EXPECT_TRUE(s.positions_settled);
}

// With disc contacts every tick is timed, its phases within the whole; without, nothing is.
TEST(StepProfile, PhasesOfATickWithDiscContactsAddUpWithinTheStep) {
  WorldDef def = ground_world();
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j)
      def.bodies.push_back(falling_disc({0.25 * j, 0.1 + 0.25 * i}, 0.1));
  }
  World w(def);
  for (int i = 0; i < 60; ++i) w.step();
  const StepProfile& p = w.profile();
  EXPECT_GT(p.step, 0.0);
  EXPECT_GT(p.broadphase, 0.0);
  EXPECT_GT(p.resting, 0.0);
  for (const double phase : {p.integrate, p.broadphase, p.impacts, p.resting, p.events}) {
    EXPECT_GE(phase, 0.0);
  }
  const double phases = p.integrate + p.broadphase + p.impacts + p.resting + p.events;
  EXPECT_LE(phases, p.step * (1 + 1e-9));
  EXPECT_GE(phases, 0.5 * p.step);  // only clock reads lie between the phases

  WorldDef free_fall;
  free_fall.settings.dt = 1.0 / 60.0;
  free_fall.bodies.push_back(falling_disc({0.0, 0.0}, 0.1));
  World f(free_fall);
  f.step();
  EXPECT_EQ(f.profile().step, 0.0);
  EXPECT_EQ(f.profile().integrate, 0.0);
}

}  // namespace contact_profile_tests
}  // namespace fixstep
