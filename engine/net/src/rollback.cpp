// fixstep::net: a rollback peer's shown world: stepped ahead on predicted inputs, rolled back
// to the first tick predicted wrong and re-simulated (fixstep/net/match_peer.hpp).
#include <fmt/format.h>

#include <algorithm>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/net/net_input_codec.hpp"
#include "match_peer_impl.hpp"

namespace fixstep::net {

bool MatchPeer::Impl::all_players_joined() const {
  const auto joined = std::count_if(remotes.begin(), remotes.end(), [&](const detail::Remote& r) {
    return r.handshaken && r.slot < players;
  });
  return joined + 1 >= players;
}

TickInput MatchPeer::Impl::predict(std::size_t player, std::uint64_t tick) const {
  // The last input's levels (buttons held, push, pointer, drag), not its events: a press, a
  // release or an impulse happens once, so repeating it would be a worse guess.
  TickInput in = known(player) > 0 ? input_at(player, known(player) - 1) : TickInput{};
  in.tick = tick;
  in.pressed = 0;
  in.released = 0;
  in.bodies.clear();
  return in;
}

void MatchPeer::Impl::check_prediction(std::size_t player, std::uint64_t tick) {
  if (frames.empty() || tick < frames.front().tick || tick >= shown->tick()) return;
  const detail::ShownFrame& f = frames[tick - frames.front().tick];
  if (((f.predicted >> player) & 1u) == 0) return;
  if (!same_input(input_at(player, tick), f.used[player])) wrong_from = std::min(wrong_from, tick);
}

void MatchPeer::Impl::step_shown() {
  const std::uint64_t t = shown->tick();
  detail::ShownFrame& f = frames.emplace_back();
  f.tick = t;
  shown->save(f.snapshot);
  if (rules_have_state()) f.rules = rules.save();
  for (std::size_t p = 0; p < players; ++p) {
    if (known(p) > t) {
      f.used[p] = input_at(p, t);
    } else {
      f.used[p] = predict(p, t);
      f.predicted |= 1u << p;
    }
  }
  if (f.predicted != 0) ++stats.predicted_ticks;
  TickInput merged = merge(std::span<const TickInput>(f.used.data(), players), *shown);
  merged.tick = t;
  rules.tick(*shown, merged);
}

bool MatchPeer::Impl::confirm_from_shown(std::uint64_t t, const std::any& shown_rules) {
  // The shown world stepped tick t with every player's real input (a prediction that proved
  // right is one), and no misprediction at or before t waits for re-simulation: its state after
  // t is the confirmed one, bit for bit (the same state, input and stepping). Taken from the
  // snapshot before t + 1 (or the shown world itself) instead of stepping t again: GGPO
  // confirms from its saved frames so.
  if (!shown || wrong_from <= t || frames.empty() || t < frames.front().tick ||
      t >= shown->tick()) {
    return false;
  }
  const detail::ShownFrame& f = frames[t - frames.front().tick];
  for (std::size_t p = 0; p < players; ++p) {
    if (((f.predicted >> p) & 1u) != 0 && !same_input(input_at(p, t), f.used[p])) return false;
  }
  if (t + 1 < shown->tick()) {
    const detail::ShownFrame& after = frames[t + 1 - frames.front().tick];
    world->restore(after.snapshot);
    if (rules_have_state()) rules.restore(after.rules);
  } else {
    shown->save(confirm_scratch);
    world->restore(confirm_scratch);
    if (rules_have_state()) rules.restore(shown_rules);
  }
  ++stats.confirmed_from_shown;
  return true;
}

void MatchPeer::Impl::roll_back() {
  stats.last_rolled_back = 0;
  if (wrong_from >= shown->tick()) {
    wrong_from = std::numeric_limits<std::uint64_t>::max();
    return;
  }
  if (frames.empty() || wrong_from < frames.front().tick) {
    fail(fmt::format("internal: a rollback to tick {} past the kept snapshots", wrong_from));
    return;
  }
  const std::uint64_t target = shown->tick();
  const std::size_t at = static_cast<std::size_t>(wrong_from - frames.front().tick);
  shown->restore(frames[at].snapshot);
  if (rules_have_state()) rules.restore(frames[at].rules);
  frames.erase(frames.begin() + static_cast<std::ptrdiff_t>(at), frames.end());
  while (shown->tick() < target) step_shown();
  const std::uint64_t n = target - wrong_from;
  ++stats.rollbacks;
  stats.rolled_back_ticks += n;
  stats.max_rolled_back = std::max(stats.max_rolled_back, n);
  stats.last_rolled_back = n;
  wrong_from = std::numeric_limits<std::uint64_t>::max();
}

namespace {

/// Time sync's average: each frame's sample weighs 1/16 (about the last 16 frames).
constexpr double sync_weight = 1.0 / 16.0;
/// What a wait takes off the averages at once: a quarter of the frame given back (the samples
/// show the rest as the packets carry it; taking it all off at once makes a peer much faster
/// than another run to max_rollback before it waits enough).
constexpr double sync_wait_credit = 0.25;
/// Frames ahead (on average) above which a frame waits.
constexpr double sync_threshold = 2.0;

}  // namespace

double MatchPeer::Impl::time_sync_ahead() {
  // GGPO's time sync: against each player heard directly (a joiner: the host; the host: each
  // player), our frame advantage (the next tick to show, against the newest of its inputs that
  // reached us, used or not) and its over us (from its newest packet: its own inputs against
  // its acknowledgement of ours; 0 before one came). Both are late by the link's delay and the
  // send interval, about the same each way, so half their difference is how far ahead of it
  // we are whatever the delay (what the old rule, "ahead of its last input by more than half
  // the round trip + 1", counted as ahead: a match on a clean link waited about one frame a
  // tick). Sampled every frame, waiting or not, and averaged over about 16.
  const std::uint64_t t = shown->tick();
  double most = 0.0;
  for (std::uint8_t p = 0; p < players; ++p) {
    if (p == slot || (!is_host && p != 0)) continue;
    const detail::Remote* heard = nullptr;
    for (const detail::Remote& r : remotes) {
      if (r.handshaken && r.slot == p && r.advantage_seq) heard = &r;
    }
    const double ours =
        static_cast<double>(t + settings.input_delay) -
        static_cast<double>(std::max<std::uint64_t>(known(p), heard ? heard->their_position : 0));
    const double sample = 0.5 * (ours - static_cast<double>(heard ? heard->their_advantage : 0));
    // (Before its first packet, nothing to average: the sample itself.)
    ahead_of[p] = heard ? ahead_of[p] + sync_weight * (sample - ahead_of[p]) : sample;
    most = std::max(most, ahead_of[p]);
  }
  return most;
}

void MatchPeer::Impl::advance_shown() {
  if (state == MatchState::failed || state == MatchState::desynced) return;
  // A host shows nothing ahead before every player has joined: there is no one to predict yet,
  // and a shown world that ran ahead would stand at its window until they come.
  if (is_host && !all_players_joined()) return;
  while (shown->tick() < next_step) step_shown();  // confirmed inputs: no prediction
  while (!frames.empty() && frames.front().tick < next_step) frames.pop_front();
  // How far ahead of the slowest player (by its last input) the shown world is (a statistic).
  const std::uint64_t t = shown->tick();
  std::int64_t advantage = 0;
  for (std::size_t p = 0; p < players; ++p) {
    if (p == slot) continue;
    const auto theirs = static_cast<std::int64_t>(known(p)) - settings.input_delay;
    advantage = std::max(advantage, static_cast<std::int64_t>(t) - theirs);
  }
  stats.frame_advantage = advantage;
  if (settings.match_ticks != 0 && t >= settings.match_ticks) return;
  const double ahead = time_sync_ahead();
  if (t - next_step >= rollback_window()) {
    ++stats.stalls;  // as far ahead as rollback may go
    note_stall(true);
    return;
  }
  note_stall(false);
  if (known(slot) <= t) return;  // the local input of the tick is not given yet
  // Never two waits in a row: a peer ahead slows to half its pace, one repeated frame at a time,
  // rather than standing still (seven waits in a row were a 117 ms freeze at a 100 ms round
  // trip).
  if (ahead > sync_threshold && !waited_last) {
    for (double& a : ahead_of) a -= sync_wait_credit;
    ++stats.waits;
    waited_last = true;
    return;
  }
  waited_last = false;
  step_shown();
}

}  // namespace fixstep::net
