// Trails as data (no rendering here: Mesa's llvmpipe and a replaced operator new do not mix under
// AddressSanitizer, see count_new.cpp): samples per tick whatever the frame rate, kept per handle,
// cut at teleports and spawns, bounded per body, hidden bodies and switched-off trails, and no
// allocation once warm. The drawn side is test_trail_frames.cpp and test_trail_cuts.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/render/draw_list.hpp"
#include "fixstep/render/frame_data.hpp"
#include "fixstep/render/trails.hpp"

extern std::atomic<bool> counting;              // count_new.cpp
extern std::atomic<std::size_t> counted_bytes;  // bytes asked for while counting

namespace fixstep {
namespace trail_tests {

struct Points {
  std::array<float, Trails::max_points> x{}, y{}, age{};
  int n = 0;
};

Points points_of(const Trails& t, const RenderFrame& f, std::size_t j) {
  Points p;
  p.n = t.points(f, j, p.x, p.y, p.age);
  return p;
}

BodyDef moving(Vec2 p, Vec2 v, double trail_time = default_trail_time) {
  BodyDef d;
  d.body = Body{.mass = 1.0, .position = p, .velocity = v};
  d.appearance = Appearance{.radius = 0.2, .trail_time = trail_time};
  return d;
}

World world_of(std::vector<BodyDef> bodies, double dt) {
  WorldDef def;
  def.settings.dt = dt;
  def.bodies = std::move(bodies);
  World w(def);
  w.set_keep_previous(true);
  return w;
}

TEST(Trails, SampledPerTickAFrameEveryKTicksShowsWhatAFrameEveryTickShows) {
  // Two identical worlds, a body circling (a spring): one drawn after every tick, one after
  // every 7th. At the 7th tick both trails hold the same points: the samples of the ticks in
  // between are there, not a chord joining the frames. Before per-tick sampling the second
  // held one sample per frame drawn.
  BodyDef d = moving({1.0, 0.0}, {0.0, 3.0});
  d.spring = SpringDamper{.anchor = {0, 0}, .stiffness = 9.0};
  World every = world_of({d}, 0.01), seventh = world_of({d}, 0.01);
  Trails a, b;
  RenderFrame fa, fb;
  for (int t = 1; t <= 70; ++t) {
    every.step();
    a.sample(every);
    fill_render_frame(every, 1.0, fa);
    a.prepare(fa);
    seventh.step();
    b.sample(seventh);
    if (t % 7 == 0) {
      fill_render_frame(seventh, 1.0, fb);
      b.prepare(fb);
    }
  }
  const Points pa = points_of(a, fa, 0), pb = points_of(b, fb, 0);
  ASSERT_EQ(pa.n, pb.n);
  EXPECT_EQ(pa.n, 36);  // every 2nd tick of 70 (0.75 s of 10 ms ticks: 75), and the body
  for (int k = 0; k < pa.n; ++k) {
    EXPECT_EQ(pa.x[k], pb.x[k]) << k;
    EXPECT_EQ(pa.y[k], pb.y[k]) << k;
    EXPECT_EQ(pa.age[k], pb.age[k]) << k;
  }
}

TEST(Trails, TheNewestPointIsTheDrawnPositionAndNoSampleLiesAheadOfIt) {
  // Drawn at alpha 0.25 (a quarter of the way into the last tick): the last point is the
  // interpolated position, and the sample of the last tick (ahead of it) is not drawn.
  World w = world_of({moving({0.0, 0.0}, {1.0, 0.0})}, 0.01);
  Trails t;
  for (int i = 0; i < 20; ++i) w.step(), t.sample(w);
  RenderFrame f;
  fill_render_frame(w, 0.25, f);
  t.prepare(f);
  const Points p = points_of(t, f, 0);
  ASSERT_GE(p.n, 3);
  EXPECT_EQ(p.x[p.n - 1], f.x[0]);
  EXPECT_NEAR(f.x[0], 0.1925, 1e-6);  // 19.25 ticks of 1 cm
  EXPECT_EQ(p.age[p.n - 1], 0.0f);
  for (int k = 0; k + 1 < p.n; ++k) {
    EXPECT_LT(p.x[k], f.x[0]) << k;  // behind the body
    EXPECT_GT(p.age[k], 0.0f) << k;
    EXPECT_LE(p.age[k], 0.75f + 1e-6f) << k;
  }
}

TEST(Trails, ATeleportCutsTheTrailAndMotionAtAnySpeedDoesNot) {
  // A body at 500 m/s (5 m a tick) keeps its trail; moved by set_position between two ticks
  // (and by set_body inside a tick's rules) it starts afresh: no point joins the old place to
  // the new.
  World w = world_of({moving({0.0, 0.0}, {500.0, 0.0})}, 0.01);
  const Entity e = w.bodies()[0];
  Trails t;
  RenderFrame f;
  for (int i = 0; i < 30; ++i) w.step(), t.sample(w);
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  EXPECT_GE(points_of(t, f, 0).n, 15);  // fast, but never cut
  w.set_position(e, {-100.0, 50.0});    // between ticks
  for (int i = 0; i < 3; ++i) w.step(), t.sample(w);
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  Points p = points_of(t, f, 0);
  for (int k = 0; k < p.n; ++k) EXPECT_GE(p.x[k], -100.0f) << k;  // nothing left of the jump
  EXPECT_EQ(p.y[0], 50.0f);
  // Within a tick (a game's rules after the step): set_body.
  w.step();
  w.set_body(e, Body{.mass = 1.0, .position = {300.0, -20.0}, .velocity = {500.0, 0.0}});
  t.sample(w);
  w.step(), t.sample(w);
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  p = points_of(t, f, 0);
  for (int k = 0; k < p.n; ++k) EXPECT_EQ(p.y[k], -20.0f) << k;
}

TEST(Trails, ASpawnedBodyAndAReusedSlotStartEmpty) {
  World w = world_of({moving({0.0, 0.0}, {1.0, 0.0}), moving({5.0, 0.0}, {1.0, 0.0})}, 0.01);
  Trails t;
  for (int i = 0; i < 10; ++i) w.step(), t.sample(w);
  const Entity second = w.bodies()[1];
  w.destroy(second);
  const Entity born = w.create_body(moving({-5.0, 3.0}, {0.0, 0.0}));
  ASSERT_EQ(born.slot(), second.slot());  // the slot is reused, with a new generation
  w.step(), t.sample(w);
  RenderFrame f;
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  EXPECT_EQ(points_of(t, f, 1).n, 1);  // the new body: itself only
  EXPECT_GE(points_of(t, f, 0).n, 6);
}

TEST(Trails, ATrailOfTenSecondsAtOneMillisecondKeepsAtMostCapacitySamples) {
  World w = world_of({moving({0.0, 0.0}, {1.0, 0.0}, max_trail_time)}, 0.001);
  Trails t;
  RenderFrame f;
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  for (int i = 0; i < 12000; ++i) w.step(), t.sample(w);
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  const Points p = points_of(t, f, 0);
  EXPECT_LE(p.n, Trails::max_points);
  EXPECT_GE(p.n, Trails::capacity - 2);
  EXPECT_NEAR(p.age[0], 10.0f, 0.25f);  // the oldest sample: 10 s ago, one stride at most
  EXPECT_NEAR(p.x[p.n - 1] - p.x[0], 10.0f, 0.25f);
}

TEST(Trails, HiddenBodiesAndSwitchedOffTrailsHaveNoneAndRestartWhereTheyAre) {
  World w = world_of({moving({0.0, 0.0}, {1.0, 0.0})}, 0.01);
  const Entity e = w.bodies()[0];
  Trails t;
  RenderFrame f;
  for (int i = 0; i < 20; ++i) w.step(), t.sample(w);
  Appearance look = *w.get<Appearance>(e);
  look.visible = false;
  w.set(e, look);
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  EXPECT_EQ(points_of(t, f, 0).n, 0);
  for (int i = 0; i < 20; ++i) w.step(), t.sample(w);
  look.visible = true;
  w.set(e, look);
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  EXPECT_EQ(points_of(t, f, 0).n, 1);  // shown again: afresh, where it is
  for (int i = 0; i < 5; ++i) w.step(), t.sample(w);
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  EXPECT_EQ(points_of(t, f, 0).n, 3);  // ticks 41 and 43 (every 2nd: 0.75 s of 10 ms ticks)
  look.trail = false;
  w.set(e, look);
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  EXPECT_EQ(points_of(t, f, 0).n, 0);
}

TEST(Trails, AFrameWithoutIdsKeysBodiesByIndexAndBadFramesAreRefused) {
  Trails t;
  RenderFrame f;
  f.x = {0.0f, 1.0f};
  f.y = {0.0f, 0.0f};
  t.prepare(f);
  f.tick = 1;
  f.x = {0.5f, 1.5f};
  t.prepare(f);
  EXPECT_EQ(points_of(t, f, 1).n, 2);
  f.ids = {Entity{1, 1}};
  EXPECT_THROW(t.prepare(f), std::invalid_argument);  // 1 id for 2 bodies
  f.ids = {Entity{1, 1}, null_entity};
  EXPECT_THROW(t.prepare(f), std::invalid_argument);
  f.ids.clear();
  f.trail_time = {0.5f, -1.0f};
  EXPECT_THROW(t.prepare(f), std::invalid_argument);
  f.trail_time = {0.5f};
  EXPECT_THROW(t.prepare(f), std::invalid_argument);
}

TEST(Trails, SamplingAndDrawListsAllocateNothingOnceWarm) {
  // 10^4 bodies sampled every tick, then 100 of them replaced by new bodies in freed slots;
  // a draw list recorded twice with the same shapes.
  std::vector<BodyDef> bodies;
  for (int i = 0; i < 10000; ++i) bodies.push_back(moving({double(i), 0.0}, {1.0, 0.0}));
  World w = world_of(bodies, 0.01);
  Trails t;
  RenderFrame f;
  w.step(), t.sample(w);
  fill_render_frame(w, 1.0, f);
  t.prepare(f);
  w.step(), t.sample(w);
  std::vector<Entity> gone(w.bodies().begin(), w.bodies().begin() + 100);
  for (const Entity e : gone) w.destroy(e);
  for (int i = 0; i < 100; ++i) w.create_body(moving({-1.0, double(i)}, {0.0, 1.0}));
  DrawList list;
  const std::vector<Vec2> poly{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  auto record = [&] {
    list.clear();
    for (int i = 0; i < 1000; ++i) {
      list.line({0, 0}, {1, double(i)}, 0.1, Rgba8{255, 0, 0, 255});
      list.polyline(poly, 2.0, Rgba8{0, 255, 0, 128}, Space::screen);
      list.polygon(poly, Rgba8{0, 0, 255, 255});
      list.label({1, 2}, "a label longer than the small string buffer", 2.0,
                 Rgba8{255, 255, 255, 255});
    }
  };
  record();
  w.step();  // the world's own first step after the edits
  counting = true;
  counted_bytes = 0;
  t.sample(w);
  fill_render_frame(w, 1.0, f);  // storage grown above: same body count
  t.prepare(f);
  w.step();
  t.sample(w);
  record();
  counting = false;
  EXPECT_EQ(counted_bytes, 0u);
  EXPECT_EQ(list.size(), 4000u);
}

}  // namespace trail_tests
}  // namespace fixstep
