// bench_discs' cost per disc from N = 10³ to 10⁵, with the two sizes timed in turn (discs.hpp:
// scaling()).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include "discs.hpp"
#include "median.hpp"

namespace discs {

namespace {

/// fixstep f64 on one thread, built and warmed up as bench_discs' rounds are.
std::unique_ptr<Stepper> warmed(const Scene& s) {
  auto p = make_stepper("fixstep_f64_t1", s);
  for (int t = 0; t < s.warmup; ++t) p->step();
  return p;
}

/// Writes and reads a buffer larger than any last-level cache this bench runs on (the Intel
/// Xeons of these runs have 105 MiB), so that the round after it finds none of its data there:
/// every round of either size starts from memory, not only the 10³ rounds after a 10⁵ round.
void empty_caches() {
  static std::vector<std::uint64_t> buffer(std::size_t{256} << 20 >> 3);
  static volatile std::uint64_t sink = 0;
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < buffer.size(); ++i) buffer[i] += i, sum += buffer[i];
  sink = sink + sum;
}

/// ns per body-step of `ticks` ticks of each of `worlds` (each world's ticks in a row), after
/// the caches were emptied.
double timed(std::vector<std::unique_ptr<Stepper>>& worlds, std::size_t bodies, int ticks) {
  empty_caches();
  const auto start = std::chrono::steady_clock::now();
  for (auto& w : worlds) {
    for (int t = 0; t < ticks; ++t) w->step();
  }
  const std::chrono::duration<double, std::nano> spent = std::chrono::steady_clock::now() - start;
  return spent.count() / (double(bodies) * double(ticks) * double(worlds.size()));
}

}  // namespace

Scaling scaling(SceneKind kind, int rounds, int ticks_per_round) {
  const Scene small = make_scene(kind, scaling_small), large = make_scene(kind, scaling_large);
  Scaling out;
  for (int set = 0; set < scaling_sets; ++set) {
    // Each set's worlds are freed before the next set's are built.
    std::vector<std::unique_ptr<Stepper>> smalls, larges;
    for (int c = 0; c < scaling_copies; ++c) smalls.push_back(warmed(small));
    larges.push_back(warmed(large));
    for (int r = 0; r < rounds; ++r) {
      // Which size goes first alternates.
      double ns_small = 0.0, ns_large = 0.0;
      if (r % 2 == 0) {
        ns_small = timed(smalls, scaling_small, ticks_per_round);
        ns_large = timed(larges, scaling_large, ticks_per_round);
      } else {
        ns_large = timed(larges, scaling_large, ticks_per_round);
        ns_small = timed(smalls, scaling_small, ticks_per_round);
      }
      out.small.push_back(ns_small), out.large.push_back(ns_large);
      std::fprintf(stderr,
                   "bench_discs: %s, cost per disc in turn, set %d of %d, round %d of %d: %.0f / "
                   "%.0f ns\n",
                   scene_name(kind), set + 1, scaling_sets, r + 1, rounds, ns_small, ns_large);
    }
  }
  return out;
}

double Scaling::ratio() const {
  std::vector<double> q;
  for (std::size_t i = 0; i < small.size() && i < large.size(); ++i)
    q.push_back(large[i] / small[i]);
  return q.empty() ? std::nan("") : fixstep::bench::median(q);
}

}  // namespace discs
