// Subnormal floats: a strongly damped f32 scene decays towards zero, and long before its state
// is subnormal the tick's intermediates are (γ v dt, a dissipation account's squares). Where an
// operation with a subnormal operand or result takes a microcode assist (Intel's CPUs; AMD's
// pay little), those ticks cost many times a normal one. This benchmark steps 20 000 f32
// springs (k = 100 N/m, m = 1 kg, dt = 1/240 s) through a whole 20 000-tick run, damped
// (b = 10 N·s/m, ζ = 0.5: the state passes the least normal float near tick 4000) and undamped,
// with WorldSettings::flush_denormals on and off. Counters: ns per body-step over the run, and
// the ticks that raised the IEEE underflow flag or (x86) the denormal-operand flag, the cause,
// counted because its cost depends on the CPU. Expected everywhere: damped with the flush
// raises no flag in any tick; damped without it raises them for thousands of ticks. On an
// Intel CPU, damped/undamped with the flush ≤ 1.2 (the run without it several times slower).
//   build/bench/bin/bench_float_hygiene
#include <benchmark/benchmark.h>

#include <cfenv>
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
  for (auto _ : state) {
    state.PauseTiming();
    auto w = spring_scene(damped, flush);
    state.ResumeTiming();
    for (int t = 0; t < ticks; ++t) w.step();
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
