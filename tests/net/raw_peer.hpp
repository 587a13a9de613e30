// Test helper: a raw transport posing as a joiner (hand-built packets) against a MatchPeer
// host, polled together with bounded waits.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/net/match_peer.hpp>
#include <fixstep/net/net_packet.hpp>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace fixstep::net_test {

/// Polls `host` and `raw` until `raw` receives a datagram (at most 2 s).
inline std::optional<std::vector<std::uint8_t>> answer(net::MatchPeer& host, net::Transport& raw) {
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(2)) {
    host.poll(0);
    net::TransportEvent ev = raw.poll(1);
    if (ev.kind == net::TransportEvent::Kind::received) return ev.bytes;
  }
  return std::nullopt;
}

/// Polls `host` and `raw` for `ms`, counting what `raw` receives and the largest datagram.
inline std::pair<int, std::size_t> listen(net::MatchPeer& host, net::Transport& raw, int ms) {
  std::pair<int, std::size_t> got{0, 0};
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(ms)) {
    host.poll(0);
    net::TransportEvent ev = raw.poll(1);
    if (ev.kind == net::TransportEvent::Kind::received) {
      ++got.first;
      got.second = std::max(got.second, ev.bytes.size());
    }
  }
  return got;
}

/// Packets `p` dropped as `e`.
inline std::uint64_t dropped(const net::MatchPeer& p, net::PacketError e) {
  return p.stats().dropped[static_cast<std::size_t>(e)];
}

/// A raw transport connected to `host` (the gate's cookie with the host's token, and ENet's
/// handshake; at most 2 s).
inline net::Transport connect_raw(net::MatchPeer& host) {
  net::Transport raw =
      net::Transport::connect({"127.0.0.1", host.port()}, {}, {}, net::parse_token(host.token()));
  for (int k = 0; k < 2000 && raw.poll(1).kind != net::TransportEvent::Kind::connected; ++k) {
    host.poll(0);
  }
  return raw;
}

/// The handshake request of a joiner playing `def`.
inline std::vector<std::uint8_t> handshake_request(const WorldDef& def) {
  std::vector<std::uint8_t> request;
  net::encode_handshake_request({}, {.nonce = 5, .definition_hash = definition_hash(def)}, request);
  return request;
}

/// Sends player 1's inputs `ticks` (from inputs.front().tick, deltas against `prev`) in one
/// inputs packet with sequence number `seq`, acknowledging `acks`.
inline void send_inputs(net::Transport& raw, std::uint32_t seq, std::span<const TickInput> ticks,
                        const TickInput& prev, std::array<std::uint32_t, net::max_players> acks) {
  std::vector<std::uint8_t> bytes;
  const net::RunToSend run{1, ticks, &prev};
  net::encode_inputs_message({.slot = 1, .sequence = seq}, 2, acks, {&run, ticks.empty() ? 0u : 1u},
                             bytes);
  raw.send(0, bytes, net::Channel::unreliable);
}

}  // namespace fixstep::net_test
