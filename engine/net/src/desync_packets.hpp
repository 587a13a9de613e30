// Internal to fixstep::net: the decoders of the messages that locate a desync
// (desync_packets.cpp), called by decode_packet (packet.cpp).
#pragma once

#include "byte_io.hpp"
#include "fixstep/net/net_packet.hpp"

namespace fixstep::net::detail {

/// Every packet's 12-byte header, of kind `kind` (packet.cpp).
void write_packet_header(ByteWriter& w, MessageKind kind, const Header& h);

/// tick_hashes after the header: player a slot of the match, 1..max_tick_hashes hashes, exact
/// size.
[[nodiscard]] PacketError decode_tick_hashes(ByteReader& r, std::size_t size,
                                             const DecodeContext& ctx, Packet& p);
/// body_states after the header: player a slot of the match, flags bits 0-3 only,
/// 1..max_body_states bodies, first + count <= body_count <= max_state_bodies, exact size.
[[nodiscard]] PacketError decode_body_states(ByteReader& r, std::size_t size,
                                             const DecodeContext& ctx, Packet& p);

}  // namespace fixstep::net::detail
