// Joints against Box2D v3.1.1 and v3.2, in one run: a chain of 100 boxes on revolute joints
// swinging down from horizontal (ticks 1–300), a pile of 100 ragdolls (11 capsules and 10
// revolute joints with angle limits each) landing in a container (ticks 61–300) and a car (a
// chassis and two wheels on wheel joints, the rear one driven) on a polyline terrain (ticks
// 1–600, 10 s) (joints.hpp), built from one description by
//   fixstep    World with BodyDef::shapes and JointDef, on 1 and 2 threads
//              (joints_fixstep.cpp);
//   box2d3     Box2D v3.1.1 and v3.2 (where bench/box2d3.cmake built them), b2World_Step(dt, 4)
//              on 1 and 2 workers (joints_box2d3.cpp).
// Every case is built and warmed up untimed, then its window is stepped with each tick timed
// alone (steady_clock around the step) and the joints' errors measured on its poses after every
// tick, untimed; the overlaps after the window. The cases run in turn, one world alive at a
// time, in `rounds` interleaved rounds (each round builds every case afresh, its stepper order
// rotated); ns per body-step is the median round's window time / (bodies × ticks). Both engines
// are deterministic, so every round gives the same errors. The report (stdout; with --report
// DIR also DIR/joints.md).
//
//   build/bench/bin/bench_joints --report docs/perf   (5 rounds: about 1–2 minutes on 2 cores)
//   build/bench/bin/bench_joints --quick              (1 round: a smoke run)
//   build/bench/bin/bench_joints --verify-only        (the checks alone; ctest bench_joints_checks)
//   --rounds N, --scene chain|ragdoll_pile|car, --stepper KEY (fixstep_t1, box2d32_w2, ...)
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/capture/capture.hpp"
#include "joints.hpp"
#include "machine_probe.hpp"
#include "median.hpp"

using namespace joints;
using fixstep::bench::core_round_trip_ns;
using fixstep::bench::load_average;

namespace {

// --- the checks, run before anything is timed (and alone with --verify-only) --------------

int failures = 0;
void check(bool ok, const std::string& what) {
  if (!ok) ++failures, std::fprintf(stderr, "bench_joints: FAILED: %s\n", what.c_str());
}

std::vector<Pose> start_poses(const JointScene& s) {
  std::vector<Pose> x;
  for (const BodySpec& b : s.bodies) x.push_back({b.position, b.angle});
  return x;
}

/// The scenes start with every joint closed and within its limits and nothing overlapping; the
/// measures give what they should on known states.
void verify_scenes_and_measures() {
  for (const JointSceneKind k : joint_scene_kinds) {
    const JointScene s = make_joint_scene(k);
    const std::vector<Pose> x = start_poses(s);
    const JointErrors e = joint_errors(s, x);
    const Overlaps o = deepest_overlaps(s, x);
    check(
        e.separation < 1e-12 && e.beyond_limit <= 1e-12 && o.between <= 1e-12 && o.statics <= 1e-12,
        fmt::format("{} at its start: separation {} m, past a limit {}, overlaps {} and {} m",
                    joint_scene_name(k), e.separation, e.beyond_limit, o.between, o.statics));
  }
  check(make_ragdoll_pile().bodies.size() == std::size_t(ragdoll_count * ragdoll_bones) &&
            make_ragdoll_pile().joints.size() == std::size_t(ragdoll_count * (ragdoll_bones - 1)),
        "the ragdoll pile has 1100 bodies and 1000 joints");
  // The chain's 6th link moved by 1 cm along x: its two joints open by 1 cm; turned by 0.1 rad
  // about its middle: each end moves by 0.25 m · 2 sin(0.05).
  const JointScene chain = make_chain(10);
  std::vector<Pose> x = start_poses(chain);
  x[5].position.x += 0.01;
  const double moved = joint_errors(chain, x).separation;
  x = start_poses(chain);
  x[5].angle += 0.1;
  const double turned = joint_errors(chain, x).separation;
  check(std::abs(moved - 0.01) < 1e-12 && std::abs(turned - 0.5 * std::sin(0.05)) < 1e-12,
        fmt::format("chain separations {} and {} m, not 0.01 and {}", moved, turned,
                    0.5 * std::sin(0.05)));
  // Two ragdolls' hips (capsules of radius 0.095 m, 0.04 m long) brought crosswise, the end of
  // one 0.1 m from the other's segment: they overlap by 0.19 - 0.1 m; a hip lying 0.05 m below
  // the ground: 0.095 + 0.05 m into it.
  const JointScene pile = make_ragdoll_pile(2);
  x = start_poses(pile);
  x[0] = {{3.0, 3.0}, 0.0};
  x[ragdoll_bones] = {{3.12, 3.0}, 1.5707963267948966};
  const double crossed = deepest_overlaps(pile, x).between;
  x = start_poses(pile);
  x[0] = {{3.0, -0.05}, 1.5707963267948966};
  const double sunk = deepest_overlaps(pile, x).statics;
  check(std::abs(crossed - 0.09) < 1e-12 && std::abs(sunk - 0.145) < 1e-12,
        fmt::format("capsule overlaps {} and {} m, not 0.09 and 0.145", crossed, sunk));
}

/// Every engine builds each scene at its start (poses within f32 rounding), keeps the chain's
/// joints closed within 5 cm over its first second, drives the car forward on the terrain, and
/// gives the same poses on 1 and 2 threads/workers (the ragdoll pile after 60 ticks).
void verify_engines() {
  const JointScene chain = make_chain(), pile = make_ragdoll_pile(), car = make_car();
  std::vector<Pose> x, y;
  for (const std::string& key : joint_stepper_keys()) {
    const std::string who = joint_stepper_label(key);
    for (const JointScene* s : {&chain, &pile, &car}) {
      make_joint_stepper(key, *s)->poses(x);
      const std::vector<Pose> x0 = start_poses(*s);
      double off = 0.0;
      for (std::size_t i = 0; i < x.size() && i < x0.size(); ++i) {
        off = std::max({off, std::abs(x[i].position.x - x0[i].position.x),
                        std::abs(x[i].position.y - x0[i].position.y),
                        std::abs(std::remainder(x[i].angle - x0[i].angle, 2 * 3.141592653589793))});
      }
      check(x.size() == x0.size() && off < 1e-5,
            fmt::format("{}: {} built {} bodies of {}, {} off their start", who,
                        joint_scene_name(s->kind), x.size(), x0.size(), off));
    }
    const auto c = make_joint_stepper(key, chain);
    double worst = 0.0;
    for (int t = 0; t < 60; ++t) {
      c->step();
      c->poses(x);
      worst = std::max(worst, joint_errors(chain, x).separation);
    }
    check(worst < 0.05, fmt::format("{}: the chain's joints opened by {} m in 1 s", who, worst));
    const auto d = make_joint_stepper(key, car);
    for (int t = 0; t < 120; ++t) d->step();
    d->poses(x);
    check(x[0].position.x > 0.5 && x[0].position.y > 0.5 && x[0].position.y < 2.0,
          fmt::format("{}: the car's chassis is at ({}, {}) m after 2 s", who, x[0].position.x,
                      x[0].position.y));
  }
  for (const std::string& key : joint_stepper_keys()) {
    if (!key.ends_with("_w1") && !key.ends_with("_t1")) continue;
    const std::string key2 = key.substr(0, key.size() - 1) + "2";
    const auto one = make_joint_stepper(key, pile), two = make_joint_stepper(key2, pile);
    for (int t = 0; t < 60; ++t) one->step(), two->step();
    one->poses(x), two->poses(y);
    check(x == y && two->threads() == 2,
          fmt::format("{}: the ragdoll pile's poses after 60 ticks differ between 1 and 2 threads",
                      joint_stepper_label(key)));
  }
}

int run_checks() {
  verify_scenes_and_measures();
  verify_engines();
  if (failures == 0) {
    std::string engines;
    for (const std::string& key : joint_stepper_keys()) {
      engines += (engines.empty() ? "" : ", ") + joint_stepper_label(key);
    }
    std::printf(
        "checks: the scenes start closed, within their limits and without overlaps; the "
        "separation and overlap measures agree with known states; %s build every scene, keep the "
        "chain closed within 5 cm, drive the car forward and are the same on 1 and 2 "
        "threads/workers\n",
        engines.c_str());
  }
  return failures;
}

// --- the timed runs ---------------------------------------------------------------------------

/// One case in one round: the window's stepping time and what was measured.
struct Round {
  double seconds = 0.0;
  JointErrors worst{};
  Overlaps overlaps{};
  double own = 0.0, distance = 0.0;
  int threads = 1;
};

Round run_case(const JointScene& s, const std::string& key) {
  using clock = std::chrono::steady_clock;
  const auto stepper = make_joint_stepper(key, s);
  for (int t = 0; t < s.warmup; ++t) stepper->step();
  std::vector<Pose> x;
  stepper->poses(x);
  const double x0 = x.at(0).position.x;
  Round r;
  clock::duration timed{};
  for (int t = 0; t < s.window; ++t) {
    const auto begin = clock::now();
    stepper->step();
    timed += clock::now() - begin;
    stepper->poses(x);
    const JointErrors e = joint_errors(s, x);
    r.worst.separation = std::max(r.worst.separation, e.separation);
    r.worst.beyond_limit = std::max(r.worst.beyond_limit, e.beyond_limit);
  }
  r.seconds = std::chrono::duration<double>(timed).count();
  r.overlaps = deepest_overlaps(s, x);
  r.own = stepper->own_overlap();
  r.distance = x.at(0).position.x - x0;
  r.threads = stepper->threads();
  return r;
}

struct Options {
  bool verify_only = false;
  int rounds = 5;
  std::optional<std::string> report, scene, stepper;
};

JointResults run_all(const Options& o) {
  JointResults res;
  res.rounds = o.rounds;
  res.load_start = load_average(), res.round_trip_start = core_round_trip_ns();
  std::vector<std::string> keys;
  for (const std::string& k : joint_stepper_keys()) {
    if (!o.stepper || *o.stepper == k) keys.push_back(k);
  }
  std::vector<JointScene> scenes;
  for (const JointSceneKind k : joint_scene_kinds) {
    if (!o.scene || *o.scene == joint_scene_name(k)) scenes.push_back(make_joint_scene(k));
  }
  if (keys.empty() || scenes.empty()) throw std::invalid_argument("no such scene or stepper");
  std::map<std::string, std::vector<double>> times;
  std::map<std::string, Round> last;
  for (int round = 0; round < o.rounds; ++round) {
    for (const JointScene& s : scenes) {
      for (std::size_t i = 0; i < keys.size(); ++i) {
        const std::string& key = keys[(i + std::size_t(round)) % keys.size()];
        const std::string id = fmt::format("{}/{}", joint_scene_name(s.kind), key);
        const Round r = run_case(s, key);
        const double ns = r.seconds * 1e9 / (double(s.bodies.size()) * s.window);
        std::printf("round %d/%d %-26s %10.1f ns per body-step, separation %.3g m\n", round + 1,
                    o.rounds, id.c_str(), ns, r.worst.separation);
        std::fflush(stdout);
        times[id].push_back(ns);
        last[id] = r;
      }
    }
  }
  for (const JointScene& s : scenes) {
    for (const std::string& key : keys) {
      const std::string id = fmt::format("{}/{}", joint_scene_name(s.kind), key);
      const std::vector<double>& t = times[id];
      const double median = fixstep::bench::median(t);
      const auto [low, high] = std::minmax_element(t.begin(), t.end());
      const Round& r = last[id];
      res.cases[id] = {.ns_per_body_step = median,
                       .spread = (*high - *low) / median,
                       .bodies = double(s.bodies.size()),
                       .joints = double(s.joints.size()),
                       .separation = r.worst.separation,
                       .beyond_limit = r.worst.beyond_limit,
                       .overlap = r.overlaps.between,
                       .static_overlap = r.overlaps.statics,
                       .own_overlap = r.own,
                       .distance = r.distance,
                       .threads = r.threads};
    }
  }
  res.load_end = load_average(), res.round_trip_end = core_round_trip_ns();
  return res;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int a = 1; a < argc; ++a) {
    const std::string_view arg = argv[a];
    const bool has_value = a + 1 < argc;
    if (arg == "--quick") {
      o.rounds = 1;
    } else if (arg == "--verify-only") {
      o.verify_only = true;
    } else if (arg == "--report" && has_value) {
      o.report = argv[++a];
    } else if (arg == "--rounds" && has_value) {
      o.rounds = std::max(1, std::atoi(argv[++a]));
    } else if (arg == "--scene" && has_value) {
      o.scene = argv[++a];
    } else if (arg == "--stepper" && has_value) {
      o.stepper = argv[++a];
    } else {
      std::fprintf(stderr,
                   "usage: bench_joints [--quick] [--verify-only] [--report DIR] [--rounds N] "
                   "[--scene chain|ragdoll_pile|car] [--stepper KEY]\n");
      return 2;
    }
  }
  try {
    if (run_checks() != 0) return 1;
    if (o.verify_only) return 0;
    const JointResults res = run_all(o);
    const std::string md = joint_report_markdown(res);
    std::fputs(md.c_str(), stdout);
    if (o.report) {
      fixstep::prepare_output_dir(*o.report);
      fixstep::write_file_atomic(*o.report + "/joints.md", md);
      std::printf("wrote %s/joints.md\n", o.report->c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_joints: %s\n", e.what());
    return 1;
  }
  return 0;
}
