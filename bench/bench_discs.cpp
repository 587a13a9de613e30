// Disc contacts against peer engines, in one run (Google Benchmark):
// a pile (ticks 41-60) and an elastic gas of N = 10³, 10⁴, 10⁵ discs of r = 5 cm, and at
// N = 10³, 10⁴ the same pile settled (ticks 361-380) and the pile of 50 cm discs (the peers'
// home scale) (discs.hpp), built by one generator and
// stepped at dt = 1/60 s by
//   fixstep    fixstep::detail::WorldKernel<Real>::step() with WorldSettings::contacts, f64 on 1
//   and 2 threads and
//              f32 on 1 (discs_fixstep.cpp); and, on the gas, the same world without contacts
//              (the discs meet only the walls: a world that asks for no contacts);
//   chipmunk   Chipmunk2D 7 with its spatial hash, its default tree, and (N <= 10⁴)
//              cpHastySpace on 2 threads (discs_chipmunk.cpp);
//   box2d      Box2D 2.4, b2CircleShape, Step(dt, 8, 3) (discs_box2d.cpp);
//   box2d3     Box2D v3.1.1 and v3.2 (where bench/box2d3.cmake built them), b2World_Step(dt, 4)
//              on 1 and 2 workers (discs_box2d3.cpp).
// Every case is built and warmed up untimed, then the same ticks are timed for every engine and
// every N (5 rounds of 4 ticks, the contenders at one N taking their rounds in turn, but for
// the asleep worlds', the median; --benchmark_min_time makes Google Benchmark choose the ticks
// instead); after the last, every engine's deepest overlap and kinetic energy are measured on
// its state the same way. The report (stdout; with --report DIR also DIR/discs.md) gives ns per
// body-step, the overlaps, fixstep's contact statistics, Box2D's broadphase share and the
// targets as ratios measured side by side. After the main run (unless --quick or a filter; or
// with --scaling), fixstep's cost per disc from 10³ to 10⁵ on the pile and the gas is timed
// again with the two sizes in turn (discs_scaling.cpp).
//
//   build/bench/bin/bench_discs --report docs/perf
//   build/bench/bin/bench_discs --quick --benchmark_min_time=0.01   (N = 10³: a smoke run)
//   build/bench/bin/bench_discs --scaling --benchmark_filter=^$  (the cost per disc alone)
//   build/bench/bin/bench_discs --verify-only  (the checks alone; ctest bench_discs_checks)
//   build/bench/bin/bench_discs --trace pile box2d 1000 300  (one case, untimed, every 10 ticks)
//   build/bench/bin/bench_discs --paced gas 10000 120  (one tick a frame at 60 Hz, as a game)
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "discs.hpp"
#include "discs_paced.hpp"
#include "fixstep/capture/capture.hpp"
#include "machine_probe.hpp"
#include "median.hpp"
#include "median_run.hpp"

using namespace discs;
using fixstep::Vec2;
using fixstep::bench::core_round_trip_ns;
using fixstep::bench::load_average;

namespace {

// --- the checks, run before anything is timed (and alone with --verify-only) --------------

int failures = 0;
void check(bool ok, const std::string& what) {
  if (!ok) ++failures, std::fprintf(stderr, "bench_discs: FAILED: %s\n", what.c_str());
}

/// The scenes start with no disc overlapping another or a wall.
void verify_scenes(std::size_t n) {
  for (SceneKind kind : {SceneKind::pile, SceneKind::gas, SceneKind::pile_large}) {
    const Scene s = make_scene(kind, n);
    const Quality q = measure(s, s.position, s.velocity);
    check(s.position.size() == n && q.disc_overlap == 0.0 && q.wall_overlap == 0.0,
          fmt::format("{} N = {}: {} discs, overlap {:.3g} m between discs, {:.3g} m with walls",
                      scene_name(kind), n, s.position.size(), q.disc_overlap, q.wall_overlap));
  }
}

/// The grid finds the deepest overlap all pairs give, on states with many overlaps.
void verify_overlap_grid() {
  for (SceneKind kind : {SceneKind::pile, SceneKind::gas}) {
    Scene s = make_scene(kind, 1500);
    for (Vec2& p : s.position) p.x *= 0.93, p.y *= kind == SceneKind::gas ? 0.3 : 0.97;
    const double grid = measure(s, s.position, s.velocity).disc_overlap;
    const double brute = overlap_brute_force(s.position, s.radius);
    check(grid == brute && grid > 0.0, fmt::format("{} squeezed: grid overlap {} m, all pairs {} m",
                                                   scene_name(kind), grid, brute));
  }
}

/// Every engine starts from the scene's state and keeps its discs finite and their centres in
/// the box, widened by r, for `ticks` ticks (walls, gravity's sign and units as meant; a fast
/// gas disc may sink deeper than r into a wall in an engine without continuous collision).
void verify_engines(std::size_t n, int ticks) {
  std::vector<Vec2> x, v;
  for (SceneKind kind : {SceneKind::pile, SceneKind::gas, SceneKind::pile_large}) {
    const Scene s = make_scene(kind, n);
    for (const char* key : stepper_keys()) {
      const auto p = make_stepper(key, s);
      p->state(x, v);
      double moved = 0.0;  // Box2D holds float: its start differs by rounding
      for (std::size_t j = 0; j < n; ++j) {
        moved =
            std::max({moved, std::abs(x[j].x - s.position[j].x), std::abs(x[j].y - s.position[j].y),
                      std::abs(v[j].x - s.velocity[j].x), std::abs(v[j].y - s.velocity[j].y)});
      }
      check(moved <= 1e-5,
            fmt::format("{} {}: starts {:.3g} from the scene", scene_name(kind), key, moved));
      for (int t = 0; t < ticks; ++t) p->step();
      p->state(x, v);
      const Quality q = measure(s, x, v);
      check(std::isfinite(q.kinetic) && q.wall_overlap < 2.0 * s.radius,
            fmt::format("{} {} after {} ticks: kinetic energy {} J, a disc {:.3g} m into a wall",
                        scene_name(kind), key, ticks, q.kinetic, q.wall_overlap));
    }
  }
}

/// Every engine drops a disc that falls as gravity says and comes to rest on the ground.
void verify_drop() {
  for (const char* key : stepper_keys()) {
    for (const std::string& f : check_drop(key)) check(false, f);
  }
}

/// The report's round-trip probe: a time above zero and under a millisecond where the process
/// may run on two CPUs, NaN (not a hang) where it may run on one, and the affinity as it was.
void verify_round_trip() {
  cpu_set_t before;
  if (sched_getaffinity(0, sizeof before, &before) != 0) return;
  if (CPU_COUNT(&before) >= 2) {
    const double ns = core_round_trip_ns();
    check(ns > 0.0 && ns < 1e6, fmt::format("the cores' round trip is {} ns", ns));
  }
  cpu_set_t one;
  CPU_ZERO(&one);
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (CPU_ISSET(c, &before)) {
      CPU_SET(c, &one);
      break;
    }
  }
  if (sched_setaffinity(0, sizeof one, &one) != 0) return;
  const double alone = core_round_trip_ns();
  sched_setaffinity(0, sizeof before, &before);
  cpu_set_t after;
  check(std::isnan(alone),
        fmt::format("on one CPU the cores' round trip is {} ns, not NaN", alone));
  check(sched_getaffinity(0, sizeof after, &after) == 0 && CPU_EQUAL(&after, &before),
        "the round-trip probe left the process's affinity changed");
}

/// Box2D v3 gives the same state on 1 and 2 workers (it is deterministic across thread counts,
/// so the task system of its 2 workers hands it every piece once).
void verify_box2d3_workers(std::size_t n, int ticks, Box2d3Release r) {
  std::vector<Vec2> x1, v1, x2, v2;
  const std::string key = box2d3_key(r);
  for (SceneKind kind : {SceneKind::pile, SceneKind::gas}) {
    const Scene s = make_scene(kind, n);
    const auto one = make_stepper(key + "_w1", s), two = make_stepper(key + "_w2", s);
    for (int t = 0; t < ticks; ++t) one->step(), two->step();
    one->state(x1, v1), two->state(x2, v2);
    check(x1 == x2 && v1 == v2 && two->stats().threads == 2,
          fmt::format("{}: Box2D {}'s state after {} ticks differs between 1 and 2 workers",
                      scene_name(kind), box2d3_version(r), ticks));
  }
}

int run_checks(bool full) {
  for (std::size_t n : {std::size_t{1000}, std::size_t{10'000}}) verify_scenes(n);
  if (full) verify_scenes(100'000);
  verify_overlap_grid();
  verify_engines(1000, 60);
  verify_drop();
  verify_round_trip();
  std::string v3;
  for (const Box2d3Release r : box2d3_releases) {
    if (box2d3_built(r)) verify_box2d3_workers(1000, 60, r);
    v3 += fmt::format("{}{}", v3.empty() ? "" : "; ",
                      box2d3_built(r) ? fmt::format("Box2D {}'s state is the same on 1 and 2 "
                                                    "workers",
                                                    box2d3_version(r))
                                      : fmt::format("Box2D {}: its source archive was not found, "
                                                    "its checks skipped",
                                                    box2d3_version(r)));
  }
  if (failures == 0) {
    std::printf(
        "checks: the scenes start without overlaps; the overlap grid agrees with all pairs; "
        "every engine starts from the scene and keeps its discs in the box for 60 ticks (N = "
        "10^3); every engine's dropped disc falls ½ g t² and rests on the ground; the cores' "
        "round-trip probe times two CPUs and gives NaN on one; %s\n",
        v3.c_str());
  }
  return failures;
}

// --- benchmarks -----------------------------------------------------------------------------

/// The contenders at one scene and N, each built and warmed up once on its first round, then
/// stepped by its rounds in turn with the others' (a 10⁵-disc world takes seconds to build and
/// warm up, and a settled pile stays settled). Interleaved rounds let a slow span of the
/// machine (on a shared VM: the host's other load, which two threads feel most) fall on every
/// contender alike, not on one case's consecutive repetitions.
struct Live {
  std::unique_ptr<Stepper> stepper;
  std::int64_t ticks = 0;
};

struct Contenders {
  std::string group;  // "<scene>/<N>"
  Scene scene;
  std::map<std::string, Live> live;
};

std::pair<const Scene&, Live&> live(SceneKind kind, const std::string& key, std::size_t n) {
  static Contenders c;
  const std::string group = fmt::format("{}/{}", scene_name(kind), n);
  if (c.group != group) {
    c.live.clear();  // the previous contenders' memory first
    c.scene = make_scene(kind, n);
    c.group = group;
  }
  Live& l = c.live[key];
  if (!l.stepper) {
    l.stepper = make_stepper(key, c.scene);
    for (int t = 0; t < c.scene.warmup; ++t) l.stepper->step();
    l.ticks = c.scene.warmup;
  }
  return {c.scene, l};
}

/// One round of `key`'s ticks; after the last (`last`), its state's overlaps and energy too.
/// Only then: measuring reads every disc, and the next round's first tick would find the caches
/// full of it (an asleep world's tick, a microsecond otherwise, took 20-45).
void bm_step(benchmark::State& st, SceneKind kind, const std::string& key, bool last) {
  const auto [scene, c] = live(kind, key, static_cast<std::size_t>(st.range(0)));
  for (auto _ : st) {
    c.stepper->step();
    benchmark::ClobberMemory();
  }
  c.ticks += static_cast<std::int64_t>(st.iterations());
  const double n = double(scene.position.size()), r = scene.radius;
  st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()) * std::int64_t(n));
  const Stats s = c.stepper->stats();
  st.counters = {{"bodies", n},
                 {"ticks", double(c.ticks)},
                 {"pairs", s.candidate_pairs},
                 {"touching", s.touching},
                 {"impacts", s.impacts},
                 {"self_r", s.self_overlap / r},
                 {"bp", s.broadphase_share},
                 {"narrow", s.collide_share},
                 {"threads", double(s.threads)}};
  if (!last) return;
  std::vector<Vec2> x, v;
  c.stepper->state(x, v);
  const Quality q = measure(scene, x, v);
  const double energy = kind == SceneKind::gas ? q.kinetic / initial_kinetic(scene)
                                               : std::sqrt(2.0 * q.kinetic / (mass * n));
  st.counters["overlap_r"] = q.disc_overlap / r;
  st.counters["wall_r"] = q.wall_overlap / r;
  st.counters["energy"] = energy;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// --trace: one case's overlaps, energy and (fixstep) contact statistics every 10 ticks.
int trace(const std::string& scene, const std::string& key, std::size_t n, int ticks) {
  const SceneKind kind = scene == "pile"           ? SceneKind::pile
                         : scene == "gas"          ? SceneKind::gas
                         : scene == "pile_settled" ? SceneKind::pile_settled
                         : scene == "pile_ball"    ? SceneKind::pile_ball
                                                   : SceneKind::pile_large;
  const Scene s = make_scene(kind, n);
  const auto start = std::chrono::steady_clock::now();
  const auto p = make_stepper(key, s);
  std::vector<Vec2> x, v;
  std::printf("built in %.3f s\n", seconds_since(start));
  auto last = std::chrono::steady_clock::now();
  double phase[4] = {};  // fixstep: broadphase, impacts, resting, the rest (s, summed)
  for (int t = 0; t <= ticks; ++t) {
    if (t % 10 == 0) {
      p->state(x, v);
      const Quality q = measure(s, x, v);
      const Stats st = p->stats();
      std::printf(
          "tick %4d  overlap/r disc %.4f wall %.4f  kinetic %.6g J  pairs %.0f touching %.0f "
          "impacts %.0f self/r %.4f sweeps %d/%d  %.4f s/tick\n",
          t, q.disc_overlap / s.radius, q.wall_overlap / s.radius, q.kinetic, st.candidate_pairs,
          st.touching, st.impacts, st.self_overlap / s.radius, st.velocity_sweeps,
          st.position_sweeps, seconds_since(last) / (t == 0 ? 1 : 10));
      if (t > 0 && phase[0] + phase[1] + phase[2] + phase[3] > 0.0) {
        std::printf("           ms/tick: broadphase %.3f impacts %.3f resting %.3f other %.3f\n",
                    phase[0] * 100, phase[1] * 100, phase[2] * 100, phase[3] * 100);
      }
      std::fill(std::begin(phase), std::end(phase), 0.0);
      last = std::chrono::steady_clock::now();
    }
    if (t < ticks) {
      p->step();
      const Stats st = p->stats();
      const double add[4] = {st.broadphase_s, st.impacts_s, st.resting_s, st.other_s};
      for (int i = 0; i < 4; ++i) phase[i] += std::isnan(add[i]) ? 0.0 : add[i];
    }
  }
  return 0;
}

struct Options {
  bool quick = false, verify_only = false, min_time_given = false, reps_given = false;
  bool filtered = false, scaling = false;  ///< --benchmark_filter given; --scaling given
  std::optional<std::string> report;
  std::vector<std::string> paced;  ///< --paced SCENE N TICKS
};

std::vector<std::int64_t> sizes(const Options& o) {
  if (o.quick) return {1000};
  return {1000, 10'000, 100'000};
}

/// Rounds of a case, each of `ticks_per_round` ticks: every engine and every N times the same
/// ticks (the pile's ticks 41-60, the settled pile's 361-380, the gas's 6-25), so that costs
/// compare like with like (a pile still settling costs more per tick than a settled one). The
/// contenders at one N take their rounds in turn.
int rounds(const Options& o) {
  if (o.reps_given || o.quick) return 1;
  return 5;
}
constexpr int ticks_per_round = 4;

/// Whether `key` steps a world asleep: its rounds run one after another, not in turn with the
/// others'. Its tick takes microseconds, which in turn would measure the caches the other
/// contenders left: the constant an asleep world costs a tick in steady state is the figure.
bool asleep(const std::string& k) {
  return k.find("_sleep") != std::string::npos;
}

/// Whether `key` is timed on `kind`.
bool contends(SceneKind kind, const std::string& k, std::int64_t n) {
  if (k == "fixstep_f64_off" && kind != SceneKind::gas) return false;
  if (k.starts_with("fixstep_i8") && kind == SceneKind::gas) return false;     // nothing rests
  if (k.starts_with("fixstep_roll") && kind != SceneKind::pile) return false;  // the peers' pile
  const bool asleep_only = kind == SceneKind::pile_ball;
  if (asleep(k) ? kind != SceneKind::pile_settled && !asleep_only : asleep_only) return false;
  return k != "chipmunk_hasty2" || n <= 10'000;  // optional; 40+ s at 10^5
}

void register_all(const Options& o) {
  for (SceneKind kind : {SceneKind::pile, SceneKind::gas, SceneKind::pile_large,
                         SceneKind::pile_settled, SceneKind::pile_ball}) {
    for (const std::int64_t n : sizes(o)) {
      if (kind != SceneKind::pile && kind != SceneKind::gas && n > 10'000) continue;
      auto add = [&](const std::string& k, int round) {
        const bool last = round == rounds(o);
        auto* b = benchmark::RegisterBenchmark(
            fmt::format("{}/{}/round:{}", scene_name(kind), k, round).c_str(),
            [kind, k, last](benchmark::State& st) { bm_step(st, kind, k, last); });
        b->Arg(n)->Unit(benchmark::kMicrosecond)->UseRealTime();
        if (!o.min_time_given) b->Iterations(ticks_per_round);
      };
      for (int round = 1; round <= rounds(o); ++round) {
        for (const char* key : stepper_keys()) {
          if (contends(kind, key, n) && !asleep(key)) add(key, round);
        }
      }
      for (const char* key : stepper_keys()) {
        for (int round = 1; round <= rounds(o) && contends(kind, key, n) && asleep(key); ++round) {
          add(key, round);
        }
      }
    }
  }
}

/// Keeps every round of every case, keyed "<scene>/<stepper>/<N>"; results() takes the median
/// time over the rounds and the quality after the last.
class Collector : public benchmark::ConsoleReporter {
 public:
  // Colours only on a terminal: reproduce.sh keeps the console output as docs/perf/discs.log.
  Collector() : ConsoleReporter(isatty(fileno(stdout)) ? OO_ColorTabular : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (!fixstep::bench::median_or_single(r)) continue;
      const auto c = [&r](const char* name) {
        const auto it = r.counters.find(name);
        return it == r.counters.end() ? std::nan("") : it->second.value;
      };
      const double n = c("bodies");
      if (std::isnan(n)) continue;
      const double ns =
          r.GetAdjustedRealTime() * (r.time_unit == benchmark::kMicrosecond ? 1e3 : 1);
      std::string name = r.run_name.function_name;
      name = name.substr(0, name.rfind("/round:"));
      rounds_[name + "/" + r.run_name.args].push_back(
          {.ns_per_body_step = ns / n,
           .bodies = n,
           .ticks = c("ticks"),
           .disc_overlap = c("overlap_r"),
           .wall_overlap = c("wall_r"),
           .kinetic_ratio = c("energy"),
           .stats = {c("pairs"), c("touching"), c("impacts"), c("self_r"), c("bp"), c("narrow"),
                     int(c("threads"))}});
    }
  }
  [[nodiscard]] Results results() const {
    Results res;
    for (const auto& [key, rounds] : rounds_) {
      std::vector<double> ns;
      for (const CaseResult& c : rounds) ns.push_back(c.ns_per_body_step);
      CaseResult last = rounds.back();
      last.ns_per_body_step = fixstep::bench::median(ns);
      res.cases[key] = last;
      const int k = static_cast<int>(rounds.size());
      int& kept = last.bodies >= 100'000 ? res.repetitions_largest : res.repetitions;
      kept = std::max(kept, k);
    }
    return res;
  }

 private:
  std::map<std::string, std::vector<CaseResult>> rounds_;
};

/// --paced SCENE N TICKS: N and TICKS as whole numbers (std::invalid_argument naming the one
/// that is not), TICKS capped at 10⁶; then paced().
int paced_run(const std::vector<std::string>& args) {
  const auto whole = [](const std::string& text, const char* what) {
    std::size_t used = 0;
    long value = -1;
    try {
      value = std::stol(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size() || value < 0) {
      throw std::invalid_argument(
          fmt::format("--paced: {} '{}' is not a whole number", what, text));
    }
    return value;
  };
  const long n = whole(args[1], "N"), ticks = whole(args[2], "TICKS");
  return paced(args[0], static_cast<std::size_t>(n), static_cast<int>(std::min(ticks, 1'000'000L)));
}

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
    else if (arg == "--trace" && a + 4 < argc)
      return trace(argv[a + 1], argv[a + 2], std::stoul(argv[a + 3]), std::stoi(argv[a + 4]));
    else if (arg == "--scaling")
      o.scaling = true;
    else if (arg == "--paced" && a + 3 < argc)
      o.paced = {argv[a + 1], argv[a + 2], argv[a + 3]}, a += 3;
    else {
      o.min_time_given = o.min_time_given || arg.starts_with("--benchmark_min_time");
      o.reps_given = o.reps_given || arg.starts_with("--benchmark_repetitions");
      o.filtered = o.filtered || arg.starts_with("--benchmark_filter");
      args.push_back(argv[a]);
    }
  }
  try {
    if (!o.paced.empty()) return paced_run(o.paced);
    if (run_checks(!o.quick && !o.verify_only) != 0) return 1;
    if (o.verify_only) return 0;

    const double load_start = load_average(), round_trip_start = core_round_trip_ns();
    int bargc = static_cast<int>(args.size());
    benchmark::Initialize(&bargc, args.data());
    if (benchmark::ReportUnrecognizedArguments(bargc, args.data())) return 2;
    register_all(o);
    Collector collector;
    benchmark::RunSpecifiedBenchmarks(&collector);
    benchmark::Shutdown();
    Results res = collector.results();
    if (o.scaling || (!o.quick && !o.filtered)) {
      for (SceneKind kind : {SceneKind::pile, SceneKind::gas}) {
        res.scaling[kind] = scaling(kind, rounds(o), ticks_per_round);
      }
    }
    res.sizes = sizes(o);
    res.load_start = load_start, res.load_end = load_average();
    res.round_trip_start = round_trip_start, res.round_trip_end = core_round_trip_ns();

    const std::string md = report_markdown(res);
    std::fputs(md.c_str(), stdout);
    if (o.report) {
      fixstep::prepare_output_dir(*o.report);
      fixstep::write_file_atomic(*o.report + "/discs.md", md);
      std::printf("wrote %s/discs.md\n", o.report->c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_discs: %s\n", e.what());
    return 1;
  }
  return 0;
}
