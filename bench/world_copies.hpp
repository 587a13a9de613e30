// Identical worlds stepped in turn within one timed round (bench_discs, bench_boxes): a round of
// one small world lasts about a millisecond, where one pause of a shared machine moves a round's
// figure by a third; a round of copies lasts some milliseconds, and each copy goes through the
// same ticks as the one world would.
#pragma once

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstddef>
#include <memory>
#include <thread>
#include <vector>

namespace fixstep::bench {

/// Steps `copies` for Google Benchmark's iterations: iteration i steps copy i / ticks_per_copy
/// (cycling when Google Benchmark chooses the iterations). Between copies, 3 ms untimed, so
/// that the last copy's helper threads have stopped spinning (Box2D v3.1's helpers in this
/// bench spin up to about a millisecond before they sleep, fixstep's worker 50 µs) and do not
/// take a core from the next copy's first tick. `copies` is not empty; ticks_per_copy >= 1.
template <class Stepper>
void step_copies(benchmark::State& st, const std::vector<std::unique_ptr<Stepper>>& copies,
                 int ticks_per_copy) {
  const std::size_t per_copy = static_cast<std::size_t>(ticks_per_copy);
  std::size_t i = 0;
  for (auto _ : st) {
    if (i > 0 && i % per_copy == 0) {
      st.PauseTiming();
      std::this_thread::sleep_for(std::chrono::milliseconds(3));
      st.ResumeTiming();
    }
    copies[(i++ / per_copy) % copies.size()]->step();
    benchmark::ClobberMemory();
  }
}

}  // namespace fixstep::bench
