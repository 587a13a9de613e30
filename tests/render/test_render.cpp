// Headless rendering through OSMesa: sizes, the world-to-pixel mapping, and what is drawn.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "fixstep/app/session.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/render/render.hpp"
#include "pixels.hpp"
#include "scene_session.hpp"

namespace fixstep {
namespace {

using testing::at;
using testing::near;
using testing::Rgb;

TEST(Render, FrameHasTheRequestedSizeAndIsOpaque) {
  Renderer r(320, 200);
  EXPECT_FALSE(r.gl_renderer().empty());
  RenderFrame empty;
  r.draw(empty, {});
  ASSERT_EQ(r.pixels().size(), 320u * 200u * 4u);
  for (std::size_t i = 3; i < r.pixels().size(); i += 4) ASSERT_EQ(r.pixels()[i], 255);
}

TEST(Render, BodyIsDrawnWhereItsPositionMaps) {
  // Camera 10 m wide on 320 px: 32 px/m, origin at pixel (160, 100), y up.
  // A red body of radius 0.5 m (16 px) at (2, 1) m must cover pixel (224, 68) and only there:
  // the mirrored points (96, 132) (y flipped and x flipped) and (224, 132) (y flipped) are not red.
  Renderer r(320, 200);
  r.set_camera(Camera{.center = {0, 0}, .width = 10.0});
  World sim(WorldDef::empty(Precision::f64, WorldSettings{}));
  BodyDef d;
  d.body.position = {2.0, 1.0};
  d.appearance = Appearance{.radius = 0.5, .color = {255, 0, 0, 255}};
  sim.create_body(d);
  RenderFrame s;
  fill_render_frame(sim, 0.0, s);
  r.draw(s, {});
  const auto p = r.to_pixel(2.0, 1.0);
  EXPECT_DOUBLE_EQ(p[0], 224.0);
  EXPECT_DOUBLE_EQ(p[1], 68.0);
  const Rgba8 red{255, 0, 0, 255};
  EXPECT_TRUE(near(at(r, 224, 68), red, 2));
  EXPECT_TRUE(near(at(r, 224 + 12, 68), red, 2));    // inside the 16 px radius
  EXPECT_FALSE(near(at(r, 224 + 22, 68), red, 60));  // outside radius + outline
  EXPECT_FALSE(near(at(r, 224, 132), red, 60));      // y is not flipped
  EXPECT_FALSE(near(at(r, 96, 132), red, 60));
}

TEST(Render, ASleepingDiscIsDrawnHalfwayToGrey) {
  // A red disc resting on the floor in a world with sleeping islands: awake, drawn red; once
  // asleep (ContactSettings::sleep), halfway from red to grey (128, 132, 140).
  Renderer r(320, 200);
  r.set_camera(Camera{.center = {0, 0}, .width = 10.0});
  WorldSettings ws;
  ws.contacts = ContactSettings{.sleep = true, .sleep_time = 0.1};
  World sim(WorldDef::empty(Precision::f64, ws));
  sim.add_plane(PlaneDef{.normal = {0, 1}, .offset = 0.0});
  BodyDef d;
  d.body.position = {2.0, 0.5};
  d.collider = Collider{.radius = 0.5};
  d.gravity = Gravity{};
  d.appearance = Appearance{.radius = 0.5, .color = {255, 0, 0, 255}};
  const Entity e = sim.create_body(d);
  sim.step();
  RenderFrame s;
  fill_render_frame(sim, 1.0, s);
  ASSERT_FALSE(sim.asleep(e));
  r.draw(s, {});
  EXPECT_TRUE(near(at(r, 224, 84), Rgba8{255, 0, 0, 255}, 2));
  for (int t = 0; t < 30 && !sim.asleep(e); ++t) sim.step();
  ASSERT_TRUE(sim.asleep(e));
  fill_render_frame(sim, 1.0, s);
  ASSERT_EQ(s.asleep.size(), 1u);
  r.draw(s, {});
  EXPECT_TRUE(near(at(r, 224, 84), Rgba8{192, 66, 70, 255}, 2));
}

TEST(Render, ACarriedSegmentIsDrawnWhereItsBodyIsAtTheFramesMoment) {
  // A segment carried by a kinematic body moving right at 3 m/s: at alpha 1 the frame has it
  // where the body is after the tick, at alpha 0.25 three quarters of a tick (3/4 · 3 m/s · dt)
  // back, as the bodies' positions are interpolated.
  World sim(WorldDef::empty(Precision::f64, WorldSettings{.dt = 0.1}));
  BodyDef k;
  k.type = BodyType::kinematic;
  k.body = Body{.mass = 1.0, .position = {0.0, 0.0}, .velocity = {3.0, 0.0}};
  const Entity e = sim.create_body(k);
  sim.add_segment(SegmentDef{.a = {-1.0, 0.0}, .b = {1.0, 0.0}, .body = e});
  sim.step();
  RenderFrame s;
  fill_render_frame(sim, 1.0, s);
  ASSERT_EQ(s.segments.size(), 1u);
  EXPECT_NEAR(s.segments[0].a.x, -0.7, 1e-12);
  fill_render_frame(sim, 0.25, s);
  EXPECT_NEAR(s.segments[0].a.x, -0.7 - 0.75 * 0.3, 1e-12);
  EXPECT_NEAR(s.segments[0].b.x, 1.3 - 0.75 * 0.3, 1e-12);
}

TEST(Render, InterpolatesBetweenTicksWithAlpha) {
  World sim(WorldDef::empty(Precision::f64, WorldSettings{.dt = 1.0}));
  BodyDef d;
  d.body.velocity = {4.0, 0.0};
  sim.create_body(d);
  sim.set_keep_previous(true);
  sim.step();  // x: 0 -> 4
  RenderFrame s;
  fill_render_frame(sim, 0.25, s);
  EXPECT_FLOAT_EQ(s.x[0], 1.0f);
}

TEST(Render, HudTextAndSpringAreDrawn) {
  Renderer r(400, 200);
  r.set_camera(Camera{.center = {0, 0}, .width = 20.0});
  RenderFrame s;
  s.x = {5.0f};
  s.y = {0.0f};
  s.radius = {0.0f};
  s.color = {Rgba8{0, 0, 0, 0}};
  s.springs = {{-5.0f, 0.0f, 0}};
  const std::string hud[] = {"tick 0"};
  r.draw(s, hud);
  // HUD: bright text pixels inside the panel at the top left.
  int bright = 0;
  for (int y = 10; y < 40; ++y)
    for (int x = 10; x < 120; ++x) bright += at(r, x, y).r > 200;
  EXPECT_GT(bright, 20);
  // Spring: light-grey pixels between anchor (100, 100) and body (300, 100).
  int spring = 0;
  for (int y = 90; y < 110; ++y)
    for (int x = 150; x < 250; ++x) spring += at(r, x, y).b > 150 && at(r, x, y).r > 120;
  EXPECT_GT(spring, 50);
}

// What a HUD adds to a frame: the box of the pixels that differ from the same frame drawn
// without it (the panel, which darkens all beneath it), and the rows of its bright text.
struct HudBox {
  int right = -1, bottom = -1, ink_top = 1 << 30, ink_bottom = -1;
};
HudBox hud_box(const Renderer& with, const std::vector<std::uint8_t>& without) {
  HudBox b;
  for (int y = 0; y < with.height(); ++y)
    for (int x = 0; x < with.width(); ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * with.width() + x) * 4;
      if (with.pixels()[i] == without[i]) continue;
      b.right = std::max(b.right, x), b.bottom = std::max(b.bottom, y);
      if (with.pixels()[i] > 200) b.ink_top = std::min(b.ink_top, y), b.ink_bottom = y;
    }
  return b;
}

TEST(Render, HudTextScaleSizesThePanelAndTheText) {
  // At the default scale 2 the panel is the one fixstep compare reserved before the scale
  // existed: 20 px of margins and 22 px a line.
  EXPECT_FLOAT_EQ(Renderer::hud_height(5, 2.0f), 130.0f);
  const std::string line = "energy balance -0.000132 %";
  const std::string hud[] = {line};
  HudBox box[2];
  for (int i = 0; i < 2; ++i) {
    const float scale = i == 0 ? 1.0f : 2.0f;
    Renderer r(600, 120);
    r.set_camera(Camera{.center = {0, 0}, .width = 20.0});
    r.draw(RenderFrame{}, {});
    const std::vector<std::uint8_t> without(r.pixels().begin(), r.pixels().end());
    r.set_hud_text_scale(scale);
    EXPECT_EQ(r.hud_text_scale(), scale);
    r.draw(RenderFrame{}, hud);
    box[i] = hud_box(r, without);
    // The panel's last column and row are the last pixels before hud_width/hud_height.
    EXPECT_NEAR(box[i].right + 1, Renderer::hud_width(line, scale), 1.0) << scale;
    EXPECT_NEAR(box[i].bottom + 1, Renderer::hud_height(1, scale), 1.0) << scale;
  }
  // Twice the scale, twice the text: the ink's height (7 font px tall) and its panel's width.
  const int ink1 = box[0].ink_bottom - box[0].ink_top + 1;
  const int ink2 = box[1].ink_bottom - box[1].ink_top + 1;
  EXPECT_GE(ink1, 6);
  EXPECT_NEAR(ink2, 2 * ink1, 2);
  EXPECT_NEAR(box[1].right - 10, 2 * (box[0].right - 10), 2);
  Renderer r(64, 64);
  for (const float bad : {0.5f, 4.5f, std::numeric_limits<float>::quiet_NaN()})
    EXPECT_THROW(r.set_hud_text_scale(bad), std::invalid_argument) << bad;
  EXPECT_EQ(r.hud_text_scale(), 2.0f);
}

TEST(Render, LinksAreZigzagsWhenFewAndThinLinesWhenMany) {
  // Two bodies 10 m apart on a 400 px frame 20 m wide: pixels (100, 100) and (300, 100).
  // The zigzag's coils reach 7 px either side of the line between them; a thin line 1.25 px
  // wide reaches less than 2 px.
  auto draw = [](std::size_t links) {
    auto r = std::make_unique<Renderer>(400, 200);
    r->set_camera(Camera{.center = {0, 0}, .width = 20.0});
    RenderFrame s;
    s.x = {-5.0f, 5.0f};
    s.y = {0.0f, 0.0f};
    s.radius = {0.0f, 0.0f};
    s.color = {Rgba8{0, 0, 0, 0}, Rgba8{0, 0, 0, 0}};
    s.link_a.assign(links, 0);
    s.link_b.assign(links, 1);
    r->draw(s, {});
    return r;
  };
  auto grey = [](const Renderer& r, int y0, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = 150; x < 250; ++x) n += at(r, x, y).b > 150 && at(r, x, y).r > 120;
    return n;
  };
  const auto few = draw(Renderer::max_zigzag_links);
  EXPECT_GT(grey(*few, 103, 108) + grey(*few, 93, 98), 40);  // the coils, off the line
  const auto many = draw(Renderer::max_zigzag_links + 1);
  EXPECT_GT(grey(*many, 99, 101), 150);                       // the line itself
  EXPECT_EQ(grey(*many, 103, 108) + grey(*many, 93, 98), 0);  // nothing off it
  const auto none = draw(0);
  EXPECT_EQ(grey(*none, 93, 108), 0);
}

TEST(Render, CameraFitIncludesGeneratedBodiesAndTheSwingOfARopePinnedAtOneEnd) {
  // A rope of 11 bodies from (0, 0) to (10, 0), pinned at (0, 0): it can swing through the
  // circle of radius 10 m round the pin, so the fit covers x in [-10, 10] and y in [-10, 10].
  const Scene rope = parse_scene(R"([world]
dt = 0.01
[[chain]]
count = 11
start = [0, 0]
spacing = [1, 0]
body = { mass = 1 }
link = { stiffness = 100 }
pin = [0]
pin_spring = { stiffness = 1000 }
)",
                                 "rope.toml");
  const Camera c = fit_camera(rope.def, 1600, 900);
  EXPECT_NEAR(c.center.x, 0.0, 1e-9);
  EXPECT_NEAR(c.center.y, 0.0, 1e-9);
  EXPECT_NEAR(c.width, 20.0 * (16.0 / 9.0) * 1.15, 1e-9);  // the 20 m height sets the width
  // Pinned at both ends, the rope keeps to its bodies' box: x in [0, 10].
  Scene both = rope;
  both.def.bodies[10].spring = both.def.bodies[0].spring;
  both.def.bodies[10].spring->anchor = both.def.bodies[10].body.position;
  const Camera b = fit_camera(both.def, 1600, 900);
  EXPECT_NEAR(b.center.x, 5.0, 1e-9);
  EXPECT_NEAR(b.width, 10.0 * 1.15, 1e-9);
}

TEST(Render, RejectsImpossibleSizes) {
  EXPECT_THROW(Renderer(4, 4), RenderError);
  EXPECT_THROW(Renderer(100000, 10), RenderError);
}

TEST(Render, SessionFramesAreReproducible) {
  // Two sessions of the same scene produce the same pixels frame for frame (virtual clock).
  const Scene scene = load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/default.toml");
  Session a = testing::scene_session(scene, 160, 90);
  Session b = testing::scene_session(scene, 160, 90);
  for (int f = 0; f < 5; ++f) {
    a.advance(1.0 / 60);
    b.advance(1.0 / 60);
    a.draw();
    b.draw();
  }
  EXPECT_TRUE(std::equal(a.renderer().pixels().begin(), a.renderer().pixels().end(),
                         b.renderer().pixels().begin()));
}

TEST(Render, ASessionOfAWorldBuiltOnAnotherThreadIsTheSessionThatBuildsItsOwn) {
  // `fixstep view` builds a reloaded world on a thread of its own and hands it to a Session:
  // the same states and the same pixels, frame for frame; a world already stepped is refused.
  const Scene scene = load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/default.toml");
  WorldDef def = scene.def;
  def.settings.track_dissipation = true;
  std::optional<World> built;
  std::thread builder([&] { built.emplace(World(def)); });
  builder.join();
  const SessionSettings settings{.width = 160, .height = 90};
  Session given(def, std::move(*built), settings);
  Session own(def, settings);
  for (int f = 0; f < 5; ++f) {
    given.advance(1.0 / 60);
    own.advance(1.0 / 60);
    given.draw();
    own.draw();
    ASSERT_EQ(given.simulation().state_hash(), own.simulation().state_hash()) << "frame " << f;
  }
  EXPECT_GT(own.simulation().tick(), 0u);
  EXPECT_DOUBLE_EQ(given.initial_energy(), own.initial_energy());
  EXPECT_TRUE(std::equal(given.renderer().pixels().begin(), given.renderer().pixels().end(),
                         own.renderer().pixels().begin()));
  World stepped = World(def);
  stepped.step();
  EXPECT_THROW(Session(def, std::move(stepped), settings), std::invalid_argument);
}

TEST(Render, ATrailBelongsToItsBodyNotToItsDenseIndex) {
  // Bodies a and b, 6 m apart, drawn for 10 frames; then a is destroyed (b moves into its
  // dense index 0) and c is created (index 1). A trail kept per index would draw a streak from
  // a's place to b's and from b's to c's; kept per handle, b and c start new trails, so the
  // frame is exactly the one a fresh renderer draws of the same state (no trails at all). A
  // body that keeps its handle keeps its trail: after it moves, the frames differ.
  auto disc = [](Vec2 at, Rgba8 color) {
    BodyDef d;
    d.body.position = at;
    d.appearance = Appearance{.radius = 0.2, .color = color};
    return d;
  };
  const Camera camera{.center = {0, 0}, .width = 10.0};
  Renderer r(320, 200), fresh(320, 200);
  r.set_camera(camera);
  fresh.set_camera(camera);
  World sim(WorldDef::empty(Precision::f64, WorldSettings{}));
  const Entity a = sim.create_body(disc({-3.1, 0.3}, {255, 0, 0, 255}));
  const Entity b = sim.create_body(disc({2.9, 0.3}, {0, 255, 0, 255}));
  RenderFrame s;
  for (int f = 0; f < 10; ++f) {  // trails sample every tick: one tick a frame here
    sim.step();
    r.sample_trails(sim);
    fill_render_frame(sim, 1.0, s);
    r.draw(s, {});
  }
  sim.destroy(a);
  sim.create_body(disc({0.1, 2.4}, {0, 0, 255, 255}));
  sim.step();
  r.sample_trails(sim);
  fill_render_frame(sim, 1.0, s);
  ASSERT_EQ(s.ids[0], b);
  r.draw(s, {});
  fresh.draw(s, {});
  EXPECT_TRUE(std::equal(r.pixels().begin(), r.pixels().end(), fresh.pixels().begin()));

  // b moves (a velocity, not a teleport: a teleport cuts its trail) and keeps its trail.
  sim.set_velocity(b, {0.0, -30.0});
  sim.step();
  r.sample_trails(sim);
  fill_render_frame(sim, 1.0, s);
  r.draw(s, {});
  Renderer last_only(320, 200);
  last_only.set_camera(camera);
  last_only.draw(s, {});
  EXPECT_FALSE(std::equal(r.pixels().begin(), r.pixels().end(), last_only.pixels().begin()));
}

TEST(Canvas, PrimitivesLandOnTheirPixelsAndClipIsExact) {
  // 100 x 80 frame on a blue background: a red 4 px horizontal line along y = 20.5 from x = 10
  // to 90 under a clip of x in [30, 60), y in [10, 40): red exactly on columns 30..59; a second
  // line along y = 60.5 lies outside the clip and leaves no trace.
  Renderer r(100, 80);
  const Rgba8 blue{0, 0, 255, 255}, red{255, 0, 0, 255}, green{0, 255, 0, 255};
  r.begin(blue);
  r.set_clip(Renderer::ClipRect{30, 10, 60, 40});
  r.line(10, 20.5f, 90, 20.5f, 4.0f, red);
  r.line(10, 60.5f, 90, 60.5f, 4.0f, red);
  r.set_clip(std::nullopt);
  r.triangle(10, 50, 40, 50, 10, 75, green);
  r.rect(70, 50, 90, 70, red);
  r.finish();
  EXPECT_TRUE(near(at(r, 30, 20), red, 2));
  EXPECT_TRUE(near(at(r, 59, 20), red, 2));
  EXPECT_TRUE(near(at(r, 29, 20), blue, 0));
  EXPECT_TRUE(near(at(r, 60, 20), blue, 0));
  EXPECT_TRUE(near(at(r, 45, 10), blue, 0));   // off the line
  EXPECT_TRUE(near(at(r, 45, 60), blue, 0));   // the clipped-away line
  EXPECT_TRUE(near(at(r, 15, 55), green, 0));  // inside the triangle
  EXPECT_TRUE(near(at(r, 38, 72), blue, 0));   // beyond its hypotenuse
  EXPECT_TRUE(near(at(r, 80, 60), red, 0));    // the unclipped rectangle
  EXPECT_TRUE(near(at(r, 5, 5), blue, 0));
}

/// Largest difference of any colour channel between two frames of the same size.
int max_difference(const Renderer& a, const Renderer& b) {
  int worst = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) {
    worst = std::max(worst, std::abs(int(a.pixels()[i]) - int(b.pixels()[i])));
  }
  return worst;
}

TEST(Canvas, PolylineDrawsWhatItsSegmentsDrawWhereTheyMeetStraight) {
  // Collinear points (and a repeated one, which is skipped) give the pixels of one line().
  const Rgba8 bg{10, 20, 30, 255}, red{255, 0, 0, 255};
  Renderer one(120, 60), strip(120, 60);
  one.begin(bg);
  one.line(10, 30.5f, 110, 30.5f, 3.0f, red);
  one.finish();
  const Renderer::PolylinePoint pts[] = {
      {10, 30.5f, red}, {40, 30.5f, red}, {40, 30.5f, red}, {75, 30.5f, red}, {110, 30.5f, red}};
  strip.begin(bg);
  strip.polyline(pts, 3.0f);
  strip.finish();
  EXPECT_LE(max_difference(one, strip), 1);
}

TEST(Canvas, PolylineInterpolatesColourAndJoinsCorners) {
  // Red at the left end to blue at the right end of a horizontal run, then a right-angle turn
  // downwards (mitred: its outer corner is filled) and a reversal back up (a flat join).
  const Rgba8 bg{0, 0, 0, 255}, red{255, 0, 0, 255}, blue{0, 0, 255, 255};
  Renderer r(120, 80);
  r.begin(bg);
  const Renderer::PolylinePoint pts[] = {
      {10, 20.5f, red}, {100.5f, 20.5f, blue}, {100.5f, 70, blue}, {100.5f, 40, blue}};
  r.polyline(pts, 4.0f);
  r.finish();
  EXPECT_TRUE(near(at(r, 12, 20), red, 12));
  EXPECT_TRUE(near(at(r, 98, 20), blue, 12));
  const Rgb mid = at(r, 55, 20);  // halfway: as much red as blue
  EXPECT_NEAR(mid.r, 128, 10);
  EXPECT_NEAR(mid.b, 128, 10);
  EXPECT_TRUE(near(at(r, 101, 19), blue, 2));  // the outer corner of the turn is covered
  EXPECT_TRUE(near(at(r, 100, 60), blue, 2));  // the vertical leg
  EXPECT_TRUE(near(at(r, 100, 74), bg, 0));    // the flat end of the reversal: no spike
  EXPECT_TRUE(near(at(r, 55, 30), bg, 0));
  EXPECT_TRUE(near(at(r, 110, 45), bg, 0));
  // Fewer than two distinct points draw nothing.
  Renderer empty(32, 32);
  empty.begin(bg);
  const Renderer::PolylinePoint one_point[] = {{16, 16, red}, {16, 16, red}};
  empty.polyline(one_point, 4.0f);
  empty.polyline({}, 4.0f);
  empty.finish();
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) ASSERT_TRUE(near(at(empty, x, y), bg, 0)) << x << "," << y;
}

TEST(Canvas, OutlinedDiscIsTheOutlineDiscThenTheFillDisc) {
  // Opaque and translucent fills and outlines, overlapping each other and a line: one pass
  // gives the pixels of the two discs drawn one after the other (8-bit rounding aside).
  const Rgba8 bg{18, 21, 28, 255}, line_c{200, 200, 60, 255};
  const struct {
    Rgba8 fill, ring;
    float r, w;
  } cases[] = {{{230, 87, 46, 255}, {8, 10, 14, 255}, 9.0f, 1.5f},
               {{76, 175, 240, 120}, {250, 250, 250, 200}, 6.3f, 2.0f},
               {{120, 210, 110, 255}, {8, 10, 14, 90}, 3.0f, 1.5f}};
  Renderer two(96, 48), one(96, 48);
  for (Renderer* r : {&two, &one}) {
    r->begin(bg);
    r->line(0, 24.5f, 96, 24.5f, 6.0f, line_c);
    r->set_clip(Renderer::ClipRect{0, 0, 90, 48});  // programs switch under a clip too
    float x = 16.0f;
    for (const auto& c : cases) {
      if (r == &two) {
        r->disc(x, 24.0f, c.r + c.w, c.ring);
        r->disc(x, 24.0f, c.r, c.fill);
      } else {
        r->disc(x, 24.0f, c.r, c.fill, c.w, c.ring);
      }
      x += 14.0f;
    }
    r->set_clip(std::nullopt);
    r->rect(80, 0, 96, 10, line_c);  // and back to the shapes program
    r->finish();
  }
  EXPECT_LE(max_difference(two, one), 2);
  EXPECT_TRUE(near(at(one, 16, 24), cases[0].fill, 1));
  EXPECT_TRUE(near(at(one, 88, 5), line_c, 0));
}

TEST(Canvas, TextOutsidePrintableAsciiIsDrawnAsQuestionMarks) {
  // stb_easy_font has glyphs for ' '..'~' only; "ω·s" (UTF-8) must not read outside its table
  // (ASan would report it) and counts as "??s".
  EXPECT_FLOAT_EQ(Renderer::text_width("\xcf\x89\xc2\xb7s", 2.0f),
                  Renderer::text_width("??s", 2.0f));
  EXPECT_FLOAT_EQ(Renderer::text_width("a\tb\x7f", 1.0f), Renderer::text_width("a?b?", 1.0f));
  Renderer r(64, 32);
  r.begin(Rgba8{0, 0, 0, 255});
  r.text(2, 2, "\xcf\x89\xc2\xb7s\x01", 2.0f, Rgba8{255, 255, 255, 255});
  r.finish();
  int ink = 0;
  for (std::size_t i = 0; i < r.pixels().size(); i += 4) ink += r.pixels()[i] > 128;
  EXPECT_GT(ink, 10);
}

TEST(Canvas, VerticalTextReadsUpwardsFromItsAnchor) {
  // "0000" at scale 2 is 4 * 6 * 2 = 48 px long; drawn vertically at (20, 70) its ink lies in
  // x in [20, 20 + 9*2) and y in (70 - 48, 70].
  Renderer r(64, 96);
  const std::string s = "0000";
  ASSERT_FLOAT_EQ(Renderer::text_width(s, 2.0f), 48.0f);
  r.begin(Rgba8{0, 0, 0, 255});
  r.text_vertical(20, 70, s, 2.0f, Rgba8{255, 255, 255, 255});
  r.finish();
  int inside = 0, outside = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool ink = at(r, x, y).r > 128;
      const bool in_box = x >= 20 && x < 38 && y >= 70 - 48 && y < 70;
      inside += ink && in_box;
      outside += ink && !in_box;
    }
  EXPECT_GT(inside, 100);
  EXPECT_EQ(outside, 0);
}

}  // namespace
}  // namespace fixstep
