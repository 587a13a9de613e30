// Subnormal floats: a strongly damped f32 scene decays towards zero, and long before its state
// is subnormal the tick's intermediates are (γ v dt, a dissipation account's squares). Where an
// operation with a subnormal operand or result takes a microcode assist (Intel's CPUs; AMD's
// pay little), those ticks cost many times a normal one. This benchmark steps 20 000 f32
// springs (k = 100 N/m, m = 1 kg, dt = 1/240 s) through a whole 20 000-tick run, damped
// (b = 10 N·s/m, ζ = 0.5: the state passes the least normal float near tick 4000) and undamped,
// with WorldSettings::flush_denormals on and off. Counters: ns per body-step over the run; the
// µs a tick of the slowest and of the fastest window of 1000 ticks (a cliff is a slow span of
// the run: the slowest window many times the fastest); and the ticks that raised the IEEE
// underflow flag or (x86) the denormal-operand flag, the cause, counted because its cost
// depends on the CPU. Expected everywhere: damped with the flush raises no flag in any tick;
// damped without it raises them for thousands of ticks. On an Intel CPU, damped/undamped with
// the flush ≤ 1.2 (the run without it several times slower, its slowest window far above its
// fastest).
//   build/bench/bin/bench_float_hygiene
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cfenv>
#include <chrono>
#include <cmath>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace {

constexpr int springs = 20'000;
constexpr int ticks = 20'000;
constexpr int window = 1000;  ///< ticks a window of the run's time profile
static_assert(ticks % window == 0, "the windows cover the run");

fixstep::detail::WorldKernel<float> spring_scene(bool damped, bool flush) {
  using namespace fixstep;
  fixstep::detail::WorldKernel<float> w(WorldSettings{.dt = 1.0 / 240.0, .flush_denormals = flush});
  for (int i = 0; i < springs; ++i) {
    const double phase = 6.283185307179586 * i / springs;
    BodyDef d;
    d.body.position = {0.5 * std::cos(phase), 0.25 * std::sin(3 * phase)};
    d.body.velocity = {std::sin(phase), -0.5 * std::cos(2 * phase)};
    d.spring = SpringDamper{.anchor = {}, .stiffness = 100.0, .damping = damped ? 10.0 : 0.0};
    w.create_body(d);
  }
  return w;
}

/// Clears the underflow and (x86) denormal-operand flags.
void clear_flags() {
  std::feclearexcept(FE_UNDERFLOW);
#if defined(__x86_64__) || defined(__i386__)
  _mm_setcsr(_mm_getcsr() & ~0x2u);
#endif
}

/// Whether the underflow or (x86) denormal-operand flag is raised.
bool flags_raised() {
  bool raised = std::fetestexcept(FE_UNDERFLOW) != 0;
#if defined(__x86_64__) || defined(__i386__)
  raised = raised || (_mm_getcsr() & 0x2u) != 0;
#endif
  return raised;
}

void BM_DampedF32Run(benchmark::State& state) {
  const bool damped = state.range(0) != 0, flush = state.range(1) != 0;
  int flagged = 0;
  double slowest = 0.0, fastest = 0.0;  // µs a tick, over the windows of the last run
  for (auto _ : state) {
    state.PauseTiming();
    auto w = spring_scene(damped, flush);
    state.ResumeTiming();
    slowest = 0.0, fastest = 0.0;
    for (int t0 = 0; t0 < ticks; t0 += window) {
      const auto start = std::chrono::steady_clock::now();
      for (int t = t0; t < t0 + window; ++t) w.step();
      const std::chrono::duration<double, std::micro> spent =
          std::chrono::steady_clock::now() - start;
      const double us = spent.count() / window;
      slowest = std::max(slowest, us), fastest = t0 == 0 ? us : std::min(fastest, us);
    }
    benchmark::DoNotOptimize(w.x().data());
    benchmark::ClobberMemory();
    // The cause, counted in an untimed second run of the same world (the flags are sticky).
    state.PauseTiming();
    auto counted = spring_scene(damped, flush);
    flagged = 0;
    for (int t = 0; t < ticks; ++t) {
      clear_flags();
      counted.step();
      flagged += flags_raised() ? 1 : 0;
    }
    state.ResumeTiming();
  }
  state.counters["ns_per_body_step"] =
      benchmark::Counter(double(state.iterations()) * springs * ticks * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["ticks_with_subnormals"] = flagged;
  state.counters["slowest_window_us_a_tick"] = slowest;
  state.counters["fastest_window_us_a_tick"] = fastest;
}
BENCHMARK(BM_DampedF32Run)
    ->ArgsProduct({{0, 1}, {1, 0}})
    ->ArgNames({"damped", "flush"})
    ->Iterations(1)
    ->Repetitions(5)
    ->Unit(benchmark::kMillisecond)
    ->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
