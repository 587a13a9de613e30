// bench_joints' steppers by key (Box2D v3's where bench/box2d3.cmake built them) and its report:
// the markdown of docs/perf/joints.md (cost per body-step and the joints' errors of the chain,
// the ragdoll pile and the car, for fixstep and Box2D v3.1.1 and v3.2).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "box2d3_release.hpp"
#include "joints.hpp"
#include "machine_probe.hpp"

#ifndef FIXSTEP_HAVE_BOX2D3
#define FIXSTEP_HAVE_BOX2D3 0
#endif
#ifndef FIXSTEP_HAVE_BOX2D32
#define FIXSTEP_HAVE_BOX2D32 0
#endif

namespace joints {

using discs::Box2d3Release;

std::unique_ptr<JointStepper> make_box2d3_joints(const JointScene& s, int workers,
                                                 Box2d3Release r) {
#if FIXSTEP_HAVE_BOX2D3
  if (r == Box2d3Release::v3_1) return discs::box2d_v3_1::make_joints(s, workers);
#endif
#if FIXSTEP_HAVE_BOX2D32
  if (r == Box2d3Release::v3_2) return discs::box2d_v3_2::make_joints(s, workers);
#endif
  (void)s, (void)workers;
  throw std::logic_error(fmt::format("Box2D v3.{} is not built", r == Box2d3Release::v3_1 ? 1 : 2));
}

std::vector<std::string> joint_stepper_keys() {
  return discs::shape_stepper_keys();
}

std::string joint_stepper_label(const std::string& key) {
  return discs::shape_stepper_label(key);
}

std::unique_ptr<JointStepper> make_joint_stepper(const std::string& key, const JointScene& s) {
  if (key == "fixstep_t1") return make_fixstep_joints(s, 1);
  if (key == "fixstep_t2") return make_fixstep_joints(s, 2);
  for (const Box2d3Release r : discs::box2d3_releases) {
    const std::string k = discs::box2d3_key(r);
    if (key == k + "_w1" && discs::box2d3_built(r)) return make_box2d3_joints(s, 1, r);
    if (key == k + "_w2" && discs::box2d3_built(r)) return make_box2d3_joints(s, 2, r);
  }
  throw std::invalid_argument("no joint stepper " + key);
}

namespace {

std::string num(double v, const char* f = "{:.3g}") {
  return std::isnan(v) ? "–" : fmt::format(fmt::runtime(f), v);
}

std::string scene_text(JointSceneKind k) {
  const JointScene s = make_joint_scene(k);
  const auto first = s.warmup + 1, last = s.warmup + s.window;
  switch (k) {
    case JointSceneKind::chain:
      return fmt::format(
          "Chain of {} boxes swinging down from horizontal ({} revolute joints), "
          "ticks {}–{}",
          s.bodies.size(), s.joints.size(), first, last);
    case JointSceneKind::ragdoll_pile:
      return fmt::format(
          "Ragdoll pile: {} ragdolls ({} capsules, {} revolute joints with angle "
          "limits) landing in a container, ticks {}–{}",
          ragdoll_count, s.bodies.size(), s.joints.size(), first, last);
    case JointSceneKind::car:
      break;
  }
  return fmt::format(
      "Car on terrain: a chassis and two wheels on wheel joints ({} Hz, ζ = {}, "
      "rear motor {} rad/s within {} N·m), ticks {}–{} ({} s)",
      car_frequency, car_damping_ratio, car_motor_speed, car_motor_torque, first, last,
      double(s.window) * tick);
}

/// One table column: its heading and the value of a case.
struct Column {
  const char* heading;
  double (*value)(const JointCase&);
  const char* format = "{:.3g}";
};

std::vector<Column> columns(JointSceneKind k) {
  std::vector<Column> c = {
      {"ns per body-step", [](const JointCase& x) { return x.ns_per_body_step; }},
      {"spread of the rounds", [](const JointCase& x) { return x.spread; }, "{:.2f}"}};
  switch (k) {
    case JointSceneKind::chain:
      c.push_back({"largest anchor separation over the window (m)",
                   [](const JointCase& x) { return x.separation; }});
      c.push_back(
          {"own deepest overlap after it (m)", [](const JointCase& x) { return x.own_overlap; }});
      break;
    case JointSceneKind::ragdoll_pile:
      c.push_back({"largest anchor separation over the window (m)",
                   [](const JointCase& x) { return x.separation; }});
      c.push_back(
          {"deepest past an angle limit (rad)", [](const JointCase& x) { return x.beyond_limit; }});
      c.push_back(
          {"capsule-capsule overlap after it (m)", [](const JointCase& x) { return x.overlap; }});
      c.push_back(
          {"into ground and walls (m)", [](const JointCase& x) { return x.static_overlap; }});
      c.push_back({"own (manifolds, m)", [](const JointCase& x) { return x.own_overlap; }});
      break;
    case JointSceneKind::car:
      c.push_back({"largest hub distance from its axis over the window (m)",
                   [](const JointCase& x) { return x.separation; }});
      c.push_back({"deepest past the suspension's travel (m)",
                   [](const JointCase& x) { return x.beyond_limit; }});
      c.push_back({"wheels into the terrain after it (m)",
                   [](const JointCase& x) { return x.static_overlap; }});
      c.push_back(
          {"distance travelled (m)", [](const JointCase& x) { return x.distance; }, "{:.1f}"});
      break;
  }
  return c;
}

}  // namespace

std::string joint_report_markdown(const JointResults& r) {
  std::string out;
  const auto line = [&out](const std::string& s) { out += s + "\n"; };
  std::string releases;
  for (const Box2d3Release v : discs::box2d3_releases) {
    releases += fmt::format("; Box2D {}{}", discs::box2d3_version(v),
                            discs::box2d3_built(v)
                                ? fmt::format(": {} substeps, sleeping off", discs::box2d3_substeps)
                                : " (its source archive was not found: its rows are absent)");
  }
  line(fmt::format(
      "Load average (1 min) {:.2f} at the start of the timed run, {:.2f} at its end. dt = 1/60 "
      "s, gravity {} m/s², μ = {} (tyres {}), e = 0; fixstep: WorldSettings::contacts at its "
      "default iterations{}.{}",
      r.load_start, r.load_end, gravity, friction, car_tyre_friction, releases,
      fixstep::bench::round_trip_sentence(r.round_trip_start, r.round_trip_end)));
  line(fmt::format(
      "\nns per body-step: the window's stepping time / (bodies × ticks), the median of {} "
      "round{} (every case built and warmed up afresh in each round, the cases in turn); spread: "
      "(slowest − fastest round) / median. The errors are measured on every engine's poses the "
      "same way (bench/joints_scene.cpp) after every tick of the window: a revolute joint's "
      "separation is the distance between its anchor as carried by each body, a wheel's the "
      "hub's distance from the axis line through the chassis's anchor; past a limit: the "
      "relative angle beyond [lower, upper] (rad), the suspension beyond its travel (m). Overlaps "
      "after the window, of the capsules and circles (the same code for every engine), beside "
      "the engine's own deepest −separation over its contact manifolds.",
      r.rounds, r.rounds == 1 ? "" : "s"));
  for (const JointSceneKind k : joint_scene_kinds) {
    const bool any = std::any_of(r.cases.begin(), r.cases.end(), [k](const auto& c) {
      return c.first.starts_with(std::string(joint_scene_name(k)) + "/");
    });
    if (!any) continue;  // a run of other scenes only (--scene)
    const std::vector<Column> cols = columns(k);
    line(fmt::format("\n#### {}\n", scene_text(k)));
    std::string head = "| stepper |", rule = "|---|";
    for (const Column& c : cols) head += fmt::format(" {} |", c.heading), rule += "---|";
    line(head);
    line(rule);
    for (const std::string& key : joint_stepper_keys()) {
      const auto it = r.cases.find(fmt::format("{}/{}", joint_scene_name(k), key));
      if (it == r.cases.end()) continue;
      std::string row = fmt::format("| {} |", joint_stepper_label(key));
      for (const Column& c : cols) row += fmt::format(" {} |", num(c.value(it->second), c.format));
      line(row);
    }
  }
  line("\n#### Speed ratios, measured side by side in this run (time of the first / the second)\n");
  line("| scene | ratio | value |");
  line("|---|---|---|");
  const std::pair<const char*, const char*> pairs[] = {
      {"box2d3_w1", "box2d32_w1"}, {"box2d3_w2", "box2d32_w2"},  {"box2d32_w1", "box2d32_w2"},
      {"box2d3_w1", "fixstep_t1"}, {"box2d32_w1", "fixstep_t1"}, {"box2d32_w2", "fixstep_t2"},
      {"fixstep_t1", "fixstep_t2"}};
  for (const JointSceneKind k : joint_scene_kinds) {
    for (const auto& [a, b] : pairs) {
      const auto ia = r.cases.find(fmt::format("{}/{}", joint_scene_name(k), a));
      const auto ib = r.cases.find(fmt::format("{}/{}", joint_scene_name(k), b));
      if (ia == r.cases.end() || ib == r.cases.end()) continue;
      line(fmt::format("| {} | {} / {} | {} |", joint_scene_name(k), joint_stepper_label(a),
                       joint_stepper_label(b),
                       num(ia->second.ns_per_body_step / ib->second.ns_per_body_step, "{:.2f}")));
    }
  }
  // The targets against Box2D v3.2: the chain of revolute joints and the ragdoll pile ≥ 1.5×
  // faster per body-step, on 1 thread / worker and on 2, at no more joint error (the largest
  // anchor separation and the largest limit violation over the window).
  line("\n#### Targets\n");
  line("| target | measured | met |");
  line("|---|---|---|");
  for (const JointSceneKind k : {JointSceneKind::chain, JointSceneKind::ragdoll_pile}) {
    for (int threads : {1, 2}) {
      const auto f = r.cases.find(fmt::format("{}/fixstep_t{}", joint_scene_name(k), threads));
      const auto b = r.cases.find(fmt::format("{}/box2d32_w{}", joint_scene_name(k), threads));
      const bool measured = f != r.cases.end() && b != r.cases.end();
      const double q = measured ? b->second.ns_per_body_step / f->second.ns_per_body_step : NAN;
      const bool ok = measured && q >= 1.5 && f->second.separation <= b->second.separation &&
                      f->second.beyond_limit <= b->second.beyond_limit;
      line(fmt::format(
          "| {0}: fixstep ({1} thread{2}) ≥ 1.5× faster per body-step than Box2D v3.2 ({1} "
          "worker{2}) at no more joint error | {3}{4} | {5} |",
          joint_scene_name(k), threads, threads == 1 ? "" : "s", num(q, "{:.2f}×"),
          measured ? fmt::format(" (separation {} against {} m, beyond a limit {} against {})",
                                 num(f->second.separation), num(b->second.separation),
                                 num(f->second.beyond_limit), num(b->second.beyond_limit))
                   : "",
          measured ? (ok ? "yes" : "**no**") : "not measured"));
    }
  }
  return out;
}

}  // namespace joints
