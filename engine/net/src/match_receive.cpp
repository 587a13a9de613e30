// fixstep::net: what a lockstep peer does with each packet it receives, after the decoder has
// validated it (fixstep/net/match_peer.hpp).
#include <fmt/format.h>

#include <algorithm>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/net/net_input_codec.hpp"
#include "match_peer_impl.hpp"

namespace fixstep::net {

namespace {

/// Most inputs a player may be ahead of the next tick to step (beyond its input delay): a
/// peer may not make another store an unbounded future.
constexpr std::uint64_t max_ahead = 2 * std::uint64_t{max_run_ticks};
/// Most state hashes held for ticks not yet stepped here.
constexpr std::size_t max_pending_hashes = 4096;

}  // namespace

detail::Remote* MatchPeer::Impl::remote(std::uint32_t conn) {
  for (detail::Remote& r : remotes) {
    if (r.conn == conn) return &r;
  }
  return nullptr;
}

DecodeContext MatchPeer::Impl::context(const detail::Remote& r) const {
  DecodeContext ctx;
  if (!r.handshaken) return ctx;
  ctx.players = players;
  ctx.own_slot = slot;
  for (std::size_t p = 0; p < players; ++p) ctx.next_needed[p] = known(p);
  return ctx;
}

void MatchPeer::Impl::handle(const TransportEvent& ev, double now) {
  using Kind = TransportEvent::Kind;
  if (ev.kind == Kind::refused) {
    if (state == MatchState::connecting) {
      fail(fmt::format(
          "the host at {}:{} refused our token (or answered without proving it): it is not this "
          "match's (MatchSettings::token, a game's --token: the 32 hexadecimal digits the host "
          "printed)",
          host_address.host, host_address.port));
    }
    return;
  }
  if (ev.kind == Kind::connected) {
    if (is_host) {
      detail::Remote r;
      r.conn = ev.peer;
      r.connected_at = r.last_heard = now;
      std::erase_if(remotes, [&](const detail::Remote& x) { return x.conn == ev.peer; });
      remotes.push_back(r);
    } else {
      detail::Remote& host = remotes.front();
      host.last_heard = now;
      std::vector<std::uint8_t> bytes;
      encode_handshake_request(header(host, MessageKind::handshake_request, Channel::reliable),
                               {spectator, nonce, def_hash}, bytes);
      send_reliable(host, bytes);
    }
    return;
  }
  detail::Remote* r = remote(ev.peer);
  if (r == nullptr) return;
  if (ev.kind == Kind::disconnected) {
    if (!is_host && !r->handshaken && state == MatchState::connecting) {
      fail(fmt::format("the host at {}:{} closed the connection before the handshake completed",
                       host_address.host, host_address.port));
    }
    const bool mattered = r->handshaken && (r->slot < players || !is_host);
    if (mattered && state != MatchState::finished) {
      fail(fmt::format("{} disconnected at tick {} (connection lost or closed)", who(*r),
                       next_step));
    }
    if (is_host) {
      const std::uint32_t conn = r->conn;
      std::erase_if(remotes, [&](const detail::Remote& x) { return x.conn == conn; });
    }
    return;
  }
  ++stats.packets_received;
  stats.bytes_received += ev.bytes.size();
  Packet p;
  const PacketError e = decode_packet(ev.bytes, context(*r), p);
  if (e != PacketError::none) {
    ++stats.dropped[static_cast<std::size_t>(e)];
    return;
  }
  receive(*r, p, ev.channel, now);
}

void MatchPeer::Impl::receive(detail::Remote& r, const Packet& p, Channel channel, double now) {
  auto drop = [&](PacketError e) { ++stats.dropped[static_cast<std::size_t>(e)]; };
  // Sequence numbers: the unreliable channel's within a window, once each; the reliable
  // channel's increasing (ENet delivers it in order).
  if (channel == Channel::unreliable) {
    if (!r.window.accept(p.header.sequence)) return drop(PacketError::out_of_window);
  } else {
    if (r.reliable_seen && p.header.sequence <= *r.reliable_seen) {
      return drop(PacketError::out_of_window);
    }
    r.reliable_seen = p.header.sequence;
  }
  const bool reliable_kind = p.header.kind != MessageKind::inputs;
  if (reliable_kind != (channel == Channel::reliable)) return drop(PacketError::unexpected);
  if (r.handshaken && p.header.slot != r.slot) return drop(PacketError::bad_slot);
  switch (p.header.kind) {
    case MessageKind::handshake_request:
      if (!is_host || r.handshaken) return drop(PacketError::unexpected);
      return on_request(r, p);
    case MessageKind::handshake_accept:
      if (is_host || r.handshaken) return drop(PacketError::unexpected);
      r.last_heard = now;
      return on_accept(r, p);
    case MessageKind::disconnect:
      if (!is_host && !r.handshaken) return on_refused(p.disconnect.reason);
      if (!r.handshaken) return drop(PacketError::unexpected);
      r.last_heard = now;
      if (p.disconnect.reason == DisconnectReason::desync && state == MatchState::playing) {
        state = MatchState::desynced;  // its recording and ours are to be compared
        desync = DesyncReport{next_step, slot, r.slot, 0, 0, {}, {}};
        error =
            fmt::format("{} found a desync and left the match (at our tick {})", who(r), next_step);
        return;
      }
      if (state != MatchState::finished && (r.slot < players || !is_host)) {
        fail(p.disconnect.reason == DisconnectReason::refused
                 ? fmt::format("{} refused us", who(r))
                 : fmt::format("{} left the match at tick {} (reason {})", who(r), next_step,
                               static_cast<int>(p.disconnect.reason)));
      }
      return;
    case MessageKind::inputs:
      r.last_heard = now;
      r.heard_inputs = true;
      return on_inputs(r, p, now);
    case MessageKind::state_hash:
      r.last_heard = now;
      return on_hash(r, p.hash);
    case MessageKind::tick_hashes:
      r.last_heard = now;
      return on_tick_hashes(r, p.tick_hashes);
    case MessageKind::body_states:
      r.last_heard = now;
      return on_body_states(r, p.body_states);
  }
}

void MatchPeer::Impl::on_request(detail::Remote& r, const Packet& p) {
  if (p.request.definition_hash != def_hash) return refuse(r, DisconnectReason::another_world);
  std::uint8_t given = no_slot;
  if (p.request.spectator) {
    // A spectator steps from tick 0: too late once the first inputs are dropped.
    const bool first_kept =
        std::all_of(base.begin(), base.begin() + players, [](std::uint64_t b) { return b == 0; });
    if (!first_kept) return refuse(r, DisconnectReason::too_late);
    if (spectators < max_spectators)
      given = static_cast<std::uint8_t>(spectator_slot_base + spectators++);
  } else {
    for (std::uint8_t s = 1; s < players && given == no_slot; ++s) {
      const bool taken = std::any_of(remotes.begin(), remotes.end(), [&](const detail::Remote& x) {
        return x.handshaken && x.slot == s;
      });
      if (!taken) given = s;
    }
  }
  if (given == no_slot) return refuse(r, DisconnectReason::refused);
  if (delay_open) {  // the first to ask: the input delay from the round trip to it
    set_input_delay(input_delay_for(transport->round_trip_ms(r.conn)));
    delay_open = false;
  }
  r.handshaken = true;
  r.slot = given;
  r.dirty = true;
  HandshakeAccept a;
  a.nonce = p.request.nonce;
  a.players = players;
  a.your_slot = given;
  a.input_delay = settings.input_delay;
  a.hash_every = settings.hash_every;
  a.host_rollback = settings.max_rollback > 0;
  a.definition_hash = def_hash;
  std::vector<std::uint8_t> bytes;
  encode_handshake_accept(header(r, MessageKind::handshake_accept, Channel::reliable), a, bytes);
  send_reliable(r, bytes);  // 31 bytes, the request's 64: no amplification
  // A spectator coming mid-match checks the ticks before it came against our hashes too
  // (sent once it has sent inputs, as every hash is: no amplification).
  for (const auto& [tick, hash] : own_hashes) {
    r.hashes_due.push_back({slot, static_cast<std::uint32_t>(tick), hash});
  }
}

void MatchPeer::Impl::on_refused(DisconnectReason why) {
  if (why == DisconnectReason::too_late) {
    fail(
        fmt::format("the host at {}:{} refused us: too late to watch (the match is past the "
                    "first ticks' inputs, which a spectator needs and the host no longer keeps)",
                    host_address.host, host_address.port));
  } else if (why == DisconnectReason::another_world) {
    fail(
        fmt::format("the host at {}:{} refused us: it plays another world (our definition "
                    "hash {:016x})",
                    host_address.host, host_address.port, def_hash));
  } else {
    fail(fmt::format("the host at {}:{} refused us: no free {} slot", host_address.host,
                     host_address.port, spectator ? "spectator" : "player"));
  }
}

void MatchPeer::Impl::on_accept(detail::Remote& r, const Packet& p) {
  const HandshakeAccept& a = p.accept;
  if (a.nonce != nonce)
    return (void)++stats.dropped[static_cast<std::size_t>(PacketError::unexpected)];
  if (a.definition_hash != def_hash) {
    fail(
        fmt::format("the host at {}:{} plays another world (definition hash {:016x}, ours "
                    "{:016x})",
                    host_address.host, host_address.port, a.definition_hash, def_hash));
    transport->disconnect(r.conn);
    return;
  }
  if (spectator != (a.your_slot >= spectator_slot_base)) {
    fail("the host gave a player's slot to a spectator, or a spectator's to a player");
    return;
  }
  r.handshaken = true;
  r.slot = 0;
  settings.input_delay = a.input_delay;
  settings.hash_every = a.hash_every;
  if (settings.session_from_host && !spectator) {
    settings.max_rollback =
        a.host_rollback ? std::max<std::uint16_t>(settings.max_rollback, 1) : std::uint16_t{0};
  }
  start(a.players, a.your_slot);
}

void MatchPeer::Impl::on_inputs(detail::Remote& r, const Packet& p, double now) {
  // Who may send whose inputs: a player its own; the host everyone's but ours; a spectator none.
  for (const InputRun& run : p.inputs.runs) {
    const bool allowed = is_host ? (run.player == r.slot && r.slot < players) : run.player != slot;
    if (!allowed) return (void)++stats.dropped[static_cast<std::size_t>(PacketError::unexpected)];
  }
  for (std::size_t q = 0; q < players; ++q) {
    const std::uint32_t acked = std::min(p.inputs.next_needed[q], known(q));
    if (acked > r.their_next[q]) {
      r.their_next[q] = acked;
      r.ack_moved_at[q] = now;
    }
  }
  const std::uint64_t limit = next_step + settings.input_delay + max_ahead;
  bool grew = false;
  for (const InputRun& run : p.inputs.runs) {
    const std::size_t q = run.player;
    if (run.first_tick > known(q)) {
      // Sent after ticks that have not arrived (lost or late): its base is missing. The sender
      // resends from our ack when it does not move.
      ++stats.gap_runs;
      continue;
    }
    if (run.first_tick > 0 && run.first_tick - 1 < base[q]) {
      // Its base tick was dropped long ago (trim_inputs): its ticks are all here already.
      ++stats.dropped[static_cast<std::size_t>(PacketError::out_of_window)];
      continue;
    }
    TickInput prev = run.first_tick == 0 ? TickInput{} : input_at(q, run.first_tick - 1);
    for (std::size_t i = 0; i < run.deltas.size(); ++i) {
      const std::uint64_t t = run.first_tick + i;
      prev = apply_delta(run.deltas[i], prev, t);
      if (t < known(q)) {
        if (t >= base[q] && !same_input(prev, input_at(q, t))) {
          ++stats.conflicting_inputs;  // the first copy stands
        }
      } else if (t >= limit) {
        ++stats.dropped[static_cast<std::size_t>(PacketError::out_of_window)];
        break;
      } else {
        inputs[q].push_back(prev);
        grew = true;
        if (shown) check_prediction(run.player, t);
      }
    }
  }
  if (grew) mark_dirty();
  // Rollback's time sync: the sender's frame advantage over us as it sent this packet (its own
  // inputs it had, against its acknowledgement of ours), from its newest packet only.
  const std::uint8_t sender = is_host ? r.slot : std::uint8_t{0};
  if (shown && sender < players && (!r.advantage_seq || p.header.sequence > *r.advantage_seq)) {
    std::uint64_t theirs = known(sender);
    for (const InputRun& run : p.inputs.runs) {
      if (run.player == sender)
        theirs = std::max<std::uint64_t>(theirs, run.first_tick + run.deltas.size());
    }
    r.their_advantage =
        static_cast<std::int64_t>(theirs) - static_cast<std::int64_t>(p.inputs.next_needed[slot]);
    r.their_position = std::max(r.their_position, theirs);
    r.advantage_seq = p.header.sequence;
  }
}

void MatchPeer::Impl::on_hash(detail::Remote& r, const StateHashMessage& m) {
  auto drop = [&](PacketError e) { ++stats.dropped[static_cast<std::size_t>(e)]; };
  if (m.player == slot) return drop(PacketError::unexpected);
  if (is_host && m.player != r.slot) return drop(PacketError::unexpected);
  if (m.tick == 0 || m.tick % settings.hash_every != 0) return drop(PacketError::bad_tick_range);
  if (their_hashes.size() >= max_pending_hashes) return drop(PacketError::out_of_window);
  their_hashes.emplace(m.tick, m);
  if (is_host) send_hash(m, &r);  // the others compare it too
  compare_hashes();
}

void MatchPeer::Impl::check_timeouts(double now) {
  if (!is_host && state == MatchState::connecting && now - started_at > handshake_timeout_ms()) {
    fail(fmt::format("no answer from the host at {}:{} within {:.0f} ms", host_address.host,
                     host_address.port, handshake_timeout_ms()));
    return;
  }
  // A peer that never completed the handshake is dropped (ENet tells it nothing).
  std::erase_if(remotes, [&](const detail::Remote& r) {
    const bool expired = is_host && !r.handshaken && now - r.connected_at > handshake_timeout_ms();
    if (expired) transport->drop(r.conn);
    return expired;
  });
  for (detail::Remote& r : remotes) {
    if (!r.handshaken) continue;
    const bool matters = !is_host || r.slot < players;
    // A joiner the host accepted but has not heard inputs from may not have the accept yet
    // (ENet resends a lost one after 500 ms, doubling): it has the handshake's time too.
    const double limit = is_host && !r.heard_inputs
                             ? std::max(peer_timeout_ms(), handshake_timeout_ms())
                             : peer_timeout_ms();
    if (matters && state == MatchState::playing && now - r.last_heard > limit) {
      fail(fmt::format("{} timed out: nothing received for {} ms (at tick {})", who(r),
                       static_cast<long long>(now - r.last_heard), next_step));
    }
  }
}

}  // namespace fixstep::net
