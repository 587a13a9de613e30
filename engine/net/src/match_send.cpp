// fixstep::net: what a lockstep peer sends: input runs (redundantly until acknowledged while
// they are small, else once and resent after a timeout), state hashes, refusals
// (fixstep/net/match_peer.hpp).
#include <algorithm>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/net/net_input_codec.hpp"
#include "match_peer_impl.hpp"

namespace fixstep::net {

namespace {

/// An inputs packet goes to each peer at least this often (ms), new ticks or not: its acks,
/// and a sign of life (peer_timeout_ms).
constexpr double heartbeat_ms = 100.0;

}  // namespace

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
  // Queued: sent just before the next inputs packet to each peer (send_inputs), so ENet puts
  // both in one datagram.
  for (detail::Remote& r : remotes) {
    if (r.handshaken && &r != except) r.hashes_due.push_back(m);
  }
}

double MatchPeer::Impl::resend_timeout(const detail::Remote& r) const {
  // The ack of a tick comes back a round trip after it is sent, plus up to the receiver's
  // send interval (it acknowledges in its next packet); resend_ms more for jitter.
  const double rtt = transport->round_trip_ms(r.conn);
  return rtt * 1.25 + settings.send_interval_ms + settings.resend_ms;
}

bool MatchPeer::Impl::resend_due(const detail::Remote& r, double now) const {
  for (std::size_t p = 0; p < players; ++p) {
    if (ours_to_send(r, p) && r.their_next[p] < r.sent_to[p] &&
        now - r.ack_moved_at[p] >= resend_timeout(r)) {
      return true;
    }
  }
  return false;
}

bool MatchPeer::Impl::redundant(std::uint8_t p, std::uint32_t acked) const {
  if (settings.redundant_bytes == 0 || acked >= known(p)) return false;
  const std::uint32_t to = std::min<std::uint32_t>(known(p), acked + max_run_ticks);
  const auto ticks = std::span<const TickInput>(inputs[p]).subspan(acked - base[p], to - acked);
  const TickInput empty{};
  return encoded_size(ticks, acked > 0 ? input_at(p, acked - 1) : empty) <=
         settings.redundant_bytes;
}

void MatchPeer::Impl::send_due(double now) {
  if (players == 0) return;
  for (detail::Remote& r : remotes) {
    if (!r.handshaken || (is_host && !r.heard_inputs)) continue;
    const double since = now - r.last_sent;
    const bool due = (r.dirty || resend_due(r, now)) && since >= settings.send_interval_ms;
    if (due || since >= heartbeat_ms) send_inputs(r, now);
  }
  std::uint32_t rtt = 0;
  for (const detail::Remote& r : remotes) {
    if (r.handshaken) rtt = std::max(rtt, transport->round_trip_ms(r.conn));
  }
  stats.round_trip_ms = rtt;
}

void MatchPeer::Impl::send_inputs(detail::Remote& r, double now) {
  // Each player's ticks the remote lacks: those not sent yet, or all from its ack when the ack
  // has not moved for a resend timeout (a packet lost).
  std::vector<RunToSend> runs;
  std::array<std::uint32_t, max_players> first{};
  for (std::uint8_t p = 0; p < players; ++p) {
    if (!ours_to_send(r, p)) continue;
    const std::uint32_t acked = r.their_next[p];
    if (acked > 0 && acked - 1 < base[p]) continue;  // a peer left that far behind times out
    // Nothing in flight: the timer starts with these ticks. Small enough: everything from the
    // ack again (redundantly). In flight for a resend timeout: resent from the ack (the timer
    // restarts). Else only the ticks not sent yet.
    const bool in_flight = r.sent_to[p] > acked;
    const bool timed_out = in_flight && now - r.ack_moved_at[p] >= resend_timeout(r);
    if (!in_flight || timed_out) r.ack_moved_at[p] = now;
    const bool small = in_flight && redundant(p, acked);
    if (timed_out && !small) ++stats.resends;
    const bool from_ack = !in_flight || timed_out || small;
    const std::uint32_t from = from_ack ? acked : r.sent_to[p];
    const std::uint32_t to = std::min<std::uint32_t>(known(p), from + max_run_ticks);
    if (from >= to) continue;
    first[p] = from;
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
  for (const RunToSend& run : runs) {
    const auto end = static_cast<std::uint32_t>(first[run.player] + run.inputs.size());
    r.sent_to[run.player] = std::max(r.sent_to[run.player], end);
  }
  std::array<std::uint32_t, max_players> acks{};
  for (std::size_t p = 0; p < players; ++p) acks[p] = known(p);
  for (const StateHashMessage& m : r.hashes_due) {
    std::vector<std::uint8_t> bytes;
    encode_state_hash(header(r, MessageKind::state_hash, Channel::reliable), m, bytes);
    send_reliable(r, bytes);
  }
  r.hashes_due.clear();
  encode_inputs_message(header(r, MessageKind::inputs, Channel::unreliable), players, acks, runs,
                        buffer);
  transport->send(r.conn, buffer, Channel::unreliable);
  ++stats.packets_sent;
  stats.bytes_sent += buffer.size();
  r.last_sent = now;
  r.dirty = false;
}

}  // namespace fixstep::net
