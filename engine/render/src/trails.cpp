// Trails (trails.hpp): per-tick samples kept per body handle, cut at teleports and spawns.
#include "fixstep/render/trails.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

namespace {

/// The dt a frame without one stands for, s.
constexpr double frame_dt_fallback = 1.0 / 60.0;
/// Longest trail in ticks: ages are taken from the samples' ticks modulo 2^32.
constexpr double max_window_ticks = 0x1p30;

/// Whether a body's tick started elsewhere than the tick before left it: more than float rounding
/// apart (World::interpolate_positions gives the end as previous + (current - previous) * 1,
/// which may differ from current by one rounding).
bool moved(float from, float to) {
  const float scale = std::max(std::abs(from), std::abs(to));
  return std::abs(to - from) > 4.0f * FLT_EPSILON * scale;
}

}  // namespace

Trails::Setting Trails::setting(bool visible, double trail_time, double dt) {
  Setting s;
  s.on = visible && trail_time > 0.0;
  const double window = std::min(trail_time / dt, max_window_ticks);
  s.window = static_cast<float>(window);
  s.every = static_cast<std::uint32_t>(std::max(1.0, std::ceil(window / (capacity - 1))));
  return s;
}

void Trails::grow(std::uint32_t slot) {
  const std::size_t n = std::size_t{slot} + 1;
  generation_.resize(n, 0);
  seen_.resize(n, 0);
  last_x_.resize(n, 0.0f);
  last_y_.resize(n, 0.0f);
  last_tick_.resize(n, 0);
  setting_.resize(n);
  head_.resize(n, 0);
  count_.resize(n, 0);
  x_.resize(n * capacity, 0.0f);
  y_.resize(n * capacity, 0.0f);
  t_.resize(n * capacity, 0);
}

template <class IdOf, class SettingOf>
void Trails::record(std::uint64_t tick, std::size_t n, IdOf&& id, std::span<const float> start_x,
                    std::span<const float> start_y, std::span<const float> end_x,
                    std::span<const float> end_y, SettingOf&& setting_of) {
  const std::uint32_t previous = stamp_++;
  for (std::size_t j = 0; j < n; ++j) {
    const Entity e = id(j);
    const std::uint32_t s = e.slot();
    if (s >= generation_.size()) grow(s);
    if (generation_[s] != e.generation || seen_[s] != previous) {  // a body new to the trails
      generation_[s] = e.generation;
      setting_[s] = setting_of(j);
      reset(s);
    } else if (!start_x.empty() && last_tick_[s] + 1 == tick &&
               (moved(last_x_[s], start_x[j]) || moved(last_y_[s], start_y[j]))) {
      reset(s);  // moved between ticks: a teleport
    }
    seen_[s] = stamp_;
    last_x_[s] = end_x[j];
    last_y_[s] = end_y[j];
    last_tick_[s] = tick;
    if (!setting_[s].on) continue;
    const std::size_t base = std::size_t{s} * capacity;
    if (count_[s] > 0) {
      const std::uint32_t newest = t_[base + (head_[s] + capacity - 1) % capacity];
      if (static_cast<std::uint32_t>(tick) - newest < setting_[s].every) continue;
    }
    const std::size_t at = base + head_[s];
    x_[at] = end_x[j];
    y_[at] = end_y[j];
    t_[at] = static_cast<std::uint32_t>(tick);
    head_[s] = static_cast<std::uint8_t>((head_[s] + 1) % capacity);
    count_[s] = static_cast<std::uint8_t>(std::min(count_[s] + 1, capacity));
  }
  sampled_ = true;
  sampled_tick_ = tick;
}

void Trails::sample(const World& world) {
  if (world.fault()) return;
  const std::size_t n = world.body_count();
  start_x_.resize(n);
  start_y_.resize(n);
  end_x_.resize(n);
  end_y_.resize(n);
  world.interpolate_positions(0.0, start_x_, start_y_);  // where the tick started
  world.interpolate_positions(1.0, end_x_, end_y_);
  const std::span<const Entity> bodies = world.bodies();
  const double dt = world.settings().dt;
  record(
      world.tick(), n, [&](std::size_t j) { return bodies[j]; }, start_x_, start_y_, end_x_, end_y_,
      [&](std::size_t j) {
        const std::optional<Appearance> a = world.get<Appearance>(bodies[j]);
        return a ? setting(a->visible, a->trail ? a->trail_time : 0.0, dt)
                 : setting(true, default_trail_time, dt);
      });
}

bool Trails::known(Entity e) const {
  const std::uint32_t s = e.slot();
  return s < generation_.size() && generation_[s] == e.generation && seen_[s] == stamp_;
}

void Trails::prepare(const RenderFrame& frame) {
  const std::size_t n = frame.x.size();
  auto check_size = [&](std::size_t size, const char* what) {
    if (size != 0 && size != n) {
      throw std::invalid_argument(
          fmt::format("RenderFrame has {} {} for {} bodies (Trails::prepare)", size, what, n));
    }
  };
  check_size(frame.ids.size(), "ids");
  check_size(frame.visible.size(), "visible flags");
  check_size(frame.trail_time.size(), "trail times");
  auto id = [&](std::size_t j) {
    const Entity e = frame.ids.empty() ? fixstep::defined_entity(j) : frame.ids[j];
    if (e.is_null())
      throw std::invalid_argument(fmt::format("RenderFrame: body {} has a null id", j));
    return e;
  };
  const double dt = frame.dt > 0.0 ? frame.dt : frame_dt_fallback;
  auto setting_of = [&](std::size_t j) {
    const double time = frame.trail_time.empty() ? default_trail_time : frame.trail_time[j];
    if (!(std::isfinite(time) && time >= 0.0)) {
      throw std::invalid_argument(fmt::format(
          "RenderFrame: body {} has trail time {} s (finite and >= 0 expected)", j, time));
    }
    return setting(frame.visible.empty() || frame.visible[j] != 0, time, dt);
  };
  // Settings first (a hidden body's trail is gone before it could be sampled below).
  for (std::size_t j = 0; j < n; ++j) {
    const Entity e = id(j);
    const Setting now = setting_of(j);
    if (!known(e)) continue;
    Setting& was = setting_[e.slot()];
    if (now.on != was.on || now.every != was.every || now.window != was.window) {
      was = now;
      reset(e.slot());
    }
  }
  if (sampled_ && sampled_tick_ == frame.tick) return;
  record(frame.tick, n, id, {}, {}, frame.x, frame.y, setting_of);
}

void Trails::clear() {
  ++stamp_;  // nothing was seen in the sample before the next one
  sampled_ = false;
}

int Trails::points(const RenderFrame& frame, std::size_t j, std::span<float, max_points> xs,
                   std::span<float, max_points> ys, std::span<float, max_points> ages) const {
  const Entity e = frame.ids.empty() ? fixstep::defined_entity(j) : frame.ids[j];
  if (!known(e)) return 0;
  const std::uint32_t s = e.slot();
  const Setting& set = setting_[s];
  if (!set.on) return 0;
  const double dt = frame.dt > 0.0 ? frame.dt : frame_dt_fallback;
  const double behind = 1.0 - frame.alpha;  // ticks from the frame's tick back to its moment
  const int count = count_[s];
  const int oldest = (head_[s] - count + capacity) % capacity;
  const std::size_t base = std::size_t{s} * capacity;
  int out = 0;
  for (int k = 0; k < count; ++k) {
    const std::size_t at = base + static_cast<std::size_t>((oldest + k) % capacity);
    const double age = double(static_cast<std::uint32_t>(frame.tick) - t_[at]) - behind;
    if (!(age > 0.0) || age > double(set.window)) continue;  // not yet drawn, or too old
    xs[static_cast<std::size_t>(out)] = x_[at];
    ys[static_cast<std::size_t>(out)] = y_[at];
    ages[static_cast<std::size_t>(out)] = static_cast<float>(age * dt);
    ++out;
  }
  xs[static_cast<std::size_t>(out)] = frame.x[j];
  ys[static_cast<std::size_t>(out)] = frame.y[j];
  ages[static_cast<std::size_t>(out)] = 0.0f;
  return out + 1;
}

}  // namespace fixstep
