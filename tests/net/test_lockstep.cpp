// Lockstep matches on loopback through the link conditioner: 2 and 8 players (and a
// spectator) with latency, jitter and 5-25 % loss finish with no desync and identical
// recordings that replay; a peer corrupted on purpose is reported at the right tick; a silent
// player times out with a clear message; a joiner with another world is refused.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/net/desync_recording.hpp>
#include <fixstep/net/net_packet.hpp>
#include <thread>

#include "net_match.hpp"
#include "raw_peer.hpp"

namespace fixstep::net_test {
namespace {

using net::MatchPeer;
using net::MatchSettings;
using net::MatchState;

TEST(Lockstep, TwoPlayersThroughALossyLinkReplayWithFixstepReplay) {
  const MatchSettings s = match(2, 600);
  const net::LinkSettings link{.latency_ms = 15.0,
                               .jitter_ms = 10.0,
                               .loss = 0.2,
                               .burst_start = 0.01,
                               .burst_length = 4.0,
                               .duplicate = 0.05,
                               .reorder = 0.05,
                               .seed = 21};
  Match m = start(s, 1, 0, link);
  ASSERT_TRUE(m.run(20000)) << m.peers[0]->error() << " / " << m.peers[1]->error();
  const Recording rec = expect_agreement(m, 600);
  EXPECT_TRUE(every_player_played(rec, 2));
  EXPECT_GT(m.link->stats().dropped, 0u);
  EXPECT_GT(m.link->stats().duplicated, 0u);
  // The recording replays bit for bit: the library's replay, and `fixstep replay` on the file.
  World sim(billiards().def);
  const ReplayReport report = replay(sim, rec);
  EXPECT_TRUE(report.ok());
  EXPECT_EQ(report.verified, 601u);  // a hash every tick, and the final one
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("fixstep_net_" + std::to_string(::getpid()) + ".rec");
  write_recording(file, rec);
  const std::string command =
      std::string(FIXSTEP_CLI) + " replay " + file.string() + " > /dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::filesystem::remove(file);
}

TEST(Lockstep, EightPlayersAndASpectatorWithRulesAgree) {
  const MatchSettings s = match(8, 200);
  const net::LinkSettings link{.latency_ms = 10.0, .jitter_ms = 8.0, .loss = 0.1, .seed = 8};
  std::vector<PressCounter> counters(9);
  std::vector<TickRules> rules;
  for (auto& c : counters) rules.push_back(press_rules(c));
  Match m = start(s, 7, 1, link, rules);
  ASSERT_TRUE(m.run(30000)) << m.describe();
  const Recording rec = expect_agreement(m, 200);
  EXPECT_TRUE(every_player_played(rec, 8));
  EXPECT_EQ(m.peers[8]->slot(), net::spectator_slot_base);
  for (const auto& c : counters) EXPECT_EQ(c.presses, counters[0].presses);
  EXPECT_GT(counters[0].presses, 0u);
  // Replayed with the rules, from their start: the same states; without them: not.
  PressCounter fresh;
  World with(billiards().def);
  EXPECT_TRUE(replay(with, rec, press_rules(fresh)).ok());
  World without(billiards().def);
  EXPECT_FALSE(replay(without, rec).ok());
}

TEST(Lockstep, ACorruptedPeerIsReportedAtTheFirstHashAfter) {
  MatchSettings s = match(2, 300);
  Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 5.0, .seed = 2});
  // Player 1's world gets a nudge once it has stepped 95 ticks: the hashes of tick 100 differ.
  bool nudged = false;
  std::uint64_t nudged_at = 0;
  EXPECT_FALSE(m.run(20000, [&](std::size_t i) {
    MatchPeer& p = *m.peers[i];
    if (i == 1 && !nudged && p.world().tick() >= 95) {
      nudged_at = p.world().tick();
      World& w = p.world_for_test();
      w.set_velocity(w.bodies()[3], {1e-9, 0.0});
      nudged = true;
    }
  }));
  ASSERT_TRUE(nudged);
  // Both peers stop (the second once the other's hash arrives) and locate the desync.
  m.keep_playing(500);
  for (int k = 0; k < 5000 && (m.peers[0]->locating() || m.peers[1]->locating()); ++k) {
    m.round(false, {});
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const std::uint64_t corrupted_at = m.peers[1]->recording().ticks;
  for (const auto& p : m.peers) {
    ASSERT_EQ(p->state(), MatchState::desynced) << p->error();
    ASSERT_TRUE(p->desync());
    const net::DesyncReport& d = *p->desync();
    EXPECT_EQ(d.tick, 100u) << p->error();
    EXPECT_NE(d.ours, d.theirs);
    EXPECT_EQ(d.our_slot, p->slot());
    EXPECT_EQ(d.their_slot, 1 - p->slot());
    // The first tick whose hashes differ: the one after the nudge (a hash of every tick of the
    // window exchanged), on both peers. The nudge is outside the ticks, so the corrupted
    // peer's re-simulation does not reproduce its hash, and both say so.
    ASSERT_TRUE(d.first_tick) << p->error();
    EXPECT_EQ(*d.first_tick, nudged_at + 1) << p->error();
    EXPECT_NE(p->error().find(fmt::format("desync at tick {}", nudged_at + 1)), std::string::npos)
        << p->error();
    EXPECT_NE(p->error().find("changed outside its ticks"), std::string::npos) << p->error();
    EXPECT_FALSE(p->locating());
  }
  EXPECT_GE(corrupted_at, 100u);
  EXPECT_EQ(m.peers[0]->desync()->ours, m.peers[1]->desync()->theirs);
  // Offline: the healthy peer's recording replays; the corrupted one's diverges right after
  // the nudge (a hash every tick: the state after tick 96 is the first the nudge changed).
  World healthy(billiards().def);
  EXPECT_TRUE(replay(healthy, m.peers[0]->recording()).ok());
  World corrupted(billiards().def);
  const ReplayReport r = replay(corrupted, m.peers[1]->recording());
  ASSERT_FALSE(r.ok());
  EXPECT_GE(r.mismatch->tick, 96u);
  EXPECT_LE(r.mismatch->tick, 100u);
  // What net_app keeps of a desync without --record: each peer's recording in a file of its
  // own, named by slot and tick, never replacing a file (a link included), read back whole.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("fixstep_desync_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::create_symlink(dir / "elsewhere.rec", dir / "game-desync-p0-t100.rec");
  const auto host_file = net::write_desync_recording(*m.peers[0], dir, "game");
  EXPECT_EQ(host_file.filename(), "game-desync-p0-t100-2.rec");
  EXPECT_FALSE(std::filesystem::exists(dir / "elsewhere.rec"));  // not written through
  const auto joiner_file = net::write_desync_recording(*m.peers[1], dir, "game");
  EXPECT_EQ(joiner_file.filename(), "game-desync-p1-t100.rec");
  EXPECT_EQ(net::write_desync_recording(*m.peers[1], dir, "game").filename(),
            "game-desync-p1-t100-2.rec");
  World from_file(billiards().def);
  EXPECT_TRUE(replay(from_file, read_recording(host_file)).ok());
  World corrupted_from_file(billiards().def);
  EXPECT_EQ(replay(corrupted_from_file, read_recording(joiner_file)).mismatch->tick,
            r.mismatch->tick);
  std::filesystem::remove_all(dir);
}

// Rules that step differently on one peer (as code that is not deterministic across machines
// does): after tick 95 they nudge body 3's vx on player 1 only. Both peers name tick 96, body
// 3 and vx, and each re-simulation reproduces its own hashes (the rules run in it too).
TEST(Lockstep, ADesyncIsLocatedToItsTickBodyAndFieldOnBothPeers) {
  MatchSettings s = match(2, 300);
  Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 5.0, .seed = 2}, apart_rules());
  EXPECT_FALSE(m.run(20000));
  for (int k = 0; k < 5000 && (m.peers[0]->locating() || m.peers[1]->locating() ||
                               m.peers[0]->state() != MatchState::desynced ||
                               m.peers[1]->state() != MatchState::desynced);
       ++k) {
    m.round(false, {});
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  for (const auto& p : m.peers) {
    ASSERT_EQ(p->state(), MatchState::desynced) << p->error();
    const net::DesyncReport& d = *p->desync();
    EXPECT_EQ(d.tick, 100u);
    ASSERT_TRUE(d.first_tick) << p->error();
    EXPECT_EQ(*d.first_tick, 96u) << p->error();
    ASSERT_TRUE(d.difference) << p->error();
    EXPECT_EQ(d.difference->body, 3u);
    EXPECT_EQ(d.difference->field, "vx");
    EXPECT_NE(d.difference->bits_ours, d.difference->bits_theirs);
    EXPECT_EQ(p->error().find("outside its ticks"), std::string::npos) << p->error();
    EXPECT_NE(p->error().find("body 3"), std::string::npos) << p->error();
    ASSERT_TRUE(p->desync_state());
    EXPECT_EQ(p->desync_state()->tick, 96u);
  }
  // Each side's value is the other's "theirs".
  EXPECT_EQ(m.peers[0]->desync()->difference->bits_ours,
            m.peers[1]->desync()->difference->bits_theirs);
}
TEST(Lockstep, ASilentPlayerTimesOutWithAClearMessage) {
  MatchSettings s = match(2, 0);
  s.peer_timeout_ms = 300;
  Match m = start(s, 1, 0, net::LinkSettings{.seed = 1});
  // Play until both have stepped some ticks, then player 1 goes silent.
  (void)m.run(500, [&](std::size_t) {});  // never finishes (match_ticks 0): bounded by time
  ASSERT_EQ(m.peers[0]->state(), MatchState::playing) << m.describe();
  ASSERT_GT(m.peers[0]->world().tick(), 10u);
  const auto start_wait = std::chrono::steady_clock::now();
  while (m.peers[0]->state() == MatchState::playing &&
         std::chrono::steady_clock::now() - start_wait < std::chrono::seconds(5)) {
    m.link->pump();
    m.peers[0]->poll(1);
    (void)m.peers[0]->advance();
  }
  ASSERT_EQ(m.peers[0]->state(), MatchState::failed);
  EXPECT_NE(m.peers[0]->error().find("player 1 (127.0.0.1:"), std::string::npos) << m.describe();
  EXPECT_NE(m.peers[0]->error().find("timed out"), std::string::npos) << m.describe();
  EXPECT_GT(m.peers[0]->stats().stalls, 0u);
}

TEST(Lockstep, AJoinerWithAnotherWorldOrAFullMatchIsRefused) {
  const MatchSettings s = match(2, 50);
  MatchPeer host = MatchPeer::host(billiards().def, s, {"127.0.0.1", 0});
  WorldDef other = billiards().def;
  other.settings.dt *= 2.0;
  MatchPeer stranger = MatchPeer::join(other, s, {"127.0.0.1", host.port()});
  MatchPeer first = MatchPeer::join(billiards().def, s, {"127.0.0.1", host.port()});
  const auto start_wait = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start_wait < std::chrono::seconds(5) &&
         (stranger.state() == MatchState::connecting || first.state() == MatchState::connecting)) {
    host.poll(1);
    stranger.poll(0);
    first.poll(0);
  }
  EXPECT_EQ(stranger.state(), MatchState::failed);
  EXPECT_NE(stranger.error().find("refused us: it plays another world"), std::string::npos)
      << "[" << stranger.error() << "]";
  ASSERT_EQ(first.state(), MatchState::playing) << first.error();
  EXPECT_EQ(first.slot(), 1);
  MatchPeer third = MatchPeer::join(billiards().def, s, {"127.0.0.1", host.port()});
  const auto again = std::chrono::steady_clock::now();
  while (third.state() == MatchState::connecting &&
         std::chrono::steady_clock::now() - again < std::chrono::seconds(5)) {
    host.poll(1);
    first.poll(0);
    third.poll(0);
  }
  EXPECT_EQ(third.state(), MatchState::failed);
  EXPECT_NE(third.error().find("refused us: no free player slot"), std::string::npos)
      << "[" << third.error() << "]";
}

/// send_interval_ms batches the ticks of that long into one packet: at most one inputs packet
/// per interval to each peer, whatever the frame rate, and the match still agrees.
TEST(Lockstep, SendIntervalBatchesTicks) {
  MatchSettings s = match(2, 120);
  s.input_delay = 8;
  s.send_interval_ms = 40;
  s.resend_ms = 40;
  s.hash_every = 60;
  Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 5.0, .seed = 6});
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(m.run(20000, {}, 5.0)) << m.describe();
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  expect_agreement(m, 120);
  for (const auto& p : m.peers) {
    // Inputs packets: at most one per 40 ms (and the first); reliable ones: the handshake's
    // and two state hashes.
    EXPECT_LE(p->stats().packets_sent, static_cast<std::uint64_t>(ms / 40.0) + 1 + 3);
    EXPECT_GT(p->stats().packets_sent, 5u);
  }
}

/// The playout delay: a lockstep player steps tick t once its own input for t + input_delay
/// is given, one tick per local input, however the other player's inputs arrive (here in
/// bursts, a packet per 40 ms). Checked after every advance() of every frame (5 ms frames);
/// stepping each tick as soon as both inputs are there broke it at tick 1.
TEST(Lockstep, APlayerPlaysTicksOutOnItsOwnInputsClock) {
  MatchSettings s = match(2, 120);
  s.input_delay = 8;
  s.send_interval_ms = 40;
  Match m = start(s, 1, 0, net::LinkSettings{.latency_ms = 2.0, .seed = 8});
  std::uint64_t behind = 0, checks = 0;
  ASSERT_TRUE(m.run(
      20000,
      [&](std::size_t i) {
        const MatchPeer& p = *m.peers[i];
        // (the last input_delay ticks play out once every own input is given)
        if (p.state() != MatchState::playing || p.next_input_tick() >= 120) return;
        ++checks;
        // Every own input given up to next_input_tick(); ticks before it minus the delay may
        // have been played out, no later one.
        EXPECT_LE(p.world().tick() + s.input_delay, p.next_input_tick()) << "slot " << i;
        if (p.world().tick() + s.input_delay < p.next_input_tick()) ++behind;
      },
      5.0))
      << m.describe();
  expect_agreement(m, 120);
  EXPECT_GT(checks, 200u);
  EXPECT_GT(behind, 0u);  // it did wait for the other's bursts at times
}

TEST(Lockstep, HostilePacketsAreDroppedAndCountedWithoutAmplification) {
  MatchSettings s = match(2, 0);
  MatchPeer host = MatchPeer::host(billiards().def, s, {"127.0.0.1", 0});
  net::Transport raw = connect_raw(host);
  // Before the handshake: garbage, a foreign protocol, inputs; no answer at all.
  const std::vector<std::uint8_t> garbage(100, 0xab);
  raw.send(0, garbage, net::Channel::unreliable);
  std::vector<std::uint8_t> inputs;
  const std::vector<TickInput> one{TickInput{6}};
  const TickInput empty{};
  const net::RunToSend run{1, one, &empty};
  net::encode_inputs_message({.slot = 1, .sequence = 0}, 2, {6, 6}, {&run, 1}, inputs);
  raw.send(0, inputs, net::Channel::unreliable);
  raw.flush();
  EXPECT_EQ(listen(host, raw, 200).first, 0);
  EXPECT_EQ(dropped(host, net::PacketError::bad_protocol_id), 1u);
  EXPECT_EQ(dropped(host, net::PacketError::unexpected), 1u);
  // The handshake: the answer is no larger than the request.
  std::vector<std::uint8_t> request;
  net::encode_handshake_request(
      {}, {.nonce = 5, .definition_hash = definition_hash(billiards().def)}, request);
  raw.send(0, request, net::Channel::reliable);
  raw.flush();
  const auto accept = answer(host, raw);
  ASSERT_TRUE(accept);
  EXPECT_LE(accept->size(), request.size());
  net::Packet p;
  ASSERT_EQ(net::decode_packet(*accept, {}, p), net::PacketError::none);
  EXPECT_EQ(p.header.kind, net::MessageKind::handshake_accept);
  EXPECT_EQ(p.accept.your_slot, 1);
  // Now a player: a replayed packet, another player's inputs, a NaN, an unknown button.
  raw.send(0, inputs, net::Channel::unreliable);
  raw.send(0, inputs, net::Channel::unreliable);  // the same sequence number again
  const net::RunToSend theirs{0, one, &empty};
  net::encode_inputs_message({.slot = 1, .sequence = 1}, 2, {6, 6}, {&theirs, 1}, inputs);
  raw.send(0, inputs, net::Channel::unreliable);
  net::encode_inputs_message({.slot = 1, .sequence = 2}, 2, {6, 6}, {&run, 1}, inputs);
  inputs[inputs.size() - 1] = 0x7f;  // the repeat item now claims 128 ticks of 1
  raw.send(0, inputs, net::Channel::unreliable);
  std::vector<std::uint8_t> impostor = request;
  impostor[6] = 0;  // a header claiming slot 0, the host's
  raw.send(0, impostor, net::Channel::unreliable);
  raw.flush();
  (void)listen(host, raw, 200);
  EXPECT_EQ(dropped(host, net::PacketError::out_of_window), 1u);
  EXPECT_EQ(dropped(host, net::PacketError::unexpected), 2u);
  EXPECT_EQ(dropped(host, net::PacketError::bad_field), 1u);
  EXPECT_EQ(dropped(host, net::PacketError::bad_slot), 1u);
  EXPECT_EQ(host.state(), MatchState::playing) << host.error();
  // The one good input was taken: with the host's own inputs, tick 6 steps (and no more: the
  // host plays tick t out once its own input for t + 6 is given, the playout delay).
  ASSERT_TRUE(host.wants_input());
  ASSERT_EQ(host.next_input_tick(), 6u);
  for (int frame = 0; frame < 20; ++frame) {
    while (host.wants_input()) host.add_input(TickInput{});
    (void)host.advance();
  }
  EXPECT_EQ(host.world().tick(), 7u);
}

}  // namespace
}  // namespace fixstep::net_test
