// fixstep::net: a desync located to its first differing tick and body. A peer keeps the
// confirmed world at its last hash ticks (checkpoints) and the state hash of every confirmed
// tick since the oldest. When a hash differs at tick T, it sends its partner (the peer it
// compared with, or the host) the hashes of every tick of the window (T - hash_every, T]; each
// side finds the first tick t0 whose hashes differ, re-simulates its state of t0 from the
// checkpoint before it and sends it body by body; each compares the other's with its own and
// names the first differing body and field (core's first_difference).
#include <fmt/format.h>

#include <algorithm>

#include "fixstep/core/world.hpp"
#include "match_peer_impl.hpp"

namespace fixstep::net {

namespace {

/// Checkpoints kept: the window of a desync found this many hash ticks late can be located.
constexpr std::size_t max_checkpoints = 8;
/// Most tick hashes of a partner held (a window's, received before our own detection).
constexpr std::size_t max_partner_hashes = 4096;

}  // namespace

void MatchPeer::Impl::checkpoint() {
  detail::Checkpoint& c = checkpoints.emplace_back();
  c.tick = next_step;
  world->save(c.snapshot);
  if (rules_have_state()) c.rules = rules.save();  // (the confirmed world's, here)
  while (checkpoints.size() > max_checkpoints) checkpoints.pop_front();
  // Tick hashes before the oldest checkpoint can no longer be re-simulated: dropped.
  const std::uint64_t oldest = checkpoints.front().tick + 1;
  while (!tick_hashes.empty() && hashes_from < oldest) {
    tick_hashes.pop_front();
    ++hashes_from;
  }
}

void MatchPeer::Impl::note_tick_hash() {
  if (tick_hashes.empty()) hashes_from = next_step;
  tick_hashes.push_back(world->state_hash());
}

detail::Remote* MatchPeer::Impl::partner_remote(std::uint8_t partner) {
  for (detail::Remote& r : remotes) {
    if (r.handshaken && (!is_host || r.slot == partner)) return &r;
  }
  return nullptr;
}

void MatchPeer::Impl::begin_locating(std::uint64_t tick, std::uint8_t partner) {
  if (locating) return;
  detail::Locating& l = locating.emplace();
  l.to = tick;
  l.from = std::max<std::uint64_t>(tick >= settings.hash_every ? tick - settings.hash_every : 0,
                                   hashes_from > 0 ? hashes_from - 1 : 0);
  l.partner = partner;
  detail::Remote* r = partner_remote(partner);
  if (r == nullptr || tick < hashes_from || tick - hashes_from >= tick_hashes.size()) {
    l.done = true;  // no one to ask, or our hashes of the window are gone
    return;
  }
  for (std::uint64_t t = l.from + 1; t <= l.to;) {
    TickHashesMessage m;
    m.player = slot;
    m.first_tick = static_cast<std::uint32_t>(t);
    for (; t <= l.to && m.hashes.size() < max_tick_hashes; ++t) {
      m.hashes.push_back(tick_hashes[t - hashes_from]);
    }
    std::vector<std::uint8_t> bytes;
    encode_tick_hashes(header(*r, MessageKind::tick_hashes, Channel::reliable), m, bytes);
    send_reliable(*r, bytes);
  }
  try_locate();
}

void MatchPeer::Impl::on_tick_hashes(detail::Remote& r, const TickHashesMessage& m) {
  // A host hears each peer's own hashes (it forwards none); it locates with one partner.
  if (is_host && m.player != r.slot) {
    ++stats.dropped[static_cast<std::size_t>(PacketError::bad_slot)];
    return;
  }
  if (locating && is_host && r.slot != locating->partner) return;
  for (std::size_t i = 0; i < m.hashes.size() && partner_hashes.size() < max_partner_hashes; ++i) {
    partner_hashes[std::uint64_t{m.first_tick} + i] = m.hashes[i];
  }
  // A partner that found a desync with us: if our hashes differ from its too, we locate it
  // with it (we may not have its hash of the window's end yet).
  if (!locating) {
    const std::uint64_t last = std::uint64_t{m.first_tick} + m.hashes.size() - 1;
    for (std::uint64_t t = m.first_tick; t <= last; ++t) {
      if (t < hashes_from || t - hashes_from >= tick_hashes.size()) continue;
      if (tick_hashes[t - hashes_from] == m.hashes[t - m.first_tick]) continue;
      if (!desync) {
        desync = DesyncReport{
            last, slot, m.player, tick_hashes[last - hashes_from], m.hashes.back(), {}, {}};
        state = MatchState::desynced;
        error = fmt::format("desync: player {}'s state hashes differ from ours at tick {}",
                            m.player, t);
      }
      begin_locating(last, is_host ? r.slot : m.player);
      break;
    }
  }
  try_locate();
}

std::optional<StateFields> MatchPeer::Impl::state_at(std::uint64_t tick) {
  const detail::Checkpoint* from = nullptr;
  for (const detail::Checkpoint& c : checkpoints) {
    if (c.tick <= tick) from = &c;
  }
  if (from == nullptr) return std::nullopt;
  for (std::size_t p = 0; p < players; ++p) {
    if (base[p] > from->tick || known(p) < tick) return std::nullopt;
  }
  World scratch(def);
  if (rules.attach) rules.attach(scratch);
  scratch.restore(from->snapshot);
  std::any held;  // the rules' state now, given back after
  if (rules_have_state()) {
    held = rules.save();
    rules.restore(from->rules);
  }
  for (std::uint64_t t = from->tick; t < tick; ++t) {
    merge_scratch.clear();
    for (std::size_t p = 0; p < players; ++p) merge_scratch.push_back(input_at(p, t));
    TickInput merged = merge(merge_scratch, scratch);
    merged.tick = t;
    rules.tick(scratch, merged);
  }
  if (rules_have_state()) rules.restore(held);
  return state_fields(scratch);
}

void MatchPeer::Impl::try_locate() {
  if (!locating || locating->done || locating->first_tick) return;
  detail::Locating& l = *locating;
  for (std::uint64_t t = l.from + 1; t <= l.to; ++t) {
    const auto theirs = partner_hashes.find(t);
    if (theirs == partner_hashes.end()) return;  // not here yet
    if (theirs->second == tick_hashes[t - hashes_from]) continue;
    l.first_tick = t;
    break;
  }
  if (!l.first_tick) l.first_tick = l.to;  // (the window's end differed: never reached)
  l.ours = state_at(*l.first_tick);
  // A state changed outside its ticks (or a stepping that is not deterministic on this
  // machine) is not reproduced by the re-simulation: said in the report.
  l.reproduced = l.ours && state_hash(*l.ours) == tick_hashes[*l.first_tick - hashes_from];
  detail::Remote* r = partner_remote(l.partner);
  if (!l.ours || r == nullptr) {
    finish_locating();
    return;
  }
  const StateFields& f = *l.ours;
  BodyStatesMessage m;
  m.player = slot;
  m.tick = static_cast<std::uint32_t>(f.tick);
  m.body_count = static_cast<std::uint32_t>(f.bodies.size());
  m.rolling = f.rolling;
  m.sleep = f.sleep;
  m.drawn = f.random_state.has_value();
  m.random_state = f.random_state.value_or(0);
  m.reproduced = l.reproduced;
  for (std::size_t i = 0; i < f.bodies.size(); i += max_body_states) {
    const std::size_t n = std::min(max_body_states, f.bodies.size() - i);
    m.first = static_cast<std::uint32_t>(i);
    m.bodies.assign(f.bodies.begin() + static_cast<std::ptrdiff_t>(i),
                    f.bodies.begin() + static_cast<std::ptrdiff_t>(i + n));
    std::vector<std::uint8_t> bytes;
    encode_body_states(header(*r, MessageKind::body_states, Channel::reliable), m, bytes);
    send_reliable(*r, bytes);
  }
  if (f.bodies.empty()) finish_locating();  // nothing to compare but the hashes
}

void MatchPeer::Impl::on_body_states(detail::Remote& r, const BodyStatesMessage& m) {
  if (!locating || locating->done || !locating->ours || m.tick != locating->ours->tick ||
      (is_host && r.slot != locating->partner)) {
    ++stats.dropped[static_cast<std::size_t>(PacketError::unexpected)];
    return;
  }
  detail::Locating& l = *locating;
  if (m.body_count != l.ours->bodies.size() || m.first != l.received) {
    // Another world's body count (or chunks out of order): the counts name the difference.
    l.theirs = StateFields{m.tick, l.ours->precision, {}, m.rolling, m.sleep, {}};
    l.theirs->bodies.resize(std::min<std::size_t>(m.body_count, l.ours->bodies.size() + 1));
    finish_locating();
    return;
  }
  l.theirs_reproduced = m.reproduced;
  if (!l.theirs) {
    l.theirs = StateFields{m.tick, l.ours->precision, {}, m.rolling, m.sleep, {}};
    if (m.drawn) l.theirs->random_state = m.random_state;
    l.theirs->bodies.reserve(m.body_count);
  }
  l.theirs->bodies.insert(l.theirs->bodies.end(), m.bodies.begin(), m.bodies.end());
  l.received += m.bodies.size();
  if (l.received == m.body_count) finish_locating();
}

void MatchPeer::Impl::finish_locating() {
  detail::Locating& l = *locating;
  l.done = true;
  if (!desync || !l.first_tick) return;
  desync->first_tick = l.first_tick;
  const std::uint64_t t = *l.first_tick;
  if (!l.ours) {
    error += fmt::format(
        "; the first tick whose hashes differ is {} (its state could not be "
        "re-simulated here)",
        t);
    return;
  }
  if (!l.theirs) {
    error += fmt::format("; the first tick whose hashes differ is {} (player {} sent no state)", t,
                         l.partner);
    return;
  }
  desync->difference = first_difference(*l.ours, *l.theirs);
  error = fmt::format(
      "desync at tick {} (the first tick whose states differ; tick {} matched), against player "
      "{}: {}{}{}",
      t, t - 1, l.partner,
      desync->difference ? describe(*desync->difference, world.get())
                         : std::string("the states re-simulated are equal field by field"),
      l.reproduced ? ""
                   : "; our re-simulation of that tick does not hash as the tick did: this "
                     "peer's state changed outside its ticks, or its stepping is not "
                     "deterministic",
      l.theirs_reproduced ? ""
                          : fmt::format("; player {}'s re-simulation of that tick does not hash "
                                        "as its tick did: its state changed outside its ticks, or "
                                        "its stepping is not deterministic",
                                        l.partner));
}

}  // namespace fixstep::net
