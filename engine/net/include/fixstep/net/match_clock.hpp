// The game's clock of a networked match: the accumulator of Fiedler's "Fix Your Timestep!"
// turned into ticks of a MatchPeer. Each frame adds the real time it took; every whole tick
// owed is played: the local input for it given (when the match wants one), then the match
// advanced. So a match runs at real time however the frames fall (a 60 Hz window and a
// 120 Hz tick play two ticks a frame, a slow frame catches up to max_owed_s); what the
// network holds up is lost, as a stalled game's time is.
#pragma once

#include <cstdint>
#include <functional>

#include "fixstep/core/input.hpp"
#include "fixstep/net/match_peer.hpp"

namespace fixstep::net {

/// The local player's input of a tick (the tick given: MatchPeer::next_input_tick()).
using InputSource = std::function<TickInput(std::uint64_t tick)>;

/// What one frame of the clock did.
struct ClockFrame {
  int ticks = 0;           ///< ticks the shown world advanced (re-simulations not counted)
  int inputs = 0;          ///< local inputs given
  bool held_up = false;    ///< a tick owed could not be played: the network held it up
  bool time_sync = false;  ///< time sync made this peer wait (rollback: it ran ahead)
};

/// The times the shown world stood still while ticks were owed (a freeze: frames in a row
/// that advanced nothing), as a player sees them.
struct Freezes {
  std::uint64_t over_100ms = 0, over_250ms = 0;  ///< freezes longer than that
  double longest_s = 0.0;                        ///< the longest, s
  /// Real time from the frame that played the first tick to the match's end (or now), s: the
  /// game's ticks over it are its pace (1/dt at real time).
  double played_s = 0.0;
};

/// A peer's accumulator: owed real time, in seconds, turned into ticks of dt.
class MatchClock {
 public:
  /// `dt`: the world's tick, s (> 0). `max_owed_s`: the most real time owed at once (the
  /// frame-time clamp of "Fix Your Timestep!": after a long frame the match catches up at
  /// most this much, s). Throws std::invalid_argument for dt or max_owed_s not > 0.
  explicit MatchClock(double dt, double max_owed_s = 0.25);

  /// Adds `frame_s` seconds of real time (>= 0; clamped to max_owed_s in all) and plays every
  /// whole tick owed: for each, the input from `input` when m.wants_input(), then
  /// m.advance(). Stops at the first tick that does not advance the shown world (held up by
  /// the network: a missing input, lockstep's wait, rollback at its window; or by time sync:
  /// a rollback peer ahead of another) and drops what is owed beyond that tick: the peers of
  /// a match stall together and resume in phase. A spectator has no input: it advances to
  /// what has arrived.
  ClockFrame frame(MatchPeer& m, double frame_s, const InputSource& input);

  [[nodiscard]] double owed_s() const { return owed_; }
  /// The freezes so far (one still going counts once it is over).
  [[nodiscard]] const Freezes& freezes() const { return freezes_; }
  [[nodiscard]] double dt() const { return dt_; }

 private:
  double dt_;
  double max_owed_;
  double owed_ = 0.0;
  double frozen_s_ = 0.0;  ///< the freeze going on: real time since the shown world last moved
  Freezes freezes_;
  void note_freeze(bool advanced, double frame_s);
  ClockFrame play(MatchPeer& m, double frame_s, const InputSource& input);
};

}  // namespace fixstep::net
