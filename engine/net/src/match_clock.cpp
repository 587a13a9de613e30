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

void MatchClock::note_freeze(bool advanced, double frame_s) {
  if (!advanced) {
    frozen_s_ += frame_s;
    return;
  }
  if (frozen_s_ > 0.1) ++freezes_.over_100ms;
  if (frozen_s_ > 0.25) ++freezes_.over_250ms;
  freezes_.longest_s = std::max(freezes_.longest_s, frozen_s_);
  frozen_s_ = 0.0;
}

ClockFrame MatchClock::frame(MatchPeer& m, double frame_s, const InputSource& input) {
  const bool begun = m.shown_world().tick() > 0;  // before: waiting for the players to join
  const bool over = m.state() != MatchState::playing;
  ClockFrame f = play(m, frame_s, input);
  if ((begun || f.ticks > 0) && !over && std::isfinite(frame_s) && frame_s > 0.0) {
    freezes_.played_s += frame_s;
  }
  // A frame with a tick owed that played none stood still; the time it took counts.
  if (begun && (f.ticks > 0 || f.held_up || f.time_sync)) {
    note_freeze(f.ticks > 0, std::isfinite(frame_s) ? std::max(frame_s, 0.0) : 0.0);
  }
  return f;
}

ClockFrame MatchClock::play(MatchPeer& m, double frame_s, const InputSource& input) {
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
    // Held up by the network or by time sync: the time is not owed later. Every peer of a
    // lockstep match stalls on the same missing input and resumes together, in phase; owing it
    // would make the peer that waited longest (the host, for the joiners) run ahead after.
    f.time_sync = m.stats().waits > waits;
    f.held_up = !f.time_sync;
    owed_ = std::min(owed_, dt_);
    break;
  }
  return f;
}

}  // namespace fixstep::net
