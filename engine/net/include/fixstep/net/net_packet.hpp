// fixstep's packets as bytes: one encoder per message and one decoder that validates every
// field (size, protocol id, version, kind, slot, tick window, input ranges) before anything is
// used, returning a typed PacketError instead (never undefined behaviour, whatever the bytes).
// Layout: docs/NETWORK.md.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/net/net_protocol.hpp"

namespace fixstep::net {

/// Bytes of the header every packet starts with.
inline constexpr std::size_t header_bytes = 12;

/// What the receiver knows that a packet is checked against.
struct DecodeContext {
  /// Players of the match; 0 before the handshake completes, when only handshake and
  /// disconnect messages are taken (any other is PacketError::unexpected).
  std::uint8_t players = 0;
  /// The receiver's own slot and, per player slot, the next tick whose input it lacks (how
  /// many consecutive ticks it holds). A run may start at or before it (never after: its
  /// first tick would be a delta against a tick the receiver does not have), and the sender
  /// cannot acknowledge more of the receiver's own ticks than the receiver has.
  std::uint8_t own_slot = no_slot;
  std::array<std::uint32_t, max_players> next_needed{};
};

/// A decoded packet: the header, and the message its kind names (the others stay default).
struct Packet {
  Header header{};
  HandshakeRequest request{};
  HandshakeAccept accept{};
  InputsMessage inputs{};
  StateHashMessage hash{};
  DisconnectMessage disconnect{};
  TickHashesMessage tick_hashes{};
  BodyStatesMessage body_states{};
};

/// Decodes `bytes` into `out` when every check passes (PacketError::none); otherwise returns
/// the first failure and `out` must not be used. Checks, in order: size (header_bytes ..
/// max_packet_bytes), protocol id, version, kind, slot (a player's < ctx.players or a
/// spectator's; no_slot only in a handshake request), the message's fixed size and reserved
/// bits, then its fields: players 2..max_players, hash_every >= 1, runs of known players each
/// once, 1..max_run_ticks ticks starting at or before ctx.next_needed, inputs in range
/// (check_input), no trailing bytes.
[[nodiscard]] PacketError decode_packet(std::span<const std::uint8_t> bytes,
                                        const DecodeContext& ctx, Packet& out);

/// The encoders: each clears `out` and writes a whole packet.
void encode_handshake_request(const Header& h, const HandshakeRequest& m,
                              std::vector<std::uint8_t>& out);
void encode_handshake_accept(const Header& h, const HandshakeAccept& m,
                             std::vector<std::uint8_t>& out);
void encode_state_hash(const Header& h, const StateHashMessage& m, std::vector<std::uint8_t>& out);
void encode_disconnect(const Header& h, const DisconnectMessage& m, std::vector<std::uint8_t>& out);
/// Throws std::invalid_argument for 0 or more than max_tick_hashes hashes.
void encode_tick_hashes(const Header& h, const TickHashesMessage& m,
                        std::vector<std::uint8_t>& out);
/// Throws std::invalid_argument for 0 or more than max_body_states bodies, or bodies beyond
/// body_count.
void encode_body_states(const Header& h, const BodyStatesMessage& m,
                        std::vector<std::uint8_t>& out);

/// A run to encode: `inputs` of player `player` from tick inputs.front().tick, each a delta
/// against the one before, the first against `prev` (the input of the tick before, or an
/// empty TickInput at tick 0).
struct RunToSend {
  std::uint8_t player = 0;
  std::span<const TickInput> inputs{};
  const TickInput* prev = nullptr;
};
/// The inputs message: `players` acks (next_needed) and the runs (at most max_players, each
/// 1..max_run_ticks ticks). Throws std::invalid_argument when the packet would exceed
/// max_packet_bytes: callers size their runs with inputs_packet_size.
void encode_inputs_message(const Header& h, std::uint8_t players,
                           const std::array<std::uint32_t, max_players>& next_needed,
                           std::span<const RunToSend> runs, std::vector<std::uint8_t>& out);
/// Bytes of the inputs message holding `runs`.
[[nodiscard]] std::size_t inputs_packet_size(std::uint8_t players, std::span<const RunToSend> runs);

}  // namespace fixstep::net
