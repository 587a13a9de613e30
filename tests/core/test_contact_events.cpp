// Contact events: disc pairs that begin and end touching, by handle, with the closing speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "test_bodies.hpp"

namespace fixstep {
namespace {

using test::ball;

TEST(ContactEvents, TwoDiscsThatStrikeAndPartGiveOneBegunAndOneEndedWithTheClosingSpeed) {
  WorldSettings s{.dt = 0.01};
  s.contacts = ContactSettings{.restitution = 1.0, .friction = 0.0};
  World sim(WorldDef::empty(Precision::f64, s));
  BodyDef a = ball("a", {-1, 0}, {2, 0});
  BodyDef b = ball("b", {1, 0}, {-1, 0});
  a.collider = b.collider = Collider{0.5};
  const Entity ea = sim.create_body(a), eb = sim.create_body(b);
  std::vector<ContactEvent> begun, ended;
  for (int t = 0; t < 200; ++t) {
    sim.step();
    begun.insert(begun.end(), sim.contacts_begun().begin(), sim.contacts_begun().end());
    ended.insert(ended.end(), sim.contacts_ended().begin(), sim.contacts_ended().end());
  }
  ASSERT_EQ(begun.size(), 1u);
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(begun[0].a, ea);
  EXPECT_EQ(begun[0].b, eb);
  EXPECT_NEAR(begun[0].normal_speed, 3.0, 1e-12);  // closing speed 2 - (-1)
  EXPECT_EQ(ended[0].normal_speed, 0.0);
}

TEST(ContactEvents, ADiscComingToRestOnAnotherBeginsOnceAndEndsWhenOneIsDestroyed) {
  WorldSettings s{.dt = 0.01};
  s.contacts = ContactSettings{.restitution = 0.0, .friction = 0.5};
  World sim(WorldDef::empty(Precision::f64, s));
  BodyDef floor = ball("floor", {0, 0});
  floor.type = BodyType::static_body;
  floor.collider = Collider{1.0};
  BodyDef top = ball("top", {0, 1.6});
  top.collider = Collider{0.5};
  top.gravity = Gravity{{0, -9.81}};
  const Entity ef = sim.create_body(floor), et = sim.create_body(top);
  int begun = 0, ended = 0;
  for (int t = 0; t < 300; ++t) {
    sim.step();
    begun += static_cast<int>(sim.contacts_begun().size());
    ended += static_cast<int>(sim.contacts_ended().size());
  }
  EXPECT_EQ(begun, 1);  // resting contact: no flicker of begin/end events
  EXPECT_EQ(ended, 0);
  sim.destroy(ef);
  sim.step();
  ASSERT_EQ(sim.contacts_ended().size(), 1u);
  EXPECT_EQ(sim.contacts_ended()[0].a, ef);  // a destroyed body's handle: stale now
  EXPECT_EQ(sim.contacts_ended()[0].b, et);
  EXPECT_FALSE(sim.contains(sim.contacts_ended()[0].a));
}

// Two discs asleep one on the other (ContactSettings::sleep) while a kinematic disc moves far
// away (so the disc phases run on): their pair is kept apart from the awake pairs while they
// sleep, and when every disc goes, in a tick without disc phases, it ends there as the awake
// pairs do. Deliberate bug checked: the asleep pairs left out of that tick's ended.
TEST(ContactEvents, ThePairOfTwoAsleepDiscsEndsWhenEveryDiscIsDestroyed) {
  WorldSettings s{.dt = 0.01};
  s.contacts = ContactSettings{.restitution = 0.0, .friction = 0.5, .sleep = true};
  WorldDef def = WorldDef::empty(Precision::f64, s);
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .friction = 0.5});
  World sim(def);
  BodyDef low = ball("low", {0, 0.5});
  BodyDef high = ball("high", {0, 1.5});
  for (BodyDef* b : {&low, &high}) {
    b->collider = Collider{0.5};
    b->gravity = Gravity{{0, -9.81}};
  }
  BodyDef mover = ball("mover", {50, 5}, {1, 0});
  mover.type = BodyType::kinematic;
  mover.collider = Collider{0.5};
  const Entity el = sim.create_body(low), eh = sim.create_body(high);
  const Entity em = sim.create_body(mover);
  int begun = 0, ended = 0;
  for (int t = 0; t < 300; ++t) {
    sim.step();
    begun += static_cast<int>(sim.contacts_begun().size());
    ended += static_cast<int>(sim.contacts_ended().size());
  }
  ASSERT_TRUE(sim.asleep(el) && sim.asleep(eh));
  EXPECT_EQ(begun, 1);  // falling asleep ends nothing
  EXPECT_EQ(ended, 0);
  for (const Entity e : {el, eh, em}) sim.destroy(e);
  sim.step();
  ASSERT_EQ(sim.contacts_ended().size(), 1u);
  EXPECT_EQ(sim.contacts_ended()[0].a, el);
  EXPECT_EQ(sim.contacts_ended()[0].b, eh);
  EXPECT_TRUE(sim.contacts_begun().empty());
}

// A block of 3000 discs on a floor (about 6000 touching pairs, from 4096 the events go by halves
// on two threads), ploughed by a kinematic disc, with 40 discs destroyed and 40 made every 10
// ticks (their slots reused: a pair of the same slots but new bodies ends and begins): one thread
// and two give the same events in the same order every tick. Deliberate bugs checked: the
// second half's events dropped, and the halves cut at a pair past the middle one's slots in
// the pairs before the tick (they differ at ticks 1 and 2).
TEST(ContactEvents, OneThreadAndTwoGiveTheSameEventsWhenManyPairsTouch) {
  auto block = [](int threads) {
    WorldSettings s{.dt = 1.0 / 60.0, .threads = threads};
    s.contacts = ContactSettings{.restitution = 0.2, .friction = 0.3};
    auto w = std::make_unique<World>(WorldDef::empty(Precision::f64, s));
    w->add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0});
    w->add_plane(PlaneDef{.normal = {1.0, 0.0}, .offset = 0.0});
    w->add_plane(PlaneDef{.normal = {-1.0, 0.0}, .offset = -6.0});
    for (int i = 0; i < 3000; ++i) {
      BodyDef d = ball("d", {0.05 + 0.1 * (i % 60), 0.05 + 0.1 * (i / 60)});
      d.collider = Collider{0.05};
      d.gravity = Gravity{{0.0, -9.81}};
      (void)w->create_body(d);
    }
    BodyDef plough = ball("plough", {-1.0, 1.0}, {2.0, 0.0});
    plough.type = BodyType::kinematic;
    plough.collider = Collider{0.3};
    (void)w->create_body(plough);
    return w;
  };
  auto one = block(1), two = block(2);
  std::size_t events = 0, most_touching = 0;
  for (int t = 0; t < 60; ++t) {
    if (t % 10 == 9) {
      for (auto* w : {one.get(), two.get()}) {
        const auto all = w->bodies();
        const std::vector<Entity> gone(all.begin() + 100 + 10 * t, all.begin() + 140 + 10 * t);
        for (const Entity e : gone) w->destroy(e);
        for (int i = 0; i < 40; ++i) {
          BodyDef d = ball("new", {0.3 + 0.12 * i, 5.5 + 0.01 * t});
          d.collider = Collider{0.05};
          d.gravity = Gravity{{0.0, -9.81}};
          (void)w->create_body(d);
        }
      }
    }
    one->step(), two->step();
    for (const auto& [a, b] : {std::pair{one->contacts_begun(), two->contacts_begun()},
                               {one->contacts_ended(), two->contacts_ended()}}) {
      ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "tick " << t + 1;
      events += a.size();
    }
    most_touching = std::max(most_touching, one->contact_stats().touching);
  }
  EXPECT_GT(most_touching, 4096u);
  EXPECT_GT(events, 500u);
}

// Both lists are in slot order (by a's slot, then b's) on every tick, also when a tick has
// pairs that struck and parted within it (begun and ended at once) beside pairs that began or
// ended touching across it: 600 discs dropped in rows into a box, bouncing (e = 0.6) as they
// pile up.
TEST(ContactEvents, BegunAndEndedAreInSlotOrderWithPairsThatStruckAndPartedAmongThem) {
  WorldSettings s{.dt = 1.0 / 60.0};
  s.contacts = ContactSettings{.restitution = 0.6, .friction = 0.3};
  World w(WorldDef::empty(Precision::f64, s));
  w.add_plane(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0});
  w.add_plane(PlaneDef{.normal = {1.0, 0.0}, .offset = 0.0});
  w.add_plane(PlaneDef{.normal = {-1.0, 0.0}, .offset = -2.0});
  for (int i = 0; i < 600; ++i) {
    BodyDef d = ball("d", {0.06 + 0.11 * (i % 18) + 0.01 * ((i / 18) % 3), 0.5 + 0.13 * (i / 18)},
                     {0.0, -1.0});
    d.collider = Collider{0.05};
    d.gravity = Gravity{{0.0, -9.81}};
    (void)w.create_body(d);
  }
  auto slot_order = [](const ContactEvent& l, const ContactEvent& r) {
    return l.a.slot() != r.a.slot() ? l.a.slot() < r.a.slot() : l.b.slot() < r.b.slot();
  };
  int mixed = 0;  // ticks whose begun has a struck pair and one that stays in touch
  for (int t = 0; t < 240; ++t) {
    w.step();
    const auto begun = w.contacts_begun(), ended = w.contacts_ended();
    ASSERT_TRUE(std::is_sorted(begun.begin(), begun.end(), slot_order)) << "tick " << t + 1;
    ASSERT_TRUE(std::is_sorted(ended.begin(), ended.end(), slot_order)) << "tick " << t + 1;
    auto struck = [&](const ContactEvent& e) {
      return std::any_of(ended.begin(), ended.end(),
                         [&](const ContactEvent& x) { return x.a == e.a && x.b == e.b; });
    };
    const auto n_struck = std::count_if(begun.begin(), begun.end(), struck);
    if (n_struck > 0 && n_struck < static_cast<std::ptrdiff_t>(begun.size())) ++mixed;
  }
  EXPECT_GT(mixed, 10);
}

}  // namespace
}  // namespace fixstep
