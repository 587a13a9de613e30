// An automatic world's thread count for its shape phase, chosen by measuring it. Whether a
// second thread pays for a world of shapes depends on the machine as much as on the world: the
// phase's passes split by halves hand their data from one core's cache to the other's, and
// that costs what the distance between the two cores costs, which on a virtual machine can
// change from one minute to the next (docs/perf/contact_solver_plan.md, "The automatic world's
// second thread for shapes", has the figures). No size fits every machine, so an automatic
// world tries: every few seconds it steps its shape phase on two threads and on one,
// alternately, and keeps the faster. The states do not depend on it: the shape phase gives the
// same bits on one thread and on two (ShapeThreads tests). Internal to the engine: not
// installed.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>

#include "phase_clock.hpp"

namespace fixstep::detail {

class ThreadChoice {
 public:
  /// Ticks of a trial: two threads, one, two, one, ...
  static constexpr int trial_ticks = 8;
  /// Ticks a choice holds before the next trial: first_hold_ticks after a world's first trial,
  /// twice as many after each next, up to hold_ticks (4 s at 60 Hz), so that a trial's four
  /// ticks on the slower count are under 2 % of the ticks. A world's first ticks are seldom its
  /// usual ones (a pile falling has few contacts), so it tries again soon, then ever less often.
  static constexpr int first_hold_ticks = 16;
  static constexpr int hold_ticks = 240;
  /// Two threads are kept where their fastest tick of the trial took at most this fraction of
  /// one thread's fastest: the second core spins through the phase, so it has to earn it.
  static constexpr double two_threads_at_most = 0.95;

  /// The shape phase's thread count this tick: `most` (threads_for's: 1 or 2) where the world
  /// does not choose (`choose`: an automatic world in which some pass of the phase could
  /// split) or has one thread; else the trial's count, or the one the last trial chose. Call
  /// once a tick, before timed().
  int threads(int most, bool choose) {
    timing_ = 0;
    if (!choose || most < 2) return most;
    if (at_ >= trial_ticks + hold_) at_ = 0, hold_ = std::min(2 * hold_, hold_ticks);
    const int at = at_++;
    if (at >= trial_ticks) return chosen_;
    if (at == 0) fastest_ = {unmeasured, unmeasured};  // (also a trial cut short by a throw)
    timing_ = at % 2 == 0 ? 2 : 1;
    return timing_;
  }
  /// Runs phase() (the shape phase of the tick threads() was asked for) and returns what it
  /// returns, timed on the steady clock where that count was a trial's (a phase that throws
  /// is not counted).
  template <class Phase>
  auto timed(Phase&& phase) {
    const int count = timing_;
    PhaseClock clock(count != 0);  // (not read otherwise)
    auto out = phase();
    if (count != 0) record(count, clock.lap());
    return out;
  }
  /// A trial's tick on `count` threads (1 or 2) took `seconds`; the trial's last tick decides
  /// (a count without a tick keeps the last choice).
  void record(int count, double seconds) {
    double& fastest = fastest_[static_cast<std::size_t>(count - 1)];
    fastest = std::min(fastest, seconds);
    if (at_ != trial_ticks) return;
    const double one = fastest_[0], two = fastest_[1];
    if (one < unmeasured && two < unmeasured) chosen_ = two <= two_threads_at_most * one ? 2 : 1;
  }
  /// The count the last trial chose (2 before the first).
  [[nodiscard]] int chosen() const { return chosen_; }
  /// This tick's count where it is a trial's (timed), else 0.
  [[nodiscard]] int timing() const { return timing_; }

 private:
  static constexpr double unmeasured = std::numeric_limits<double>::infinity();
  int at_ = 0;  ///< the tick's place in a trial and its hold
  int hold_ = first_hold_ticks;
  int timing_ = 0;  ///< this tick's trial count; 0: not timed
  int chosen_ = 2;
  std::array<double, 2> fastest_{unmeasured, unmeasured};  ///< s, on one and on two threads
};

}  // namespace fixstep::detail
