#include "fixstep/core/loop.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

FixedStepLoop::FixedStepLoop(const World& world, const LoopSettings& settings)
    : FixedStepLoop(world.settings().dt, settings) {}

FixedStepLoop::FixedStepLoop(double dt, const LoopSettings& settings)
    : dt_(dt), settings_(settings), due_(dt * (1.0 - 1e-9)) {
  if (!std::isfinite(dt) || dt <= 0.0) {
    throw std::invalid_argument(fmt::format("loop: dt must be finite and > 0 s (got {})", dt));
  }
  if (!std::isfinite(settings.max_frame_time) || settings.max_frame_time <= 0.0) {
    throw std::invalid_argument(fmt::format(
        "loop: max_frame_time must be finite and > 0 s (got {})", settings.max_frame_time));
  }
  if (settings.max_ticks_per_frame < 0) {
    throw std::invalid_argument("loop: max_ticks_per_frame must be >= 0 (0 = derived)");
  }
  tick_cap_ = settings.max_ticks_per_frame > 0
                  ? settings.max_ticks_per_frame
                  : static_cast<int>(std::min(std::ceil(settings.max_frame_time / dt), 1e6)) + 1;
}

void FixedStepLoop::set_time_scale(double scale) {
  if (!std::isfinite(scale) || scale < 0.0) {
    throw std::invalid_argument(
        fmt::format("loop: time scale must be finite and >= 0 (got {})", scale));
  }
  time_scale_ = scale;
}

void FixedStepLoop::restore(const State& state) {
  if (!(state.accumulator >= 0.0 && state.accumulator < dt_)) {
    throw std::invalid_argument(fmt::format(
        "loop: a restored accumulator must be in [0, dt = {} s) (got {})", dt_, state.accumulator));
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
