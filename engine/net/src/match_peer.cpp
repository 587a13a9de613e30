// fixstep::net: a lockstep peer's construction, stepping and hashes (fixstep/net/match_peer.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/net/net_input_codec.hpp"
#include "match_peer_impl.hpp"

namespace fixstep::net {

namespace {

void check_settings(const MatchSettings& s) {
  if (s.players < 2 || s.players > max_players) {
    throw std::invalid_argument(
        fmt::format("match: players must be 2 .. {} (got {})", max_players, s.players));
  }
  if (s.hash_every < 1) throw std::invalid_argument("match: hash_every must be >= 1 tick");
  if (!s.token.empty() && !parse_token(s.token)) {
    throw std::invalid_argument(fmt::format(
        "match: the token must be 32 hexadecimal digits (got {} characters)", s.token.size()));
  }
}

std::unique_ptr<MatchPeer::Impl> make_impl(const WorldDef& def, const MatchSettings& settings,
                                           TickRules rules, InputMerge merge) {
  auto impl = std::make_unique<MatchPeer::Impl>();
  impl->settings = settings;
  impl->def = def;
  impl->def_hash = definition_hash(def);
  impl->world = std::make_unique<World>(def);
  impl->rules = std::move(rules);
  if (impl->rules.attach) impl->rules.attach(*impl->world);
  impl->merge = merge ? std::move(merge) : InputMerge(merge_inputs);
  impl->started_at = detail::clock_ms();
  if (!settings.record_file.empty()) {  // before a port is bound: a bad path fails first
    impl->writer.emplace(def, settings.scene_name, settings.record_hash_every, settings.record_file,
                         settings.scene_text);
    if (!settings.rules_name.empty())
      impl->writer->set_rules(settings.rules_name, settings.rules_version);
  }
  // A nonce that differs between runs and peers; only echoed, never trusted for security.
  impl->nonce = std::random_device{}();
  return impl;
}

/// ENet's own timeout of a reliable command (a state hash, a ping) left unacknowledged: well
/// beyond peer_timeout_ms, so that the match's "not heard from" decides when a link is dead,
/// and a link that still carries packets through heavy loss (ENet doubles its resend time up
/// to 32 round trips) is not cut by an unlucky run of lost resends.
TimeoutSettings enet_timeouts(const MatchSettings& s) {
  const auto at_most = [](std::uint64_t ms) {
    return static_cast<std::uint32_t>(std::min<std::uint64_t>(ms, 0xffffffffu));
  };
  return {at_most(std::uint64_t{s.peer_timeout_ms} * 4),
          at_most(std::uint64_t{s.peer_timeout_ms} * 8)};
}

}  // namespace

TickInput merge_inputs(std::span<const TickInput> players, const World& /*world*/) {
  TickInput out;
  bool dragging = false;
  for (const TickInput& in : players) {
    out.push.x += in.push.x;
    out.push.y += in.push.y;
    out.held |= in.held;
    out.pressed |= in.pressed;
    out.released |= in.released;
    if (!dragging && !in.drag_body.is_null()) {
      out.pointer = in.pointer;
      out.drag_body = in.drag_body;
      dragging = true;
    }
    out.bodies.insert(out.bodies.end(), in.bodies.begin(), in.bodies.end());
  }
  if (!dragging && !players.empty()) out.pointer = players[0].pointer;
  return out;
}

std::uint64_t MatchStats::dropped_total() const {
  std::uint64_t n = 0;
  for (std::uint64_t d : dropped) n += d;
  return n;
}

MatchPeer::MatchPeer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MatchPeer::MatchPeer(MatchPeer&&) noexcept = default;
MatchPeer& MatchPeer::operator=(MatchPeer&&) noexcept = default;
MatchPeer::~MatchPeer() = default;

MatchPeer MatchPeer::host(const WorldDef& def, const MatchSettings& settings, const Address& bind,
                          TickRules rules, InputMerge merge) {
  check_settings(settings);
  auto impl = make_impl(def, settings, std::move(rules), std::move(merge));
  impl->is_host = true;
  impl->token = settings.token.empty() ? random_gate_key() : *parse_token(settings.token);
  impl->transport.emplace(Transport::listen(bind, max_players - 1 + max_spectators,
                                            enet_timeouts(settings), impl->token));
  impl->start(settings.players, 0);
  return MatchPeer(std::move(impl));
}

MatchPeer MatchPeer::join(const WorldDef& def, const MatchSettings& settings, const Address& host,
                          bool spectator, TickRules rules, InputMerge merge, const Address& bind) {
  const std::optional<GateKey> token = parse_token(settings.token);
  if (!token) {
    throw std::invalid_argument(
        settings.token.empty()
            ? "match: joining needs the host's token (MatchSettings::token; a game's --token: "
              "the 32 hexadecimal digits the host prints)"
            : fmt::format("match: the token must be 32 hexadecimal digits (got {} characters)",
                          settings.token.size()));
  }
  auto impl = make_impl(def, settings, std::move(rules), std::move(merge));
  impl->spectator = spectator;
  impl->host_address = host;
  impl->token = *token;
  impl->transport.emplace(Transport::connect(host, enet_timeouts(settings), bind, *token));
  detail::Remote r;
  r.conn = 0;
  r.slot = 0;
  r.connected_at = r.last_heard = impl->started_at;
  impl->remotes.push_back(r);
  return MatchPeer(std::move(impl));
}

void MatchPeer::Impl::set_input_delay(std::uint16_t delay) {
  settings.input_delay = delay;
  for (std::size_t p = 0; p < players; ++p) {
    inputs[p].clear();
    base[p] = 0;
    for (std::uint64_t t = 0; t < delay; ++t) inputs[p].push_back(TickInput{t});
  }
}

void MatchPeer::Impl::start(std::uint8_t player_count, std::uint8_t own_slot) {
  players = player_count;
  slot = own_slot;
  state = MatchState::playing;
  set_input_delay(settings.input_delay);
  // A lockstep host adapting to the round trip picks its input delay when the first peer asks
  // to join (on_request), before it takes an input.
  delay_open = is_host && settings.adapt_to_round_trip && settings.max_rollback == 0;
  if (settings.max_rollback > 0 && slot < players) {
    shown = std::make_unique<World>(def);
    if (rules.attach) rules.attach(*shown);
    if (rules_have_state()) confirmed_rules = rules.save();
  }
  checkpoint();  // tick 0: a desync in the first window is located from here
  if (!settings.record_in_memory) return;
  recorder.emplace(def, settings.scene_name, settings.record_hash_every, settings.scene_text);
  if (!settings.rules_name.empty())
    recorder->set_rules(settings.rules_name, settings.rules_version);
}

void MatchPeer::Impl::fail(std::string why) {
  if (state == MatchState::failed || state == MatchState::desynced) return;
  state = MatchState::failed;
  error = std::move(why);
}

std::string MatchPeer::Impl::who(const detail::Remote& r) const {
  const std::string address = transport->peer_address(r.conn);
  if (!is_host) return fmt::format("the host ({})", address);
  if (r.slot < max_players) return fmt::format("player {} ({})", r.slot, address);
  if (r.slot != no_slot)
    return fmt::format("spectator {} ({})", r.slot - spectator_slot_base, address);
  return fmt::format("a peer that has not joined ({})", address);
}

void MatchPeer::Impl::mark_dirty() {
  for (detail::Remote& r : remotes) r.dirty = true;
}

void MatchPeer::Impl::record_hash(std::uint64_t tick, std::uint64_t hash) {
  own_hashes[tick] = hash;
  if (slot < players) send_hash({slot, static_cast<std::uint32_t>(tick), hash}, nullptr);
  compare_hashes();
}

void MatchPeer::Impl::compare_hashes() {
  for (auto it = their_hashes.begin(); it != their_hashes.end();) {
    const auto own = own_hashes.find(it->first);
    if (own == own_hashes.end()) {
      ++it;
      continue;
    }
    ++stats.hashes_compared;
    if (own->second != it->second.hash && !desync) {
      desync =
          DesyncReport{it->first, slot, it->second.player, own->second, it->second.hash, {}, {}};
      state = MatchState::desynced;
      error = fmt::format(
          "desync at tick {}: our state (slot {}) hashes {:016x}, player {}'s {:016x}; the "
          "hashes of tick {} matched",
          it->first, slot, own->second, it->second.player, it->second.hash,
          it->first >= settings.hash_every ? it->first - settings.hash_every : 0);
      begin_locating(it->first, it->second.player);
    }
    it = their_hashes.erase(it);
  }
}

void MatchPeer::poll(std::uint32_t wait_ms) {
  Impl& m = *impl_;
  for (;;) {
    const TransportEvent ev = m.transport->poll(wait_ms);
    wait_ms = 0;
    if (ev.kind == TransportEvent::Kind::none) break;
    m.handle(ev, detail::clock_ms());
  }
  const double now = detail::clock_ms();
  m.check_timeouts(now);
  m.send_due(now);
  m.transport->flush();
  const TransportCounters c = m.transport->counters();
  m.stats.wire_datagrams_sent = c.datagrams_sent;
  m.stats.wire_bytes_sent = c.bytes_sent + c.datagrams_sent * ip_udp_header_bytes;
  m.stats.wire_datagrams_received = c.datagrams_received;
  m.stats.wire_bytes_received = c.bytes_received + c.datagrams_received * ip_udp_header_bytes;
}

bool MatchPeer::wants_input() const {
  const Impl& m = *impl_;
  if (m.state != MatchState::playing || m.slot >= m.players || m.delay_open) return false;
  const std::uint64_t next = m.known(m.slot);
  if (m.settings.match_ticks != 0 && next >= m.settings.match_ticks) return false;
  const std::uint64_t stepping = m.shown ? m.shown->tick() : m.next_step;
  return next < stepping + m.settings.input_delay + 1;
}

std::uint16_t MatchPeer::input_delay() const {
  return impl_->settings.input_delay;
}

std::uint16_t MatchPeer::rollback_window() const {
  return impl_->rollback_window();
}

double MatchPeer::peer_timeout_ms() const {
  return impl_->peer_timeout_ms();
}

std::uint64_t MatchPeer::next_input_tick() const {
  return impl_->slot < impl_->players ? impl_->known(impl_->slot) : 0;
}

void MatchPeer::add_input(TickInput input) {
  Impl& m = *impl_;
  if (!wants_input()) throw std::logic_error("MatchPeer::add_input: no input wanted now");
  if (check_input(input) != PacketError::none) {
    throw std::invalid_argument(
        "MatchPeer::add_input: an input the network refuses: a "
        "non-finite value, an unknown button or body input kind, more "
        "than max_net_body_inputs body inputs, or a joint input (a match's merge sets joints)");
  }
  input.tick = m.known(m.slot);
  if (m.settings.pointer_on_grid) input.pointer = round_to_pointer_grid(input.pointer);
  m.inputs[m.slot].push_back(std::move(input));
  m.mark_dirty();
}

int MatchPeer::Impl::step_confirmed() {
  // A lockstep player plays tick t out when its own input for t + input_delay is given (the
  // playout delay): one tick per local input, on the player's clock, however the other
  // players' inputs arrive (in bursts of a send interval); a rollback peer's confirmed world
  // and a spectator's step as soon as every input is there. The match's last input_delay
  // ticks have no later local input: once every own input is given, each call steps one, as
  // a given input would have (a clock calling once a tick owed plays them at real time).
  const bool paced = !shown && slot < players;
  int stepped = 0;
  auto ready = [&] {
    for (std::size_t p = 0; p < players; ++p) {
      if (known(p) <= next_step) return false;
    }
    if (!paced) return true;  // (a spectator's slot has no inputs of its own)
    const bool all_given = settings.match_ticks != 0 && known(slot) >= settings.match_ticks;
    if (all_given) return stepped == 0;
    return known(slot) > next_step + settings.input_delay;
  };
  if (settings.match_ticks != 0 && next_step >= settings.match_ticks) {
    state = MatchState::finished;
    return 0;
  }
  if (!ready()) return 0;
  // Rollback: the rules object holds the shown world's state; the confirmed world's meanwhile.
  const bool swap = shown && rules_have_state();
  std::any shown_rules;
  if (swap) {
    shown_rules = rules.save();
    rules.restore(confirmed_rules);
  }
  while (state == MatchState::playing && ready()) {
    merge_scratch.clear();
    for (std::size_t p = 0; p < players; ++p) merge_scratch.push_back(input_at(p, next_step));
    TickInput merged = merge(merge_scratch, *world);
    merged.tick = next_step;
    if (!confirm_from_shown(next_step, shown_rules)) {
      rules.tick(*world, merged);
    }
    record_tick(merged);
    ++next_step;
    ++stepped;
    note_tick_hash();
    if (next_step % settings.hash_every == 0) {
      record_hash(next_step, tick_hashes.back());
      checkpoint();
    }
    if (settings.match_ticks != 0 && next_step >= settings.match_ticks) {
      state = MatchState::finished;
    }
  }
  if (swap) {
    confirmed_rules = rules.save();
    rules.restore(shown_rules);
  }
  return stepped;
}

void MatchPeer::Impl::trim_inputs() {
  // Kept: from the tick before the first one anyone may still need (a delta's base): the next
  // confirmed tick, the shown world's, and each connected peer's next needed tick.
  constexpr std::uint64_t chunk = 1024;  // dropped at once, so erasing costs O(1) a tick
  std::size_t stored = 0;
  for (std::size_t p = 0; p < players; ++p) {
    std::uint64_t keep = next_step;
    if (shown) keep = std::min<std::uint64_t>(keep, shown->tick());
    // (A desync's first tick is re-simulated from the oldest checkpoint.)
    if (!checkpoints.empty()) keep = std::min<std::uint64_t>(keep, checkpoints.front().tick + 1);
    for (const detail::Remote& r : remotes) {
      if (r.handshaken) keep = std::min<std::uint64_t>(keep, r.their_next[p]);
    }
    keep = std::min<std::uint64_t>(keep, known(p));
    if (keep > 0 && keep - 1 >= base[p] + chunk) {
      const std::uint64_t drop = keep - 1 - base[p];
      inputs[p].erase(inputs[p].begin(), inputs[p].begin() + static_cast<std::ptrdiff_t>(drop));
      base[p] += drop;
    }
    stored += inputs[p].size();
  }
  stats.stored_inputs = stored;
}

int MatchPeer::advance() {
  Impl& m = *impl_;
  const bool shown_behind = m.shown && m.state == MatchState::finished;
  if (m.state != MatchState::playing && !shown_behind) return 0;
  // Rollback: the shown world re-simulated first, so that the confirmed ticks it stepped with
  // every real input are taken from its snapshots rather than stepped again.
  if (m.shown) m.roll_back();
  const int stepped = m.step_confirmed();
  if (m.shown) m.advance_shown();
  m.trim_inputs();
  if (m.shown) return stepped;
  // A stall waits for another peer: this player's own input for the next tick is given (a
  // frame that gave no input, between two ticks, waits for nobody).
  const bool own_given = m.slot >= m.players || m.known(m.slot) > m.next_step;
  // (Before the first tick, the players are still joining.)
  const bool stalled =
      stepped == 0 && own_given && m.state == MatchState::playing && m.next_step > 0;
  if (stalled) ++m.stats.stalls;
  m.note_stall(stalled);
  return stepped;
}

void MatchPeer::Impl::note_stall(bool stalled) {
  const double now = detail::clock_ms();
  if (stalled) {
    if (stall_since < 0.0) stall_since = now;
  } else if (stall_since >= 0.0) {
    stats.stalled_ms += now - stall_since;
    stall_since = -1.0;
  }
}

MatchState MatchPeer::state() const {
  return impl_->state;
}
const std::string& MatchPeer::error() const {
  return impl_->error;
}
const std::optional<DesyncReport>& MatchPeer::desync() const {
  return impl_->desync;
}
bool MatchPeer::locating() const {
  return impl_->state == MatchState::desynced && impl_->locating && !impl_->locating->done;
}
std::optional<StateFields> MatchPeer::desync_state() const {
  if (!impl_->locating || !impl_->locating->done) return std::nullopt;
  return impl_->locating->ours;
}
const MatchStats& MatchPeer::stats() const {
  return impl_->stats;
}
std::uint8_t MatchPeer::slot() const {
  return impl_->slot;
}
std::uint8_t MatchPeer::players() const {
  return impl_->players;
}
std::uint16_t MatchPeer::port() const {
  return impl_->transport->port();
}
std::string MatchPeer::token() const {
  return format_token(impl_->token);
}
GateCounters MatchPeer::gate_counters() const {
  return impl_->transport->gate_counters();
}
const World& MatchPeer::world() const {
  return *impl_->world;
}
const World& MatchPeer::shown_world() const {
  return impl_->shown ? *impl_->shown : *impl_->world;
}
World& MatchPeer::world_for_test() {
  return *impl_->world;
}

bool MatchPeer::settled() const {
  const Impl& m = *impl_;
  if (m.state != MatchState::finished) return false;
  for (const detail::Remote& r : m.remotes) {
    if (!r.handshaken || !r.hashes_due.empty()) {
      if (r.handshaken) return false;
      continue;
    }
    for (std::uint8_t p = 0; p < m.players; ++p) {
      if (m.ours_to_send(r, p) && r.their_next[p] < m.known(p)) return false;
    }
  }
  return true;
}

void MatchPeer::leave() {
  Impl& m = *impl_;
  for (detail::Remote& r : m.remotes) {
    if (!r.handshaken) continue;
    std::vector<std::uint8_t> bytes;
    // A desynced peer says so: the others stop desynced too and keep their recordings.
    encode_disconnect(
        m.header(r, MessageKind::disconnect, Channel::reliable),
        {m.state == MatchState::desynced ? DisconnectReason::desync : DisconnectReason::leaving},
        bytes);
    m.send_reliable(r, bytes);
    m.transport->disconnect(r.conn);
  }
  m.transport->flush();
  if (m.state == MatchState::playing || m.state == MatchState::connecting) {
    m.fail("left the match");
  }
}

}  // namespace fixstep::net
