// Latency hidden by the measured round trip (MatchSettings::adapt_to_round_trip): a lockstep
// host picks the input delay from the round trip to its first joiner, and every peer plays it;
// a rollback peer's window follows the round trip; the timeouts grow with it.
#include <gtest/gtest.h>

#include <cmath>

#include "net_match.hpp"

namespace fixstep::net_test {
namespace {

/// The delay MatchSettings documents for a round trip of rtt_ms, billiards' 2 ms tick and a
/// packet on every input: ceil((rtt + 1000/60) / 2) + 1 ticks.
std::uint16_t documented_delay(double rtt_ms) {
  return static_cast<std::uint16_t>(std::ceil((rtt_ms + 1000.0 / 60.0) / 2.0) + 1.0);
}

// 40 ms each way: ENet measures a round trip of 80 ms and a little more (its own timing, the
// conditioner's polling), so the delay is that of 80–110 ms, and the joiner plays the host's.
TEST(RoundTrip, ALockstepHostPicksTheInputDelayFromTheRoundTripToItsJoiner) {
  net::MatchSettings s = match(2, 200);
  s.adapt_to_round_trip = true;
  Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 40.0, .seed = 3});
  EXPECT_FALSE(m.peers[0]->wants_input());  // no delay before anyone asked to join
  ASSERT_TRUE(m.run(30000)) << m.describe();
  expect_agreement(m, 200);
  const std::uint16_t delay = m.peers[0]->input_delay();
  EXPECT_GE(delay, documented_delay(80.0));
  EXPECT_LE(delay, documented_delay(110.0));
  EXPECT_EQ(m.peers[1]->input_delay(), delay);
}

// The same link without adapting keeps the delay given.
TEST(RoundTrip, TheDelayGivenIsKeptWhenNotAdapting) {
  net::MatchSettings s = match(2, 60);
  Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 40.0, .seed = 3});
  ASSERT_TRUE(m.run(30000)) << m.describe();
  EXPECT_EQ(m.peers[0]->input_delay(), s.input_delay);
  EXPECT_EQ(m.peers[1]->input_delay(), s.input_delay);
}

// A rollback peer at 40 ms each way: its window grows from max_rollback (8) to cover the round
// trip and a frame, ceil((80 + 16.7) / 2) + 2 = 51 ticks or a little more, and it rolls back
// further than 8 ticks.
TEST(RoundTrip, ARollbackWindowFollowsTheRoundTrip) {
  net::MatchSettings s = match(2, 400);
  s.adapt_to_round_trip = true;
  s.input_delay = 2;
  s.max_rollback = 8;
  Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 40.0, .seed = 5});
  ASSERT_TRUE(m.run(30000, {}, 1000.0 / 200.0)) << m.describe();
  expect_agreement(m, 400);
  for (const auto& p : m.peers) {
    EXPECT_GE(p->rollback_window(), 51u) << "slot " << int(p->slot());
    EXPECT_LE(p->rollback_window(), 70u) << "slot " << int(p->slot());
  }
}

// The timeouts grow with the round trip: at 150 ms each way, a peer timeout given as 500 ms
// becomes at least 8 round trips (about 2.4 s) on both peers, while a match that does not adapt
// keeps the 500 ms. A finished program answers for this long (linger_and_leave): a host that
// left after the 500 ms given could leave its joiner short of its last ticks on a lossy link,
// and the joiner, which waits the 8 round trips, then times out.
TEST(RoundTrip, ThePeerTimeoutGrowsToEightRoundTrips) {
  for (const bool adapt : {true, false}) {
    net::MatchSettings s = match(2, 100);
    s.adapt_to_round_trip = adapt;
    s.peer_timeout_ms = 500;
    s.handshake_timeout_ms = 10000;
    Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 150.0, .seed = 7});
    ASSERT_TRUE(m.run(30000)) << m.describe();
    for (const auto& p : m.peers) {
      const double rtt = p->stats().round_trip_ms;
      ASSERT_GE(rtt, 300.0) << "slot " << int(p->slot());
      if (adapt) {
        EXPECT_EQ(p->peer_timeout_ms(), net::timeout_round_trips * rtt)
            << "slot " << int(p->slot());
      } else {
        EXPECT_EQ(p->peer_timeout_ms(), 500.0) << "slot " << int(p->slot());
      }
    }
  }
}

}  // namespace
}  // namespace fixstep::net_test
