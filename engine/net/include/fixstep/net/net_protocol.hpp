// fixstep's network protocol: the messages peers exchange, their limits and the typed errors
// the decoder (net_packet.hpp) returns. The byte layout is in docs/NETWORK.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/core/state_difference.hpp"

namespace fixstep::net {

/// First four bytes of every packet ("FXSN" little-endian): a datagram without them is not
/// fixstep's and is dropped before anything else is read.
inline constexpr std::uint32_t protocol_id = 0x4e535846u;
/// The protocol version this build speaks; a packet of another version is refused.
inline constexpr std::uint8_t protocol_version = 7;
/// Largest packet, bytes (under a 1280-byte IPv6 minimum MTU with UDP and ENet headers).
inline constexpr std::size_t max_packet_bytes = 1200;
/// Most players of one match, and most spectators.
inline constexpr std::size_t max_players = 8;
inline constexpr std::size_t max_spectators = 8;
/// The slot byte of a peer that has none yet (a handshake request).
inline constexpr std::uint8_t no_slot = 0xff;
/// Spectators' slots are spectator_slot_base + k, k < max_spectators.
inline constexpr std::uint8_t spectator_slot_base = 0x80;
/// Most ticks one input run carries (a sender resends at most this many unacknowledged ticks).
inline constexpr std::uint32_t max_run_ticks = 256;
/// Most ticks an input run may start after the receiver's next needed tick (the ticks
/// between in flight or lost: the receiver skips such a run, and the sender resends from its
/// acknowledgement when that stops moving).
inline constexpr std::uint32_t max_gap_ticks = 2 * max_run_ticks;
/// Most per-body inputs one player's tick may carry on the network (TickInput::bodies).
inline constexpr std::size_t max_net_body_inputs = 16;
/// Handshake requests are padded to this size, so that no fixstep reply to a peer that has not
/// completed the handshake is larger than what it sent (no amplification; before it, the
/// host's gate answers only with less than it got: net_gate.hpp).
inline constexpr std::size_t handshake_request_bytes = 64;

/// Message kinds (the header's kind byte).
enum class MessageKind : std::uint8_t {
  handshake_request = 1,  ///< a joining peer asks for a slot
  handshake_accept = 2,   ///< the host gives it one, with the match's settings
  inputs = 3,             ///< input runs and acks (unreliable, resent until acknowledged)
  state_hash = 4,         ///< a confirmed tick's state hash (desync detection)
  disconnect = 5,         ///< a peer leaves, with a reason
  tick_hashes = 6,        ///< after a desync: the state hash of every tick of its window
  body_states = 7,        ///< after a desync: the bodies' state at its first differing tick
};
inline constexpr std::uint8_t max_message_kind = 7;

/// Most tick hashes one tick_hashes message carries, and most bodies one body_states message.
inline constexpr std::size_t max_tick_hashes = 128;
inline constexpr std::size_t max_body_states = 18;
/// Most bodies a body_states message may announce (a world's state sent after a desync).
inline constexpr std::uint32_t max_state_bodies = 1u << 22;

/// What the decoder found wrong with a packet (the caller counts them; none is ever used).
enum class PacketError : std::uint8_t {
  none = 0,
  too_short,        ///< fewer bytes than the header or the message's fixed part
  too_long,         ///< more than max_packet_bytes
  bad_protocol_id,  ///< not a fixstep packet
  bad_version,      ///< another protocol version
  bad_kind,         ///< an unknown message kind
  bad_slot,         ///< a slot that is neither a player's (< players) nor a spectator's
  bad_field,        ///< a reserved bit or byte set, an enum out of range, a size field wrong
  trailing_bytes,   ///< bytes after the message's end
  bad_tick_range,   ///< an input run outside the acceptable window of ticks
  bad_input,        ///< an input out of range: a non-finite number, an unknown button bit,
                    ///< too many body inputs, an unknown body input kind
  out_of_window,    ///< a sequence number too old, or already received (a replay)
  unexpected,       ///< a valid message the receiver does not take in its state
};
inline constexpr std::size_t packet_error_count = 13;
/// "too_short", "bad_protocol_id", ...
[[nodiscard]] std::string_view packet_error_name(PacketError e);

/// Every packet starts with this (12 bytes; docs/NETWORK.md).
struct Header {
  MessageKind kind = MessageKind::inputs;
  std::uint8_t slot = no_slot;  ///< the sender's slot
  std::uint32_t sequence = 0;   ///< the sender's packet counter, +1 per packet sent to a peer
};

struct HandshakeRequest {
  bool spectator = false;
  std::uint32_t nonce = 0;            ///< echoed in the accept
  std::uint64_t definition_hash = 0;  ///< the joiner's world (a host with another refuses)
};

struct HandshakeAccept {
  std::uint32_t nonce = 0;        ///< the request's
  std::uint8_t players = 2;       ///< 2 .. max_players
  std::uint8_t your_slot = 0;     ///< a player's (< players) or a spectator's slot
  std::uint16_t input_delay = 0;  ///< ticks
  std::uint16_t hash_every = 0;   ///< ticks between exchanged state hashes, >= 1
  /// The host plays rollback (its MatchSettings::max_rollback > 0), else lockstep: a joiner
  /// that takes the host's kind (MatchSettings::session_from_host) plays the same.
  bool host_rollback = false;
  std::uint64_t definition_hash = 0;  ///< the host's world (a joiner with another refuses)
};

/// One tick of an input run as sent: the fields `mask` names (InputField bits) are in
/// `fields`, the others are the previous tick's (net_input_codec.hpp, apply_delta).
struct InputDelta {
  std::uint8_t mask = 0;
  TickInput fields{};
};

/// Consecutive inputs of one player: ticks first_tick .. first_tick + deltas.size() - 1, each a
/// delta against the tick before (the first against the receiver's input of first_tick - 1,
/// or an empty TickInput at tick 0).
struct InputRun {
  std::uint8_t player = 0;
  std::uint32_t first_tick = 0;
  std::vector<InputDelta> deltas;
};

/// The inputs message: every player's next tick the sender is missing (acks, index = slot,
/// `players` entries) and runs of inputs the receiver is missing.
struct InputsMessage {
  std::array<std::uint32_t, max_players> next_needed{};  ///< per player slot
  std::vector<InputRun> runs;
};

struct StateHashMessage {
  std::uint8_t player = 0;  ///< whose state it is (a host forwards others' hashes)
  std::uint32_t tick = 0;   ///< the state after this many ticks
  std::uint64_t hash = 0;   ///< World::state_hash()
};

/// After a desync: `player`'s state hashes of ticks first_tick .. first_tick + hashes.size() - 1
/// (1..max_tick_hashes), so that the receiver finds the first tick whose states differ.
struct TickHashesMessage {
  std::uint8_t player = 0;
  std::uint32_t first_tick = 0;
  std::vector<std::uint64_t> hashes;
};

/// After a desync: part of `player`'s state after `tick` ticks (the first tick whose hashes
/// differ): bodies first .. first + bodies.size() - 1 (1..max_body_states) of body_count, with
/// the parts the hash covers (rolling, sleep) and random()'s state (drawn: has one).
struct BodyStatesMessage {
  std::uint8_t player = 0;
  std::uint32_t tick = 0;
  std::uint32_t body_count = 0;
  std::uint32_t first = 0;
  bool rolling = false, sleep = false, drawn = false;
  /// The sender's re-simulation of `tick` hashes as its tick did (else its state changed
  /// outside its ticks, or its stepping is not deterministic).
  bool reproduced = true;
  std::uint64_t random_state = 0;
  std::vector<BodyState> bodies;
};

enum class DisconnectReason : std::uint8_t {
  leaving = 1,
  refused = 2,  ///< the host refused the handshake: no free slot
  desync = 3,
  timeout = 4,
  another_world = 5,  ///< the host refused the handshake: the joiner's world is another
  /// The host refused a spectator: it no longer keeps the match's first inputs (it keeps a
  /// bounded window of them), so a spectator, which steps from tick 0, could not follow.
  too_late = 6,
};

struct DisconnectMessage {
  DisconnectReason reason = DisconnectReason::leaving;
};

}  // namespace fixstep::net
