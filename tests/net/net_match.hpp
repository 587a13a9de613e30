// Test helper: a lockstep match of several peers on loopback, through a link conditioner,
// polled from one thread until every peer is done or a deadline passes (never hangs).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/net/link_conditioner.hpp>
#include <fixstep/net/match_peer.hpp>
#include <fixstep/scene/scene.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace fixstep::net_test {

/// The billiards scene (16 discs, four cushions) with its text, as a recording carries it.
inline const Scene& billiards() {
  static const Scene scene =
      load_scene(std::string(FIXSTEP_SOURCE_DIR) + "/assets/scenes/billiards.toml");
  return scene;
}

/// Player `slot`'s scripted input of `tick`: an impulse on its own ball now and then, the
/// pointer moving in steps, a button held in spells (so presses and releases too).
inline TickInput scripted_input(const World& world, std::uint8_t slot, std::uint64_t tick) {
  TickInput in;
  const auto bodies = world.bodies();
  if (tick % 25 == slot % 25) {
    const double s = static_cast<double>(slot) + 1.0;
    in.bodies.push_back({bodies[slot % bodies.size()],
                         BodyInputKind::impulse,
                         {0.002 * s, -0.001 * s * static_cast<double>(tick % 3)}});
  }
  const bool held = ((tick / 40) + slot) % 3 == 0;
  in.held = held ? std::uint32_t{button_left} : 0u;
  in.pointer = {0.1 * slot, 0.01 * static_cast<double>(tick / 10)};
  return in;
}

/// The peers of one match: the host first, then the joiners (players, then spectators).
struct Match {
  std::vector<std::unique_ptr<net::MatchPeer>> peers;
  std::unique_ptr<net::LinkConditioner> link;

  /// One round: pump the link, and for every peer poll, give the inputs it wants
  /// (scripted_input, with pressed/released from the held bits; one when `one_input`, as a
  /// program sampling once a frame does) when `frame` is true, and advance; `each_tick(peer
  /// index)` after each advance.
  void round(bool frame, const std::function<void(std::size_t)>& each_tick,
             bool one_input = false) {
    round(std::vector<bool>(peers.size(), frame), each_tick, one_input);
  }
  /// round() with a frame for peer i when frames[i].
  void round(const std::vector<bool>& frames, const std::function<void(std::size_t)>& each_tick,
             bool one_input) {
    if (link) link->pump();
    prev_held.resize(peers.size(), 0);
    for (std::size_t i = 0; i < peers.size(); ++i) {
      net::MatchPeer& p = *peers[i];
      const bool frame = frames[i];
      p.poll(0);
      while (frame && p.wants_input()) {
        TickInput in = scripted_input(p.world(), p.slot(), p.next_input_tick());
        in.pressed = in.held & ~prev_held[i];
        in.released = prev_held[i] & ~in.held;
        prev_held[i] = in.held;
        p.add_input(in);
        if (one_input) break;
      }
      if (frame) (void)p.advance();
      if (each_tick) each_tick(i);
    }
  }

  /// Rounds until every peer is finished, one fails or desyncs, or `deadline_ms` passes; a
  /// frame (one input, advance) every `frame_ms` (0: every round, with every input wanted).
  /// Returns whether every peer finished.
  bool run(double deadline_ms, const std::function<void(std::size_t)>& each_tick = {},
           double frame_ms = 0.0) {
    return run(deadline_ms, each_tick, std::vector<double>(peers.size(), frame_ms));
  }
  /// run() with peer i's frames every frame_ms[i].
  bool run(double deadline_ms, const std::function<void(std::size_t)>& each_tick,
           const std::vector<double>& frame_ms) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> next_frame(peers.size(), 0.0);
    std::vector<bool> frames(peers.size());
    for (;;) {
      const double elapsed =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      for (std::size_t i = 0; i < peers.size(); ++i) {
        frames[i] = elapsed >= next_frame[i];
        if (frames[i]) next_frame[i] += frame_ms[i];
      }
      round(frames, each_tick, frame_ms[0] > 0.0);
      bool all_done = true;
      for (const auto& p : peers) {
        const net::MatchState s = p->state();
        if (s == net::MatchState::failed || s == net::MatchState::desynced) return false;
        all_done = all_done && s == net::MatchState::finished;
      }
      if (all_done) {
        linger(std::max(5000.0, deadline_ms - elapsed));
        return true;
      }
      if (elapsed > deadline_ms) return false;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }

  /// Rounds after the match, as a program lingers, so the last acknowledgements and hashes
  /// arrive: at least 20, and until every peer has compared a hash (the reliable channel
  /// resends a lost one after a backed-off timeout, so under loss a peer's first may come
  /// seconds after the end), for at most `max_ms`.
  void linger(double max_ms) {
    const auto start = std::chrono::steady_clock::now();
    auto compared = [&] {
      return std::all_of(peers.begin(), peers.end(),
                         [](const auto& p) { return p->stats().hashes_compared > 0; });
    };
    auto waited_ms = [&] {
      return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
          .count();
    };
    for (int k = 0; k < 20 || (!compared() && waited_ms() < max_ms); ++k) {
      round(false, {});
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }

  /// Every peer's state, confirmed tick and error or desync tick, a line each: what a failed
  /// run() prints, so the peer that stopped the match is named.
  [[nodiscard]] std::string describe() const {
    std::string out;
    for (std::size_t i = 0; i < peers.size(); ++i) {
      const net::MatchPeer& p = *peers[i];
      out += "\npeer " + std::to_string(i) + ": state " +
             std::to_string(static_cast<int>(p.state())) + ", tick " +
             std::to_string(p.world().tick()) + ", packets received " +
             std::to_string(p.stats().packets_received) + ", hashes compared " +
             std::to_string(p.stats().hashes_compared) + ", dropped " +
             std::to_string(p.stats().dropped_total());
      if (!p.error().empty()) out += ", error: " + p.error();
      if (p.desync()) out += ", desync at tick " + std::to_string(p.desync()->tick);
    }
    return out;
  }

  /// Keeps every peer playing for `ms` (failed or desynced ones too: they ignore it).
  void keep_playing(double ms) {
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
               .count() < ms) {
      round(true, {});
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }

  std::vector<std::uint32_t> prev_held;
};

/// The match token of the tests' matches (host and joiners share their settings).
inline constexpr const char* test_token = "00112233445566778899aabbccddeeff";

inline net::MatchSettings match(std::uint8_t players, std::uint64_t ticks) {
  net::MatchSettings s;
  s.players = players;
  s.input_delay = 6;
  s.hash_every = 10;
  s.match_ticks = ticks;
  s.peer_timeout_ms = 3000;
  // Most tests step faster than real time (as fast as inputs arrive): a packet on every new
  // input, not the default's one per 50 ms (SlowLinks.Defaults... plays the default).
  s.send_interval_ms = 0;
  s.scene_name = billiards().file;
  s.scene_text = billiards().text;
  s.token = test_token;
  s.adapt_to_round_trip = false;  // the delays and timeouts as given (MatchPeer.* adapt)
  return s;
}

/// The link's lossless_ms when start() is asked for a clean handshake and the link sets none:
/// the connections and handshakes get through, then the loss starts. At 20 % loss ENet's
/// backed-off resends make about one join in a few hundred take longer than 20 s, and a match
/// of 8 has 8 joins; these tests are about the match (SlowLinks plays its handshake over the
/// lossy link, HostilePeers times handshakes out).
constexpr double lossless_handshake_ms = 1000.0;

/// A host and `joiners` joining through `link` (spectators last), playing `world` (billiards
/// when null).
inline Match start(const net::MatchSettings& s, int joiners, int spectators,
                   const net::LinkSettings& link, const std::vector<TickRules>& rules = {},
                   bool clean_handshake = true, const WorldDef* world = nullptr) {
  Match m;
  const WorldDef def = world ? *world : billiards().def;
  auto rules_of = [&](std::size_t i) { return i < rules.size() ? rules[i] : TickRules{}; };
  m.peers.push_back(std::make_unique<net::MatchPeer>(
      net::MatchPeer::host(def, s, {"127.0.0.1", 0}, rules_of(0))));
  net::LinkSettings l = link;
  if (clean_handshake && l.lossless_ms == 0.0) l.lossless_ms = lossless_handshake_ms;
  m.link = std::make_unique<net::LinkConditioner>(net::Address{"127.0.0.1", m.peers[0]->port()}, l);
  for (int i = 0; i < joiners + spectators; ++i) {
    m.peers.push_back(std::make_unique<net::MatchPeer>(
        net::MatchPeer::join(def, s, {"127.0.0.1", m.link->port()}, i >= joiners,
                             rules_of(static_cast<std::size_t>(i) + 1))));
  }
  return m;
}

/// Rules that step differently on player 1 (as code not deterministic across machines does):
/// after tick 95 they add 1e-9 m/s to body 3's vx there only; player 0's do nothing.
inline std::vector<TickRules> apart_rules() {
  TickRules apart;
  apart.after_tick = [](World& w, const TickInput& in) {
    if (in.tick != 95) return;
    const Vec2 v = w.body(w.bodies()[3]).velocity;
    w.set_velocity(w.bodies()[3], {v.x + 1e-9, v.y});
  };
  TickRules plain;
  plain.after_tick = [](World&, const TickInput&) {};
  return {plain, apart};
}

/// Every peer finished with the same recording, every hash exchanged matched, nothing
/// malformed was received; returns the host's recording.
inline Recording expect_agreement(const Match& m, std::uint64_t ticks) {
  const Recording first = m.peers[0]->recording();
  EXPECT_EQ(first.ticks, ticks);
  const std::string text = format_recording(first);
  for (const auto& p : m.peers) {
    EXPECT_EQ(p->state(), net::MatchState::finished) << p->error();
    EXPECT_FALSE(p->desync());
    EXPECT_EQ(format_recording(p->recording()), text) << "slot " << int(p->slot());
    EXPECT_GT(p->stats().hashes_compared, 0u) << "slot " << int(p->slot()) << m.describe();
    // Only the conditioner's duplicates are dropped (as replays: out_of_window); nothing
    // malformed, nothing unexpected.
    const auto& dropped = p->stats().dropped;
    const auto window = dropped[static_cast<std::size_t>(net::PacketError::out_of_window)];
    const auto early = dropped[static_cast<std::size_t>(net::PacketError::unexpected)];
    EXPECT_EQ(early, 0u);  // a host sends a joiner inputs only once it has the accept
    EXPECT_EQ(p->stats().dropped_total(), window + early) << [&] {
      std::string s;
      for (std::size_t k = 0; k < dropped.size(); ++k)
        s += std::string(net::packet_error_name(static_cast<net::PacketError>(k))) + "=" +
             std::to_string(dropped[k]) + " ";
      return s;
    }();
    // (a held-back datagram may also arrive more than 64 packets late)
    EXPECT_LE(window, m.link->stats().duplicated + m.link->stats().held_back);
    EXPECT_EQ(p->stats().conflicting_inputs, 0u);
  }
  return first;
}

/// Whether the merged input of some tick carries body inputs of `players` different bodies.
inline bool every_player_played(const Recording& rec, std::size_t players) {
  std::vector<bool> seen(players, false);
  for (const TickInput& in : rec.inputs) {
    for (const BodyInput& b : in.bodies) {
      if (b.body.slot() < players) seen[b.body.slot()] = true;
    }
  }
  return std::all_of(seen.begin(), seen.end(), [](bool b) { return b; });
}

/// Rules with state: a counter of button presses, and every press a kick to a ball chosen by
/// it, so the rules change the world and a replay without them would differ.
struct PressCounter {
  std::uint64_t presses = 0;
};

inline TickRules press_rules(PressCounter& c) {
  return stateful_rules(c, [](PressCounter& st, World& world, const TickInput& in) {
    if (in.pressed == 0) return;
    ++st.presses;
    const auto bodies = world.bodies();
    const Entity e = bodies[st.presses % bodies.size()];
    world.set_velocity(e, {0.05 * static_cast<double>(st.presses % 7), -0.03});
  });
}

}  // namespace fixstep::net_test
