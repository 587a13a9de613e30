// bench_discs --paced: the disc scenes stepped as a game steps them, one tick a frame at 60
// frames a second (discs_paced.hpp). Between two ticks every engine's threads are idle for most
// of a frame: a second thread that sleeps between ticks must be woken for each one, and the
// caches and the virtual CPUs have cooled. Back-to-back ticks (the Google Benchmark cases) see
// none of that.
#include "discs_paced.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <thread>
#include <vector>

#include "median.hpp"

namespace discs {
namespace {

using Clock = std::chrono::steady_clock;

/// One stepper's ticks, each timed (s).
struct Lane {
  std::string key;
  std::unique_ptr<Stepper> stepper;
  std::vector<double> tick_s;
};

SceneKind paced_kind(const std::string& scene) {
  if (scene == "pile") return SceneKind::pile;
  if (scene == "gas") return SceneKind::gas;
  if (scene == "pile_settled") return SceneKind::pile_settled;
  throw std::invalid_argument(
      fmt::format("--paced: scene '{}' is none of pile, gas, pile_settled", scene));
}

/// The steppers compared: fixstep on 1 and 2 threads, then Box2D v3.2 on 1 and 2 workers where
/// it was built.
std::vector<std::string> paced_keys() {
  std::vector<std::string> keys{"fixstep_f64_t1", "fixstep_f64_t2"};
  if (box2d3_built(Box2d3Release::v3_2)) {
    keys.push_back(std::string(box2d3_key(Box2d3Release::v3_2)) + "_w1");
    keys.push_back(std::string(box2d3_key(Box2d3Release::v3_2)) + "_w2");
  }
  return keys;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

}  // namespace

int paced(const std::string& scene, std::size_t n, int ticks) {
  if (n < 2 || n > 100'000) throw std::invalid_argument("--paced: N must be 2 to 100000");
  if (ticks < paced_block || ticks > 36'000) {
    throw std::invalid_argument(fmt::format("--paced: ticks must be {} to 36000", paced_block));
  }
  const Scene s = make_scene(paced_kind(scene), n);
  std::vector<Lane> lanes;
  for (const std::string& key : paced_keys()) {
    lanes.push_back({key, make_stepper(key, s), {}});
    for (int t = 0; t < s.warmup; ++t) lanes.back().stepper->step();
  }
  const int blocks = ticks / paced_block;
  std::fprintf(stderr, "paced: %s, N = %zu, %d ticks a stepper at 60 Hz (%.0f s)\n", scene.c_str(),
               n, blocks * paced_block, blocks * paced_block * lanes.size() * paced_frame.count());
  // Blocks of ticks in turn, so that a slow span of the machine falls on every stepper.
  auto next = Clock::now();
  for (int b = 0; b < blocks; ++b) {
    for (Lane& lane : lanes) {
      for (int t = 0; t < paced_block; ++t) {
        next += std::chrono::duration_cast<Clock::duration>(paced_frame);
        std::this_thread::sleep_until(next);
        const auto start = Clock::now();
        lane.stepper->step();
        lane.tick_s.push_back(std::chrono::duration<double>(Clock::now() - start).count());
      }
    }
    if (isatty(STDERR_FILENO) != 0) std::fprintf(stderr, "\rpaced: block %d of %d", b + 1, blocks);
  }
  if (isatty(STDERR_FILENO) != 0) std::fprintf(stderr, "\n");
  std::printf("| stepper | mean us a tick | median | p90 | mean / fixstep 1 thread's |\n");
  std::printf("|---|---|---|---|---|\n");
  double one = 0.0;
  for (const Lane& lane : lanes) {
    double mean = 0.0;
    for (const double t : lane.tick_s) mean += t;
    mean /= static_cast<double>(lane.tick_s.size());
    if (one == 0.0) one = mean;
    std::printf("| %s | %.1f | %.1f | %.1f | %.2f |\n", stepper_label(lane.key).c_str(), mean * 1e6,
                fixstep::bench::median(lane.tick_s) * 1e6, quantile(lane.tick_s, 0.9) * 1e6,
                mean / one);
  }
  return 0;
}

}  // namespace discs
