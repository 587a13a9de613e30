// The stacker game's level and rules (demos/stacker/game.hpp) without a window: its towers of
// box shapes stand still on their own for ten seconds (nothing scores, nothing drifts, sinks
// or turns); the recorded session (assets/recordings/stacker.rec, the autopilot's three shots)
// replays with the rules, every hash verified, to the score tests/stacker_replay.sh expects,
// and passes fixstep::SyncTest with the rules at K = 1 and 8.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fixstep/core/components.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/sync_test.hpp>
#include <fixstep/core/world.hpp>
#include <optional>

#include "fixstep/io/recording_file.hpp"
#include "stacker/game.hpp"

namespace stacker_tests {

using namespace stacker;

constexpr const char* recorded_game =
    "score=12 targets=2 shots_left=0 down=11111000001111111 phase=over";

// Ten seconds untouched: every piece stays within a millimetre of where the level put it (the
// boxes start exactly touching) and turns less than a thousandth of a radian; none scores.
TEST(Stacker, TheTowersStandStillForTenSeconds) {
  fixstep::World sim(make_level());
  GameState game;
  double worst_move = 0.0, worst_turn = 0.0;
  for (int t = 0; t < 1200; ++t) {
    play_tick(game, fixstep::TickInput{.tick = std::uint64_t(t)}, sim);
    for (const fixstep::Entity e : sim.defined_bodies()) {
      const int i = piece_number(sim, e);
      if (i < 0) continue;
      const fixstep::Body b = sim.body(e);
      worst_move = std::max(worst_move, fixstep::length(b.position - piece(i).at));
      worst_turn = std::max(worst_turn, std::abs(b.angle));
    }
  }
  EXPECT_LT(worst_move, 1e-3);
  EXPECT_LT(worst_turn, 1e-3);
  EXPECT_EQ(describe(game), "score=0 targets=0 shots_left=3 down=00000000000000000 phase=loaded");
  EXPECT_FALSE(sim.fault().has_value());
}

fixstep::Recording recorded_session() {
  return fixstep::read_recording(FIXSTEP_SOURCE_DIR "/assets/recordings/stacker.rec");
}

TEST(Stacker, RecordedSessionReplaysWithTheRules) {
  const fixstep::Recording rec = recorded_session();
  GameState game;
  const fixstep::ReplayReport report = fixstep::replay(make_level(), rec, rules(game));
  ASSERT_TRUE(report.ok()) << "mismatch at tick " << report.mismatch->tick;
  EXPECT_EQ(report.verified, rec.hashes.size() + 1);
  EXPECT_EQ(report.final_hash, rec.final_hash);
  EXPECT_EQ(describe(game), recorded_game);
  // Without the rules the band is never cut: the recording does not replay.
  EXPECT_FALSE(fixstep::replay(make_level(), rec).ok());
}

// The session tick by tick: nothing sinks into anything (the deepest overlap of shapes the
// solver leaves), no piece passes through the ground, no fault.
TEST(Stacker, RecordedSessionLeavesNoDeepOverlapAndNothingBelowTheGround) {
  const fixstep::Recording rec = recorded_session();
  fixstep::World sim(make_level());
  GameState game;
  double deepest = 0.0, lowest = 1e9;
  for (std::uint64_t t = 0; t < rec.ticks; ++t) {
    play_tick(game, rec.input_at(t), sim);
    deepest = std::max(deepest, sim.contact_stats().deepest_shape_overlap);
    for (const fixstep::Entity e : sim.defined_bodies()) {
      const int i = piece_number(sim, e);
      // Its lowest point: the centre less the half-diagonal covers every angle (a loose bound).
      if (i >= 0) lowest = std::min(lowest, sim.body(e).position.y);
    }
  }
  EXPECT_LT(deepest, 0.02);  // m
  EXPECT_GT(lowest, 0.1);    // m: the thinnest half-extent is 0.15 m
  EXPECT_FALSE(sim.fault().has_value());
  EXPECT_EQ(describe(game), recorded_game);
}

TEST(Stacker, RecordedSessionPassesTheSyncTestWithTheRules) {
  const fixstep::Recording rec = recorded_session();
  for (const int k : {1, 8}) {
    GameState game;
    fixstep::World sim(make_level());
    fixstep::SyncTest test(sim, k, rules(game));
    for (std::uint64_t t = 0; t < rec.ticks; ++t) {
      ASSERT_TRUE(test.step(rec.input_at(t))) << "K=" << k << ": tick " << test.mismatch()->tick;
    }
    EXPECT_EQ(sim.state_hash(), rec.final_hash) << "K=" << k;
    EXPECT_EQ(describe(game), recorded_game) << "K=" << k;
  }
}

}  // namespace stacker_tests
