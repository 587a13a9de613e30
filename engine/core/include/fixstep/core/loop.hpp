// The frame loop of Glenn Fiedler's "Fix Your Timestep!" (2004): frame time is added to an
// accumulator and drained in physics ticks of exactly dt, so physics never depends on the frame
// rate; rendering interpolates between the last two ticks with alpha = accumulator / dt.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "fixstep/core/input.hpp"

namespace fixstep {

class World;

/// How the loop guards frames; the tick length dt is the world's (WorldSettings::dt).
struct LoopSettings {
  double max_frame_time = 0.25;  ///< frame-time clamp, s ("Fix Your Timestep!": 0.25 s)
  /// Hard cap on ticks per frame, the second guard against the spiral of death (when ticks
  /// take longer than they simulate). 0 = derive: ceil(max_frame_time / dt) + 1.
  int max_ticks_per_frame = 0;
};

/// What one frame of the loop did.
struct FrameResult {
  int ticks = 0;              ///< physics ticks run this frame
  double alpha = 0.0;         ///< interpolation weight of the current state, in [0, 1)
  double clamped_time = 0.0;  ///< frame time discarded by the clamp, s
  double dropped_time = 0.0;  ///< accumulated time discarded because the tick cap was hit, s
};

/// Drives physics ticks from frame times. Pure: it owns no clock and no world; advance() is
/// given the frame time and a tick callback, which makes it testable with scripted times.
class FixedStepLoop {
 public:
  /// The loop of `world`'s ticks: dt = world.settings().dt. Throws std::invalid_argument on a
  /// non-finite or non-positive clamp or a negative tick cap.
  explicit FixedStepLoop(const World& world, const LoopSettings& settings = {});
  /// The loop of ticks of `dt` seconds (finite and > 0), for a program stepping something else
  /// than one World. Throws std::invalid_argument as above and for a bad dt.
  explicit FixedStepLoop(double dt, const LoopSettings& settings = {});

  /// Adds frame_seconds (clamped to max_frame_time, then scaled by time_scale) to the
  /// accumulator and calls tick(TickInput) once per whole dt in it, up to the tick cap.
  /// Every tick of this frame receives `input` with its own tick index filled in.
  /// While paused nothing accumulates; a requested single step runs exactly one tick.
  template <class TickFn>
  FrameResult advance(double frame_seconds, TickInput input, TickFn&& tick);
  /// As above, but each tick gets its own input: sampler.sample(tick index), so a press or
  /// release collected between two ticks reaches exactly one tick (see InputSampler).
  template <class TickFn>
  FrameResult advance(double frame_seconds, InputSampler& sampler, TickFn&& tick);

  /// The accumulator loop itself: calls tick_at(tick index) once per tick it runs, leaving the
  /// input of each tick to the caller (a sampler, a recording, a script).
  template <class TickAt>
  FrameResult advance_with(double frame_seconds, TickAt&& tick_at);

  /// The loop's restorable state (part of a snapshot): the accumulator and the tick count.
  struct State {
    double accumulator = 0.0;  ///< s
    std::uint64_t ticks = 0;
    friend constexpr bool operator==(const State&, const State&) = default;
  };
  [[nodiscard]] State state() const { return {accumulator_, ticks_}; }
  /// Restores a state(); throws std::invalid_argument unless 0 <= accumulator < dt (finite).
  void restore(const State& state);

  void set_paused(bool paused) { paused_ = paused; }
  [[nodiscard]] bool paused() const { return paused_; }
  /// While paused, the next advance() runs exactly one tick.
  void request_single_step() { single_step_ = true; }
  /// Multiplies simulated time per real second (0.25 = slow motion). Must be finite, >= 0.
  void set_time_scale(double scale);
  [[nodiscard]] double time_scale() const { return time_scale_; }
  /// Ticks run since construction or reset().
  [[nodiscard]] std::uint64_t ticks() const { return ticks_; }
  /// alpha = accumulator / dt, in [0, 1).
  [[nodiscard]] double alpha() const { return accumulator_ / dt_; }
  /// The tick length, s.
  [[nodiscard]] double dt() const { return dt_; }
  [[nodiscard]] const LoopSettings& settings() const { return settings_; }
  /// Empties the accumulator and the tick count (restart).
  void reset() {
    accumulator_ = 0.0;
    ticks_ = 0;
  }

 private:
  double dt_;
  LoopSettings settings_;
  int tick_cap_;
  /// A tick is due once the accumulator reaches dt less a relative 1e-9: 0.25 s of frames
  /// must give 25 ticks of 0.01 s, although 0.25 - 24 * 0.01 rounds to just below 0.01 in
  /// binary. At most 1e-9 dt per tick is rounded away (clamped at 0), never accumulated.
  double due_;
  double accumulator_ = 0.0;
  double time_scale_ = 1.0;
  std::uint64_t ticks_ = 0;
  bool paused_ = false;
  bool single_step_ = false;
};

template <class TickFn>
FrameResult FixedStepLoop::advance(double frame_seconds, TickInput input, TickFn&& tick) {
  return advance_with(frame_seconds, [&](std::uint64_t t) {
    input.tick = t;
    tick(static_cast<const TickInput&>(input));
  });
}

template <class TickFn>
FrameResult FixedStepLoop::advance(double frame_seconds, InputSampler& sampler, TickFn&& tick) {
  return advance_with(frame_seconds, [&](std::uint64_t t) {
    const TickInput input = sampler.sample(t);
    tick(input);
  });
}

template <class TickAt>
FrameResult FixedStepLoop::advance_with(double frame_seconds, TickAt&& tick_at) {
  FrameResult r;
  if (!(frame_seconds >= 0.0)) frame_seconds = 0.0;  // NaN or a clock going backwards
  if (paused_) {
    if (single_step_) {
      tick_at(ticks_++);
      r.ticks = 1;
    }
    single_step_ = false;
    r.alpha = alpha();
    return r;
  }
  single_step_ = false;
  if (frame_seconds > settings_.max_frame_time) {
    r.clamped_time = frame_seconds - settings_.max_frame_time;
    frame_seconds = settings_.max_frame_time;
  }
  accumulator_ += frame_seconds * time_scale_;
  while (accumulator_ >= due_) {
    if (r.ticks == tick_cap_) {
      // Give up on the backlog but keep the fraction, so alpha stays in [0, 1).
      const double keep = std::fmod(accumulator_, dt_);
      r.dropped_time = accumulator_ - keep;
      accumulator_ = keep;
      break;
    }
    tick_at(ticks_++);
    accumulator_ = std::max(accumulator_ - dt_, 0.0);
    ++r.ticks;
  }
  r.alpha = alpha();
  return r;
}

/// Headless capture clock: every frame lasts exactly 1/fps, so captured frames are reproducible.
class VirtualClock {
 public:
  /// Throws std::invalid_argument unless fps is finite and > 0.
  explicit VirtualClock(double fps);
  /// Seconds elapsed since the previous frame: always 1/fps.
  [[nodiscard]] double frame_seconds() const { return 1.0 / fps_; }

 private:
  double fps_;
};

/// Wall clock for windows (std::chrono::steady_clock, monotonic).
class RealClock {
 public:
  RealClock() : last_(std::chrono::steady_clock::now()) {}
  /// Seconds elapsed since the previous call (or construction).
  double frame_seconds() {
    const auto now = std::chrono::steady_clock::now();
    const std::chrono::duration<double> d = now - last_;
    last_ = now;
    return d.count();
  }

 private:
  std::chrono::steady_clock::time_point last_;
};

}  // namespace fixstep
