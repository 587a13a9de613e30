// bench_boxes' steppers by key and its report: the markdown of docs/perf/boxes.md (cost per
// body-step and deepest overlaps of the pyramid and the box pile, for fixstep and Box2D v3).
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "boxes.hpp"
#include "machine_probe.hpp"

namespace boxes {

using discs::Box2d3Release;

std::vector<std::string> box_stepper_keys() {
  return discs::shape_stepper_keys();
}

std::string box_stepper_label(const std::string& key) {
  return discs::shape_stepper_label(key);
}

std::unique_ptr<BoxStepper> make_box_stepper(const std::string& key, const BoxScene& s) {
  if (key == "fixstep_t1") return make_fixstep_boxes(s, 1);
  if (key == "fixstep_t2") return make_fixstep_boxes(s, 2);
  for (const Box2d3Release r : discs::box2d3_releases) {
    const std::string k = discs::box2d3_key(r);
    if (key == k + "_w1" && discs::box2d3_built(r)) return make_box2d3_boxes(s, 1, r);
    if (key == k + "_w2" && discs::box2d3_built(r)) return make_box2d3_boxes(s, 2, r);
  }
  throw std::invalid_argument("no box stepper " + key);
}

namespace {

std::string size_text(std::int64_t n) {
  const int e = int(std::lround(std::log10(double(n))));
  return std::llround(std::pow(10.0, e)) == n ? fmt::format("10^{}", e) : fmt::format("{}", n);
}

std::string num(double v, const char* f = "{:.3g}") {
  return std::isnan(v) ? "–" : fmt::format(fmt::runtime(f), v);
}

/// The scene's cases: the pyramid's and the tower's one size, the pile's sizes.
std::vector<std::pair<BoxSceneKind, std::int64_t>> scene_cases(const BoxResults& r) {
  std::vector<std::pair<BoxSceneKind, std::int64_t>> out = {
      {BoxSceneKind::pyramid, std::int64_t(make_pyramid().start.size())},
      {BoxSceneKind::tower, std::int64_t(make_tower().start.size())}};
  for (const std::int64_t n : r.pile_sizes) out.emplace_back(BoxSceneKind::box_pile, n);
  return out;
}

std::string scene_text(BoxSceneKind k) {
  if (k == BoxSceneKind::tower) {
    return fmt::format("tower of {} boxes, ticks {}–{}", tower_boxes, pyramid_warmup + 1,
                       pyramid_warmup + 20);
  }
  return k == BoxSceneKind::pyramid
             ? fmt::format("pyramid of {} rows, ticks {}–{}", pyramid_rows, pyramid_warmup + 1,
                           pyramid_warmup + 20)
             : fmt::format("box pile, ticks {}–{}", pile_warmup + 1, pile_warmup + 20);
}

}  // namespace

std::string box_report_markdown(const BoxResults& r) {
  std::string out;
  const auto line = [&out](const std::string& s) { out += s + "\n"; };
  std::string releases;
  for (const Box2d3Release v : discs::box2d3_releases) {
    releases += fmt::format("; Box2D {}{}", discs::box2d3_version(v),
                            discs::box2d3_built(v)
                                ? fmt::format(": {} substeps, sleeping off", discs::box2d3_substeps)
                                : "");
  }
  line(fmt::format(
      "Load average (1 min) {:.2f} at the start of the timed run, {:.2f} at its end. dt = 1/60 "
      "s; boxes of 1 m, 1 kg, μ = {}, e = {}, gravity {} m/s²{}.{}",
      r.load_start, r.load_end, friction, restitution, gravity, releases,
      fixstep::bench::round_trip_sentence(r.round_trip_start, r.round_trip_end)));
  if (r.fixstep_problem) {
    line(fmt::format("\nfixstep: shapes not yet supported ({}); its rows are left out.",
                     *r.fixstep_problem));
  }
  line(
      fmt::format("\n#### Boxes: ns per body-step (time of one step / dynamic boxes), median of {} "
                  "repetition{}; deepest overlap after the timed steps, m\n",
                  r.repetitions, r.repetitions == 1 ? "" : "s"));
  line(
      "Box-box: the separating axis theorem on every engine's poses (the same code for every "
      "engine); ground and walls: the deepest corner past them; own: the engine's deepest "
      "-separation over its contact manifolds (Box2D's as of its last collide phase, fixstep's "
      "after its solve); pyramid and tower: how far the top box has dropped, pile: the boxes' mean "
      "height.\n");
  line(
      "| scene | N | stepper | ns per body-step | box-box overlap | into ground and walls | own "
      "(manifolds) | pyramid, tower: top's drop, pile: mean height (m) |");
  line("|---|---|---|---|---|---|---|---|");
  for (const auto& [kind, n] : scene_cases(r)) {
    for (const std::string& key : box_stepper_keys()) {
      const auto it = r.cases.find(fmt::format("{}/{}/{}", box_scene_name(kind), key, n));
      if (it == r.cases.end()) continue;
      const BoxCase& c = it->second;
      line(fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} |", scene_text(kind), size_text(n),
                       box_stepper_label(key), num(c.ns_per_body_step), num(c.box_overlap),
                       num(c.static_overlap), num(c.own_overlap), num(c.height)));
    }
  }
  line("\n#### Speed ratios, measured side by side in this run (time of the first / the second)\n");
  line("| scene | N | ratio | value |");
  line("|---|---|---|---|");
  const std::pair<const char*, const char*> pairs[] = {
      {"box2d3_w1", "box2d32_w1"}, {"box2d3_w2", "box2d32_w2"},  {"box2d32_w1", "box2d32_w2"},
      {"box2d3_w1", "fixstep_t1"}, {"box2d32_w1", "fixstep_t1"}, {"box2d32_w2", "fixstep_t2"},
      {"fixstep_t1", "fixstep_t2"}};
  for (const auto& [kind, n] : scene_cases(r)) {
    for (const auto& [a, b] : pairs) {
      const auto ia = r.cases.find(fmt::format("{}/{}/{}", box_scene_name(kind), a, n));
      const auto ib = r.cases.find(fmt::format("{}/{}/{}", box_scene_name(kind), b, n));
      if (ia == r.cases.end() || ib == r.cases.end()) continue;
      line(fmt::format("| {} | {} | {} / {} | {} |", box_scene_name(kind), size_text(n),
                       box_stepper_label(a), box_stepper_label(b),
                       num(ia->second.ns_per_body_step / ib->second.ns_per_body_step, "{:.2f}")));
    }
  }
  // The targets against Box2D v3.2: the 20-row pyramid and the settling pile of 10^4 boxes ≥
  // 1.5× faster per body-step, on 1 thread / worker and on 2, at no more box-box overlap.
  line("\n#### Targets\n");
  line("| target | measured | met |");
  line("|---|---|---|");
  for (const auto& [kind, n] : scene_cases(r)) {
    if (kind == BoxSceneKind::tower || (kind == BoxSceneKind::box_pile && n != 10'000)) continue;
    for (int threads : {1, 2}) {
      const auto f =
          r.cases.find(fmt::format("{}/fixstep_t{}/{}", box_scene_name(kind), threads, n));
      const auto b =
          r.cases.find(fmt::format("{}/box2d32_w{}/{}", box_scene_name(kind), threads, n));
      const bool measured = f != r.cases.end() && b != r.cases.end();
      const double q = measured ? b->second.ns_per_body_step / f->second.ns_per_body_step : NAN;
      const bool ok = measured && q >= 1.5 && f->second.box_overlap <= b->second.box_overlap;
      line(fmt::format(
          "| {0}, N = {1}: fixstep ({2} thread{3}) ≥ 1.5× faster per body-step than Box2D v3.2 "
          "({2} worker{3}) at no more box-box overlap | {4}{5} | {6} |",
          scene_text(kind), size_text(n), threads, threads == 1 ? "" : "s", num(q, "{:.2f}×"),
          measured ? fmt::format(" (overlap {} against {} m)", num(f->second.box_overlap),
                                 num(b->second.box_overlap))
                   : "",
          measured ? (ok ? "yes" : "**no**") : "not measured"));
    }
  }
  return out;
}

}  // namespace boxes
