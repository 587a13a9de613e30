// The game's clock of a match (fixstep/net/match_clock.hpp): on a clean link a peer plays as
// many ticks as the frames' real time asks, however many ticks a frame holds, in lockstep and
// in rollback. Frames here are virtual (1/60 s each, whatever the wall clock), so what is
// checked is the clock's arithmetic and the match's pacing, not the machine's speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <fixstep/net/match_clock.hpp>
#include <stdexcept>
#include <thread>
#include <vector>

#include "net_match.hpp"

namespace fixstep::net_test {
namespace {

/// Billiards stepped at 120 ticks/s (as air hockey is): two ticks a frame of 1/60 s.
WorldDef at_120_hz() {
  WorldDef def = billiards().def;
  def.settings.dt = 1.0 / 120.0;
  return def;
}

/// What play_frames saw: each peer's shown tick at the end, and the most ticks one frame of
/// any peer played.
struct Played {
  std::vector<std::uint64_t> ticks;
  int most_a_frame = 0;
};

/// Plays `frames` frames of 1/60 s on every peer of a 2-player match (at_120_hz) over a clean
/// link; between two frames the packets are pumped until each peer has heard of the other's
/// ticks.
Played play_frames(const net::MatchSettings& s, int frames) {
  const WorldDef def = at_120_hz();
  Match m = start(s, 1, 0, net::LinkSettings{}, {}, true, &def);
  for (int k = 0; k < 400 && m.peers[1]->state() != net::MatchState::playing; ++k) {
    m.round(false, {});
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(m.peers[1]->state(), net::MatchState::playing) << m.describe();
  std::vector<net::MatchClock> clocks(2, net::MatchClock(def.settings.dt));
  Played played;
  for (int f = 0; f < frames; ++f) {
    for (std::size_t i = 0; i < 2; ++i) {
      net::MatchPeer& p = *m.peers[i];
      const net::ClockFrame frame = clocks[i].frame(p, 1.0 / 60.0, [&](std::uint64_t tick) {
        return scripted_input(p.world(), p.slot(), tick);
      });
      played.most_a_frame = std::max(played.most_a_frame, frame.ticks);
    }
    for (int k = 0; k < 5; ++k) {  // the ticks' inputs across, and acknowledged
      m.round(false, {});
      std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
  }
  played.ticks = {m.peers[0]->shown_world().tick(), m.peers[1]->shown_world().tick()};
  return played;
}

// 300 frames of 1/60 s are 5 s: 600 ticks. A peer may be behind by what the link has not
// carried yet (a frame's ticks: packets cross between two frames here), never ahead (a
// rollback peer's confirmed world, and the shown one with it, by at most the input delay + 1:
// its own inputs are given that far ahead). Playing
// one input and one advance() a frame, as the window's loop did before the clock, steps 300.
TEST(MatchClock, LockstepPlaysTheTicksThatRealTimeAsks) {
  net::MatchSettings s = match(2, 0);
  const auto ticks = play_frames(s, 300).ticks;
  for (const std::uint64_t t : ticks) {
    EXPECT_LE(t, 600u);
    EXPECT_GE(t, 600u - 2u * 2u);
  }
}

TEST(MatchClock, RollbackPlaysTheTicksThatRealTimeAsks) {
  net::MatchSettings s = match(2, 0);
  s.input_delay = 2;
  s.max_rollback = 16;
  const auto ticks = play_frames(s, 300).ticks;
  for (const std::uint64_t t : ticks) {
    EXPECT_LE(t, 600u + 2u + 1u);  // its own inputs are given up to input_delay + 1 ahead
    EXPECT_GE(t, 600u - 2u * 2u);
  }
}

// A lockstep player plays tick t out when it gives its input for t + input_delay; the match's
// last input_delay ticks have no later input. They play at real time too, two a frame of
// 1/60 s, not all in the frame after the last input (which made the last 16 ticks here, and
// 130 ms of a real match on a 50 ms round trip, one jump).
TEST(MatchClock, LockstepPlaysTheMatchsLastTicksAtRealTime) {
  net::MatchSettings s = match(2, 120);
  s.input_delay = 16;
  const Played played = play_frames(s, 90);  // 1.5 s: the match's 1 s and the input delay
  EXPECT_EQ(played.ticks, (std::vector<std::uint64_t>{120, 120}));
  EXPECT_LE(played.most_a_frame, 3);  // 2, or 3 where the owed time's rounding carries one
}

TEST(MatchClock, RefusesATickOrAClampThatIsNotPositive) {
  EXPECT_THROW(net::MatchClock(0.0), std::invalid_argument);
  EXPECT_THROW(net::MatchClock(-0.01), std::invalid_argument);
  EXPECT_THROW(net::MatchClock(0.01, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace fixstep::net_test
