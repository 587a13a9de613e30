// A world mostly asleep (ContactSettings::sleep): its disc phases visit the awake discs and the
// sleepers next to them only (ContactStats::disc_visited), so a ball flying above an asleep
// pile costs what one disc does; and the states and contact events are bit for bit those of a
// tick that visits every disc. The reference for the second: the same world with enough far
// discs awake that every tick visits every disc (more than a quarter of the discs awake),
// which touch nothing of it. The work is counted, not timed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {
namespace {

constexpr double disc_r = 0.05;  // m, every disc's

/// A floor (e = 0, μ = 0.3) and `rows` rows of `columns` jittered discs of 1 kg poured on it
/// between two walls, which fall asleep after 0.25 s at rest.
WorldDef asleep_pile(int columns, int rows, Precision precision = Precision::f64) {
  WorldDef def;
  def.precision = precision;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts =
      ContactSettings{.restitution = 0.0, .friction = 0.3, .sleep = true, .sleep_time = 0.25};
  const double half = 1.2 * disc_r * columns + disc_r;
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .friction = 0.3});
  def.planes.push_back(PlaneDef{.normal = {1, 0}, .offset = -half, .friction = 0.3});
  def.planes.push_back(PlaneDef{.normal = {-1, 0}, .offset = -half, .friction = 0.3});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.2 * disc_r, 0.2 * disc_r);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) {
      BodyDef b;
      b.body = Body{.mass = 1.0,
                    .position = {-half + 2 * disc_r + 2.4 * disc_r * j + jitter(rng),
                                 2 * disc_r + 2.4 * disc_r * i}};
      b.collider = Collider{.radius = disc_r};
      b.gravity = Gravity{};
      def.bodies.push_back(b);
    }
  }
  return def;
}

/// A disc of 1 kg at (x, y) moving at (vx, vy) (m, m/s), under gravity or not, e = `e`.
BodyDef live_ball(double x, double y, double vx, double vy, bool falls, double e = 0.0) {
  BodyDef b;
  b.body = Body{.mass = 1.0, .position = {x, y}, .velocity = {vx, vy}};
  b.collider = Collider{.radius = disc_r, .restitution = e};
  if (falls) b.gravity = Gravity{};
  return b;
}

/// `count` discs without gravity rising at 0.3 m/s far above everything (from y = 1000 m,
/// between the walls, 0.2 m apart): awake for ever, touching nothing.
void add_far_drifters(WorldDef& def, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    const double x = -1.0 + 0.2 * double(i % 10), y = 1000.0 + 0.2 * double(i / 10);
    def.bodies.push_back(live_ball(x, y, 0.0, 0.3, false));
  }
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> event_pairs(std::span<const ContactEvent> e) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const ContactEvent& c : e) out.emplace_back(c.a.slot(), c.b.slot());
  return out;
}

TEST(SleepLive, ABallAboveAnAsleepPileVisitsOneDisc) {
  WorldDef def = asleep_pile(20, 10);
  // Level, without gravity, 2 m above the pile: awake, and near nothing.
  def.bodies.push_back(live_ball(-0.5, 2.5, 0.2, 0.0, false));
  World w(def);
  int asleep_at = -1;
  for (int t = 0; t < 1200 && asleep_at < 0; ++t) {
    w.step();
    if (w.contact_stats().sleeping == 200) asleep_at = t;
  }
  ASSERT_GE(asleep_at, 0) << "the pile never fell asleep";
  for (int t = 0; t < 120; ++t) {
    w.step();
    const ContactStats& s = w.contact_stats();
    ASSERT_EQ(s.sleeping, 200u);
    EXPECT_EQ(s.disc_visited, 1u) << "tick " << t;  // the ball, not the 200 sleepers
    EXPECT_EQ(s.free_stepped, 1u);
    EXPECT_EQ(s.candidate_pairs, 0u);
  }
}

TEST(SleepLive, AnAwakeSensorSensesTheSleepersItOverlaps) {
  // A sensor wakes no sleeper, but senses those it overlaps: they join its ticks.
  WorldDef def = asleep_pile(20, 10);
  BodyDef sensor = live_ball(-0.4, 3.0, 0.0, 0.0, false);
  sensor.collider->radius = 0.2;
  sensor.collider->sensor = true;
  def.bodies.push_back(sensor);
  WorldDef every = def;
  add_far_drifters(every, def.bodies.size());
  World a(def), b(every);
  for (int t = 0; t < 1200 && a.contact_stats().sleeping < 200; ++t) a.step(), b.step();
  ASSERT_EQ(a.contact_stats().sleeping, 200u);
  Vec2 top{0.0, 0.0};  // the highest sleeper
  for (const Entity e : a.bodies()) {
    if (a.asleep(e) && a.body(e).position.y > top.y) top = a.body(e).position;
  }
  const Vec2 over{top.x, top.y + 0.2};  // the sensor's disc (r = 0.2 m) dips into the top row
  a.set_position(a.bodies()[200], over), b.set_position(b.bodies()[200], over);
  for (int t = 0; t < 10; ++t) {
    a.step(), b.step();
    const ContactStats& s = a.contact_stats();
    EXPECT_EQ(s.sleeping, 200u);
    EXPECT_GT(s.disc_visited, 1u);        // the sensor and the sleepers it may overlap
    EXPECT_LT(s.disc_visited, 201u / 4);  // not the pile
    ASSERT_FALSE(a.sensor_overlaps().empty());
    ASSERT_EQ(a.sensor_overlaps().size(), b.sensor_overlaps().size());
    for (std::size_t i = 0; i < a.sensor_overlaps().size(); ++i) {
      EXPECT_EQ(a.sensor_overlaps()[i].visitor.slot(), b.sensor_overlaps()[i].visitor.slot());
    }
  }
}

/// Steps a and b (b: a plus `extra` bodies appended, far and awake) together for `ticks` ticks;
/// every tick the first a.body_count() bodies' states and a's contact events and impacts must
/// be bit for bit b's. Returns the ticks in which a visited fewer discs than b.
int compare_with_every_disc_visited(World& a, World& b, int ticks) {
  const std::size_t n = a.body_count();
  int fewer = 0;
  for (int t = 0; t < ticks; ++t) {
    a.step(), b.step();
    const auto ea = a.bodies(), eb = b.bodies();
    for (std::size_t j = 0; j < n; ++j) {
      const Body x = a.body(ea[j]), y = b.body(eb[j]);
      if (x.position.x != y.position.x || x.position.y != y.position.y ||
          x.velocity.x != y.velocity.x || x.velocity.y != y.velocity.y) {
        ADD_FAILURE() << "tick " << t << ": body " << j << " differs";
        return fewer;
      }
    }
    EXPECT_EQ(event_pairs(a.contacts_begun()), event_pairs(b.contacts_begun())) << "tick " << t;
    EXPECT_EQ(event_pairs(a.contacts_ended()), event_pairs(b.contacts_ended())) << "tick " << t;
    EXPECT_EQ(a.impacts().size(), b.impacts().size()) << "tick " << t;
    EXPECT_EQ(a.contact_stats().sleeping, b.contact_stats().sleeping) << "tick " << t;
    fewer += a.contact_stats().disc_visited < b.contact_stats().disc_visited ? 1 : 0;
  }
  return fewer;
}

TEST(SleepLive, BallsDroppedOnAnAsleepPileStepAsWhenEveryDiscIsVisited) {
  for (const Precision p : {Precision::f64, Precision::f32}) {
    SCOPED_TRACE(precision_name(p));
    WorldDef def = asleep_pile(20, 10, p);
    // Dropped from high up, they arrive fast (about 20 m/s) after the pile sleeps: impacts on
    // sleepers, islands woken within a tick, paths beyond their boxes; one bounces (e = 0.8).
    def.bodies.push_back(live_ball(-0.3, 22.0, 0.0, 0.0, true));
    def.bodies.push_back(live_ball(0.01, 26.0, 0.0, 0.0, true, 0.8));
    def.bodies.push_back(live_ball(0.4, 30.0, -0.5, 0.0, true));
    WorldDef every = def;
    add_far_drifters(every, def.bodies.size());  // half the discs awake: every disc visited
    World a(def), b(every);
    const int fewer = compare_with_every_disc_visited(a, b, 480);
    EXPECT_GE(fewer, 100);  // a visited the live discs only in many ticks
  }
}

TEST(SleepLive, ADiscKnockedBeyondItsBoxMeetsASleeper) {
  // B, struck at 30 m/s early in a tick, crosses within it a gap to the sleeper S that no box of
  // the tick's start reached: S joins the tick through B's grown box (disc_reach.cpp), is met
  // as a static disc, and wakes after it, as when every disc is visited.
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{.restitution = 1.0, .sleep = true, .sleep_time = 0.25};
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0});
  const double y = disc_r + 0.01, xb = 0.0;
  def.bodies.push_back(live_ball(xb - 2 * disc_r - 0.01, y, 0.0, 0.0, false, 1.0));  // A
  def.bodies.push_back(live_ball(xb, y, 0.0, 0.0, false, 1.0));                      // B
  def.bodies.push_back(live_ball(xb + 0.55, disc_r, 0.0, 0.0, true));                // S
  for (int i = 0; i < 20; ++i) def.bodies.push_back(live_ball(5.0 + 0.2 * i, disc_r, 0, 0, true));
  WorldDef every = def;
  add_far_drifters(every, def.bodies.size());
  World a(def), b(every);
  for (int t = 0; t < 60; ++t) a.step(), b.step();
  ASSERT_EQ(a.contact_stats().sleeping, 23u);
  for (World* w : {&a, &b}) {
    w->set_velocity(w->bodies()[0], {30.0, 0.0});
    w->set_velocity(w->bodies()[1], {0.1, 0.0});
  }
  std::size_t sleeper_contacts = 0;
  for (int t = 0; t < 3; ++t) {
    a.step(), b.step();
    sleeper_contacts += a.contact_stats().sleeper_contacts;
    const auto ea = a.bodies(), eb = b.bodies();
    for (std::size_t j = 0; j < 23; ++j) {
      EXPECT_EQ(a.body(ea[j]).position.x, b.body(eb[j]).position.x) << "tick " << t << " " << j;
      EXPECT_EQ(a.body(ea[j]).velocity.x, b.body(eb[j]).velocity.x) << "tick " << t << " " << j;
    }
    EXPECT_LT(a.contact_stats().disc_visited, 23u);
  }
  // B bounced off S (e = 1 against a static disc), not through it.
  EXPECT_LT(a.body(a.bodies()[1]).position.x, xb + 0.55 - 2 * disc_r + 1e-9);
  EXPECT_GE(sleeper_contacts, 1u);  // S met as a sleeper, then woken
}

TEST(SleepLive, ContactEventsOfWokenIslandsPairUp) {
  WorldDef def = asleep_pile(12, 8);
  def.bodies.push_back(live_ball(0.0, 60.0, 0.0, 0.0, true));
  World w(def);
  // Each pair begins once before it ends, and ends only once begun.
  std::set<std::pair<std::uint32_t, std::uint32_t>> touching;
  std::size_t woken = 0;
  for (int t = 0; t < 900; ++t) {
    w.step();
    woken += w.contact_stats().woken;
    const auto begun = event_pairs(w.contacts_begun()), ended = event_pairs(w.contacts_ended());
    auto in = [](const auto& list, const auto& p) { return std::ranges::count(list, p) != 0; };
    for (const auto& p : ended) {  // struck and parted within the tick: in both, never kept
      if (in(begun, p) && !touching.contains(p)) continue;
      EXPECT_EQ(touching.erase(p), 1u) << "tick " << t << ": ended without beginning";
    }
    for (const auto& p : begun) {
      if (in(ended, p)) continue;
      EXPECT_TRUE(touching.insert(p).second) << "tick " << t << ": began twice";
    }
  }
  EXPECT_GE(woken, 1u);
}

}  // namespace
}  // namespace fixstep
