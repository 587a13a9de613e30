// bench_discs' report on Box2D v3 (discs_report.hpp): the table of fixstep beside Box2D v3.1.1
// and v3.2, the report's line on the releases built, and issue 33's targets against v3.1.1.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <string>

#include "discs.hpp"
#include "discs_report.hpp"

namespace discs::report {

void box2d3_table(const View& v, const Line& line) {
  line(fmt::format(
      "\n#### fixstep against Box2D {}{}: ns per body-step, median of {}; deepest disc-disc "
      "overlap / r after the timed steps (fixstep f64 1 thread · Box2D v3 1 worker)\n",
      box2d3_version(),
      box2d3_built(Box2d3Release::v3_2) ? " and " + box2d3_version(Box2d3Release::v3_2) : "",
      repetitions_text(v.r)));
  if (!box2d3_built()) {
    line("Box2D v3 not built (bench/box2d3.cmake: its source archive was not found).");
    return;
  }
  const bool v32 = box2d3_built(Box2d3Release::v3_2);
  line(fmt::format(
      "| scene | N | fixstep f64 1 thread | fixstep f64 2 threads | fixstep 8/3 iterations 1 "
      "thread | fixstep 8/3 iterations 2 threads | Box2D {0} 1 worker | Box2D {0} 2 workers |{1} "
      "deepest overlap / r: fixstep · fixstep 8/3 · Box2D {0}{2} |",
      box2d3_version(),
      v32 ? fmt::format(" Box2D {0} 1 worker | Box2D {0} 2 workers |",
                        box2d3_version(Box2d3Release::v3_2))
          : "",
      v32 ? " · Box2D " + box2d3_version(Box2d3Release::v3_2) : ""));
  line(v32 ? "|---|---|---|---|---|---|---|---|---|---|---|"
           : "|---|---|---|---|---|---|---|---|---|");
  // keys: fixstep 1 and 2 threads, 8/3 iterations 1 and 2 (empty: none), the overlaps' keys.
  const auto row = [&](const std::string& label, SceneKind s, std::int64_t n,
                       const std::array<const char*, 4>& fixstep, const char* f_overlap,
                       const char* f8_overlap) {
    const CaseResult* b = v.at(s, "box2d3_w1", n);
    const CaseResult* b32 = v.at(s, "box2d32_w1", n);
    const CaseResult* f = v.at(s, f_overlap, n);
    const CaseResult* f8 = *f8_overlap ? v.at(s, f8_overlap, n) : nullptr;
    if (!b && !f && !b32) return;
    const auto ns = [&](const char* key) { return *key ? num(v.ns(s, key, n)) : "–"; };
    const auto overlap = [](const CaseResult* c) { return c ? num(c->disc_overlap) : "–"; };
    line(fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} |{} {} · {} · {}{} |", label,
                     size_text(n), ns(fixstep[0]), ns(fixstep[1]), ns(fixstep[2]), ns(fixstep[3]),
                     ns("box2d3_w1"), ns("box2d3_w2"),
                     v32 ? fmt::format(" {} | {} |", ns("box2d32_w1"), ns("box2d32_w2")) : "",
                     overlap(f), overlap(f8), overlap(b), v32 ? " · " + overlap(b32) : ""));
  };
  const std::array<const char*, 4> plain = {"fixstep_f64_t1", "fixstep_f64_t2", "fixstep_i8_t1",
                                            "fixstep_i8_t2"};
  for (auto n : v.r.sizes) {
    row(fmt::format("pile, r = {} m", small_radius), SceneKind::pile, n, plain, plain[0], plain[2]);
  }
  for (auto n : v.r.sizes) {
    row(fmt::format("settled pile (ticks {}–{}), r = {} m", pile_settled_warmup + 1,
                    pile_settled_warmup + 20, small_radius),
        SceneKind::pile_settled, n, plain, plain[0], plain[2]);
  }
  for (auto n : v.r.sizes)
    row(fmt::format("pile, r = {} m", large_radius), SceneKind::pile_large, n, plain, plain[0],
        plain[2]);
  for (auto n : v.r.sizes) row("gas", SceneKind::gas, n, plain, plain[0], plain[2]);
  // Box2D's circles rotate: its pile is a pile of rolling discs (the same cases as its pile
  // above), beside fixstep's rolling discs (fixstep_roll_*) on the same pile.
  for (auto n : v.r.sizes) {
    row(fmt::format("pile of rolling discs, r = {} m (fixstep: ContactSettings::rolling)",
                    small_radius),
        SceneKind::pile, n, {"fixstep_roll_t1", "fixstep_roll_t2", "", ""}, "fixstep_roll_t1", "");
  }
}

std::string box2d3_summary() {
  std::string out;
  for (const Box2d3Release r : box2d3_releases) {
    if (!box2d3_built(r)) continue;
    out += fmt::format("; Box2D {}: {} substeps, linear slop {:.3g} m, sleeping off",
                       box2d3_version(r), box2d3_substeps, box2d3_linear_slop(r));
  }
  return out.empty() ? "; Box2D v3 not built" : out;
}

void box2d3_targets(const View& v, const Line& line) {
  if (!box2d3_built()) return;
  constexpr std::int64_t n4 = 10'000;
  for (const SceneKind s : {SceneKind::pile, SceneKind::pile_settled}) {
    for (const bool box2d_iterations : {false, true}) {
      for (int threads : {1, 2}) {
        const std::string f_key =
            fmt::format("fixstep_{}_t{}", box2d_iterations ? "i8" : "f64", threads);
        const std::string b_key = threads == 1 ? "box2d3_w1" : "box2d3_w2";
        const CaseResult* f = v.at(s, f_key, n4);
        const CaseResult* b = v.at(s, b_key, n4);
        const bool measured = f && b;
        const double ratio = measured ? b->ns_per_body_step / f->ns_per_body_step : nan;
        const bool shallow = measured && f->disc_overlap <= b->disc_overlap / 5.0;
        line(fmt::format(
            "| {7}, N = 10^4: fixstep f64{6} ({0} thread{1}) ≥ 2× faster per body-step than "
            "Box2D v3 ({0} worker{1}), at no more than a fifth of its overlap | {2}× (overlap / "
            "r: fixstep {3}, Box2D v3 {4}) | {5} |",
            threads, threads == 1 ? "" : "s", num(ratio, "{:.2f}"),
            measured ? num(f->disc_overlap) : "–", measured ? num(b->disc_overlap) : "–",
            verdict(measured, ratio >= 2.0 && shallow), box2d_iterations ? ", 8/3 iterations" : "",
            s == SceneKind::pile ? "pile" : "settled pile"));
      }
    }
  }
  for (int threads : {1, 2}) {
    const std::string f_key = threads == 1 ? "fixstep_f64_t1" : "fixstep_f64_t2";
    const std::string b_key = threads == 1 ? "box2d3_w1" : "box2d3_w2";
    std::string measured_text;
    bool all = !v.r.sizes.empty(), ok = true;
    for (auto n : v.r.sizes) {
      const double q = v.ns(SceneKind::gas, b_key, n) / v.ns(SceneKind::gas, f_key, n);
      all = all && !std::isnan(q), ok = ok && q >= 3.0;
      measured_text += fmt::format("{}N = {}: {}", measured_text.empty() ? "" : ", ", size_text(n),
                                   num(q, "{:.2f}×"));
    }
    line(fmt::format(
        "| gas, every N: fixstep f64 ({0} thread{1}) ≥ 3× faster per body-step than Box2D v3 "
        "({0} worker{1}) | {2} | {3} |",
        threads, threads == 1 ? "" : "s", measured_text, verdict(all, ok)));
  }
}

/// The targets against Box2D v3.2 (its 1 and 2 workers against fixstep f64 on as many threads):
/// the settling pile ≥ 1.5× at every N at no more than a fifth of its overlap, the settled pile
/// ≥ 2× at 10^4, the gas ≥ 3× at every N.
void box2d32_targets(const View& v, const Line& line) {
  if (!box2d3_built(Box2d3Release::v3_2)) return;
  const std::string peer = "Box2D " + box2d3_version(Box2d3Release::v3_2);
  struct Target {
    SceneKind scene;
    const char* name;
    double ratio;
    bool shallow;  // at no more than a fifth of the peer's overlap
    bool every_n;  // else N = 10^4 only
  };
  const Target targets[] = {{SceneKind::pile, "settling pile (ticks 41–60)", 1.5, true, true},
                            {SceneKind::pile_settled, "settled pile", 2.0, true, false},
                            {SceneKind::gas, "gas", 3.0, false, true}};
  for (const Target& t : targets) {
    for (int threads : {1, 2}) {
      const std::string f_key = fmt::format("fixstep_f64_t{}", threads);
      const std::string b_key = fmt::format("box2d32_w{}", threads);
      std::string measured;
      bool all = true, ok = true;
      for (auto n : v.r.sizes) {
        if (!t.every_n && n != 10'000) continue;
        const CaseResult* f = v.at(t.scene, f_key, n);
        const CaseResult* b = v.at(t.scene, b_key, n);
        if (!f || !b) {
          all = false;
          continue;
        }
        const double q = b->ns_per_body_step / f->ns_per_body_step;
        const bool shallow = !t.shallow || f->disc_overlap <= b->disc_overlap / 5.0;
        ok = ok && q >= t.ratio && shallow;
        measured += fmt::format("{}N = {}: {}{}", measured.empty() ? "" : ", ", size_text(n),
                                num(q, "{:.2f}×"),
                                t.shallow ? fmt::format(" (overlap / r {} against {})",
                                                        num(f->disc_overlap), num(b->disc_overlap))
                                          : "");
      }
      line(fmt::format(
          "| {0}{1}: fixstep f64 ({2} thread{3}) ≥ {4}× faster per body-step than {5} ({2} "
          "worker{3}){6} | {7} | {8} |",
          t.name, t.every_n ? ", every N" : ", N = 10^4", threads, threads == 1 ? "" : "s", t.ratio,
          peer, t.shallow ? ", at no more than a fifth of its overlap" : "",
          measured.empty() ? "–" : measured, verdict(all && !measured.empty(), ok)));
    }
  }
}

}  // namespace discs::report
