// Spectators who join a match already under way: one that comes while the host still keeps
// every input sees the whole match and checks it against every state hash made before it
// came; one that comes after the host dropped the first ticks' inputs is refused with a clear
// message (the host keeps a bounded window of inputs, never the whole match).
#include <gtest/gtest.h>

#include <chrono>

#include "net_match.hpp"

namespace fixstep::net_test {
namespace {

using net::MatchPeer;
using net::MatchState;

/// Plays `m` (a frame for every peer every round) until its host has confirmed `tick`, for at
/// most 20 s; returns whether it got there.
bool play_to(Match& m, std::uint64_t tick) {
  const auto start = std::chrono::steady_clock::now();
  while (m.peers[0]->world().tick() < tick) {
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(20)) return false;
    if (m.peers[0]->state() != MatchState::playing) return false;
    m.round(true, {});
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  return true;
}

void add_spectator(Match& m, const net::MatchSettings& s) {
  m.peers.push_back(std::make_unique<MatchPeer>(
      MatchPeer::join(billiards().def, s, {"127.0.0.1", m.link->port()}, /*spectator=*/true)));
}

TEST(LateSpectators, OneWhoComesMidMatchSeesAllOfItAndChecksEveryHash) {
  const net::MatchSettings s = match(2, 400);
  Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 2.0, .seed = 4});
  ASSERT_TRUE(play_to(m, 200)) << m.describe();
  add_spectator(m, s);
  ASSERT_TRUE(m.run(20000)) << m.describe();
  expect_agreement(m, 400);
  // Every one of the host's 40 hashes (a hash every 10 ticks), the 20 made before it came
  // too, and the player's made after it came (about 20; the last may still be on its way):
  // without the earlier ones it compares about 36.
  EXPECT_GE(m.peers[2]->stats().hashes_compared, 40u + 15u) << m.describe();
}

TEST(LateSpectators, OneWhoComesAfterTheFirstTicksWereDroppedIsRefused) {
  const net::MatchSettings s = match(2, 0);  // endless
  Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 2.0, .seed = 5});
  ASSERT_TRUE(play_to(m, 2200)) << m.describe();
  add_spectator(m, s);
  const auto start_wait = std::chrono::steady_clock::now();
  while (m.peers[2]->state() == MatchState::connecting &&
         std::chrono::steady_clock::now() - start_wait < std::chrono::seconds(10)) {
    m.round(true, {});
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ASSERT_EQ(m.peers[2]->state(), MatchState::failed) << m.describe();
  EXPECT_NE(m.peers[2]->error().find("too late"), std::string::npos) << m.peers[2]->error();
  // The players play on.
  EXPECT_EQ(m.peers[0]->state(), MatchState::playing) << m.describe();
  EXPECT_EQ(m.peers[1]->state(), MatchState::playing) << m.describe();
}

}  // namespace
}  // namespace fixstep::net_test
