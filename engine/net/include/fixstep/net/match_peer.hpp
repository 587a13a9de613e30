// A networked match, in one of two kinds, over the same protocol:
// - deterministic lockstep (MatchSettings::max_rollback = 0): every peer steps tick t once
//   every player's input for t has arrived, so all peers compute the same states bit for bit
//   (fixstep's determinism), sending only inputs. Local input is played `input_delay` ticks
//   after it is given (the playout delay), so a link whose round trip is shorter than the delay
//   never stalls.
// - rollback (max_rollback > 0, GGPO-style): besides the confirmed world, a shown world runs
//   ahead on predicted inputs of the remote players (their last input's levels); when a real
//   input differs from the prediction, the shown world is restored from the snapshot of that
//   tick and re-simulated, at most max_rollback ticks.
// A host (player 0) relays the inputs of each player to the others (a star: a joining peer
// knows only the host's address); spectators receive them all and send none. Peers exchange
// state hashes of confirmed ticks every hash_every ticks; a mismatch stops the match with a
// located report. Each peer records the confirmed inputs as a fixstep recording: streamed into
// a file (MatchSettings::record_file), kept in memory (record_in_memory), or both.
// docs/NETWORK.md.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/rules.hpp"
#include "fixstep/core/state_difference.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/net/net_protocol.hpp"
#include "fixstep/net/net_transport.hpp"

namespace fixstep::net {

/// The input a tick is stepped with, from the players' inputs of that tick (index = slot). Runs
/// on every peer inside the tick, before World::step, so it must be deterministic (as rules
/// are): it may read the world (a player's buttons turned into an impulse on the body it
/// controls, found by handle).
using InputMerge = std::function<TickInput(std::span<const TickInput> players, const World& world)>;

/// The default merge: body inputs concatenated in slot order; push summed in slot order;
/// held, pressed and released or-ed; pointer and drag body the first player's (by slot) that
/// drags a body, else player 0's pointer and no drag.
[[nodiscard]] TickInput merge_inputs(std::span<const TickInput> players, const World& world);

/// The match: what the host decides and sends joiners in the handshake (players, input_delay,
/// hash_every), and what each peer decides for itself (the rest).
struct MatchSettings {
  std::uint8_t players = 2;  ///< 2 .. max_players
  /// Ticks between giving an input and its tick (a lockstep player plays tick t out when it
  /// gives its input for t + input_delay). The default, 100 ms at 60 ticks/s, covers two send
  /// intervals (the default's) and a round trip on a local network: pick it above the round
  /// trip + 2 send intervals, in ticks, to never stall.
  std::uint16_t input_delay = 6;
  /// Ticks between exchanged state hashes, >= 1. Each exchange is a reliable message and its
  /// acknowledgement (what that costs in bandwidth: docs/NETWORK.md).
  std::uint16_t hash_every = 60;
  std::uint64_t match_ticks = 0;  ///< the match ends after this many ticks; 0: never
  /// Rollback: most ticks the shown world may run ahead of the confirmed one on predicted
  /// inputs (and so the longest re-simulation); 0: lockstep (the shown world is the confirmed
  /// one). This peer's own choice: peers of either kind play one match.
  std::uint16_t max_rollback = 0;
  /// A joiner: play the kind the host plays, which its accept says (HandshakeAccept::
  /// host_rollback): rollback with this max_rollback (at least 1) when the host plays rollback,
  /// lockstep when it plays lockstep. The input delay is the host's either way, so a lockstep
  /// joiner of a rollback host plays at its short delay and waits for the host's inputs every
  /// round trip (docs/NETWORK.md). A host and a spectator ignore it.
  bool session_from_host = false;
  /// A player's inputs not yet acknowledged are sent again in every inputs packet (redundantly:
  /// a lost packet is made good by the next one, no round trip lost, as GGPO sends every
  /// unacknowledged input) while they encode in at most this many bytes (net_input_codec.hpp:
  /// unchanged ticks cost a byte per 128, a moving pointer 2–6 bytes a tick: the default holds
  /// a round trip of busy play); beyond it, ticks in flight are sent once and resent from the
  /// ack after a resend timeout. 0: always once.
  std::uint32_t redundant_bytes = 256;
  /// Inputs in flight sent once (above) are resent from the receiver's ack when it has not
  /// moved for 1.25 round trips + send_interval_ms + this margin (ms).
  std::uint32_t resend_ms = 10;
  /// Least time between two inputs packets to one peer, ms: 0 sends one on every new input
  /// and every new input received (about two a tick), more batches the ticks of that long into
  /// one packet (fewer headers, less bandwidth, up to as much more latency each way). The
  /// default is 3 ticks at 60 ticks/s (its bandwidth against the others': docs/NETWORK.md).
  std::uint32_t send_interval_ms = 50;
  /// add_input rounds the player's pointer to the pointer grid (net_input_codec.hpp:
  /// round_to_pointer_grid, about 1 mm) before it is played, sent or recorded, so that a
  /// moving pointer costs 2–6 bytes a tick on the wire instead of 16. Every peer plays the
  /// rounded pointer, so the match stays deterministic either way; false sends it exactly.
  bool pointer_on_grid = true;
  /// Latency hidden by the measured round trip (ENet's estimate, ms; docs/NETWORK.md):
  /// - a lockstep host picks the input delay when the first peer asks to join, from the round
  ///   trip to it: ceil((rtt + send_interval_ms + a 60 Hz frame) / dt) + 1 ticks, at least
  ///   input_delay (then the floor) and at most max_input_delay; it takes no input of its own
  ///   before (wants_input() is false);
  /// - a rollback peer lets its shown world run ahead by up to
  ///   ceil((rtt + 2 send_interval_ms + a 60 Hz frame) / dt) + 2 ticks, at least max_rollback
  ///   and at most max_rollback_window, following the round trip as it is measured;
  /// - the timeouts (peer_timeout_ms, handshake_timeout_ms) grow to at least
  ///   timeout_round_trips round trips.
  /// false: input_delay, max_rollback and the timeouts as given.
  bool adapt_to_round_trip = true;
  /// A player (or the host) not heard from for this long stops the match ("timed out").
  /// ENet's own timeout of an unacknowledged reliable message is set to 4–8 times this, so
  /// that heavy loss on a live link does not cut it.
  std::uint32_t peer_timeout_ms = 5000;
  /// A connection that has not completed the handshake after this long is dropped. ENet
  /// resends a lost connect after 500 ms, doubling each time (a message lost twice in a row
  /// arrives after 1.5 s, three times after 3.5 s), and the handshake is four messages: raise
  /// this for lossy links (a joiner that gives up early retries nothing).
  std::uint32_t handshake_timeout_ms = 3000;
  /// The match's token, 32 hexadecimal digits (net_gate.hpp: a joiner proves it on a cookie of
  /// the host's before ENet reads a datagram of its). A host given none makes a random one
  /// (MatchPeer::token); a joiner must give the host's.
  std::string token;
  /// Recording: the scene name and text (Recorder), the state hash stored every this many
  /// ticks, and the rules' name and version when the match has rules (Recorder::set_rules).
  std::string scene_name = "network match";
  std::string scene_text;
  std::uint64_t record_hash_every = 1;
  std::string rules_name;
  std::uint32_t rules_version = 0;
  /// The recording streamed into this file as the confirmed ticks are stepped (io's
  /// RecordingWriter: a temporary file beside it, renamed into place by
  /// MatchPeer::finish_recording; memory O(1) whatever the match's length); empty: none. The
  /// bytes are those format_recording writes of MatchPeer::recording() for the same ticks.
  /// Near max_recording_bytes the file is finished there, whole, and the rest of the match is
  /// not recorded into it (MatchPeer::recording_cut).
  std::filesystem::path record_file;
  /// Whether the peer also keeps the recording in memory for MatchPeer::recording() (its memory
  /// grows with the match: a hash and up to one input change a tick). A long match sets false
  /// and streams (record_file).
  bool record_in_memory = true;
};

/// The longest input delay a lockstep host picks (adapt_to_round_trip), ticks.
inline constexpr std::uint16_t max_input_delay = 255;
/// The longest rollback window a rollback peer grows to (adapt_to_round_trip), ticks.
inline constexpr std::uint16_t max_rollback_window = 120;
/// Round trips a peer is waited for at least before it times out (adapt_to_round_trip).
inline constexpr std::uint32_t timeout_round_trips = 8;

/// Where a peer's match is.
enum class MatchState : std::uint8_t {
  connecting,  ///< waiting for the transport or the handshake
  playing,
  finished,  ///< match_ticks stepped
  desynced,  ///< a state hash differed: desync() says where
  failed,    ///< refused, timed out or disconnected: error() says why
};

/// Where two peers' states first differed, as far as the exchanged hashes show: the state
/// after `tick` ticks hashed `ours` on player (or spectator) `our_slot` and `theirs` on
/// `their_slot`; the hashes of the tick hash_every before matched.
struct DesyncReport {
  std::uint64_t tick = 0;
  std::uint8_t our_slot = 0, their_slot = 0;
  std::uint64_t ours = 0, theirs = 0;
  /// Once located (MatchPeer::locating() false): the first tick whose states differ (the
  /// peers exchanged every tick's hash of the window), and the first body and field that
  /// differ there (their states exchanged body by body; names: the confirmed world's bodies).
  std::optional<std::uint64_t> first_tick;
  std::optional<StateDifference> difference;
};

/// What a peer counted.
struct MatchStats {
  std::uint64_t packets_sent = 0, bytes_sent = 0;
  std::uint64_t packets_received = 0, bytes_received = 0;
  /// Packets dropped, by PacketError (index = its value): malformed, out of window, replayed,
  /// unexpected. None of them is ever used.
  std::array<std::uint64_t, packet_error_count> dropped{};
  std::uint64_t conflicting_inputs = 0;  ///< resent inputs that differ from the first copy
  /// Input runs skipped: they started after a tick not arrived yet (lost or late)
  std::uint64_t gap_runs = 0;
  /// Input runs resent from the receiver's ack after a resend timeout (a packet lost while
  /// the ticks in flight were sent once: MatchSettings::redundant_bytes)
  std::uint64_t resends = 0;
  /// On the wire (Transport::counters at the last poll): UDP datagrams, and their bytes with
  /// the IPv4 and UDP headers (ip_udp_header_bytes each), ENet's headers, acknowledgements
  /// and pings included; all connections of this peer together.
  std::uint64_t wire_datagrams_sent = 0, wire_bytes_sent = 0;
  std::uint64_t wire_datagrams_received = 0, wire_bytes_received = 0;
  /// advance() calls that stepped nothing while this player's input for the next tick was
  /// given (a spectator: any that stepped nothing): waiting for another player's input
  std::uint64_t stalls = 0;
  /// Time spent waiting so (a rollback peer: at its rollback window), ms
  double stalled_ms = 0.0;
  std::uint32_t round_trip_ms = 0;  ///< to the host (a joiner) or the slowest player (a host)
  std::uint64_t hashes_compared = 0;
  /// Players' inputs held now (all players): those no peer needs any more are dropped in
  /// chunks of 1024 ticks, so this stays bounded however long the match.
  std::uint64_t stored_inputs = 0;
  // Rollback only:
  std::uint64_t predicted_ticks = 0;    ///< shown ticks stepped with a predicted input
  std::uint64_t rollbacks = 0;          ///< restores of the shown world
  std::uint64_t rolled_back_ticks = 0;  ///< ticks re-simulated, in all
  std::uint64_t max_rolled_back = 0;    ///< the most ticks one rollback re-simulated
  std::uint64_t last_rolled_back = 0;   ///< ticks the last advance() re-simulated
  /// Confirmed ticks taken from the shown world's snapshot (it had stepped them with every
  /// real input) instead of stepped a second time
  std::uint64_t confirmed_from_shown = 0;
  /// advance() calls that waited for time sync: this peer ahead of another by over 2 frames,
  /// on average, the link's delay taken out (GGPO's frame advantage)
  std::uint64_t waits = 0;
  /// The shown tick minus the slowest player's (its last input we have), last frame: the link's
  /// delay included, so not what time sync acts on
  std::int64_t frame_advantage = 0;
  [[nodiscard]] std::uint64_t dropped_total() const;
};

/// One peer of a match, lockstep or rollback (MatchSettings::max_rollback): the host or a joiner
/// (player or spectator). Single-threaded: call poll() and advance() often (every frame, or
/// every millisecond in a test).
class MatchPeer {
 public:
  /// Hosts a match of `def` as player 0, listening on `bind` (127.0.0.1 and a port; port 0
  /// picks one: port()), behind the gate of settings.token (a random one when it is empty:
  /// token()). `rules` run after every tick (held by reference: they must outlive
  /// the peer); `merge` makes each tick's input (merge_inputs when empty). Throws
  /// TransportError when the port cannot be bound, std::invalid_argument for bad settings.
  [[nodiscard]] static MatchPeer host(const WorldDef& def, const MatchSettings& settings,
                                      const Address& bind, TickRules rules = {},
                                      InputMerge merge = {});
  /// Joins the match hosted at `host` as a player (or a spectator). players, input_delay and
  /// hash_every come from the host; the rest from `settings`. The host refuses a joiner whose
  /// world differs (definition hash), and its gate one without the host's token
  /// (settings.token: the joiner fails "refused our token"). The joiner's socket is bound to `bind`
  /// (127.0.0.1 and any port by default, which reaches hosts on this machine only; 0.0.0.0 or an
  /// address of this machine's to reach others). Throws TransportError when it cannot be bound,
  /// std::invalid_argument when settings.token is not 32 hexadecimal digits.
  [[nodiscard]] static MatchPeer join(const WorldDef& def, const MatchSettings& settings,
                                      const Address& host, bool spectator = false,
                                      TickRules rules = {}, InputMerge merge = {},
                                      const Address& bind = {});
  MatchPeer(MatchPeer&&) noexcept;
  MatchPeer& operator=(MatchPeer&&) noexcept;
  ~MatchPeer();

  /// Receives and handles every packet that has arrived (waiting at most wait_ms for the
  /// first), sends what is due, checks timeouts.
  void poll(std::uint32_t wait_ms = 0);
  /// Whether the local player may give the next input (a player, playing, fewer than
  /// input_delay + 1 inputs ahead of the next tick to step).
  [[nodiscard]] bool wants_input() const;
  /// The local player's input for tick next_input_tick() (its tick field is set; its pointer
  /// rounded to the pointer grid first, MatchSettings::pointer_on_grid). Throws
  /// std::logic_error when !wants_input(), std::invalid_argument when the network refuses it
  /// (check_input).
  void add_input(TickInput input);
  [[nodiscard]] std::uint64_t next_input_tick() const;
  /// Ticks between a local input and its tick: the host's (MatchSettings::input_delay, or
  /// picked from the round trip), known once the handshake is done.
  [[nodiscard]] std::uint16_t input_delay() const;
  /// Rollback: the most ticks the shown world may run ahead of the confirmed one now
  /// (MatchSettings::max_rollback, or grown to the round trip); 0 in lockstep.
  [[nodiscard]] std::uint16_t rollback_window() const;
  /// How long a peer not heard from is waited for now, ms: MatchSettings::peer_timeout_ms, or
  /// at least timeout_round_trips times the round trip measured (adapt_to_round_trip). The
  /// others wait for this one as long, so it also bounds how long a finished peer answers
  /// (settled) or a desynced one locates (locating) before leave().
  [[nodiscard]] double peer_timeout_ms() const;
  /// Steps every tick whose inputs have all arrived (none past match_ticks), running the
  /// merge, World::step and the rules, recording each; returns the ticks stepped. A lockstep
  /// player steps tick t once its own input for t + input_delay is given, and the match's last
  /// input_delay ticks, which have no later input, one a call. Nothing stepped while playing
  /// counts a stall. Rollback: then rolls the shown world back to the
  /// first tick whose prediction was wrong and re-simulates, and steps it one tick ahead when
  /// the local input for it is there, it is less than max_rollback ticks ahead of the confirmed
  /// world and time sync allows. The rules' state (TickRules save and restore, which rollback
  /// needs for rules with state) is the shown world's between calls.
  int advance();

  [[nodiscard]] MatchState state() const;
  [[nodiscard]] const std::string& error() const;  ///< why it failed ("" otherwise)
  [[nodiscard]] const std::optional<DesyncReport>& desync() const;
  /// Whether a desync is still being located with the peer it was found against (their hashes
  /// of every tick of the window, then their state of the first tick that differs): poll()
  /// until false (bounded by peer_timeout_ms()) before leave(), then desync() names the tick and
  /// the body. A peer that leaves tells the others it desynced (they stop desynced too).
  [[nodiscard]] bool locating() const;
  /// This peer's state of the first tick that differs, once located (nullopt before, or when
  /// it could not be re-simulated).
  [[nodiscard]] std::optional<StateFields> desync_state() const;
  [[nodiscard]] const MatchStats& stats() const;
  [[nodiscard]] std::uint8_t slot() const;     ///< no_slot until the handshake completes
  [[nodiscard]] std::uint8_t players() const;  ///< 0 until the handshake completes
  [[nodiscard]] std::uint16_t port() const;    ///< the bound port
  /// The match's token (32 hexadecimal digits): a joiner's MatchSettings::token.
  [[nodiscard]] std::string token() const;
  /// What the host's gate answered and dropped (zeros on a joiner).
  [[nodiscard]] GateCounters gate_counters() const;
  /// The confirmed world: every tick stepped with every player's real input.
  [[nodiscard]] const World& world() const;
  /// What to show: the rollback world (ahead on predictions), or the confirmed one in lockstep.
  [[nodiscard]] const World& shown_world() const;
  /// The world, for a test that corrupts one peer's state on purpose (a desync).
  [[nodiscard]] World& world_for_test();
  /// The recording of the ticks stepped so far (Recorder::finish at the current state). Throws
  /// std::logic_error when the match never started or MatchSettings::record_in_memory is false.
  [[nodiscard]] Recording recording() const;
  /// Ends the streamed recording (MatchSettings::record_file) at the confirmed world's state and
  /// renames it into place: every confirmed tick (each stepped with every player's real input,
  /// so a rollback peer's predictions are never in it), whether the match finished, failed,
  /// desynced or is stopped between two ticks. Returns the ticks the file holds (those up to
  /// recording_cut() when it was finished at its size limit), nullopt when there is no file (none
  /// asked for, or a joiner whose handshake never completed: its temporary file is removed with
  /// the peer, as it is when this is never called; a host's match starts at once, so its file
  /// may hold 0 ticks).
  /// Throws io's std::runtime_error when the file cannot be written. Once; nullopt after.
  std::optional<std::uint64_t> finish_recording();
  /// The tick at which the streamed recording was finished because it neared
  /// max_recording_bytes (nullopt: it was not).
  [[nodiscard]] std::optional<std::uint64_t> recording_cut() const;
  /// Bytes of the streamed recording held in memory now (not yet handed to the file): at most
  /// about 64 KiB plus hash_every ticks' lines, whatever the match's length; 0 without a file.
  [[nodiscard]] std::uint64_t recording_bytes_held() const;
  /// Whether the match is finished and every peer this one sends to has acknowledged every
  /// input it needs from us (a joiner: its own; the host: every player's it relays) and has
  /// been sent every state hash: leaving now leaves no peer short of a tick. Poll until it
  /// holds (bounded by peer_timeout_ms()), then leave().
  [[nodiscard]] bool settled() const;
  /// Leaves: tells the others (disconnect) and flushes. The peer is finished or failed after.
  void leave();

  struct Impl;  ///< internal (engine/net/src/match_peer_impl.hpp)

 private:
  explicit MatchPeer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace fixstep::net
