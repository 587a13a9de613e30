// Coupled systems (links between bodies) against the hand-written loop and two peer engines,
// in one run (Google Benchmark), on two scenes (coupled.hpp): a chain (N bodies in a line,
// pulled at one end, anchored at the other) and a cloth (a grid held by a frame):
//   fixstep    fixstep::detail::WorldKernel<Real>::step(), semi-implicit Euler, f64 and f32, 1 and
//   2 threads
//              (WorldSettings::threads): the link pass, the per-body gather, the update;
//   edge loop  the same arithmetic written by hand as an edge list: for each link in order
//              f = -k d - b u, acc[a] += f, acc[b] -= f; then per body a = field + acc/m,
//              v += a h, x += v h. Every body adds its links' forces in link order, as the
//              engine's gather does, so it must give the engine's states bit for bit: checked
//              before anything is timed, for both precisions and 1 and 2 threads;
//   chipmunk   Chipmunk2D 7 cpSpace + cpDampedSpring (peers_chipmunk.cpp);
//   box2d      Box2D 2.4 b2World + b2DistanceJoint (peers_box2d.cpp);
// at N = 10², 10³, 10⁴, 10⁵ bodies and dt = 1/60 s. Before timing it measures, untimed, each
// stepper's error against the chain's reference solution (coupled_reference.cpp) at
// dt = 1/30 ... 1/480 s over 2 s, and the energy balance. After the run it prints (and with
// --report DIR writes DIR/coupled.md and the work-precision plot DIR/coupled_work_precision.png)
// the tables and the targets as ratios measured side by side.
//
//   build/bench/bin/bench_coupled --report docs/perf
//   build/bench/bin/bench_coupled --quick --benchmark_min_time=0.01   (N <= 10³: a smoke run)
//   build/bench/bin/bench_coupled --verify-only  (the checks alone; ctest bench_coupled_checks)
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupled.hpp"
#include "fixstep/capture/capture.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/world.hpp"
#include "median_run.hpp"

using namespace fixstep;
using namespace coupled;

namespace {

constexpr double tick = 1.0 / 60.0;  // s: the timed step
constexpr double duration = 2.0;     // s: the accuracy runs
constexpr double sample =
    1.0 / 30;  // s: errors are sampled at multiples of it (every dt divides it)
/// What --verify-only allows a stepper's max position error on the chain (N = 100, 2 s) at
/// dt = 1/240 s, m: about 3x what each measured on the development machine (fixstep and
/// Chipmunk 0.2-0.4 mm; Box2D 1.0 cm, its implicit spring damping the motion strongly).
double accuracy_tolerance(const std::string& key) {
  return key == "box2d" ? 3e-2 : 1e-3;
}

// --- accuracy against the reference ------------------------------------------------------

std::vector<double> sample_times() {
  std::vector<double> t;
  for (int k = 1; k <= int(std::lround(duration / sample)); ++k) t.push_back(k * sample);
  return t;
}

Accuracy measure(const std::string& key, const Scene& s, const Reference& ref, double dt) {
  const auto p = make_stepper(key, s, dt, /*track=*/true);
  Accuracy a{.stepper = key, .n = s.bodies.size(), .dt = dt};
  std::vector<Body> st(s.bodies.size());
  p->state(st);
  const double e0 = energy(s, st), eq = equilibrium_energy(s);
  const auto per_sample = std::lround(sample / dt);
  a.min_link = 1e300;
  for (std::size_t k = 0; k < ref.states.size(); ++k) {
    for (long i = 0; i < per_sample; ++i) p->step();
    p->state(st);
    double err = 0.0;
    for (std::size_t j = 0; j < st.size(); ++j) {
      const Body& r = ref.states[k][j];
      const double e = std::hypot(st[j].position.x - r.position.x, st[j].position.y - r.position.y);
      err = std::isnan(e) ? INFINITY : std::max(err, e);
    }
    for (const fixstep::IndexLink& l : s.links) {
      a.min_link =
          std::min(a.min_link, std::hypot(st[l.body_a].position.x - st[l.body_b].position.x,
                                          st[l.body_a].position.y - st[l.body_b].position.y));
    }
    a.err_max = std::max(a.err_max, err);
    if (k + 1 == ref.states.size()) a.err_end = err;
  }
  a.energy_end = (energy(s, st) - eq) / (e0 - eq);
  a.energy_ref_end = (energy(s, ref.states.back()) - eq) / (e0 - eq);
  a.balance = (energy(s, st) + p->dissipated() - e0) / (e0 - eq);
  return a;
}

std::vector<double> accuracy_steps() {
  return {1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240, 1.0 / 480};
}

std::vector<Accuracy> accuracy_study(std::string& method) {
  std::vector<Accuracy> out;
  for (const std::size_t n : {std::size_t{100}, std::size_t{1000}}) {
    const Scene s = make_chain(n);
    const auto times = sample_times();
    const Reference ref = reference(s, times);
    method = ref.method;
    for (const char* key : accurate_steppers()) {
      for (const double dt : accuracy_steps()) out.push_back(measure(key, s, ref, dt));
    }
  }
  return out;
}

// --- the checks, run before anything is timed (and alone with --verify-only) --------------

int failures = 0;
void check(bool ok, const std::string& what) {
  if (!ok) ++failures, std::fprintf(stderr, "bench_coupled: FAILED: %s\n", what.c_str());
}

/// Bodies whose x, y, vx or vy differ in any bit (the states are Real converted exactly).
std::size_t differing(const Peer& a, const Peer& b, std::size_t n) {
  std::vector<Body> sa(n), sb(n);
  a.state(sa), b.state(sb);
  std::size_t count = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const double va[4] = {sa[j].position.x, sa[j].position.y, sa[j].velocity.x, sa[j].velocity.y};
    const double vb[4] = {sb[j].position.x, sb[j].position.y, sb[j].velocity.x, sb[j].velocity.y};
    count += std::memcmp(va, vb, sizeof va) != 0;
  }
  return count;
}

/// The edge loop, the engine on 1 thread, on 2 threads and with its dissipation account
/// step `ticks` times: all must hold the same bits.
void verify_bits(SceneKind kind, std::size_t n_asked, int ticks, bool two_threads) {
  const Scene s = make_scene(kind, n_asked);
  const std::size_t n = s.bodies.size();
  for (const char* p : {"f64", "f32"}) {
    const auto edge = make_stepper(fmt::format("edge_{}", p), s, tick);
    const auto one = make_stepper(fmt::format("fixstep_{}_t1", p), s, tick);
    const auto tracked = make_stepper(fmt::format("fixstep_{}_t1", p), s, tick, true);
    const auto two = two_threads ? make_stepper(fmt::format("fixstep_{}_t2", p), s, tick) : nullptr;
    for (int t = 0; t < ticks; ++t) {
      edge->step(), one->step(), tracked->step();
      if (two) two->step();
    }
    const auto what = fmt::format("{} N = {} {} after {} ticks", scene_name(kind), n, p, ticks);
    check(differing(*edge, *one, n) == 0,
          fmt::format("{}: {} bodies of the edge loop differ from the engine's", what,
                      differing(*edge, *one, n)));
    check(differing(*tracked, *one, n) == 0, what + ": track_dissipation changed the states");
    if (two) {
      check(two->threads_used() == 2, what + ": threads = 2 did not use 2 threads");
      check(differing(*two, *one, n) == 0, what + ": 2 threads differ from 1 thread");
    }
  }
}

/// The reference against a second computation of it: exact::LinearNetwork against RK4 at
/// h = 1/60 s / 256.
void verify_reference() {
  const Scene s = make_chain(100);
  const auto times = sample_times();
  const Reference ref = reference(s, times);
  const Reference other = rk4_reference(s, times, 256);
  double worst = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    for (std::size_t j = 0; j < s.bodies.size(); ++j) {
      worst =
          std::max(worst, std::hypot(ref.states[k][j].position.x - other.states[k][j].position.x,
                                     ref.states[k][j].position.y - other.states[k][j].position.y));
    }
  }
  const double tol = 1e-9;
  check(worst <= tol, fmt::format("reference ({}) vs {}: {:.2e} m > {:.0e} m", ref.method,
                                  other.method, worst, tol));
  std::printf("checks: reference %s; against %s: %.2e m (<= %.0e m)\n", ref.method.c_str(),
              other.method.c_str(), worst, tol);
}

/// Every stepper follows the reference to a loose tolerance at dt = 1/240 s (N = 100, 2 s),
/// and no link of the chain comes near zero length (where Box2D's clamp would act).
void verify_accuracy() {
  const Scene s = make_chain(100);
  const Reference ref = reference(s, sample_times());
  for (const char* key : accurate_steppers()) {
    const Accuracy a = measure(key, s, ref, 1.0 / 240);
    const double tol = accuracy_tolerance(key);
    check(a.err_max <= tol,
          fmt::format(
              "{}: max position error {:.2e} m > {:.0e} m (chain N = 100, dt = 1/240 s, {} s)", key,
              a.err_max, tol, duration));
    check(a.min_link >= 0.05,
          fmt::format("{}: a chain link shrank to {:.3f} m (< 0.05 m)", key, a.min_link));
    std::printf(
        "checks: %-12s chain N = 100, dt = 1/240 s: max position error %.2e m (<= %.0e m), "
        "shortest link %.3f m\n",
        key, a.err_max, tol, a.min_link);
  }
}

int run_checks() {
  verify_bits(SceneKind::chain, 1001, 300, false);
  verify_bits(SceneKind::cloth, 33 * 33, 300, false);
  verify_bits(SceneKind::chain, 10'001, 100, true);  // >= 2 x 4096: both threads get work
  verify_bits(SceneKind::cloth, 101 * 101, 100, true);
  if (failures == 0) {
    std::printf(
        "checks: the edge-list loop reproduces fixstep bit for bit (chain and cloth, f64 "
        "and f32, 1 and 2 threads, with and without the dissipation account)\n");
  }
  verify_reference();
  verify_accuracy();
  return failures;
}

// --- benchmarks -----------------------------------------------------------------------------

const Scene& cached_scene(SceneKind kind, std::size_t n) {
  static std::map<std::pair<int, std::size_t>, Scene> scenes;
  auto it = scenes.find({int(kind), n});
  if (it == scenes.end()) it = scenes.emplace(std::pair{int(kind), n}, make_scene(kind, n)).first;
  return it->second;
}

void bm_step(benchmark::State& st, SceneKind kind, const std::string& key) {
  const Scene& s = cached_scene(kind, static_cast<std::size_t>(st.range(0)));
  const auto p = make_stepper(key, s, tick);
  p->step();  // first-step work (the engine builds its passes' arrays) stays untimed
  for (auto _ : st) {
    p->step();
    benchmark::ClobberMemory();
  }
  st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()) *
                       static_cast<std::int64_t>(s.bodies.size()));
  st.counters["bodies"] = double(s.bodies.size());
  st.counters["links"] = double(s.links.size());
}

struct Options {
  bool quick = false, verify_only = false, min_time_given = false, reps_given = false;
  std::optional<std::string> report;
};

std::vector<std::int64_t> sizes(const Options& o) {
  if (o.quick) return {100, 1000};
  return {100, 1000, 10'000, 100'000};
}

void register_all(const Options& o) {
  const int reps = o.reps_given ? 1 : o.quick ? 1 : 5;
  for (SceneKind kind : {SceneKind::chain, SceneKind::cloth}) {
    for (const std::int64_t n : sizes(o)) {  // the contenders at one N run one after another
      for (const char* key : timed_steppers()) {
        auto* b = benchmark::RegisterBenchmark(
            fmt::format("{}/{}", scene_name(kind), key).c_str(),
            [kind, k = std::string(key)](benchmark::State& st) { bm_step(st, kind, k); });
        b->Arg(n)->Unit(benchmark::kMicrosecond)->UseRealTime();
        if (!o.min_time_given) b->MinTime(o.quick ? 0.02 : 0.1);
        if (!o.reps_given && reps > 1) b->Repetitions(reps)->ReportAggregatesOnly(true);
      }
    }
  }
}

/// Keeps the median real time per step and the bodies of every benchmark, keyed by its name
/// without the aggregate suffix: "<scene>/<stepper>/<N>".
class Collector : public benchmark::ConsoleReporter {
 public:
  // Colours only on a terminal: reproduce.sh keeps the console output as docs/perf/coupled.log.
  Collector() : ConsoleReporter(isatty(fileno(stdout)) ? OO_ColorTabular : OO_Tabular) {}
  std::map<std::string, Timing> timings;
  int repetitions = 1;
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (!fixstep::bench::median_or_single(r)) continue;
      repetitions = std::max(repetitions, int(r.repetitions));
      const double ns =
          r.GetAdjustedRealTime() * (r.time_unit == benchmark::kMicrosecond ? 1e3 : 1.0);
      const auto it = r.counters.find("bodies");
      if (it == r.counters.end()) continue;
      timings[r.run_name.function_name + "/" + r.run_name.args] = {ns / it->second.value,
                                                                   it->second.value};
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  std::vector<char*> args;
  for (int a = 0; a < argc; ++a) {
    const std::string_view arg = argv[a];
    if (arg == "--quick")
      o.quick = true;
    else if (arg == "--verify-only")
      o.verify_only = true;
    else if (arg.starts_with("--report="))
      o.report = std::string(arg.substr(9));
    else if (arg == "--report" && a + 1 < argc)
      o.report = argv[++a];
    else {
      o.min_time_given = o.min_time_given || arg.starts_with("--benchmark_min_time");
      o.reps_given = o.reps_given || arg.starts_with("--benchmark_repetitions");
      args.push_back(argv[a]);
    }
  }
  try {
    if (run_checks() != 0) return 1;
    if (o.verify_only) return 0;

    Results res{.sizes = sizes(o), .duration = duration};
    std::printf("measuring accuracy (chain, N = 10^2 and 10^3, dt = 1/30 ... 1/480 s, %g s)...\n",
                duration);
    res.accuracy = accuracy_study(res.reference_method);

    int bargc = static_cast<int>(args.size());
    benchmark::Initialize(&bargc, args.data());
    if (benchmark::ReportUnrecognizedArguments(bargc, args.data())) return 2;
    register_all(o);
    Collector collector;
    benchmark::RunSpecifiedBenchmarks(&collector);
    benchmark::Shutdown();
    res.timings = collector.timings;
    res.repetitions = collector.repetitions;

    const std::string md = report_markdown(res);
    std::fputs(md.c_str(), stdout);
    if (o.report) {
      prepare_output_dir(*o.report);
      write_file_atomic(*o.report + "/coupled.md", md);
      const std::string png = *o.report + "/coupled_work_precision.png";
      if (write_plot(res, png))
        std::printf("wrote %s/coupled.md and %s\n", o.report->c_str(), png.c_str());
      else
        std::printf("wrote %s/coupled.md (no plot: the N = 1000 chain timings were not run)\n",
                    o.report->c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_coupled: %s\n", e.what());
    return 1;
  }
  return 0;
}
