// Internal to fixstep::net: a lockstep peer's state (fixstep/net/match_peer.hpp), shared by the
// files that step it (match_peer.cpp), receive (match_receive.cpp) and send
// (match_send.cpp).
#pragma once

#include <any>
#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/core/state_difference.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/io/recording_writer.hpp"
#include "fixstep/net/match_peer.hpp"
#include "fixstep/net/net_packet.hpp"
#include "sequence_window.hpp"

namespace fixstep::net::detail {

inline double clock_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// Another peer this one has a connection to: the host's players and spectators, or a joiner's
/// host.
struct Remote {
  std::uint32_t conn = 0;  ///< Transport's id
  bool handshaken = false;
  std::uint8_t slot = no_slot;
  double connected_at = 0.0, last_heard = 0.0, last_sent = -1e300;
  bool dirty = true;  ///< something new to send
  /// An inputs packet came from it: it has the handshake's accept (a host sends a joiner no
  /// inputs before, which it would drop).
  bool heard_inputs = false;
  std::array<std::uint32_t, max_players> their_next{};  ///< per player: what it has (acks)
  /// Per player: the end of the ticks sent to it at least once, and when its ack last moved
  /// (or the ticks in flight were last resent): while small (redundant()) they are sent again
  /// in every packet; else once, and resent from the ack only when it has not moved for a
  /// retransmission timeout (resend_timeout).
  std::array<std::uint32_t, max_players> sent_to{};
  std::array<double, max_players> ack_moved_at{};
  SequenceWindow window;                               ///< unreliable channel
  std::optional<std::uint32_t> reliable_seen;          ///< the reliable channel's last
  std::uint32_t seq_unreliable = 0, seq_reliable = 0;  ///< sent
  /// State hashes to send with the next inputs packet (one datagram for both).
  std::vector<StateHashMessage> hashes_due;
  /// Rollback's time sync: its frame advantage over us when it sent its newest inputs packet
  /// (its own inputs known against its acknowledgement of ours), the end of its own inputs
  /// it has sent (arrived in order or not), and that packet's sequence.
  std::int64_t their_advantage = 0;
  std::uint64_t their_position = 0;
  std::optional<std::uint32_t> advantage_seq;
};

/// The confirmed world's state after `tick` ticks (a hash tick, or 0) and the rules' (TickRules
/// save), from which a desync's first differing tick is re-simulated.
struct Checkpoint {
  std::uint64_t tick = 0;
  WorldSnapshot snapshot;
  std::any rules;
};

/// A desync being located with one other peer (the partner): both send the state hash of
/// every tick of the window (from, to], find the first tick whose hashes differ, and send their
/// state of that tick body by body (desync_locate.cpp).
struct Locating {
  std::uint64_t from = 0, to = 0;
  std::uint8_t partner = 0;  ///< the partner's slot
  std::optional<std::uint64_t> first_tick;
  std::optional<StateFields> ours, theirs;
  std::uint64_t received = 0;     ///< bodies of theirs received
  bool reproduced = true;         ///< our re-simulation of first_tick hashes as the tick did
  bool theirs_reproduced = true;  ///< the partner's did (body_states)
  bool done = false;
};

/// Rollback: the shown world's state before tick `tick`, and the inputs it was stepped with.
struct ShownFrame {
  std::uint64_t tick = 0;
  WorldSnapshot snapshot;
  std::any rules;  ///< TickRules::save() before the tick (rules with state)
  std::array<TickInput, max_players> used{};
  std::uint32_t predicted = 0;  ///< bit p: used[p] was a prediction
};

}  // namespace fixstep::net::detail

namespace fixstep::net {

struct MatchPeer::Impl {
  bool is_host = false;
  bool spectator = false;
  Address host_address;
  MatchSettings settings;
  WorldDef def;
  std::uint64_t def_hash = 0;
  std::unique_ptr<World> world;
  TickRules rules;
  InputMerge merge;
  std::optional<Transport> transport;
  std::optional<Recorder> recorder;  ///< settings.record_in_memory
  /// settings.record_file: created with the peer, reset once finished (finish_recording, or
  /// near max_recording_bytes: recording_cut).
  std::optional<RecordingWriter> writer;
  std::optional<std::uint64_t> recording_cut;
  bool recording_taken = false;  ///< finish_recording has answered
  MatchState state = MatchState::connecting;
  std::string error;
  std::optional<DesyncReport> desync;
  MatchStats stats;
  std::uint8_t slot = no_slot;
  std::uint8_t players = 0;
  /// Per player, the inputs of ticks base[p] .. known(p) - 1: those before are dropped once
  /// no one needs them (trim_inputs), so memory does not grow with the match's length.
  std::array<std::vector<TickInput>, max_players> inputs;
  std::array<std::uint64_t, max_players> base{};
  std::uint64_t next_step = 0;
  std::vector<detail::Remote> remotes;
  std::map<std::uint64_t, std::uint64_t> own_hashes;            ///< tick -> our state hash
  std::multimap<std::uint64_t, StateHashMessage> their_hashes;  ///< not compared yet
  std::uint32_t nonce = 0;
  GateKey token{};  ///< the match's (net_gate.hpp)
  double started_at = 0.0;
  double stall_since = -1.0;
  std::uint8_t spectators = 0;
  std::vector<std::uint8_t> buffer;
  std::vector<TickInput> merge_scratch;
  // Rollback (settings.max_rollback > 0, players only): the shown world, its frames for the
  // ticks [frames.front().tick, shown->tick()), the first tick predicted wrong, the rules'
  // state of the confirmed world while the rules object holds the shown one's.
  std::unique_ptr<World> shown;
  std::deque<detail::ShownFrame> frames;
  std::uint64_t wrong_from = std::numeric_limits<std::uint64_t>::max();
  std::any confirmed_rules;
  WorldSnapshot confirm_scratch;  ///< the shown world's state, to confirm its last tick from
  /// Time sync, per player heard directly (a joiner: the host; the host: each player): how
  /// many frames this peer is ahead of it, averaged (advance_shown).
  std::array<double, max_players> ahead_of{};
  bool waited_last = false;  ///< the last advance_shown waited for time sync
  // Locating a desync (desync_locate.cpp): checkpoints at the last hash ticks, the state hash
  // of every confirmed tick since the oldest (tick_hashes[i]: after tick hashes_from + i),
  // the partner's tick hashes, the exchange.
  std::deque<detail::Checkpoint> checkpoints;
  std::deque<std::uint64_t> tick_hashes;
  std::uint64_t hashes_from = 1;
  std::map<std::uint64_t, std::uint64_t> partner_hashes;
  std::optional<detail::Locating> locating;
  /// A lockstep host adapting its input delay: not picked yet (no one asked to join).
  bool delay_open = false;

  /// Rollback: the window now (MatchSettings::adapt_to_round_trip).
  [[nodiscard]] std::uint16_t rollback_window() const;
  /// The input delay a lockstep host picks for a round trip of rtt_ms.
  [[nodiscard]] std::uint16_t input_delay_for(std::uint32_t rtt_ms) const;
  /// Fixes the input delay at `delay`: every player's first `delay` ticks are empty.
  void set_input_delay(std::uint16_t delay);
  /// Stall time: a stall begins (stalled) or ends (MatchStats::stalled_ms).
  void note_stall(bool stalled);
  [[nodiscard]] double peer_timeout_ms() const;       ///< adapted to the round trip
  [[nodiscard]] double handshake_timeout_ms() const;  ///< adapted to the round trip

  // match_peer.cpp
  void start(std::uint8_t players, std::uint8_t slot);  ///< the handshake done
  void fail(std::string why);
  [[nodiscard]] std::uint32_t known(std::size_t player) const {
    return static_cast<std::uint32_t>(base[player] + inputs[player].size());
  }
  [[nodiscard]] std::string who(const detail::Remote& r) const;
  void record_hash(std::uint64_t tick, std::uint64_t hash);
  void compare_hashes();
  void mark_dirty();

  [[nodiscard]] bool rules_have_state() const { return rules && rules.save && rules.restore; }
  int step_confirmed();
  [[nodiscard]] const TickInput& input_at(std::size_t player, std::uint64_t tick) const {
    return inputs[player][tick - base[player]];
  }
  void trim_inputs();
  void record_tick(const TickInput& merged);  ///< the confirmed tick just stepped

  // rollback.cpp
  [[nodiscard]] TickInput predict(std::size_t player, std::uint64_t tick) const;
  void check_prediction(std::size_t player, std::uint64_t tick);
  void step_shown();
  void roll_back();
  /// Confirms tick t from the shown world's snapshot when it stepped t with every real input
  /// (`shown_rules`: the shown world's rules state now). Returns whether it did.
  bool confirm_from_shown(std::uint64_t t, const std::any& shown_rules);
  void advance_shown();
  [[nodiscard]] bool all_players_joined() const;  ///< a host: every player slot handshaken
  [[nodiscard]] double time_sync_ahead();         ///< frames ahead of the others, averaged

  // desync_locate.cpp
  void checkpoint();      ///< the confirmed world at a hash tick (or 0)
  void note_tick_hash();  ///< the confirmed tick just stepped
  void begin_locating(std::uint64_t tick, std::uint8_t partner);
  void on_tick_hashes(detail::Remote& r, const TickHashesMessage& m);
  void on_body_states(detail::Remote& r, const BodyStatesMessage& m);
  void try_locate();
  void finish_locating();
  [[nodiscard]] std::optional<StateFields> state_at(std::uint64_t tick);
  [[nodiscard]] detail::Remote* partner_remote(std::uint8_t slot);

  // match_receive.cpp
  void handle(const TransportEvent& ev, double now);
  void receive(detail::Remote& r, const Packet& p, Channel channel, double now);
  void on_request(detail::Remote& r, const Packet& p);
  void on_accept(detail::Remote& r, const Packet& p);
  void on_refused(DisconnectReason why);
  void on_inputs(detail::Remote& r, const Packet& p, double now);
  void on_hash(detail::Remote& r, const StateHashMessage& m);
  void check_timeouts(double now);
  [[nodiscard]] detail::Remote* remote(std::uint32_t conn);
  [[nodiscard]] DecodeContext context(const detail::Remote& r) const;

  // match_send.cpp
  void send_due(double now);
  void send_inputs(detail::Remote& r, double now);
  [[nodiscard]] double resend_timeout(const detail::Remote& r) const;
  [[nodiscard]] bool resend_due(const detail::Remote& r, double now) const;
  /// Whether player p's ticks from `acked` on encode within settings.redundant_bytes (sent
  /// again in every packet until acknowledged).
  [[nodiscard]] bool redundant(std::uint8_t p, std::uint32_t acked) const;
  [[nodiscard]] bool ours_to_send(const detail::Remote& r, std::size_t player) const {
    return is_host ? player != r.slot : player == slot;
  }
  void send_reliable(detail::Remote& r, const std::vector<std::uint8_t>& bytes);
  void send_hash(const StateHashMessage& m, const detail::Remote* except);
  void refuse(detail::Remote& r, DisconnectReason why);
  [[nodiscard]] Header header(detail::Remote& r, MessageKind kind, Channel channel);
};

}  // namespace fixstep::net
