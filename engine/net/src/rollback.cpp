// fixstep::net: a rollback peer's shown world: stepped ahead on predicted inputs, rolled back
// to the first tick predicted wrong and re-simulated (fixstep/match_peer.hpp).
#include <fmt/format.h>

#include <algorithm>

#include "fixstep/net_input_codec.hpp"
#include "match_peer_impl.hpp"

namespace fixstep::net {

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
  shown->step(merged);
  if (rules) rules.after_tick(*shown, merged);
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

void MatchPeer::Impl::advance_shown() {
  roll_back();
  if (state == MatchState::failed || state == MatchState::desynced) return;
  while (shown->tick() < next_step) step_shown();  // confirmed inputs: no prediction
  while (!frames.empty() && frames.front().tick < next_step) frames.pop_front();
  // Time sync: how far ahead of the slowest player (by its last input) the shown world is.
  const std::uint64_t t = shown->tick();
  std::int64_t advantage = 0;
  for (std::size_t p = 0; p < players; ++p) {
    if (p == slot) continue;
    const auto theirs = static_cast<std::int64_t>(known(p)) - settings.input_delay;
    advantage = std::max(advantage, static_cast<std::int64_t>(t) - theirs);
  }
  stats.frame_advantage = advantage;
  if (settings.match_ticks != 0 && t >= settings.match_ticks) return;
  if (t - next_step >= settings.max_rollback) {
    ++stats.stalls;  // as far ahead as rollback may go
    return;
  }
  if (known(slot) <= t) return;  // the local input of the tick is not given yet
  const double half_trip = 0.5e-3 * stats.round_trip_ms * settings.tick_rate_hz;
  if (static_cast<double>(advantage) > half_trip + 1.0) {
    ++stats.waits;
    return;
  }
  step_shown();
}

}  // namespace fixstep::net
