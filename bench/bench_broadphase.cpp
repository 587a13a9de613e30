// The disc broadphase: the engine's hierarchical grid
// (engine/core/src/grid_broadphase.hpp) on one and two threads against sweep-and-prune on x
// (written here: sorted by (min_x, index) with std::sort every call, or kept in last call's
// order and re-sorted by insertion sort, nearly sorted tick to tick), all giving the same
// (a, b)-ordered pairs (checked before anything is timed), on two scenes:
//   pile  discs of radius 0.05-0.1 m (uniform) on a hexagonal lattice of spacing 0.2 m in a
//         square, indices row by row from the bottom (pour order), boxes inflated by 2 mm;
//   gas   discs of the same radii at uniform random positions in a square at 10% area
//         fraction, velocities uniform in [-5, 5] m/s per axis, dt = 1/60 s, each box the
//         disc swept over the tick; 16 ticks precomputed (walls reflect), played back and forth
//         so that sweep-and-prune's kept order sees one tick's motion per call;
// at N = 10^3, 10^4, 10^5. Reports ns per body per call (ns_per_body) and the pairs found.
//
//   build/bench/bin/bench_broadphase
//   build/bench/bin/bench_broadphase --benchmark_filter=grid   (the engine's alone)
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "grid_broadphase.hpp"

using fixstep::detail::DiscPair;
using fixstep::detail::GridBroadphase;
using fixstep::detail::SweptBox;

namespace {

constexpr double r_min = 0.05, r_max = 0.1;  // m

/// Frames of boxes of one scene (a pile has one).
struct Scene {
  std::vector<std::vector<SweptBox>> frames;
  std::vector<std::uint8_t> active;
};

Scene make_pile(std::size_t n) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> radius(r_min, r_max);
  const double d = 2 * r_max, row = d * std::sqrt(3.0) / 2, sweep = 0.002;
  const auto cols = static_cast<std::size_t>(std::ceil(std::sqrt(double(n))));
  Scene s;
  s.frames.resize(1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = i / cols, c = i % cols;
    const double x = d * (double(c) + 0.5 * double(r % 2)), y = row * double(r);
    const double e = radius(rng) + sweep;
    s.frames[0].push_back({x - e, y - e, x + e, y + e});
  }
  s.active.assign(n, 1);
  return s;
}

Scene make_gas(std::size_t n, int ticks = 16) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double mean_r2 = (r_max * r_max * r_max - r_min * r_min * r_min) / (3 * (r_max - r_min));
  const double side = std::sqrt(double(n) * M_PI * mean_r2 / 0.1), dt = 1.0 / 60;
  std::vector<double> x(n), y(n), vx(n), vy(n), r(n);
  for (std::size_t i = 0; i < n; ++i) {
    r[i] = r_min + (r_max - r_min) * u(rng);
    x[i] = side * u(rng), y[i] = side * u(rng);
    vx[i] = 10 * u(rng) - 5, vy[i] = 10 * u(rng) - 5;
  }
  Scene s;
  s.frames.resize(static_cast<std::size_t>(ticks));
  for (auto& boxes : s.frames) {
    for (std::size_t i = 0; i < n; ++i) {
      double x1 = x[i] + vx[i] * dt, y1 = y[i] + vy[i] * dt;
      if (x1 < 0 || x1 > side) vx[i] = -vx[i], x1 = x[i];
      if (y1 < 0 || y1 > side) vy[i] = -vy[i], y1 = y[i];
      boxes.push_back({std::min(x[i], x1) - r[i], std::min(y[i], y1) - r[i],
                       std::max(x[i], x1) + r[i], std::max(y[i], y1) + r[i]});
      x[i] = x1, y[i] = y1;
    }
  }
  s.active.assign(n, 1);
  return s;
}

/// Sweep-and-prune on x with the grid's contract (one thread).
class SweepAndPrune {
 public:
  explicit SweepAndPrune(bool keep_order) : keep_order_(keep_order) {}

  bool find_pairs(std::span<const SweptBox> boxes, std::span<const std::uint8_t> active,
                  std::size_t max_pairs, std::vector<DiscPair>& pairs) {
    const std::size_t n = boxes.size();
    if (!keep_order_ || order_.size() != n) {
      order_.resize(n);
      for (std::size_t i = 0; i < n; ++i) order_[i] = static_cast<std::uint32_t>(i);
    }
    items_.resize(n);
    for (std::size_t k = 0; k < n; ++k) items_[k] = {boxes[order_[k]], order_[k]};
    const auto less = [](const Item& p, const Item& q) {
      return p.box.min_x < q.box.min_x || (p.box.min_x == q.box.min_x && p.index < q.index);
    };
    if (keep_order_) {
      insertion_sort(less);
    } else {
      std::sort(items_.begin(), items_.end(), less);
    }
    for (std::size_t k = 0; k < n; ++k) order_[k] = items_[k].index;
    pairs.clear();
    if (!sweep(active, max_pairs)) return false;
    fixstep::detail::order_pairs(raw_, {}, n, offset_, pairs);
    return true;
  }

 private:
  struct Item {
    SweptBox box;
    std::uint32_t index;
  };
  template <class Less>
  void insertion_sort(Less less) {
    for (std::size_t i = 1; i < items_.size(); ++i) {
      const Item it = items_[i];
      std::size_t j = i;
      for (; j > 0 && less(it, items_[j - 1]); --j) items_[j] = items_[j - 1];
      items_[j] = it;
    }
  }
  bool sweep(std::span<const std::uint8_t> active, std::size_t max_pairs) {
    raw_.clear();
    const std::size_t n = items_.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Item& p = items_[k];
      for (std::size_t j = k + 1; j < n && items_[j].box.min_x <= p.box.max_x; ++j) {
        const Item& q = items_[j];
        if (p.box.min_y > q.box.max_y || q.box.min_y > p.box.max_y) continue;
        if (!active[p.index] && !active[q.index]) continue;
        raw_.push_back({std::min(p.index, q.index), std::max(p.index, q.index)});
      }
      if (raw_.size() > max_pairs) return false;
    }
    return true;
  }

  bool keep_order_;
  std::vector<std::uint32_t> order_;
  std::vector<Item> items_;
  std::vector<DiscPair> raw_;
  std::vector<std::uint32_t> offset_;
};

const Scene& scene(bool gas, std::size_t n) {
  static std::vector<std::pair<std::size_t, Scene>> cache[2];
  for (const auto& [m, s] : cache[gas]) {
    if (m == n) return s;
  }
  cache[gas].emplace_back(n, gas ? make_gas(n) : make_pile(n));
  return cache[gas].back().second;
}

/// Frame k of a back-and-forth playback of `count` frames.
std::size_t ping_pong(std::size_t k, std::size_t count) {
  if (count == 1) return 0;
  const std::size_t period = 2 * (count - 1), t = k % period;
  return t < count ? t : period - t;
}

enum class Method { grid1, grid2, sap_sort, sap_keep };

template <class Find>
void run(benchmark::State& state, const Scene& s, Find&& find) {
  std::vector<DiscPair> pairs;
  std::size_t k = 0, found = 0;
  if (!find(s.frames[0], pairs)) state.SkipWithError("max_pairs exceeded");  // warm, sorted
  for (auto _ : state) {
    const auto& boxes = s.frames[ping_pong(k++, s.frames.size())];
    if (!find(boxes, pairs)) state.SkipWithError("max_pairs exceeded");
    found += pairs.size();
    benchmark::DoNotOptimize(pairs.data());
  }
  const double n = double(s.active.size());
  state.counters["ns_per_body"] = benchmark::Counter(
      n * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pairs"] = double(found) / double(std::max<std::size_t>(k, 1));
}

void bm(benchmark::State& state, bool gas, Method method) {
  const Scene& s = scene(gas, static_cast<std::size_t>(state.range(0)));
  const std::size_t cap = 64 * s.active.size();
  if (method == Method::grid1 || method == Method::grid2) {
    GridBroadphase bp;
    if (state.range(1) != 0) bp.set_parallel_min(0);  // split whatever n (to measure it)
    const int threads = method == Method::grid2 ? 2 : 1;
    run(state, s, [&](const std::vector<SweptBox>& b, std::vector<DiscPair>& p) {
      return bp.find_pairs(b, s.active, cap, p, threads);
    });
  } else {
    SweepAndPrune sap(method == Method::sap_keep);
    run(state, s, [&](const std::vector<SweptBox>& b, std::vector<DiscPair>& p) {
      return sap.find_pairs(b, s.active, cap, p);
    });
  }
}

/// Every method gives the grid's pairs on every scene: checked before timing.
void verify() {
  for (bool gas : {false, true}) {
    for (std::size_t n : {1000, 10000, 100000}) {
      const Scene& s = scene(gas, n);
      GridBroadphase bp;
      SweepAndPrune sort(false), keep(true);
      for (const auto& boxes : s.frames) {
        std::vector<DiscPair> want, got;
        bp.find_pairs(boxes, s.active, 64 * n, want, 1);
        const bool same = bp.find_pairs(boxes, s.active, 64 * n, got, 2) && got == want &&
                          sort.find_pairs(boxes, s.active, 64 * n, got) && got == want &&
                          keep.find_pairs(boxes, s.active, 64 * n, got) && got == want;
        if (!same) throw std::runtime_error(fmt::format("pairs differ: gas={} n={}", gas, n));
      }
    }
  }
}

void print_load(const char* when) {
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) == 3) {
    fmt::print("load average {}: {:.2f} {:.2f} {:.2f} (2 cores)\n", when, load[0], load[1],
               load[2]);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  verify();
  const std::pair<const char*, Method> methods[] = {{"grid_1thread", Method::grid1},
                                                    {"grid_2threads", Method::grid2},
                                                    {"sap_sort", Method::sap_sort},
                                                    {"sap_insertion", Method::sap_keep}};
  for (bool gas : {false, true}) {
    for (const auto& [name, method] : methods) {
      auto* b =
          benchmark::RegisterBenchmark(fmt::format("{}/{}", gas ? "gas" : "pile", name).c_str(),
                                       [gas, m = method](benchmark::State& st) { bm(st, gas, m); });
      b->ArgNames({"n", "split"})->Unit(benchmark::kMicrosecond);
      // One thread: CPU time (the machine is shared); two: wall time, what a tick waits for.
      if (method == Method::grid2) b->UseRealTime();
      for (long n : {1000, 10000, 100000}) b->Args({n, 0});
      if (method == Method::grid2) b->Args({1000, 1})->Args({10000, 1});
    }
  }
  print_load("before");
  benchmark::RunSpecifiedBenchmarks();
  print_load("after");
  benchmark::Shutdown();
  return 0;
}
