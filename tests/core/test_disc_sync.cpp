// The sync test (fixstep/core/sync_test.hpp) on worlds with disc-disc contacts:
// rollbacks of 1 and 7 ticks over a pile poured into a box and a kinematic paddle, long enough
// for impacts, resting contacts with warm-started impulses and the paddle's pushes to happen,
// with every integrator in f64 and f32. Each case also checks that contacts really happened,
// so it cannot pass on a world where nothing touches.
#include <gtest/gtest.h>

#include <cstdint>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/sync_test.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "link_between.hpp"

namespace fixstep {
namespace {

/// 60 discs of radius 5 cm (a 6 × 10 jittered grid) poured under gravity into a box of three
/// planes 0.8 m wide (e = 0.3, μ = 0.3 between discs), and a kinematic paddle (a disc of
/// radius 8 cm moving right at 1 m/s from just outside the left wall, 15 cm above the floor)
/// with a dynamic body hanging from it on a damped link. dt = 1/60 s.
WorldDef pile_and_paddle(Integrator integrator, Precision precision) {
  WorldDef def;
  def.precision = precision;
  def.settings.dt = 1.0 / 60.0;
  def.settings.integrator = integrator;
  def.settings.track_dissipation = true;  // the sync test compares the dissipated bits too
  def.settings.contacts = ContactSettings{.restitution = 0.3, .friction = 0.3};
  // No guard is asked for: explicit Euler's bob grows by 0.3 % a tick, bounded here.
  const double r = 0.05, half = 0.4;
  def.planes = {PlaneDef{.normal = {0, 1}, .offset = 0.0, .restitution = 0.2, .friction = 0.3},
                PlaneDef{.normal = {1, 0}, .offset = -half, .restitution = 0.2, .friction = 0.3},
                PlaneDef{.normal = {-1, 0}, .offset = -half, .restitution = 0.2, .friction = 0.3}};
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> jitter(-0.2 * r, 0.2 * r);
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 6; ++j) {
      BodyDef b;
      b.body = Body{.mass = 1.0,
                    .position = {-half + 2 * r + 2.6 * r * j + jitter(rng),
                                 2 * r + 2.4 * r * i + jitter(rng)}};
      b.collider = Collider{.radius = r};
      b.gravity = Gravity{};
      def.bodies.push_back(b);
    }
  }
  BodyDef paddle;
  paddle.type = BodyType::kinematic;
  paddle.body = Body{.mass = 1.0, .position = {-half - 0.1, 0.15}, .velocity = {1.0, 0.0}};
  paddle.collider = Collider{.radius = 0.08};
  def.bodies.push_back(paddle);
  // No collider: it swings below the paddle, through the ground. Its link has no rest length,
  // so implicit Euler solves the world's linear system (Newton's iterations over all 62
  // bodies take ~20 s a test in the Debug ASan build).
  BodyDef bob;
  bob.body = Body{.mass = 0.5, .position = {-half - 0.1, -0.2}};
  bob.gravity = Gravity{};
  def.bodies.push_back(bob);
  def.links.push_back(fixstep::test::link_between(def.bodies.size() - 1, def.bodies.size() - 2,
                                                  {.stiffness = 40.0, .damping = 0.5}));
  return def;
}

/// Ticks t of a push to the right (0.5 m/s² for ticks 30..39), else none.
TickInput input_at(std::uint64_t t) {
  TickInput in{.tick = t};
  if (t >= 30 && t < 40) in.push = {0.5, 0.0};
  return in;
}

/// Steps `ticks` ticks of pile_and_paddle under a SyncTest with rollbacks of `k` ticks, and
/// beside it the same world without rollbacks; expects no mismatch, the same final state, and
/// impacts, resting contacts and the paddle's pushes along the way.
void expect_rolls_back(Integrator integrator, Precision precision, int k, std::uint64_t ticks) {
  SCOPED_TRACE(testing::Message() << integrator_name(integrator) << " " << precision_name(precision)
                                  << " K = " << k);
  WorldDef def = pile_and_paddle(integrator, precision);
  def.allow_unstable = true;  // every integrator, explicit Euler's unstable paddle spring too
  World plain = World(def);
  World tested = World(def);
  SyncTest sync(tested, k);
  std::size_t impacts = 0, touching_ticks = 0, paddle_hits = 0;
  const auto paddle = static_cast<std::uint32_t>(def.bodies.size() - 2);
  for (std::uint64_t t = 0; t < ticks; ++t) {
    plain.step(input_at(t));
    ASSERT_TRUE(sync.step(input_at(t))) << "mismatch after tick " << sync.mismatch()->tick;
    impacts += plain.contact_stats().impacts;
    touching_ticks += plain.contact_stats().touching > 0 ? 1 : 0;
    for (const Impact& i : plain.impacts()) paddle_hits += plain.index_of(i.b) == paddle ? 1 : 0;
  }
  EXPECT_EQ(tested.state_hash(), plain.state_hash());
  EXPECT_EQ(tested.dissipated_energy(), plain.dissipated_energy());
  EXPECT_EQ(tested.external_work(), plain.external_work());
  EXPECT_GT(sync.resimulated(), (ticks - 1) * static_cast<std::uint64_t>(k) / 2);
  // Not vacuous: discs hit each other, rested on each other with warm-started impulses for
  // most of the run, and the paddle struck some.
  EXPECT_GE(impacts, 20u);
  EXPECT_GE(touching_ticks, ticks / 2);
  EXPECT_GE(paddle_hits, 1u);
  EXPECT_FALSE(plain.fault());
}

/// One integrator and precision; each runs rollbacks of 1 and of 7 ticks over 1 s (60 ticks),
/// in which the pile lands and the paddle sweeps the box from 0.1 to 0.9 s: measured, about
/// 5400 impacts (some 240 of them the paddle's) and resting pairs, warm-started, at every tick.
struct SyncCase {
  Integrator integrator;
  Precision precision;
};

void PrintTo(const SyncCase& c, std::ostream* out) {
  *out << integrator_name(c.integrator) << " " << precision_name(c.precision);
}

class DiscSync : public testing::TestWithParam<SyncCase> {};

TEST_P(DiscSync, RollsBackAPileAndAPaddleBitExactly) {
  for (const int k : {1, 7}) expect_rolls_back(GetParam().integrator, GetParam().precision, k, 60);
}

std::vector<SyncCase> sync_cases() {
  std::vector<SyncCase> cases;
  for (const Precision p : {Precision::f64, Precision::f32}) {
    for (const Integrator i : all_integrators) cases.push_back({i, p});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryIntegratorAndPrecision, DiscSync, testing::ValuesIn(sync_cases()),
                         [](const testing::TestParamInfo<SyncCase>& info) {
                           return std::string(integrator_name(info.param.integrator)) + "_" +
                                  std::string(precision_name(info.param.precision));
                         });

}  // namespace
}  // namespace fixstep
