// The trade on networks: every fixstep integrator at every step size against the
// two peer engines, error against cost, on the two networks of bench_coupled (coupled.hpp):
//   chain   100 bodies in a line, pulled at one end, anchored at the other;
//   cloth   a 10 x 10 grid held by a frame of anchored springs;
// both linear with proportional damping, so exact::LinearNetwork gives their exact motion.
//   error   largest |x - x_exact| over the bodies and over samples every 1/30 s for 2 s, m;
//   cost    wall time per simulated second, µs: the median of `reps` rounds in which every
//           configuration steps its 2 s in turn (round-robin, so load that comes and goes hits
//           all alike), from a fresh world each time, untimed set-up excluded.
// Configurations: fixstep f64 on one thread, each of the six integrators at the game's tick
// dt = 1/60 s with 1, 2, 4, ... 128 substeps (h = dt / substeps); Chipmunk2D 7 and Box2D 2.4
// with one Step per h = 1/60 s / k, k = 1 ... 64 (their way to a smaller step). A run whose
// error exceeds 1 m (or is not finite) is unstable and reaches no target.
// Writes DIR/network_trade.md: per scene the cheapest configuration of each stepper reaching
// 1e-2, 1e-4 and 1e-6 m and the overall cheapest, then every configuration's error and cost.
//
//   build/bench/bin/network_trade --out docs/perf [--reps N] [--quick]
//   (--quick: substeps up to 8, 1 round: the smoke run ctest network_trade_smoke makes)
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "coupled.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/integrators.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/file_write.hpp"
#include "world_kernel.hpp"

using namespace coupled;
using fixstep::Body;
using fixstep::Integrator;

namespace {

constexpr double tick = 1.0 / 60.0;               // s, the game's tick
constexpr double duration = 2.0;                  // s simulated per run
constexpr double sample = 1.0 / 30.0;             // s between error samples
constexpr double unstable_error = 1.0;            // m
constexpr double targets[] = {1e-2, 1e-4, 1e-6};  // m
/// Forest–Ruth with DampingSplit::per_step, as a stepper of its own.
constexpr const char* per_step_name = "forest_ruth:per_step";

/// One configuration: a fixstep integrator at `substeps` per tick, or a peer at dt = tick / k.
struct Config {
  std::string
      stepper;  ///< integrator name (forest_ruth:per_step: DampingSplit), "chipmunk", "box2d"
  int k = 1;    ///< substeps per tick (fixstep) or steps per tick (peers)
  double error = 0.0;  ///< m
  double cost = 0.0;   ///< µs per simulated second
  [[nodiscard]] bool fixstep() const { return stepper != "chipmunk" && stepper != "box2d"; }
  [[nodiscard]] bool stable() const { return std::isfinite(error) && error <= unstable_error; }
  [[nodiscard]] std::string label() const {
    return fixstep() ? fmt::format("fixstep {}, {} substep{}", stepper, k, k == 1 ? "" : "s")
                     : fmt::format("{}, dt = 1/{} s", stepper_label(stepper), 60 * k);
  }
};

/// A fresh stepper for c on scene s: steps of h = tick / c.k (fixstep: one tick of c.k
/// substeps per step() call).
class Runner {
 public:
  Runner(const Config& c, const Scene& s) : mass_(s.bodies.size()) {
    for (std::size_t j = 0; j < mass_.size(); ++j) mass_[j] = s.bodies[j].body.mass;
    if (c.fixstep()) {
      const bool per_step = c.stepper == per_step_name;
      world_ = make_world<double>(
          s,
          {.dt = tick,
           .integrator = per_step ? Integrator::forest_ruth : *fixstep::parse_integrator(c.stepper),
           .substeps = c.k,
           .threads = 1,
           .damping_split =
               per_step ? fixstep::DampingSplit::per_step : fixstep::DampingSplit::per_stage});
      calls_per_tick_ = 1;
    } else {
      peer_ = make_stepper(c.stepper, s, tick / c.k);
      calls_per_tick_ = c.k;
    }
  }
  void ticks(long n) {
    for (long t = 0; t < n; ++t) {
      if (world_) {
        world_->step();
      } else {
        for (int i = 0; i < calls_per_tick_; ++i) peer_->step();
      }
    }
  }
  void state(std::vector<Body>& out) const {
    if (peer_) return peer_->state(out);
    for (std::size_t j = 0; j < out.size(); ++j) {
      out[j] = {mass_[j], {world_->x()[j], world_->y()[j]}, {world_->vx()[j], world_->vy()[j]}};
    }
  }

 private:
  std::vector<double> mass_;
  std::unique_ptr<fixstep::detail::WorldKernel<double>> world_;
  std::unique_ptr<Peer> peer_;
  int calls_per_tick_ = 1;
};

/// Largest position error of c over the run, m (samples every 1/30 s against ref).
double error_of(const Config& c, const Scene& s, const Reference& ref) {
  Runner r(c, s);
  std::vector<Body> st(s.bodies.size());
  double worst = 0.0;
  for (const auto& exact : ref.states) {
    r.ticks(std::lround(sample / tick));
    r.state(st);
    for (std::size_t j = 0; j < st.size(); ++j) {
      const double e = std::hypot(st[j].position.x - exact[j].position.x,
                                  st[j].position.y - exact[j].position.y);
      if (!(e <= worst)) worst = std::isnan(e) ? INFINITY : e;
    }
    if (!std::isfinite(worst) || worst > 1e6) return INFINITY;  // no use stepping on
  }
  return worst;
}

/// Median µs per simulated second of each configuration, `reps` rounds round-robin.
void time_all(std::vector<Config>& configs, const Scene& s, int reps) {
  std::vector<std::vector<double>> samples(configs.size());
  const long n = std::lround(duration / tick);
  for (int r = 0; r < reps; ++r) {
    for (std::size_t i = 0; i < configs.size(); ++i) {
      if (!configs[i].stable()) continue;
      Runner run(configs[i], s);
      const auto t0 = std::chrono::steady_clock::now();
      run.ticks(n);
      const double sec =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      samples[i].push_back(sec / duration * 1e6);
    }
  }
  for (std::size_t i = 0; i < configs.size(); ++i) {
    auto& v = samples[i];
    if (v.empty()) continue;
    std::sort(v.begin(), v.end());
    configs[i].cost = v[v.size() / 2];
  }
}

std::vector<Config> configurations(bool quick) {
  std::vector<Config> out;
  const int max_substeps = quick ? 8 : 128, max_peer = quick ? 8 : 64;
  std::vector<std::string> names;
  for (Integrator i : fixstep::all_integrators) names.emplace_back(fixstep::integrator_name(i));
  names.emplace_back(per_step_name);
  for (const std::string& name : names) {
    for (int k = 1; k <= max_substeps; k *= 2) out.push_back({name, k});
  }
  for (const char* peer : {"chipmunk", "box2d"}) {
    for (int k = 1; k <= max_peer; k *= 2) out.push_back({peer, k});
  }
  return out;
}

/// The cheapest stable configuration of `stepper` (empty: any) with error <= target.
const Config* cheapest(const std::vector<Config>& cs, const std::string& stepper, double target) {
  const Config* best = nullptr;
  for (const Config& c : cs) {
    if (!stepper.empty() && c.stepper != stepper) continue;
    if (!c.stable() || c.error > target || c.cost <= 0.0) continue;
    if (!best || c.cost < best->cost) best = &c;
  }
  return best;
}

std::string cell(const Config* c) {
  if (!c) return "not reached";
  return fmt::format("{} ({:.3g} µs, {:.1e} m)",
                     c->fixstep() ? fmt::format("{} substep{}", c->k, c->k == 1 ? "" : "s")
                                  : fmt::format("dt = 1/{} s", 60 * c->k),
                     c->cost, c->error);
}

std::string scene_report(const std::string& title, const std::vector<Config>& cs) {
  std::vector<std::string> steppers;
  for (const Config& c : cs) {
    if (std::find(steppers.begin(), steppers.end(), c.stepper) == steppers.end())
      steppers.push_back(c.stepper);
  }
  std::string md = fmt::format("#### {}: the cheapest configuration per target error\n\n", title);
  md +=
      "Each cell: the cheapest step that reaches the target (cost per simulated second, its "
      "largest position error).\n\n| stepper | 1e-2 m | 1e-4 m | 1e-6 m |\n|---|---|---|---|\n";
  for (const std::string& st : steppers) {
    const Config& any =
        *std::find_if(cs.begin(), cs.end(), [&](auto& c) { return c.stepper == st; });
    md += fmt::format("| {} |", any.fixstep() ? "fixstep " + st : stepper_label(st));
    for (double t : targets) md += fmt::format(" {} |", cell(cheapest(cs, st, t)));
    md += "\n";
  }
  md += "| **cheapest of all** |";
  for (double t : targets) {
    const Config* c = cheapest(cs, "", t);
    md +=
        fmt::format(" {} |", c ? c->label() + fmt::format(": {:.3g} µs", c->cost) : "not reached");
  }
  md += "\n\nAt each target, the peers' cheapest against fixstep's cheapest (cost ratio):\n\n";
  for (double t : targets) {
    const Config* f = nullptr;
    for (const Config& c : cs) {
      if (c.fixstep() && c.stable() && c.error <= t && c.cost > 0 && (!f || c.cost < f->cost))
        f = &c;
    }
    for (const char* peer : {"chipmunk", "box2d"}) {
      const Config* p = cheapest(cs, peer, t);
      md += fmt::format("- {:.0e} m, {}: {}\n", t, stepper_label(peer),
                        !p   ? "does not reach it"
                        : !f ? "reached; fixstep does not"
                             : fmt::format("{:.1f}x fixstep's cost ({} vs {})", p->cost / f->cost,
                                           p->label(), f->label()));
    }
  }
  md += fmt::format(
      "\n#### {}: every configuration\n\n| configuration | largest error (m) | "
      "µs per simulated second |\n|---|---|---|\n",
      title);
  for (const Config& c : cs) {
    md += c.stable() ? fmt::format("| {} | {:.2e} | {:.3g} |\n", c.label(), c.error, c.cost)
                     : fmt::format("| {} | unstable | – |\n", c.label());
  }
  return md + "\n";
}

double load_average() {
  std::ifstream f("/proc/loadavg");
  double a = -1.0;
  f >> a;
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out;
  int reps = 5;
  bool quick = false;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--out" && a + 1 < argc) {
      out = argv[++a];
    } else if (arg == "--reps" && a + 1 < argc) {
      reps = std::max(1, std::atoi(argv[++a]));
    } else if (arg == "--quick") {
      quick = true, reps = 1;
    } else {
      std::fprintf(stderr, "usage: network_trade [--out DIR] [--reps N] [--quick]\n");
      return 2;
    }
  }
  const double load_before = load_average();
  std::vector<double> times;
  for (int k = 1; k <= int(std::lround(duration / sample)); ++k) times.push_back(k * sample);
  std::string md;
  bool ordered = true;
  for (SceneKind kind : {SceneKind::chain, SceneKind::cloth}) {
    const Scene s = make_scene(kind, 100);
    const Reference ref = reference(s, times);
    std::vector<Config> cs = configurations(quick);
    for (Config& c : cs) c.error = error_of(c, s, ref);
    time_all(cs, s, reps);
    const std::string title =
        fmt::format("{} ({} bodies, {} links)", scene_name(kind), s.bodies.size(), s.links.size());
    md += scene_report(title, cs);
    std::fprintf(stderr, "network_trade: %s done\n", title.c_str());
    // Sanity: every fixstep integrator's error falls as its step does (where still above
    // rounding), or the study measures nothing.
    for (Integrator i : fixstep::all_integrators) {
      const std::string name(fixstep::integrator_name(i));
      double prev = INFINITY;
      for (const Config& c : cs) {
        if (c.stepper != name || !c.stable()) continue;
        if (c.error > 1e-9 && c.error > prev * 1.01) ordered = false;
        prev = c.error;
      }
    }
  }
  const std::string head = fmt::format(
      "Error against cost on the chain and the cloth of section 6 (100 bodies each, 2 s against "
      "exact::LinearNetwork), every fixstep integrator (f64, one thread) at 1-{} substeps of "
      "dt = 1/60 s and the peers at dt = 1/60 ... 1/{} s; cost: median of {} round-robin "
      "rounds. Load average {:.2f} before the run, {:.2f} after.\n\n",
      quick ? 8 : 128, quick ? 480 : 3840, reps, load_before, load_average());
  md = head + md;
  std::fputs(md.c_str(), stdout);
  if (!out.empty()) {
    try {  // atomically, as every file fixstep writes: never a half-written report
      fixstep::write_file_atomically(out + "/network_trade.md", md);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "network_trade: %s\n", e.what());
      return 1;
    }
  }
  if (!ordered) {
    std::fprintf(stderr, "network_trade: an integrator's error grew as its step shrank\n");
    return 1;
  }
  return 0;
}
