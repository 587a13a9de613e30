// The wall clock of World::profile() (StepProfile): laps of std::chrono::steady_clock between the
// phases of a tick, read only when asked to, so that worlds that report no profile pay nothing.
// Internal to fixstep::core.
#pragma once

#include <chrono>

namespace fixstep::detail {

class PhaseClock {
 public:
  /// Starts the clock when `on`; otherwise every lap is 0 and the clock is never read.
  explicit PhaseClock(bool on) : on_(on) {
    if (on_) start_ = last_ = Clock::now();
  }
  /// Seconds since the last lap (or the start), and a new lap begins.
  double lap() {
    if (!on_) return 0.0;
    const Clock::time_point now = Clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }
  /// Seconds from the start to the last lap.
  [[nodiscard]] double total() const {
    return on_ ? std::chrono::duration<double>(last_ - start_).count() : 0.0;
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool on_;
  Clock::time_point start_{}, last_{};
};

}  // namespace fixstep::detail
