// fixstep::net: the messages that locate a desync, as bytes (fixstep/net/net_packet.hpp):
// tick_hashes (a window's state hash per tick) and body_states (a state, body by body).
#include "desync_packets.hpp"

#include <stdexcept>

#include "byte_io.hpp"
#include "fixstep/net/net_packet.hpp"

namespace fixstep::net {

namespace {

constexpr std::size_t tick_hashes_fixed = header_bytes + 6;   // player, first tick, count
constexpr std::size_t body_states_fixed = header_bytes + 23;  // ... flags, random state
constexpr std::size_t body_state_bytes = 6 * 8 + 2 * 4;

/// A player's slot of the match or a spectator's.
bool is_peer_slot(std::uint8_t slot, std::uint8_t players) {
  return slot < players ||
         (slot >= spectator_slot_base && slot < spectator_slot_base + max_spectators);
}

}  // namespace

namespace detail {

PacketError decode_tick_hashes(ByteReader& r, std::size_t size, const DecodeContext& ctx,
                               Packet& p) {
  if (size < tick_hashes_fixed) return PacketError::too_short;
  TickHashesMessage& m = p.tick_hashes;
  m.player = r.u8();
  m.first_tick = r.u32();
  const std::uint8_t count = r.u8();
  if (!is_peer_slot(m.player, ctx.players)) return PacketError::bad_slot;
  if (count == 0 || count > max_tick_hashes) return PacketError::bad_field;
  if (size < tick_hashes_fixed + 8 * std::size_t{count}) return PacketError::too_short;
  if (size > tick_hashes_fixed + 8 * std::size_t{count}) return PacketError::trailing_bytes;
  m.hashes.resize(count);
  for (std::uint64_t& h : m.hashes) h = r.u64();
  return PacketError::none;
}

PacketError decode_body_states(ByteReader& r, std::size_t size, const DecodeContext& ctx,
                               Packet& p) {
  if (size < body_states_fixed) return PacketError::too_short;
  BodyStatesMessage& m = p.body_states;
  m.player = r.u8();
  m.tick = r.u32();
  m.body_count = r.u32();
  m.first = r.u32();
  const std::uint8_t count = r.u8();
  const std::uint8_t flags = r.u8();
  m.random_state = r.u64();
  if (!is_peer_slot(m.player, ctx.players)) return PacketError::bad_slot;
  if ((flags & ~15u) != 0 || count == 0 || count > max_body_states) return PacketError::bad_field;
  if (m.body_count > max_state_bodies || std::uint64_t{m.first} + count > m.body_count) {
    return PacketError::bad_field;
  }
  m.rolling = (flags & 1u) != 0;
  m.sleep = (flags & 2u) != 0;
  m.drawn = (flags & 4u) != 0;
  m.reproduced = (flags & 8u) == 0;
  if (size < body_states_fixed + body_state_bytes * count) return PacketError::too_short;
  if (size > body_states_fixed + body_state_bytes * count) return PacketError::trailing_bytes;
  m.bodies.resize(count);
  for (BodyState& b : m.bodies) {
    b.x = r.f64();
    b.y = r.f64();
    b.vx = r.f64();
    b.vy = r.f64();
    b.theta = r.f64();
    b.omega = r.f64();
    b.sleep_ticks = r.u32();
    b.island = r.u32();
  }
  return PacketError::none;
}

}  // namespace detail

void encode_tick_hashes(const Header& h, const TickHashesMessage& m,
                        std::vector<std::uint8_t>& out) {
  if (m.hashes.empty() || m.hashes.size() > max_tick_hashes) {
    throw std::invalid_argument("net::encode_tick_hashes: 1 to max_tick_hashes hashes");
  }
  out.clear();
  detail::ByteWriter w(out);
  detail::write_packet_header(w, MessageKind::tick_hashes, h);
  w.u8(m.player);
  w.u32(m.first_tick);
  w.u8(static_cast<std::uint8_t>(m.hashes.size()));
  for (const std::uint64_t x : m.hashes) w.u64(x);
}

void encode_body_states(const Header& h, const BodyStatesMessage& m,
                        std::vector<std::uint8_t>& out) {
  if (m.bodies.empty() || m.bodies.size() > max_body_states ||
      std::uint64_t{m.first} + m.bodies.size() > m.body_count) {
    throw std::invalid_argument(
        "net::encode_body_states: 1 to max_body_states bodies of body_count");
  }
  out.clear();
  detail::ByteWriter w(out);
  detail::write_packet_header(w, MessageKind::body_states, h);
  w.u8(m.player);
  w.u32(m.tick);
  w.u32(m.body_count);
  w.u32(m.first);
  w.u8(static_cast<std::uint8_t>(m.bodies.size()));
  w.u8(static_cast<std::uint8_t>((m.rolling ? 1u : 0u) | (m.sleep ? 2u : 0u) | (m.drawn ? 4u : 0u) |
                                 (m.reproduced ? 0u : 8u)));
  w.u64(m.random_state);
  for (const BodyState& b : m.bodies) {
    w.f64(b.x);
    w.f64(b.y);
    w.f64(b.vx);
    w.f64(b.vy);
    w.f64(b.theta);
    w.f64(b.omega);
    w.u32(b.sleep_ticks);
    w.u32(b.island);
  }
}

}  // namespace fixstep::net
