#include "fixstep/loop.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace fixstep {

FixedStepLoop::FixedStepLoop(const LoopSettings& settings)
    : settings_(settings), due_(settings.dt * (1.0 - 1e-9)) {
  if (!std::isfinite(settings.dt) || settings.dt <= 0.0) {
    throw std::invalid_argument(
        fmt::format("loop: dt must be finite and > 0 s (got {})", settings.dt));
  }
  if (!std::isfinite(settings.max_frame_time) || settings.max_frame_time <= 0.0) {
    throw std::invalid_argument(fmt::format(
        "loop: max_frame_time must be finite and > 0 s (got {})", settings.max_frame_time));
  }
  if (settings.max_ticks_per_frame < 0) {
    throw std::invalid_argument("loop: max_ticks_per_frame must be >= 0 (0 = derived)");
  }
  tick_cap_ =
      settings.max_ticks_per_frame > 0
          ? settings.max_ticks_per_frame
          : static_cast<int>(std::min(std::ceil(settings.max_frame_time / settings.dt), 1e6)) + 1;
}

void FixedStepLoop::set_time_scale(double scale) {
  if (!std::isfinite(scale) || scale < 0.0) {
    throw std::invalid_argument(
        fmt::format("loop: time scale must be finite and >= 0 (got {})", scale));
  }
  time_scale_ = scale;
}

void FixedStepLoop::restore(const State& state) {
  if (!(state.accumulator >= 0.0 && state.accumulator < settings_.dt)) {
    throw std::invalid_argument(
        fmt::format("loop: a restored accumulator must be in [0, dt = {} s) (got {})", settings_.dt,
                    state.accumulator));
  }
  accumulator_ = state.accumulator;
  ticks_ = state.ticks;
}

VirtualClock::VirtualClock(double fps) : fps_(fps) {
  if (!std::isfinite(fps) || fps <= 0.0) {
    throw std::invalid_argument(fmt::format("clock: fps must be finite and > 0 (got {})", fps));
  }
}

}  // namespace fixstep
