// What each integrator costs per tick on damped networks, side by side in one run:
//   cloth.toml   assets/scenes/cloth.toml (400 bodies, 1520 damped links with rest lengths,
//                dt = 2.5 ms, one step per tick), as `fixstep run` steps it;
//   cloth 10^4   a 100 x 100 grid of 0.01 kg bodies, structural and shear links of 10 Hz,
//                ζ = 0.1, hanging from two corners, dt = 1/120 s, 2 substeps;
// each in f64 and f32, on 1 and 2 threads (WorldSettings::threads), Forest–Ruth also with
// DampingSplit::per_step (its cheaper variant, order 2 in the damping), with the dissipation
// account on as scenes keep it. Every integrator's world is stepped in turn, `reps` rounds of
// `ticks` ticks each, so load that comes and goes hits all alike; the table gives the median
// time per tick and its ratio to semi-implicit Euler's median in the same round-robin.
//
//   build/bench/bin/bench_network_integrators [--out DIR] [--reps N]
//     (writes DIR/network_integrators.md; the first line gives the load average)
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "fixstep/capture/capture.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"

using namespace fixstep;

namespace {

struct Case {
  std::string name;
  WorldDef def;
  int ticks;  ///< per timed batch
};

std::string big_cloth_toml() {
  return R"([world]
dt = 0.008333333333333333
substeps = 2
integrator = "semi_implicit_euler"
allow_unstable = true

[[grid]]
name = "cloth"
columns = 100
rows = 100
origin = [-2.5, 0.0]
spacing = [0.05, -0.05]
body = { mass = 0.01, gravity = [0.0, -9.81], drag = 0.0005 }
link = { frequency = 10.0, damping_ratio = 0.1 }
shear = { frequency = 10.0, damping_ratio = 0.1 }
pin = [[0, 0], [99, 0]]
pin_spring = { frequency = 10.0, damping_ratio = 1.0 }
)";
}

std::vector<Case> cases() {
  const WorldDef cloth = load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/cloth.toml").def;
  const WorldDef big = parse_scene(big_cloth_toml(), "cloth 10^4").def;
  return {{"cloth.toml", cloth, 400}, {"cloth 10^4", big, 10}};
}

double load_average() {
  std::ifstream f("/proc/loadavg");
  double a = -1.0;
  f >> a;
  return a;
}

/// The columns: each integrator with the default DampingSplit, then Forest–Ruth with per_step
/// (its cheaper, order-2-in-damping variant).
struct Timed {
  Integrator integrator;
  DampingSplit split = DampingSplit::per_stage;
};
constexpr Timed timed[] = {{Integrator::semi_implicit_euler},
                           {Integrator::velocity_verlet},
                           {Integrator::rk4},
                           {Integrator::forest_ruth},
                           {Integrator::forest_ruth, DampingSplit::per_step}};

/// Median seconds per tick of each integrator on `c` at precision p and `threads`.
std::vector<double> time_case(const Case& c, Precision p, int threads, int reps) {
  std::vector<World> sims;
  for (const Timed& i : timed) {
    WorldDef d = c.def;
    d.precision = p, d.settings.integrator = i.integrator, d.settings.threads = threads;
    d.settings.damping_split = i.split;
    sims.push_back(World(d));
    sims.back().step();  // first-tick work (the passes' arrays) stays untimed
  }
  std::vector<std::vector<double>> samples(sims.size());
  for (int r = 0; r < reps; ++r) {
    for (std::size_t k = 0; k < sims.size(); ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      for (int t = 0; t < c.ticks; ++t) sims[k].step();
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      samples[k].push_back(s / c.ticks);
    }
  }
  std::vector<double> median;
  for (auto& s : samples) {
    std::sort(s.begin(), s.end());
    median.push_back(s[s.size() / 2]);
  }
  return median;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out;
  int reps = 15;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--out" && a + 1 < argc)
      out = argv[++a];
    else if (arg == "--reps" && a + 1 < argc)
      reps = std::max(1, std::stoi(argv[++a]));
    else {
      std::fprintf(stderr, "usage: bench_network_integrators [--out DIR] [--reps N]\n");
      return 2;
    }
  }
  const double load_before = load_average();
  std::string md = fmt::format(
      "Time per tick of each integrator on damped networks, median of {} rounds stepped side by "
      "side, and its ratio to semi-implicit Euler in the same run (targets: velocity Verlet <= "
      "2x, Forest–Ruth <= 4x; per_step: DampingSplit::per_step). Load average {:.2f} before the "
      "run",
      reps, load_before);
  std::string table =
      "\n\n| world | precision | threads | semi_implicit_euler | velocity_verlet | rk4 | "
      "forest_ruth | forest_ruth, per_step |\n|---|---|---|---|---|---|---|---|\n";
  for (const Case& c : cases()) {
    for (Precision p : {Precision::f64, Precision::f32}) {
      for (int threads : {1, 2}) {
        const std::vector<double> t = time_case(c, p, threads, reps);
        std::string row = fmt::format("| {} ({} bodies) | {} | {} |", c.name, c.def.bodies.size(),
                                      precision_name(p), threads);
        for (std::size_t k = 0; k < t.size(); ++k) {
          row += fmt::format(" {:.1f} µs ({:.2f}x) |", t[k] * 1e6, t[k] / t[0]);
        }
        table += row + "\n";
        std::printf("%s\n", row.c_str());
        std::fflush(stdout);
      }
    }
  }
  md += fmt::format(", {:.2f} after.{}", load_average(), table);
  std::fputs(md.c_str(), stdout);
  if (!out.empty()) {
    prepare_output_dir(out);
    write_file_atomic(out + "/network_integrators.md", md);
    std::printf("wrote %s/network_integrators.md\n", out.c_str());
  }
  return 0;
}
