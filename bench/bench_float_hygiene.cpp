// Subnormal floats: a strongly damped f32 scene decays into subnormal numbers and, on x86,
// every arithmetic operation on them takes a microcode assist (~100 cycles). fixstep flushes
// them to zero while stepping (WorldSettings::flush_denormals). This benchmark steps the same
// scene fresh (tick 0) and aged (after 10^4 ticks, deep in the subnormal range), with the
// flush on and off. Expected: aged/flush:0 is tens of times slower; aged/flush:1 is not.
//   build/release/bin/bench_float_hygiene
#include <benchmark/benchmark.h>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

namespace {

constexpr int bodies = 256;
constexpr int age_ticks = 10'000;

fixstep::detail::WorldKernel<float> damped_scene(bool flush) {
  using namespace fixstep;
  // k = 100 N/m, b = 20 N*s/m, m = 1 kg (ζ = 1): amplitude e^{-10 t}, below 1e-38 by t = 9 s.
  fixstep::detail::WorldKernel<float> w(WorldSettings{.dt = 0.01, .flush_denormals = flush});
  for (int i = 0; i < bodies; ++i) {
    BodyDef d;
    d.body.position = {1.0 + 0.01 * i, 0.5};
    d.spring = SpringDamper{.anchor = {}, .stiffness = 100.0, .damping = 20.0};
    w.create_body(d);
  }
  return w;
}

void BM_DampedF32Step(benchmark::State& state) {
  const bool aged = state.range(0) != 0, flush = state.range(1) != 0;
  auto w = damped_scene(flush);
  if (aged) {
    for (int i = 0; i < age_ticks; ++i) w.step();
  }
  for (auto _ : state) {
    w.step();
    benchmark::DoNotOptimize(w.x().data());
    benchmark::ClobberMemory();
  }
  // seconds / (body-steps * 1e-9) = ns per body-step
  state.counters["ns_per_body_step"] =
      benchmark::Counter(double(state.iterations()) * bodies * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
// 500 ticks per measurement: a fresh scene reaches the subnormal range only after ~870 ticks,
// so "fresh" stays fresh while it is timed.
BENCHMARK(BM_DampedF32Step)
    ->ArgsProduct({{0, 1}, {1, 0}})
    ->ArgNames({"aged", "flush"})
    ->Iterations(500)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
