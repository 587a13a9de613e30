// What a call through World's public interface costs, per call: the price of the World holding
// its state behind a pointer (world.hpp), compared before and after by building this file
// against two versions of the library.
//
//   body_edit    set_velocity of one body of 10 (a program's edit between ticks)
//   state_hash   state_hash of 10 bodies
//   save_restore save into a warm WorldSnapshot, then restore from it, 10 bodies
//   tick         one step() of 10 spring-damper and projectile bodies (semi-implicit Euler)
//   body_read    body() of one body of 10
//
//   build/bench/bin/bench_world_api
#include <benchmark/benchmark.h>

#include <cstddef>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace {

/// Ten bodies: five on anchored spring-dampers, five projectiles under gravity with drag.
fixstep::WorldDef ten_bodies() {
  fixstep::WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  for (int i = 0; i < 10; ++i) {
    fixstep::BodyDef b;
    b.body.position = {double(i), 1.0};
    b.body.velocity = {0.5, 2.0};
    if (i < 5) {
      b.spring =
          fixstep::SpringDamper{.anchor = {double(i), 0.0}, .stiffness = 40.0, .damping = 0.5};
    } else {
      b.gravity = fixstep::Gravity{};
      b.drag = fixstep::LinearDrag{.coefficient = 0.1};
    }
    def.bodies.push_back(b);
  }
  return def;
}

void BM_BodyEdit(benchmark::State& state) {
  fixstep::World w(ten_bodies());
  const fixstep::Entity e = w.bodies()[3];
  double v = 0.0;
  for (auto _ : state) {
    w.set_velocity(e, {v, 1.0});
    v += 1e-9;
  }
}
BENCHMARK(BM_BodyEdit);

void BM_BodyRead(benchmark::State& state) {
  fixstep::World w(ten_bodies());
  const fixstep::Entity e = w.bodies()[3];
  for (auto _ : state) benchmark::DoNotOptimize(w.body(e));
}
BENCHMARK(BM_BodyRead);

void BM_StateHash(benchmark::State& state) {
  fixstep::World w(ten_bodies());
  for (auto _ : state) benchmark::DoNotOptimize(w.state_hash());
}
BENCHMARK(BM_StateHash);

void BM_SaveRestore(benchmark::State& state) {
  fixstep::World w(ten_bodies());
  w.step();
  fixstep::WorldSnapshot snap;
  w.save(snap);  // warm: the snapshot's storage exists
  for (auto _ : state) {
    w.save(snap);
    w.restore(snap);
  }
}
BENCHMARK(BM_SaveRestore);

void BM_Tick(benchmark::State& state) {
  fixstep::World w(ten_bodies());
  for (auto _ : state) w.step();
}
BENCHMARK(BM_Tick);

}  // namespace

BENCHMARK_MAIN();
