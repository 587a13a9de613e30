#include "step_cost.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world_settings.hpp>

namespace fixstep::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// One sample: batches of `ticks` ticks from `start` until `min_seconds` have passed; returns
/// wall seconds per tick.
double sample(World& sim, const WorldSnapshot& start, std::uint64_t ticks, double min_seconds) {
  std::uint64_t stepped = 0;
  double elapsed = 0.0;
  while (elapsed < min_seconds || stepped == 0) {
    sim.restore(start);
    const auto t0 = Clock::now();
    for (std::uint64_t k = 0; k < ticks && !sim.fault(); ++k, ++stepped) sim.step();
    elapsed += std::chrono::duration<double>(Clock::now() - t0).count();
    if (sim.fault() && sim.tick() == start.tick()) break;  // faults at once: nothing to time
  }
  return stepped > 0 ? elapsed / static_cast<double>(stepped) : 0.0;
}

}  // namespace

double step_cost(const World& world) {
  World sim = world;  // a copy: the caller's world is not stepped
  WorldSnapshot start;
  sim.save(start);
  const double dt = sim.settings().dt;
  // Batches of one simulated second, or fewer ticks when a tick is slow (a first, warming
  // tick estimates it), so that a slow world takes a few ticks, not seconds.
  constexpr double min_seconds = 2e-3, slow_sample = 50e-3;
  const double first = sample(sim, start, 1, 0.0);
  const double per_second = std::max(1.0, std::ceil(1.0 / dt));
  const auto ticks = static_cast<std::uint64_t>(
      std::clamp(std::ceil(min_seconds / std::max(first, 1e-9)), 1.0, per_second));
  std::array<double, 5> samples{};
  std::size_t n = 0;
  for (; n < samples.size(); ++n) {
    samples[n] = sample(sim, start, ticks, min_seconds);
    if (samples[n] * static_cast<double>(ticks) > slow_sample) {
      ++n;
      break;
    }
  }
  return *std::min_element(samples.begin(), samples.begin() + static_cast<std::ptrdiff_t>(n)) / dt;
}

}  // namespace fixstep::cli
