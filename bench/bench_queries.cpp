// World's spatial queries (query.hpp) against brute force, and what a collision filter saves.
//
//   queries  N discs of radius 0.05-0.1 m at uniform random positions in a square at 10 % area
//            fraction; per iteration one query of each kind: a circle of 0.5 m, a box of 1 m,
//            a ray of 2 m (all hits) at random places, through World's grid and by brute force
//            over every disc (written here, same tests), at N = 10^3, 10^4, 10^5. The grid is
//            built once (the world does not change between queries): build cost is reported
//            apart (BM_GridBuild: the first query after a step).
//   filtered the elastic gas of 10^4 discs stepped with every pair filtered apart (one
//            negative group) against the same gas with collide = false on every disc (no disc in
//            the contact set at all) and against the unfiltered gas: a filtered pair costs the
//            broadphase, never the narrowphase.
//
//   build/bench/bin/bench_queries
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/query.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace {

using fixstep::Vec2;

fixstep::World gas(std::size_t n, int mode) {  // mode 0: plain, 1: filtered, 2: collide = false
  fixstep::WorldSettings s{.dt = 1.0 / 60.0};
  s.contacts = fixstep::ContactSettings{.restitution = 1.0};
  fixstep::World w(fixstep::WorldDef::empty(fixstep::Precision::f64, s));
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> radius(0.05, 0.1), velocity(-5, 5);
  const double side = std::sqrt(double(n) * 3.14159 * 0.075 * 0.075 / 0.1);
  std::uniform_real_distribution<double> place(0, side);
  for (std::size_t i = 0; i < n; ++i) {
    fixstep::BodyDef b;
    b.body = fixstep::Body{.mass = 1,
                           .position = {place(rng), place(rng)},
                           .velocity = {velocity(rng), velocity(rng)}};
    b.collider = fixstep::Collider{radius(rng)};
    if (mode == 1) b.collider->filter.group = -1;
    if (mode == 2) b.collider->collide = false;
    w.create_body(b);
  }
  for (const Vec2 n_ : {Vec2{1, 0}, Vec2{-1, 0}, Vec2{0, 1}, Vec2{0, -1}}) {
    const double off = n_.x + n_.y > 0 ? 0.0 : -side;
    w.add_plane(fixstep::PlaneDef{.normal = n_, .offset = off, .restitution = 1.0});
  }
  return w;
}

double side_of(std::size_t n) {
  return std::sqrt(double(n) * 3.14159 * 0.075 * 0.075 / 0.1);
}

void BM_Queries(benchmark::State& state, bool grid) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const fixstep::World w = gas(n, 0);
  std::vector<Vec2> pos;
  std::vector<double> rad;
  for (const fixstep::Entity e : w.bodies()) {
    pos.push_back(w.body(e).position), rad.push_back(w.get<fixstep::Collider>(e)->radius);
  }
  std::vector<fixstep::QueryHit> out(256);
  std::vector<fixstep::RayHit> rays(256);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> place(0, side_of(n)), angle(0, 6.283185307179586);
  std::size_t found = 0;
  (void)w.overlap_circle({0, 0}, 1, out);  // builds the grid
  for (auto _ : state) {
    const Vec2 c{place(rng), place(rng)};
    const double a = angle(rng);
    const Vec2 t{2 * std::cos(a), 2 * std::sin(a)};
    if (grid) {
      found += w.overlap_circle(c, 0.5, out);
      found += w.overlap_aabb({c.x - 0.5, c.y - 0.5}, {c.x + 0.5, c.y + 0.5}, out);
      found += w.cast_ray_all(c, t, rays);
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const double dx = pos[i].x - c.x, dy = pos[i].y - c.y;
        const double reach = rad[i] + 0.5;
        found += dx * dx + dy * dy <= reach * reach;
        const double bx = pos[i].x - std::clamp(pos[i].x, c.x - 0.5, c.x + 0.5);
        const double by = pos[i].y - std::clamp(pos[i].y, c.y - 0.5, c.y + 0.5);
        found += bx * bx + by * by <= rad[i] * rad[i];
        const double b = dx * t.x + dy * t.y, cc = dx * dx + dy * dy - rad[i] * rad[i];
        const double d = b * b - (t.x * t.x + t.y * t.y) * cc;
        found += cc > 0 && b < 0 && d >= 0;  // enters (fraction test left out: cheaper still)
      }
    }
  }
  benchmark::DoNotOptimize(found);
  state.counters["us_per_3_queries"] = benchmark::Counter(
      double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_GridBuild(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  fixstep::World w = gas(n, 0);
  std::vector<fixstep::QueryHit> out(16);
  const fixstep::Entity e = w.bodies()[0];
  const Vec2 p = w.body(e).position;
  for (auto _ : state) {
    w.set_position(e, p);  // marks the grid out of date without stepping
    benchmark::DoNotOptimize(w.overlap_circle({0, 0}, 0.1, out));
  }
  state.counters["ns_per_disc"] =
      benchmark::Counter(double(state.iterations()) * double(n) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Step(benchmark::State& state, int mode) {
  const auto n = static_cast<std::size_t>(state.range(0));
  fixstep::World w = gas(n, mode);
  for (int t = 0; t < 5; ++t) w.step();
  for (auto _ : state) w.step();
  state.counters["ns_per_body_step"] =
      benchmark::Counter(double(state.iterations()) * double(n) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["candidate_pairs"] = double(w.contact_stats().candidate_pairs);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Queries, grid, true)->RangeMultiplier(10)->Range(1000, 100000);
BENCHMARK_CAPTURE(BM_Queries, brute_force, false)->RangeMultiplier(10)->Range(1000, 100000);
BENCHMARK(BM_GridBuild)->RangeMultiplier(10)->Range(1000, 100000);
BENCHMARK_CAPTURE(BM_Step, gas_plain, 0)->Arg(10000);
BENCHMARK_CAPTURE(BM_Step, gas_all_filtered, 1)->Arg(10000);
BENCHMARK_CAPTURE(BM_Step, gas_collide_false, 2)->Arg(10000);
BENCHMARK_MAIN();
