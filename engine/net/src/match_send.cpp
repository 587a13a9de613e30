// fixstep::net: what a lockstep peer sends: input runs resent until acknowledged, state
// hashes, refusals (fixstep/match_peer.hpp).
#include <algorithm>

#include "match_peer_impl.hpp"

namespace fixstep::net {

Header MatchPeer::Impl::header(detail::Remote& r, MessageKind kind, Channel channel) {
  std::uint32_t& seq = channel == Channel::reliable ? r.seq_reliable : r.seq_unreliable;
  return Header{kind, slot, seq++};
}

void MatchPeer::Impl::send_reliable(detail::Remote& r, const std::vector<std::uint8_t>& bytes) {
  transport->send(r.conn, bytes, Channel::reliable);
  ++stats.packets_sent;
  stats.bytes_sent += bytes.size();
}

void MatchPeer::Impl::refuse(detail::Remote& r, DisconnectReason why) {
  std::vector<std::uint8_t> bytes;
  // 13 bytes to a 64-byte request: no amplification.
  encode_disconnect(Header{MessageKind::disconnect, slot, r.seq_reliable++}, {why}, bytes);
  transport->send(r.conn, bytes, Channel::reliable);
  transport->disconnect(r.conn);
}

void MatchPeer::Impl::send_hash(const StateHashMessage& m, const detail::Remote* except) {
  for (detail::Remote& r : remotes) {
    if (!r.handshaken || &r == except) continue;
    std::vector<std::uint8_t> bytes;
    encode_state_hash(header(r, MessageKind::state_hash, Channel::reliable), m, bytes);
    send_reliable(r, bytes);
  }
}

void MatchPeer::Impl::send_due(double now) {
  if (players == 0) return;
  for (detail::Remote& r : remotes) {
    if (!r.handshaken || (is_host && !r.heard_inputs)) continue;
    const double since = now - r.last_sent;
    if ((r.dirty && since >= settings.send_interval_ms) || since >= settings.resend_ms) {
      send_inputs(r, now);
    }
  }
  std::uint32_t rtt = 0;
  for (const detail::Remote& r : remotes) {
    if (r.handshaken) rtt = std::max(rtt, transport->round_trip_ms(r.conn));
  }
  stats.round_trip_ms = rtt;
}

void MatchPeer::Impl::send_inputs(detail::Remote& r, double now) {
  // Each player's ticks the remote lacks, from what it acknowledged: resent until it does.
  std::vector<RunToSend> runs;
  for (std::uint8_t p = 0; p < players; ++p) {
    const bool ours_to_send = is_host ? p != r.slot : p == slot;
    if (!ours_to_send) continue;
    const std::uint32_t from = r.their_next[p];
    if (from > 0 && from - 1 < base[p]) continue;  // a peer left that far behind times out
    const std::uint32_t to = std::min<std::uint32_t>(known(p), from + max_run_ticks);
    if (from >= to) continue;
    runs.push_back({p, std::span<const TickInput>(inputs[p]).subspan(from - base[p], to - from),
                    from > 0 ? &input_at(p, from - 1) : nullptr});
  }
  // A packet too large: the longest run halved until it fits (the rest goes next time).
  while (inputs_packet_size(players, runs) > max_packet_bytes) {
    auto longest = std::max_element(runs.begin(), runs.end(), [](const auto& a, const auto& b) {
      return a.inputs.size() < b.inputs.size();
    });
    longest->inputs = longest->inputs.first(std::max<std::size_t>(1, longest->inputs.size() / 2));
  }
  std::array<std::uint32_t, max_players> acks{};
  for (std::size_t p = 0; p < players; ++p) acks[p] = known(p);
  encode_inputs_message(header(r, MessageKind::inputs, Channel::unreliable), players, acks, runs,
                        buffer);
  transport->send(r.conn, buffer, Channel::unreliable);
  ++stats.packets_sent;
  stats.bytes_sent += buffer.size();
  r.last_sent = now;
  r.dirty = false;
}

}  // namespace fixstep::net
