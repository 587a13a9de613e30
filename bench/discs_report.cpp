// bench_discs' steppers by key and its report: the markdown of docs/perf/discs.md (cost per
// body-step, overlaps, energy, fixstep's contact statistics, Box2D's broadphase share, targets;
// the tables and targets against Box2D v3 in discs_report_box2d3.cpp).
#include "discs_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "discs.hpp"
#include "machine_probe.hpp"
#include "median.hpp"

namespace discs {

using namespace report;

namespace {
// The fixstep keys first (the contact statistics' table takes the first 4); Box2D v3's last,
// those of the releases built.
std::vector<const char*> make_keys() {
  std::vector<const char*> k = {"fixstep_f64_t1",   "fixstep_f64_t2",
                                "fixstep_f32_t1",   "fixstep_f64_off",
                                "fixstep_i8_t1",    "fixstep_i8_t2",
                                "fixstep_roll_t1",  "fixstep_roll_t2",
                                "fixstep_sleep_t1", "fixstep_sleep_t2",
                                "chipmunk_hash",    "chipmunk_tree",
                                "chipmunk_hasty2",  "box2d"};
  if (box2d3_built(Box2d3Release::v3_1)) k.insert(k.end(), {"box2d3_w1", "box2d3_w2"});
  if (box2d3_built(Box2d3Release::v3_2)) {
    k.insert(k.end(), {"box2d32_w1", "box2d32_w2", "box2d32_sleep_w1", "box2d32_sleep_w2"});
  }
  return k;
}
const std::vector<const char*> key_list = make_keys();
const std::span<const char* const> keys(key_list);
constexpr SceneKind all_scenes[] = {SceneKind::pile, SceneKind::gas, SceneKind::pile_large,
                                    SceneKind::pile_settled};
constexpr SceneKind main_scenes[] = {SceneKind::pile, SceneKind::gas};
/// The scenes with cost and quality tables: every scene, and the asleep pile with a ball.
constexpr SceneKind table_scenes[] = {SceneKind::pile, SceneKind::gas, SceneKind::pile_large,
                                      SceneKind::pile_settled, SceneKind::pile_ball};
}  // namespace

std::span<const char* const> stepper_keys() {
  return keys;
}

std::string stepper_label(const std::string& key) {
  if (key == "fixstep_f64_t1") return "fixstep f64, 1 thread";
  if (key == "fixstep_f64_t2") return "fixstep f64, 2 threads";
  if (key == "fixstep_f32_t1") return "fixstep f32, 1 thread";
  if (key == "fixstep_f64_off") return "fixstep f64, contacts off (walls only)";
  if (key == "fixstep_i8_t1") return "fixstep f64, 8/3 iterations, 1 thread";
  if (key == "fixstep_i8_t2") return "fixstep f64, 8/3 iterations, 2 threads";
  if (key == "fixstep_roll_t1") return "fixstep f64, rolling discs, 1 thread";
  if (key == "fixstep_roll_t2") return "fixstep f64, rolling discs, 2 threads";
  if (key == "fixstep_sleep_t1") return "fixstep f64, sleeping islands, 1 thread";
  if (key == "fixstep_sleep_t2") return "fixstep f64, sleeping islands, 2 threads";
  const std::string cp = fmt::format("Chipmunk2D {} (f64)", chipmunk_version());
  if (key == "chipmunk_hash") return cp + ", spatial hash";
  if (key == "chipmunk_tree") return cp + ", bounding-box tree";
  if (key == "chipmunk_hasty2") return cp + ", cpHastySpace 2 threads";
  if (key == "box2d") return fmt::format("Box2D {} (f32)", box2d_version());
  for (const Box2d3Release r : box2d3_releases) {
    const std::string k = box2d3_key(r);
    if (key == k + "_w1") return fmt::format("Box2D {} (f32), 1 worker", box2d3_version(r));
    if (key == k + "_w2") return fmt::format("Box2D {} (f32), 2 workers", box2d3_version(r));
    if (key == k + "_sleep_w1") {
      return fmt::format("Box2D {} (f32), sleeping on, 1 worker", box2d3_version(r));
    }
    if (key == k + "_sleep_w2") {
      return fmt::format("Box2D {} (f32), sleeping on, 2 workers", box2d3_version(r));
    }
  }
  return key;
}

std::unique_ptr<Stepper> make_stepper(const std::string& key, const Scene& s) {
  if (key == "fixstep_f64_t1") return make_fixstep(s, false, 1, true);
  if (key == "fixstep_f64_t2") return make_fixstep(s, false, 2, true);
  if (key == "fixstep_f32_t1") return make_fixstep(s, true, 1, true);
  if (key == "fixstep_f64_off") return make_fixstep(s, false, 1, false);
  if (key == "fixstep_i8_t1") return make_fixstep(s, false, 1, true, true);
  if (key == "fixstep_i8_t2") return make_fixstep(s, false, 2, true, true);
  if (key == "fixstep_roll_t1") return make_fixstep(s, false, 1, true, false, true);
  if (key == "fixstep_roll_t2") return make_fixstep(s, false, 2, true, false, true);
  if (key == "fixstep_sleep_t1") return make_fixstep(s, false, 1, true, false, false, true);
  if (key == "fixstep_sleep_t2") return make_fixstep(s, false, 2, true, false, false, true);
  if (key == "chipmunk_hash") return make_chipmunk(s, ChipmunkIndex::hash);
  if (key == "chipmunk_tree") return make_chipmunk(s, ChipmunkIndex::tree);
  if (key == "chipmunk_hasty2") return make_chipmunk(s, ChipmunkIndex::hasty);
  if (key == "box2d") return make_box2d(s);
  for (const Box2d3Release r : box2d3_releases) {
    const std::string k = box2d3_key(r);
    if (key == k + "_w1" && box2d3_built(r)) return make_box2d3(s, 1, r);
    if (key == k + "_w2" && box2d3_built(r)) return make_box2d3(s, 2, r);
    if (key == k + "_sleep_w1" && box2d3_built(r)) return make_box2d3(s, 1, r, true);
    if (key == k + "_sleep_w2" && box2d3_built(r)) return make_box2d3(s, 2, r, true);
  }
  throw std::invalid_argument("no stepper " + key);
}

// The helpers discs_report_box2d3.cpp shares (discs_report.hpp).
namespace report {

std::string size_text(std::int64_t n) {
  const int e = int(std::lround(std::log10(double(n))));
  return std::llround(std::pow(10.0, e)) == n ? fmt::format("10^{}", e) : fmt::format("{}", n);
}

std::string num(double v, const char* f) {
  return std::isnan(v) ? "–" : fmt::format(fmt::runtime(f), v);
}

std::string repetitions_text(const Results& r) {
  const auto reps = [](int k) {
    return k == 1 ? std::string("1 round") : fmt::format("{} interleaved rounds", k);
  };
  const bool largest = std::find(r.sizes.begin(), r.sizes.end(), 100'000) != r.sizes.end();
  if (!largest || r.repetitions_largest == r.repetitions) return reps(r.repetitions);
  return fmt::format("{} ({} at N = 10^5)", reps(r.repetitions), r.repetitions_largest);
}

std::string verdict(bool measured, bool ok) {
  return !measured ? "not measured" : ok ? "yes" : "**no**";
}

}  // namespace report

namespace {

std::string title(SceneKind s) {
  switch (s) {
    case SceneKind::pile:
      return fmt::format("Pile, ticks {}–{} (r = {} m)", pile_warmup + 1, pile_warmup + 20,
                         small_radius);
    case SceneKind::gas:
      return fmt::format("Elastic gas (r = {} m)", small_radius);
    case SceneKind::pile_settled:
      return fmt::format("Settled pile, ticks {}–{} (r = {} m)", pile_settled_warmup + 1,
                         pile_settled_warmup + 20, small_radius);
    case SceneKind::pile_ball:
      return fmt::format("Settled pile asleep and a ball flying above it, ticks {}–{} (r = {} m)",
                         pile_settled_warmup + 1, pile_settled_warmup + 20, small_radius);
    case SceneKind::pile_large:
      break;
  }
  return fmt::format("Settled pile of large discs (r = {} m)", large_radius);
}

std::string header(const Results& r, std::string& rule) {
  std::string head = "| stepper |";
  rule = "|---|";
  for (auto n : r.sizes) head += fmt::format(" N = {} |", size_text(n)), rule += "---|";
  return head;
}

/// One table with a row per stepper and a column per N, of cell(case) where the case ran.
void table(const View& v, SceneKind s, const Line& line,
           const std::function<std::string(const CaseResult&)>& cell,
           std::span<const char* const> rows = keys) {
  std::string rule;
  line(header(v.r, rule)), line(rule);
  for (const char* key : rows) {
    std::string row = fmt::format("| {} |", stepper_label(key));
    bool any = false;
    for (auto n : v.r.sizes) {
      const CaseResult* c = v.at(s, key, n);
      any = any || c;
      row += fmt::format(" {} |", c ? cell(*c) : "–");
    }
    if (any) line(row);
  }
}

void cost_tables(const View& v, const Line& line) {
  for (SceneKind s : table_scenes) {
    line(fmt::format("\n#### {}: ns per body-step (time of one step / discs), median of {}\n",
                     title(s), repetitions_text(v.r)));
    table(v, s, line, [](const CaseResult& c) { return num(c.ns_per_body_step); });
  }
  line("\n#### Speed ratios, measured side by side in this run (time of the other / fixstep's)\n");
  std::string rule;
  const std::string head = header(v.r, rule);
  line("| scene |" + head.substr(1)), line("|---" + rule);
  // Each peer against fixstep on as many threads (Box2D v3's 2 workers against 2 threads).
  const std::pair<const char*, const char*> peers[] = {
      {"chipmunk_hash", "fixstep_f64_t1"},   {"chipmunk_tree", "fixstep_f64_t1"},
      {"chipmunk_hasty2", "fixstep_f64_t1"}, {"box2d", "fixstep_f64_t1"},
      {"box2d3_w1", "fixstep_f64_t1"},       {"box2d3_w2", "fixstep_f64_t2"},
      {"box2d32_w1", "fixstep_f64_t1"},      {"box2d32_w2", "fixstep_f64_t2"}};
  for (SceneKind s : all_scenes) {
    for (const auto& [p, f] : peers) {
      if (!std::ranges::count(keys, std::string_view(p))) continue;
      std::string row =
          fmt::format("| {} | {} / {} |", scene_name(s), stepper_label(p),
                      f == std::string_view("fixstep_f64_t1") ? "fixstep f64 (1 thread)"
                                                              : "fixstep f64 (2 threads)");
      for (auto n : v.r.sizes)
        row += fmt::format(" {} |", num(v.ns(s, p, n) / v.ns(s, f, n), "{:.2f}"));
      line(row);
    }
    std::string row = fmt::format("| {} | fixstep f64: 1 thread / 2 threads |", scene_name(s));
    for (auto n : v.r.sizes) {
      row += fmt::format(
          " {} |", num(v.ns(s, "fixstep_f64_t1", n) / v.ns(s, "fixstep_f64_t2", n), "{:.2f}"));
    }
    line(row);
  }
}

void quality_tables(const View& v, const Line& line) {
  for (SceneKind s : table_scenes) {
    line(fmt::format(
        "\n#### {}: deepest overlap after the timed steps, disc-disc / disc-wall, as a fraction "
        "of r; {} (ticks stepped in brackets)\n",
        title(s), s == SceneKind::gas ? "kinetic energy / at tick 0" : "rms speed (m/s)"));
    table(v, s, line, [](const CaseResult& c) {
      return fmt::format("{} / {}; {} ({})", num(c.disc_overlap), num(c.wall_overlap),
                         num(c.kinetic_ratio, "{:.4g}"), num(c.ticks, "{:.0f}"));
    });
  }
  line(
      "\n#### fixstep's own contact statistics (World::contact_stats(), last tick): broadphase "
      "candidate pairs per disc / touching pairs per disc / impacts per disc / its own deepest "
      "overlap over r; threads used in the last tick (World::threads_used()). fixstep's split "
      "of a tick's time (World::profile(): broadphase, impacts, resting solver, events) is "
      "printed every 10 ticks by `bench_discs --trace SCENE KEY N TICKS`.\n");
  for (SceneKind s : all_scenes) {
    line(fmt::format("\n{}:\n", title(s)));
    table(
        v, s, line,
        [](const CaseResult& c) {
          return fmt::format("{} / {} / {} / {}; {}", num(c.stats.candidate_pairs / c.bodies),
                             num(c.stats.touching / c.bodies), num(c.stats.impacts / c.bodies),
                             num(c.stats.self_overlap), c.stats.threads);
        },
        keys.first(4));
  }
  line(
      "\n#### Box2D's own split of a step (b2Profile, summed over every step of the case; v3: "
      "its `pairs` as the broadphase, `collide` as the narrow phase)\n");
  std::string rule;
  const std::string head = header(v.r, rule);
  line("| scene |" + head.substr(head.find('|', 1) + 1)), line(rule);
  for (SceneKind s : all_scenes) {
    for (const char* key : {"box2d", "box2d3_w1", "box2d3_w2", "box2d32_w1", "box2d32_w2"}) {
      if (!std::ranges::count(keys, std::string_view(key))) continue;
      std::string row = fmt::format("| {}, {}: broadphase / narrow phase, share of the step |",
                                    scene_name(s), stepper_label(key));
      for (auto n : v.r.sizes) {
        const CaseResult* c = v.at(s, key, n);
        row += fmt::format(" {} |",
                           c ? fmt::format("{} / {}", num(c->stats.broadphase_share, "{:.2f}"),
                                           num(c->stats.collide_share, "{:.2f}"))
                             : "–");
      }
      line(row);
    }
  }
}

/// The targets for the peers: ≥ 5× faster than both at N = 10⁴ with no deeper overlap.
void peer_targets(const View& v, const Line& line) {
  constexpr std::int64_t n = 10'000;
  for (SceneKind s : all_scenes) {
    const CaseResult* f = v.at(s, "fixstep_f64_t1", n);
    for (const char* peer : {"chipmunk", "box2d"}) {
      const CaseResult* p = nullptr;  // Chipmunk: its faster one-thread index
      for (const char* key : {"chipmunk_hash", "chipmunk_tree", "box2d"}) {
        const CaseResult* c = v.at(s, key, n);
        if (!c || !std::string(key).starts_with(peer)) continue;
        if (!p || c->ns_per_body_step < p->ns_per_body_step) p = c;
      }
      const bool measured = f && p;
      const double ratio = measured ? p->ns_per_body_step / f->ns_per_body_step : nan;
      const bool deeper = measured && f->disc_overlap > p->disc_overlap;
      line(fmt::format(
          "| {}, N = 10^4: fixstep f64 (1 thread) ≥ 5× faster per body-step than {}{}, with no "
          "deeper overlap | {}× (overlap / r: fixstep {}, peer {}) | {} |",
          scene_name(s), peer == std::string("box2d") ? "Box2D" : "Chipmunk2D",
          peer == std::string("box2d") ? "" : " (its faster index)", num(ratio, "{:.2f}"),
          measured ? num(f->disc_overlap) : "–", measured ? num(p->disc_overlap) : "–",
          verdict(measured, ratio >= 5.0 && !deeper)));
    }
  }
}

/// The cost per disc from 10³ to 10⁵: from the sizes timed in turn where they were (the
/// verdict's), and from the main run's groups, minutes apart.
void cost_per_disc_target(const View& v, const Line& line, SceneKind s) {
  double lo = INFINITY, hi = 0.0;
  for (auto n : v.r.sizes) {
    const double ns = v.ns(s, "fixstep_f64_t1", n);
    if (!std::isnan(ns)) lo = std::min(lo, ns), hi = std::max(hi, ns);
  }
  const bool grouped = v.r.sizes.size() == 3 && hi > 0.0;
  const std::string from_groups =
      grouped ? fmt::format("{:.2f}× from the main run's groups (highest / lowest)", hi / lo)
              : std::string("–");
  const auto it = v.r.scaling.find(s);
  if (it == v.r.scaling.end() || it->second.small.empty()) {
    line(fmt::format(
        "| {}: fixstep f64's cost per disc within 1.5× from N = 10^3 to 10^5 | {} | {} |",
        scene_name(s), from_groups, verdict(grouped, hi / lo <= 1.5)));
    return;
  }
  const Scaling& c = it->second;
  const double q = c.ratio();
  line(fmt::format(
      "| {}: fixstep f64's cost per disc within 1.5× from N = 10^3 to 10^5 | {:.2f}× with the "
      "sizes in turn (median of {} rounds' 10^5 / 10^3; {:.0f} and {:.0f} ns per body-step); "
      "{} | {} |",
      scene_name(s), q, c.small.size(), fixstep::bench::median(c.small),
      fixstep::bench::median(c.large), from_groups, verdict(true, q <= 1.5)));
}

void scaling_targets(const View& v, const Line& line) {
  for (SceneKind s : main_scenes) cost_per_disc_target(v, line, s);
  for (SceneKind s : main_scenes) {
    const double q = v.ns(s, "fixstep_f64_t1", 100'000) / v.ns(s, "fixstep_f64_t2", 100'000);
    line(fmt::format(
        "| {}: ≥ 1.5× from the second core at N = 10^5 (fixstep f64, 1 thread / 2 threads) | {} | "
        "{} |",
        scene_name(s), std::isnan(q) ? "–" : fmt::format("{:.2f}×", q),
        verdict(!std::isnan(q), q >= 1.5)));
  }
  for (SceneKind s : {SceneKind::pile, SceneKind::pile_large}) {
    for (auto n : v.r.sizes) {
      const CaseResult* f = v.at(s, "fixstep_f64_t1", n);
      if (!f) continue;
      line(fmt::format(
          "| {}, N = {}: fixstep's deepest overlap < 1 % of the radius (point 6's test target, "
          "here on the timed pile) | {} | {} |",
          scene_name(s), size_text(n), num(f->disc_overlap),
          verdict(true, f->disc_overlap < 0.01)));
    }
  }
}

/// The sleeping target: a settled pile asleep costs at most 5 % of it awake.
void sleep_targets(const View& v, const Line& line) {
  constexpr std::int64_t n4 = 10'000;
  for (int threads : {1, 2}) {
    const std::string awake = fmt::format("fixstep_f64_t{}", threads);
    const std::string asleep = fmt::format("fixstep_sleep_t{}", threads);
    const double q =
        v.ns(SceneKind::pile_settled, asleep, n4) / v.ns(SceneKind::pile_settled, awake, n4);
    line(fmt::format(
        "| settled pile (ticks {}–{}), N = 10^4, {} thread{}: asleep (ContactSettings::sleep) "
        "≤ 5 % of its awake cost per body-step | {} ({} against {} ns) | {} |",
        pile_settled_warmup + 1, pile_settled_warmup + 20, threads, threads == 1 ? "" : "s",
        num(100.0 * q, "{:.1f} %"), num(v.ns(SceneKind::pile_settled, asleep, n4)),
        num(v.ns(SceneKind::pile_settled, awake, n4)), verdict(!std::isnan(q), q <= 0.05)));
    // Sleep that costs nothing: ≤ 0.5 ns a body-step asleep, and ≤ 10× Box2D v3.2's asleep.
    const double ns = v.ns(SceneKind::pile_settled, asleep, n4);
    line(fmt::format(
        "| settled pile asleep, N = 10^4, {} thread{}: ≤ 0.5 ns per body-step | {} ns | {} |",
        threads, threads == 1 ? "" : "s", num(ns), verdict(!std::isnan(ns), ns <= 0.5)));
    const double peer =
        v.ns(SceneKind::pile_settled, fmt::format("box2d32_sleep_w{}", threads), n4);
    line(fmt::format(
        "| settled pile asleep, N = 10^4, {0} thread{1}: ≤ 10× Box2D v3.2's asleep cost ({0} "
        "worker{1}) | {2}× ({3} against {4} ns) | {5} |",
        threads, threads == 1 ? "" : "s", num(ns / peer, "{:.1f}"), num(ns), num(peer),
        verdict(!std::isnan(ns / peer), ns / peer <= 10.0)));
    // A world mostly asleep costs a small constant plus its awake bodies: the same targets
    // with one ball awake above the asleep pile (N = 10^4 + 1 bodies).
    const double ball = v.ns(SceneKind::pile_ball, asleep, n4);
    const double ball_peer =
        v.ns(SceneKind::pile_ball, fmt::format("box2d32_sleep_w{}", threads), n4);
    line(fmt::format(
        "| settled pile asleep and one ball awake above it, N = 10^4, {} thread{}: ≤ 0.5 ns per "
        "body-step | {} ns | {} |",
        threads, threads == 1 ? "" : "s", num(ball), verdict(!std::isnan(ball), ball <= 0.5)));
    line(fmt::format(
        "| settled pile asleep and one ball awake above it, N = 10^4, {0} thread{1}: ≤ 10× Box2D "
        "v3.2's cost ({0} worker{1}) | {2}× ({3} against {4} ns) | {5} |",
        threads, threads == 1 ? "" : "s", num(ball / ball_peer, "{:.1f}"), num(ball),
        num(ball_peer), verdict(!std::isnan(ball / ball_peer), ball / ball_peer <= 10.0)));
  }
}

}  // namespace

std::string targets_markdown(const Results& r) {
  const View v{r};
  std::string out;
  const Line line = [&out](const std::string& s) { out += s + "\n"; };
  line("\n#### Targets\n");
  line("| target | measured | met |");
  line("|---|---|---|");
  peer_targets(v, line);
  scaling_targets(v, line);
  box2d3_targets(v, line);
  box2d32_targets(v, line);
  sleep_targets(v, line);
  std::string costs;
  for (auto n : r.sizes) {
    const double q =
        v.ns(SceneKind::gas, "fixstep_f64_t1", n) / v.ns(SceneKind::gas, "fixstep_f64_off", n);
    costs +=
        fmt::format("{}N = {}: {}", costs.empty() ? "" : ", ", size_text(n), num(q, "{:.2f}×"));
  }
  line(fmt::format(
      "\nWhat the contacts cost fixstep on the gas (time with contacts / the same world without "
      "them): {}. Worlds without contacts at today's speed: measured before/after by "
      "bench_throughput (engine rows), bench_coupled (fixstep rows) and the contacts-off rows "
      "above (docs/PERFORMANCE.md, section 7).",
      costs));
  return out;
}

std::string report_markdown(const Results& r) {
  const View v{r};
  std::string out;
  const Line line = [&out](const std::string& s) { out += s + "\n"; };
  line(fmt::format(
      "Load average (1 min) {:.2f} at the start of the timed run, {:.2f} at its end (the "
      "benchmark itself adds about 1). dt = 1/60 s; r = {} m (pile_large: {} m), m = {} kg; "
      "Chipmunk: {} "
      "iterations, collision slop {} m; Box2D {}: {} velocity / {} position iterations, linear "
      "slop {:.3g} m{}.{}",
      r.load_start, r.load_end, small_radius, large_radius, mass, chipmunk_iterations,
      chipmunk_slop, box2d_version(), box2d_velocity_iterations, box2d_position_iterations,
      box2d_linear_slop(), box2d3_summary(),
      fixstep::bench::round_trip_sentence(r.round_trip_start, r.round_trip_end)));
  box2d3_table(v, line);
  cost_tables(v, line);
  quality_tables(v, line);
  return out + targets_markdown(r);
}

}  // namespace discs
