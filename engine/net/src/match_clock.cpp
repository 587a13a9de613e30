// fixstep::net: a networked match played on the game's clock (fixstep/net/match_clock.hpp).
#include "fixstep/net/match_clock.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fixstep::net {

MatchClock::MatchClock(double dt, double max_owed_s) : dt_(dt), max_owed_(max_owed_s) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("MatchClock: dt must be > 0");
  if (!(max_owed_s > 0.0) || !std::isfinite(max_owed_s)) {
    throw std::invalid_argument("MatchClock: max_owed_s must be > 0");
  }
}

ClockFrame MatchClock::frame(MatchPeer& m, double frame_s, const InputSource& input) {
  ClockFrame f;
  if (std::isfinite(frame_s) && frame_s > 0.0) owed_ = std::min(owed_ + frame_s, max_owed_);
  const bool player = m.slot() < m.players();
  if (!player) {  // a spectator shows what has arrived
    const std::uint64_t before = m.shown_world().tick();
    (void)m.advance();
    f.ticks = static_cast<int>(m.shown_world().tick() - before);
    owed_ = std::min(owed_, dt_);
    return f;
  }
  while (owed_ >= dt_) {
    if (m.wants_input()) {
      m.add_input(input(m.next_input_tick()));
      ++f.inputs;
    }
    const std::uint64_t before = m.shown_world().tick();
    const std::uint64_t waits = m.stats().waits;
    (void)m.advance();
    const std::uint64_t after = m.shown_world().tick();
    if (after > before) {
      f.ticks += static_cast<int>(after - before);
      owed_ = std::max(owed_ - dt_ * static_cast<double>(after - before), 0.0);
      continue;
    }
    if (m.stats().waits > waits) {
      f.time_sync = true;
      owed_ = std::min(owed_, dt_);
    } else {
      f.held_up = true;
    }
    break;
  }
  return f;
}

}  // namespace fixstep::net
