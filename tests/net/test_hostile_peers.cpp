// A hostile or broken joiner against a lockstep host, by hand-built packets (BAD_INPUTS rows
// N11 and N14): a packet more than the sequence window behind, inputs more than 512 ticks
// ahead, a connection that never completes the handshake. Each is dropped and counted, and the
// host plays on with what it had.
#include <gtest/gtest.h>

#include <vector>

#include "net_match.hpp"
#include "raw_peer.hpp"

namespace fixstep::net_test {
namespace {

using net::MatchPeer;
using net::MatchState;
using net::PacketError;

/// A host with a raw joiner that has completed the handshake (slot 1).
struct Handshaken {
  MatchPeer host;
  net::Transport raw;
};

Handshaken handshaken(const net::MatchSettings& s) {
  const WorldDef def = billiards().def;
  MatchPeer host = MatchPeer::host(def, s, {"127.0.0.1", 0});
  net::Transport raw = connect_raw(host);
  raw.send(0, handshake_request(def), net::Channel::reliable);
  raw.flush();
  const auto accept = answer(host, raw);
  EXPECT_TRUE(accept);
  return {std::move(host), std::move(raw)};
}

/// The host gives its inputs while it wants them and advances, `frames` times.
void play(MatchPeer& host, int frames) {
  for (int frame = 0; frame < frames; ++frame) {
    while (host.wants_input()) host.add_input(TickInput{});
    (void)host.advance();
  }
}

TEST(HostilePeers, APacketMoreThanTheWindowBehindIsDroppedAndCounted) {
  Handshaken m = handshaken(match(2, 0));
  const TickInput empty{};
  const std::vector<TickInput> tick6{TickInput{6}}, tick7{TickInput{7}};
  send_inputs(m.raw, 0, tick6, empty, {6, 6});
  send_inputs(m.raw, 100, {}, empty, {6, 7});  // a heartbeat: the newest sequence is 100
  // 64 behind the newest: out of the window, however new its ticks (tick 7 not yet had).
  send_inputs(m.raw, 36, tick7, tick6[0], {6, 7});
  m.raw.flush();
  (void)listen(m.host, m.raw, 200);
  EXPECT_EQ(dropped(m.host, PacketError::out_of_window), 1u);
  EXPECT_EQ(m.host.stats().dropped_total(), 1u);
  EXPECT_EQ(m.host.state(), MatchState::playing) << m.host.error();
  // Tick 6 steps with the one input taken; tick 7's input never arrived, so tick 7 does not.
  play(m.host, 20);
  EXPECT_EQ(m.host.world().tick(), 7u);
  // 63 behind: inside the window, taken; tick 7 steps.
  send_inputs(m.raw, 37, tick7, tick6[0], {6, 7});
  m.raw.flush();
  (void)listen(m.host, m.raw, 200);
  EXPECT_EQ(m.host.stats().dropped_total(), 1u);
  play(m.host, 20);
  EXPECT_EQ(m.host.world().tick(), 8u);
  EXPECT_EQ(m.host.state(), MatchState::playing) << m.host.error();
}

TEST(HostilePeers, InputsMoreThan512TicksAheadAreDroppedAndCounted) {
  Handshaken m = handshaken(match(2, 0));
  // Player 1's ticks 6 .. 773 in three runs of 256 (a run's most), each starting where the
  // last ended (so the decoder takes them): the host, at tick 0 with an input delay of 6,
  // stores them up to tick 6 + 512 - 1 = 517 and drops the rest.
  std::vector<TickInput> ticks;
  for (std::uint64_t t = 6; t < 6 + 3 * net::max_run_ticks; ++t) ticks.push_back(TickInput{t});
  const TickInput empty{};
  const std::span<const TickInput> all(ticks);
  for (std::uint32_t k = 0; k < 3; ++k) {
    const auto run = all.subspan(k * net::max_run_ticks, net::max_run_ticks);
    send_inputs(m.raw, k, run, k == 0 ? empty : all[k * net::max_run_ticks - 1], {6, 6});
  }
  m.raw.flush();
  (void)listen(m.host, m.raw, 200);
  EXPECT_EQ(dropped(m.host, PacketError::out_of_window), 1u);
  EXPECT_EQ(m.host.stats().dropped_total(), 1u);
  EXPECT_EQ(m.host.stats().gap_runs, 0u);
  // The host plays on with the ticks it stored: its own inputs and player 1's 518 (0 .. 517).
  play(m.host, 30);
  EXPECT_EQ(m.host.state(), MatchState::playing) << m.host.error();
  EXPECT_EQ(m.host.world().tick(), 30u);
  EXPECT_EQ(m.host.stats().stored_inputs, m.host.next_input_tick() + 518u);
}

/// A joiner the host accepted but never heard inputs from may still be waiting for the accept
/// (ENet resends a lost one after 500 ms, doubling): the host gives it the handshake's time,
/// not only peer_timeout_ms, then times it out with the usual message.
TEST(HostilePeers, AnAcceptedJoinerNotHeardFromHasTheHandshakesTime) {
  net::MatchSettings s = match(2, 0);
  s.peer_timeout_ms = 200;
  s.handshake_timeout_ms = 1500;
  Handshaken m = handshaken(s);      // the raw joiner never sends inputs
  (void)listen(m.host, m.raw, 700);  // over 3 peer timeouts, under the handshake's
  EXPECT_EQ(m.host.state(), MatchState::playing) << m.host.error();
  (void)listen(m.host, m.raw, 1500);
  EXPECT_EQ(m.host.state(), MatchState::failed);
  EXPECT_NE(m.host.error().find("timed out: nothing received for"), std::string::npos)
      << m.host.error();
}

TEST(HostilePeers, AConnectionThatNeverCompletesTheHandshakeIsDroppedSilently) {
  net::MatchSettings s = match(2, 0);
  s.handshake_timeout_ms = 150;
  const WorldDef def = billiards().def;
  MatchPeer host = MatchPeer::host(def, s, {"127.0.0.1", 0});
  net::Transport silent = connect_raw(host);
  // Past the timeout: the host dropped the connection and told it nothing.
  EXPECT_EQ(listen(host, silent, 400).first, 0);
  // Its handshake, late, goes to a connection the host no longer has: no answer.
  silent.send(0, handshake_request(def), net::Channel::reliable);
  silent.flush();
  EXPECT_EQ(listen(host, silent, 400).first, 0);
  EXPECT_EQ(host.state(), MatchState::playing) << host.error();
  // The slot is still free: a joiner that completes the handshake in time gets it.
  net::Transport prompt = connect_raw(host);
  prompt.send(0, handshake_request(def), net::Channel::reliable);
  prompt.flush();
  const auto accept = answer(host, prompt);
  ASSERT_TRUE(accept);
  net::Packet p;
  ASSERT_EQ(net::decode_packet(*accept, {}, p), PacketError::none);
  EXPECT_EQ(p.header.kind, net::MessageKind::handshake_accept);
  EXPECT_EQ(p.accept.your_slot, 1);
}

}  // namespace
}  // namespace fixstep::net_test
