// The accumulator loop of "Fix Your Timestep!" with scripted frame times.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "fixstep/app/key_bindings.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep {
namespace {

constexpr double dt = 0.01;

TEST(Loop, SteadySixtyHzRunsOneOrTwoTicksPerFrameAndKeepsTime) {
  FixedStepLoop loop(dt);
  double elapsed = 0;
  for (int f = 1; f <= 600; ++f) {
    const FrameResult r = loop.advance(1.0 / 60, {}, [](const TickInput&) {});
    elapsed += 1.0 / 60;
    EXPECT_TRUE(r.ticks == 1 || r.ticks == 2) << "frame " << f;
    EXPECT_GE(r.alpha, 0.0);
    EXPECT_LT(r.alpha, 1.0);
    // simulated time + accumulator == real time (no time lost or invented)
    EXPECT_NEAR(loop.ticks() * dt + r.alpha * dt, elapsed, 1e-9);
  }
  EXPECT_NEAR(double(loop.ticks()), 1000.0, 1.0);  // 10 s at 100 ticks/s
}

TEST(Loop, JitteryFramesNeverLoseOrInventTime) {
  FixedStepLoop loop(dt);
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> frame(0.001, 0.05);
  double elapsed = 0;
  for (int f = 0; f < 5000; ++f) {
    const double t = frame(rng);
    const FrameResult r = loop.advance(t, {}, [](const TickInput&) {});
    elapsed += t;
    ASSERT_GE(r.alpha, 0.0);
    ASSERT_LT(r.alpha, 1.0);
    ASSERT_NEAR(loop.ticks() * dt + r.alpha * dt, elapsed, 1e-8);
  }
}

TEST(Loop, FiveSecondHitchIsClampedToQuarterSecond) {
  FixedStepLoop loop(dt);
  const FrameResult r = loop.advance(5.0, {}, [](const TickInput&) {});
  EXPECT_EQ(r.ticks, 25);  // 0.25 s / 0.01 s, not 500
  EXPECT_NEAR(r.clamped_time, 4.75, 1e-12);
  EXPECT_LT(r.alpha, 1.0);
}

TEST(Loop, TickCapDropsTheBacklogButKeepsAlphaBelowOne) {
  FixedStepLoop loop(dt, LoopSettings{.max_frame_time = 0.25, .max_ticks_per_frame = 10});
  const FrameResult r = loop.advance(0.2049, {}, [](const TickInput&) {});
  EXPECT_EQ(r.ticks, 10);
  EXPECT_NEAR(r.dropped_time, 0.10, 1e-9);  // 20 ticks due, 10 run, the 10 others dropped
  EXPECT_NEAR(r.alpha, 0.49, 1e-6);
}

TEST(Loop, PauseSingleStepAndTimeScale) {
  FixedStepLoop loop(dt);
  loop.set_paused(true);
  EXPECT_EQ(loop.advance(1.0, {}, [](const TickInput&) {}).ticks, 0);
  loop.request_single_step();
  EXPECT_EQ(loop.advance(1.0 / 60, {}, [](const TickInput&) {}).ticks, 1);
  EXPECT_EQ(loop.advance(1.0 / 60, {}, [](const TickInput&) {}).ticks, 0);
  loop.set_paused(false);
  loop.set_time_scale(0.5);
  int ticks = 0;
  for (int f = 0; f < 60; ++f) ticks += loop.advance(1.0 / 60, {}, [](const TickInput&) {}).ticks;
  EXPECT_NEAR(ticks, 50, 1);  // half speed: 0.5 s of simulated time
  EXPECT_THROW(loop.set_time_scale(-1), std::invalid_argument);
}

TEST(Loop, WindowKeysPauseStepAndScaleTimeWithinLimits) {
  FixedStepLoop loop(dt);
  auto run_frame = [&] { return loop.advance(1.0 / 60, {}, [](const TickInput&) {}).ticks; };
  apply_loop_keys(UserEvents{.toggle_pause = true}, loop);
  EXPECT_TRUE(loop.paused());
  EXPECT_EQ(run_frame(), 0);
  apply_loop_keys(UserEvents{.single_step = true}, loop);
  EXPECT_EQ(run_frame(), 1);
  EXPECT_EQ(run_frame(), 0);
  apply_loop_keys(UserEvents{.toggle_pause = true}, loop);
  EXPECT_FALSE(loop.paused());
  apply_loop_keys(UserEvents{.time_scale_steps = 3}, loop);
  EXPECT_EQ(loop.time_scale(), 8.0);
  apply_loop_keys(UserEvents{.time_scale_steps = 3}, loop);
  EXPECT_EQ(loop.time_scale(), 16.0);  // the default limit
  apply_loop_keys(UserEvents{.time_scale_steps = 3}, loop, 64.0);
  EXPECT_EQ(loop.time_scale(), 64.0);
  apply_loop_keys(UserEvents{.time_scale_steps = -20}, loop);
  EXPECT_EQ(loop.time_scale(), 1.0 / 16);
  apply_loop_keys(UserEvents{.single_step = true}, loop);  // '.' while running pauses too
  EXPECT_TRUE(loop.paused());
}

TEST(Loop, EachTickReceivesTheFramesInputWithItsOwnIndex) {
  FixedStepLoop loop(dt);
  std::vector<TickInput> seen;
  const TickInput frame_input{.tick = 999, .push = {1.0, -2.0}};
  loop.advance(0.035, frame_input, [&](const TickInput& in) { seen.push_back(in); });
  loop.advance(0.02, TickInput{}, [&](const TickInput& in) { seen.push_back(in); });
  ASSERT_EQ(seen.size(), 5u);
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i].tick, i);
  EXPECT_EQ(seen[2].push, (Vec2{1.0, -2.0}));
  EXPECT_EQ(seen[3].push, (Vec2{}));
}

/// Physics state after exactly n ticks of the default scene, frames arriving at `fps`.
std::uint64_t hash_after(std::uint64_t n, double fps) {
  World sim = World(load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/default.toml").def);
  FixedStepLoop loop(sim);
  const VirtualClock clock(fps);
  while (sim.tick() < n) {
    loop.advance(clock.frame_seconds(), {}, [&](const TickInput& in) {
      if (sim.tick() < n) sim.step(in);
    });
  }
  return sim.state_hash();
}

TEST(Loop, StateAfterNTicksIsBitIdenticalAtAnyFrameRate) {
  constexpr std::uint64_t n = 777;
  World direct = World(load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/default.toml").def);
  for (std::uint64_t i = 0; i < n; ++i) direct.step();
  EXPECT_EQ(hash_after(n, 30), direct.state_hash());
  EXPECT_EQ(hash_after(n, 60), direct.state_hash());
  EXPECT_EQ(hash_after(n, 144), direct.state_hash());
}

TEST(Loop, RejectsBadSettings) {
  EXPECT_THROW(FixedStepLoop(0.0), std::invalid_argument);
  EXPECT_THROW(FixedStepLoop(0.01, LoopSettings{.max_frame_time = -1}), std::invalid_argument);
  EXPECT_THROW(VirtualClock(0), std::invalid_argument);
}

}  // namespace
}  // namespace fixstep
