// fixstep::net: packets encoded and decoded (fixstep/net/net_packet.hpp).
#include <stdexcept>

#include "byte_io.hpp"
#include "desync_packets.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/net/net_input_codec.hpp"
#include "fixstep/net/net_packet.hpp"

namespace fixstep::net {

namespace {

constexpr std::size_t accept_bytes = header_bytes + 19;
constexpr std::size_t state_hash_bytes = header_bytes + 13;
constexpr std::size_t disconnect_bytes = header_bytes + 1;
constexpr std::size_t run_header_bytes = 9;  // player, first tick, ticks, item bytes

void write_header(detail::ByteWriter& w, const Header& h) {
  w.u32(protocol_id);
  w.u8(protocol_version);
  w.u8(static_cast<std::uint8_t>(h.kind));
  w.u8(h.slot);
  w.u8(0);
  w.u32(h.sequence);
}

bool is_spectator_slot(std::uint8_t slot) {
  return slot >= spectator_slot_base && slot < spectator_slot_base + max_spectators;
}

bool is_slot(std::uint8_t slot, std::uint8_t players) {
  return slot < players || is_spectator_slot(slot);
}

PacketError read_header(detail::ByteReader& r, std::size_t size, Header& h) {
  if (size < header_bytes) return PacketError::too_short;
  if (size > max_packet_bytes) return PacketError::too_long;
  if (r.u32() != protocol_id) return PacketError::bad_protocol_id;
  if (r.u8() != protocol_version) return PacketError::bad_version;
  const std::uint8_t kind = r.u8();
  if (kind < 1 || kind > max_message_kind) return PacketError::bad_kind;
  h.kind = static_cast<MessageKind>(kind);
  h.slot = r.u8();
  if (r.u8() != 0) return PacketError::bad_field;
  h.sequence = r.u32();
  return PacketError::none;
}

PacketError decode_request(detail::ByteReader& r, std::size_t size, Packet& p) {
  if (size < handshake_request_bytes) return PacketError::too_short;
  if (size > handshake_request_bytes) return PacketError::trailing_bytes;
  if (p.header.slot != no_slot) return PacketError::bad_slot;
  const std::uint8_t flags = r.u8();
  if ((flags & ~1u) != 0) return PacketError::bad_field;
  p.request.spectator = (flags & 1u) != 0;
  p.request.nonce = r.u32();
  p.request.definition_hash = r.u64();
  if (!r.zeros(handshake_request_bytes - header_bytes - 13)) return PacketError::bad_field;
  return PacketError::none;
}

PacketError decode_accept(detail::ByteReader& r, std::size_t size, Packet& p) {
  if (size < accept_bytes) return PacketError::too_short;
  if (size > accept_bytes) return PacketError::trailing_bytes;
  HandshakeAccept& a = p.accept;
  a.nonce = r.u32();
  a.players = r.u8();
  a.your_slot = r.u8();
  a.input_delay = r.u16();
  a.hash_every = r.u16();
  const std::uint8_t flags = r.u8();
  a.host_rollback = (flags & 1u) != 0;
  a.definition_hash = r.u64();
  if ((flags & ~1u) != 0) return PacketError::bad_field;
  if (p.header.slot != 0) return PacketError::bad_slot;  // the host is player 0
  if (a.players < 2 || a.players > max_players || a.hash_every == 0) return PacketError::bad_field;
  if (!is_slot(a.your_slot, a.players) || a.your_slot == 0) return PacketError::bad_slot;
  return PacketError::none;
}

PacketError decode_run(detail::ByteReader& r, std::span<const std::uint8_t> bytes,
                       const DecodeContext& ctx, std::uint32_t seen, InputRun& run) {
  run.player = r.u8();
  run.first_tick = r.u32();
  const std::uint16_t ticks = r.u16();
  const std::uint16_t item_bytes = r.u16();
  if (!r.ok()) return PacketError::too_short;
  if (run.player >= ctx.players) return PacketError::bad_slot;
  if ((seen >> run.player) & 1u) return PacketError::bad_field;  // one run per player
  if (ticks == 0 || ticks > max_run_ticks) return PacketError::bad_tick_range;
  // A run may start after the receiver's next needed tick (the ticks between are in flight
  // or lost: it skips the run), but not far after it.
  if (run.first_tick > std::uint64_t{ctx.next_needed[run.player]} + max_gap_ticks ||
      std::uint64_t{run.first_tick} + ticks > max_recording_ticks) {
    return PacketError::bad_tick_range;
  }
  if (item_bytes > r.remaining()) return PacketError::too_short;
  std::size_t used = 0;
  const PacketError e =
      decode_inputs(bytes.subspan(r.position(), item_bytes), ticks, run.deltas, used);
  if (e != PacketError::none) return e;
  if (used != item_bytes) return PacketError::bad_field;
  for (std::size_t i = 0; i < item_bytes; ++i) (void)r.u8();
  return PacketError::none;
}

PacketError decode_inputs_message(detail::ByteReader& r, std::span<const std::uint8_t> bytes,
                                  const DecodeContext& ctx, Packet& p) {
  InputsMessage& m = p.inputs;
  if (r.u8() != ctx.players) return PacketError::bad_field;
  for (std::size_t i = 0; i < ctx.players; ++i) m.next_needed[i] = r.u32();
  const std::uint8_t run_count = r.u8();
  if (!r.ok()) return PacketError::too_short;
  if (ctx.own_slot < ctx.players && m.next_needed[ctx.own_slot] > ctx.next_needed[ctx.own_slot]) {
    return PacketError::bad_tick_range;  // acknowledges ticks the receiver never sent
  }
  if (run_count > ctx.players) return PacketError::bad_field;
  m.runs.resize(run_count);
  std::uint32_t seen = 0;
  for (InputRun& run : m.runs) {
    if (const PacketError e = decode_run(r, bytes, ctx, seen, run); e != PacketError::none) {
      return e;
    }
    seen |= 1u << run.player;
  }
  return r.remaining() == 0 ? PacketError::none : PacketError::trailing_bytes;
}

PacketError decode_body(detail::ByteReader& r, std::span<const std::uint8_t> bytes,
                        const DecodeContext& ctx, Packet& p) {
  const std::size_t size = bytes.size();
  switch (p.header.kind) {
    case MessageKind::handshake_request:
      return decode_request(r, size, p);
    case MessageKind::handshake_accept:
      return decode_accept(r, size, p);
    case MessageKind::disconnect: {
      if (size < disconnect_bytes) return PacketError::too_short;
      if (size > disconnect_bytes) return PacketError::trailing_bytes;
      const std::uint8_t reason = r.u8();
      if (reason < 1 || reason > 6) return PacketError::bad_field;
      p.disconnect.reason = static_cast<DisconnectReason>(reason);
      return PacketError::none;
    }
    default:
      break;
  }
  if (ctx.players == 0) return PacketError::unexpected;  // before the handshake
  if (!is_slot(p.header.slot, ctx.players)) return PacketError::bad_slot;
  if (p.header.kind == MessageKind::state_hash) {
    if (size < state_hash_bytes) return PacketError::too_short;
    if (size > state_hash_bytes) return PacketError::trailing_bytes;
    p.hash.player = r.u8();
    p.hash.tick = r.u32();
    p.hash.hash = r.u64();
    return p.hash.player < ctx.players ? PacketError::none : PacketError::bad_slot;
  }
  if (p.header.kind == MessageKind::tick_hashes) return detail::decode_tick_hashes(r, size, ctx, p);
  if (p.header.kind == MessageKind::body_states) return detail::decode_body_states(r, size, ctx, p);
  return decode_inputs_message(r, bytes, ctx, p);
}

}  // namespace

void detail::write_packet_header(detail::ByteWriter& w, MessageKind kind, const Header& h) {
  write_header(w, {kind, h.slot, h.sequence});
}

std::string_view packet_error_name(PacketError e) {
  static constexpr std::string_view names[packet_error_count] = {
      "none",      "too_short",     "too_long",  "bad_protocol_id", "bad_version",
      "bad_kind",  "bad_slot",      "bad_field", "trailing_bytes",  "bad_tick_range",
      "bad_input", "out_of_window", "unexpected"};
  const auto i = static_cast<std::size_t>(e);
  return i < packet_error_count ? names[i] : std::string_view("unknown");
}

PacketError decode_packet(std::span<const std::uint8_t> bytes, const DecodeContext& ctx,
                          Packet& out) {
  detail::ByteReader r(bytes);
  if (const PacketError e = read_header(r, bytes.size(), out.header); e != PacketError::none) {
    return e;
  }
  if (ctx.players > max_players) return PacketError::unexpected;
  return decode_body(r, bytes, ctx, out);
}

void encode_handshake_request(const Header& h, const HandshakeRequest& m,
                              std::vector<std::uint8_t>& out) {
  out.clear();
  detail::ByteWriter w(out);
  write_header(w, {MessageKind::handshake_request, no_slot, h.sequence});
  w.u8(m.spectator ? 1 : 0);
  w.u32(m.nonce);
  w.u64(m.definition_hash);
  w.zeros(handshake_request_bytes - w.size());
}

void encode_handshake_accept(const Header& h, const HandshakeAccept& m,
                             std::vector<std::uint8_t>& out) {
  out.clear();
  detail::ByteWriter w(out);
  write_header(w, {MessageKind::handshake_accept, h.slot, h.sequence});
  w.u32(m.nonce);
  w.u8(m.players);
  w.u8(m.your_slot);
  w.u16(m.input_delay);
  w.u16(m.hash_every);
  w.u8(m.host_rollback ? 1 : 0);
  w.u64(m.definition_hash);
}

void encode_state_hash(const Header& h, const StateHashMessage& m, std::vector<std::uint8_t>& out) {
  out.clear();
  detail::ByteWriter w(out);
  write_header(w, {MessageKind::state_hash, h.slot, h.sequence});
  w.u8(m.player);
  w.u32(m.tick);
  w.u64(m.hash);
}

void encode_disconnect(const Header& h, const DisconnectMessage& m,
                       std::vector<std::uint8_t>& out) {
  out.clear();
  detail::ByteWriter w(out);
  write_header(w, {MessageKind::disconnect, h.slot, h.sequence});
  w.u8(static_cast<std::uint8_t>(m.reason));
}

std::size_t inputs_packet_size(std::uint8_t players, std::span<const RunToSend> runs) {
  std::size_t n = header_bytes + 2 + 4 * std::size_t{players};
  for (const RunToSend& run : runs) {
    const TickInput empty{};
    n += run_header_bytes + encoded_size(run.inputs, run.prev ? *run.prev : empty);
  }
  return n;
}

void encode_inputs_message(const Header& h, std::uint8_t players,
                           const std::array<std::uint32_t, max_players>& next_needed,
                           std::span<const RunToSend> runs, std::vector<std::uint8_t>& out) {
  if (players > max_players || runs.size() > players) {
    throw std::invalid_argument("net::encode_inputs_message: more runs or players than allowed");
  }
  out.clear();
  detail::ByteWriter w(out);
  write_header(w, {MessageKind::inputs, h.slot, h.sequence});
  w.u8(players);
  for (std::size_t i = 0; i < players; ++i) w.u32(next_needed[i]);
  w.u8(static_cast<std::uint8_t>(runs.size()));
  const TickInput empty{};
  for (const RunToSend& run : runs) {
    if (run.inputs.empty() || run.inputs.size() > max_run_ticks) {
      throw std::invalid_argument("net::encode_inputs_message: a run of 0 or too many ticks");
    }
    w.u8(run.player);
    w.u32(static_cast<std::uint32_t>(run.inputs.front().tick));
    w.u16(static_cast<std::uint16_t>(run.inputs.size()));
    const std::size_t length_at = w.size();
    w.u16(0);
    encode_inputs(run.inputs, run.prev ? *run.prev : empty, out);
    const std::size_t items = out.size() - length_at - 2;
    w.patch_u16(length_at, static_cast<std::uint16_t>(items));
  }
  if (out.size() > max_packet_bytes) {
    throw std::invalid_argument("net::encode_inputs_message: packet over max_packet_bytes");
  }
}

}  // namespace fixstep::net
