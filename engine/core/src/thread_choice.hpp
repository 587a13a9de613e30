// An automatic world's thread count for its shape phase or its disc phases, chosen by
// measuring it. Whether a second thread pays depends on the machine as much as on the world:
// the phase's passes split by halves hand their data from one core's cache to the other's,
// and that costs what the distance between the two cores costs, which on a virtual machine
// can change from one minute to the next (docs/perf/contact_solver_plan.md, "The automatic
// world's second thread for shapes" and "... for discs", has the figures); a paced game also
// wakes the worker every tick. No size fits every machine, so an automatic world tries: every
// few seconds it steps the phase on two threads and on one, alternately, and keeps the
// faster. The states do not depend on it: the phases give the same bits on one thread and on
// two (ShapeThreads, DiscThreads tests). Internal to the engine: not installed.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

#include "phase_clock.hpp"

namespace fixstep::detail {

class ThreadChoice {
 public:
  /// Ticks of a trial, in pairs: two threads twice, one twice, two twice, ... The second tick
  /// of a pair is timed: the first leaves the worker as a run of ticks on that count leaves it
  /// (spinning from the tick before on two threads, asleep after a tick on one), so that the
  /// timed tick pays the wake-ups that count pays (a tick on two threads right after one on
  /// one paid a wake-up that back-to-back ticks on two do not).
  static constexpr int trial_ticks = 12;
  /// Ticks a choice holds before the next trial: first_hold_ticks after a world's first trial,
  /// twice as many after each next, up to hold_ticks (6 s at 60 Hz), so that a trial's six
  /// ticks on the slower count are under 2 % of the ticks. A world's first ticks are seldom its
  /// usual ones (a pile falling has few contacts), so it tries again soon, then ever less often.
  static constexpr int first_hold_ticks = 16;
  static constexpr int hold_ticks = 360;
  /// Two threads are kept where their median timed tick of the trial took at most this fraction
  /// of one thread's: the second core spins through the phase, so it has to earn it. (The
  /// median of three: a tick preempted, or one on two threads whose worker happened to be
  /// near, does not decide; the fastest did, and chose two threads for a paced gas whose ticks
  /// on two took 1.4 times as long as on one.)
  static constexpr double two_threads_at_most = 0.95;

  /// The phase's thread count this tick: `most` (threads_for's: 1 or 2) where the world
  /// does not choose (`choose`: an automatic world in which some pass of the phase could
  /// split) or has one thread; else the trial's count, or the one the last trial chose. Call
  /// once a tick, before timed().
  int threads(int most, bool choose) {
    timing_ = 0;
    if (!choose || most < 2) return most;
    if (at_ >= trial_ticks + hold_) at_ = 0, hold_ = std::min(2 * hold_, hold_ticks);
    const int at = at_++;
    if (at >= trial_ticks) return chosen_;
    if (at == 0) timed_ = {0, 0};  // (also a trial cut short by a throw)
    const int count = (at / 2) % 2 == 0 ? 2 : 1;
    if (at % 2 == 1) timing_ = count;
    return count;
  }
  /// Runs phase() (the phase of the tick threads() was asked for) and returns what it
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
    const auto c = static_cast<std::size_t>(count - 1);
    if (timed_[c] < per_count) seconds_[c][timed_[c]++] = seconds;
    if (at_ != trial_ticks || timed_[0] == 0 || timed_[1] == 0) return;
    chosen_ = median(1) <= two_threads_at_most * median(0) ? 2 : 1;
  }
  /// The count the last trial chose (2 before the first).
  [[nodiscard]] int chosen() const { return chosen_; }
  /// This tick's count where it is a trial's timed tick, else 0.
  [[nodiscard]] int timing() const { return timing_; }

 private:
  static constexpr std::size_t per_count = trial_ticks / 4;  ///< timed ticks on each count
  int at_ = 0;  ///< the tick's place in a trial and its hold
  int hold_ = first_hold_ticks;
  int timing_ = 0;  ///< this tick's trial count; 0: not timed
  int chosen_ = 2;
  std::array<std::size_t, 2> timed_{0, 0};  ///< the trial's timed ticks on one and on two threads
  std::array<std::array<double, per_count>, 2> seconds_{};  ///< and their times (s)
  /// The median of count c's timed ticks (of two, the longer).
  [[nodiscard]] double median(std::size_t c) const {
    static_assert(per_count == 3);
    const auto& t = seconds_[c];
    if (timed_[c] < 3) return timed_[c] == 1 ? t[0] : std::max(t[0], t[1]);
    return std::max(std::min(t[0], t[1]), std::min(std::max(t[0], t[1]), t[2]));
  }
};

}  // namespace fixstep::detail
