// What a change of sleep costs (ContactSettings::sleep): an island that falls asleep or wakes
// updates the awake runs, the islands' rings and the union-find from the bodies that changed,
// not from every body. A large world whose islands fall asleep and wake all the time steps to
// the same bits, sleep and previous positions as the same world made to rebuild them from
// every body at each change, while its plane pass still visits the awake discs only. The work
// is counted, not timed.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "awake_runs.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {
namespace {

constexpr int clusters = 60;  // of 4 discs touching in a row, 0.85 m from one to the next
constexpr int row_discs = 4 * clusters;
constexpr int row_boxes = 40;  // 0.4 m x 0.2 m, 1 m apart beyond the discs
constexpr double change_radius = 0.05;

/// A floor (e = 0, μ = 0.5) under clusters of discs and a row of boxes that settle and fall
/// asleep (below 0.2 m/s for 0.25 s: some still slide as they do), a static post among the
/// discs, and a kinematic disc that slides along above the row at 0.5 m/s from x = -1 m, low
/// enough to wake the discs it passes.
WorldDef change_scene() {
  WorldDef def = WorldDef::empty(Precision::f64, WorldSettings{.dt = 1.0 / 60.0, .threads = 1});
  def.settings.contacts = ContactSettings{.restitution = 0.0, .friction = 0.5, .sleep = true};
  def.settings.contacts->sleep_time = 0.25;
  def.settings.contacts->sleep_speed = 0.2;
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .friction = 0.5});
  for (int i = 0; i < row_discs; ++i) {
    BodyDef b;
    b.body = Body{.mass = 1.0, .position = {0.85 * (i / 4) + 0.1 * (i % 4), change_radius}};
    b.collider = Collider{.radius = change_radius};
    b.gravity = Gravity{};
    def.add_body(b);
  }
  for (int i = 0; i < row_boxes; ++i) {
    BodyDef b;
    b.body = Body{.mass = 1.0, .position = {0.85 * clusters + 1.0 * i, 0.1}};
    b.shapes.push_back(make_box(0.2, 0.1));
    b.gravity = Gravity{};
    def.add_body(b);
  }
  BodyDef post;
  post.type = BodyType::static_body;
  post.body = Body{.mass = 1.0, .position = {0.85 * 10 + 0.6, 0.3}};
  post.collider = Collider{.radius = change_radius};
  def.add_body(post);
  BodyDef slider;
  slider.type = BodyType::kinematic;
  slider.body = Body{.mass = 1.0, .position = {-1.0, 0.14}, .velocity = {1.0, 0.0}};
  slider.collider = Collider{.radius = change_radius};
  def.add_body(slider);
  return def;
}

/// The awake dynamic discs: those the plane pass visits.
std::size_t awake_row_discs(const World& w) {
  std::size_t n = 0;
  for (int i = 0; i < row_discs; ++i) n += w.asleep(w.bodies()[i]) ? 0 : 1;
  return n;
}

// Every few ticks an edit or an input wakes an island somewhere along the rows: a disc kicked
// up (set_velocity), a disc moved (set_position), a box struck (impulse input); the slider
// wakes the discs it reaches, and each island falls asleep again a quarter of a second after
// it comes to rest. The reference restores its own snapshot before each tick, so each of its
// changes rebuilds the runs from every body and its next tick passes over every body.
TEST(SleepChange, IslandsFallingAsleepAndWakingStepAsWhenRebuiltFromEveryBody) {
  const WorldDef def = change_scene();
  World lean(def), full(def);
  lean.set_keep_previous(true), full.set_keep_previous(true);
  WorldSnapshot snapshot;
  const std::size_t n = lean.body_count();
  std::vector<float> lx(n), ly(n), fx(n), fy(n);
  std::size_t woken = 0, most_asleep = 0, lean_visits = 0, full_visits = 0;
  for (int t = 1; t <= 900; ++t) {
    TickInput in;
    const std::size_t disc = (t * 37) % row_discs;
    for (World* w : {&lean, &full}) {
      const Entity e = w->bodies()[disc];
      if (t % 3 == 0) w->set_velocity(e, {0.8, 3.0});  // onto the next cluster
      if (t % 13 == 0) w->set_position(e, {w->body(e).position.x, 0.2});
    }
    if (t % 11 == 0) {
      const Entity box = lean.bodies()[row_discs + (t * 7) % row_boxes];
      in.bodies.push_back(
          BodyInput{.body = box, .kind = BodyInputKind::impulse, .value = {0.5, 2.0}});
    }
    full.save(snapshot), full.restore(snapshot);
    const std::size_t awake = awake_row_discs(lean);  // edits wake before the step, input in it
    lean.step(in), full.step(in);
    ASSERT_EQ(lean.state_hash(), full.state_hash()) << "tick " << t;
    const ContactStats& a = lean.contact_stats();
    const ContactStats& b = full.contact_stats();
    ASSERT_EQ(a.sleeping, b.sleeping) << "tick " << t;
    ASSERT_EQ(a.woken, b.woken) << "tick " << t;
    ASSERT_EQ(a.free_stepped, b.free_stepped) << "tick " << t;
    // Where a frame drawn between this tick and the next starts from: sleepers where they
    // sleep, the others where the tick began.
    lean.interpolate_positions(0.0, lx, ly), full.interpolate_positions(0.0, fx, fy);
    ASSERT_EQ(lx, fx) << "tick " << t;
    ASSERT_EQ(ly, fy) << "tick " << t;
    // The plane pass visits the discs awake as the tick begins (not on the first tick, which
    // passes over every disc; input wakes its islands within the tick, discs among them).
    if (t > 1 && in.bodies.empty()) {
      ASSERT_EQ(a.plane_tested, awake) << "tick " << t;
      lean_visits += a.plane_tested, full_visits += b.plane_tested;
    }
    woken += a.woken, most_asleep = std::max(most_asleep, a.sleeping);
  }
  // What the run went through: most bodies asleep at once, many islands woken within ticks
  // (by input and by the slider; an edit wakes one between ticks, which ContactStats::woken
  // does not count), and a plane pass that visited far fewer discs than the reference's,
  // which passes over every one.
  EXPECT_GE(most_asleep, static_cast<std::size_t>(row_discs + row_boxes) - 30);
  EXPECT_GE(woken, 80u);
  EXPECT_LT(lean_visits * 4, full_visits);
}

// The runs updated from the indices added and removed are those collected from the set the
// indices make: random sets of up to 200 indices, with additions and removals at the ends of
// runs, inside them, between them and beyond them.
TEST(SleepChange, RunsUpdatedFromTheChangesAreTheRunsOfTheNewSet) {
  std::mt19937 random(20261201);
  std::vector<detail::IndexRun> runs, updated, expected;
  for (int trial = 0; trial < 2000; ++trial) {
    const std::uint32_t size = 1 + random() % 200;
    std::vector<char> in(size), now(size);
    for (char& c : in) c = static_cast<char>(random() % 3 != 0);
    detail::collect_runs(
        size, [&](std::uint32_t i) { return in[i] != 0; }, runs);
    std::vector<std::uint32_t> add, remove;
    now = in;
    for (std::uint32_t i = 0; i < size; ++i) {
      if (random() % 5 != 0) continue;  // a fifth of the indices change
      (in[i] != 0 ? remove : add).push_back(i);
      now[i] = static_cast<char>(in[i] == 0);
    }
    detail::update_runs(runs, add, remove, updated);
    detail::collect_runs(
        size, [&](std::uint32_t i) { return now[i] != 0; }, expected);
    ASSERT_EQ(updated.size(), expected.size()) << "trial " << trial;
    for (std::size_t r = 0; r < expected.size(); ++r) {
      ASSERT_EQ(updated[r].begin, expected[r].begin) << "trial " << trial << " run " << r;
      ASSERT_EQ(updated[r].end, expected[r].end) << "trial " << trial << " run " << r;
    }
  }
}

}  // namespace
}  // namespace fixstep
