// The camera a program drives through Session (set_view, follow, zoom, clear_trails) and the
// automatic view, which keeps the bodies it fits out from under the HUD.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/app/session.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/render/hud_layout.hpp"
#include "fixstep/render/render.hpp"
#include "pixels.hpp"

namespace fixstep {
namespace {

using testing::at;
using testing::Rgb;

// A body's colour as drawn: within 8 of what was asked (the outline's blend at its edge).
bool is(Rgb p, Rgba8 c, int tol = 8) {
  return testing::near(p, c, tol);
}
// Red over the background, a grid line, or under the HUD's dark panel (which leaves ~105).
bool reddish(Rgb p) {
  return p.r > 60 && p.r > p.g + 40 && p.r > p.b + 40;
}

using testing::red;
constexpr Rgba8 yellow{250, 200, 60, 255};

BodyDef ball(Vec2 p, Vec2 v, Rgba8 color) {
  BodyDef d;
  d.body = Body{.mass = 1.0, .position = p, .velocity = v};
  d.appearance = Appearance{.radius = 0.4, .color = color};
  return d;
}

/// A 320 x 200 session without HUD of `bodies` (no forces: they keep their velocities).
std::unique_ptr<Session> quiet_session(std::vector<BodyDef> bodies) {
  WorldDef def;
  def.settings.dt = 1.0 / 60;
  def.bodies = std::move(bodies);
  auto s = std::make_unique<Session>(def, SessionSettings{.width = 320, .height = 200});
  s->set_show_engine_hud(false);
  return s;
}

TEST(Camera, SetViewPutsAKnownPointAtAKnownPixel) {
  // A yellow ball far away widens the automatic view, in which the red one is elsewhere.
  const auto owner = quiet_session({ball({5.0, 4.0}, {}, red), ball({-20.0, -10.0}, {}, yellow)});
  Session& s = *owner;
  s.draw();
  EXPECT_FALSE(is(at(s.renderer(), 224, 100), red));
  // 10 m across 320 px: 32 px per m; (5, 4) m is 2 m right of the centre (3, 4): pixel (224, 100).
  s.set_view({3.0, 4.0}, 10.0);
  EXPECT_EQ(s.view().center.x, 3.0);
  EXPECT_EQ(s.view().width, 10.0);
  s.draw();
  EXPECT_TRUE(is(at(s.renderer(), 224, 100), red));
  EXPECT_TRUE(is(at(s.renderer(), 224 + 10, 100), red));   // inside the 12.8 px radius
  EXPECT_FALSE(is(at(s.renderer(), 224 + 16, 100), red));  // beyond it and the outline
  EXPECT_THROW(s.set_view({3.0, 4.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(s.set_view({std::nan(""), 4.0}, 10.0), std::invalid_argument);
  EXPECT_THROW(s.set_view({3.0, 4.0}, std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  EXPECT_EQ(s.view().width, 10.0);  // a refused view changes nothing
}

TEST(Camera, FollowByNameFromTheStartAndAgainAfterARestart) {
  WorldDef def;
  def.settings.dt = 1.0 / 60;
  def.bodies = {ball({0.0, 0.5}, {6.0, 0.0}, red), ball({0.0, -1.5}, {}, yellow)};
  def.bodies[0].name = "runner";
  Session s(def,
            SessionSettings{.width = 320, .height = 200, .view_width = 10.0, .follow = "runner"});
  s.set_show_engine_hud(false);
  const Entity runner = s.simulation().find("runner");
  EXPECT_EQ(s.followed(), runner);
  const VirtualClock clock(60.0);
  for (int f = 1; f <= 30; ++f) s.advance(clock.frame_seconds());
  s.draw();
  // The view is centred on the position drawn (interpolated, within a tick of the state's).
  EXPECT_NEAR(s.view().center.x, s.simulation().body(runner).position.x, 6.0 / 60 + 1e-6);
  EXPECT_GT(s.view().center.x, 2.5);  // m: about 3 m after 0.5 s at 6 m/s
  EXPECT_TRUE(is(at(s.renderer(), 160, 100), red));
  s.simulation().destroy(runner);
  s.draw();
  EXPECT_EQ(s.followed(), null_entity);
  s.restart();  // the named body is back (the same handle, as at the first build) and followed
  EXPECT_EQ(s.followed(), s.simulation().find("runner"));
  s.draw();
  EXPECT_EQ(s.view().center.x, 0.0);
  EXPECT_EQ(s.view().center.y, 0.5);
  EXPECT_TRUE(is(at(s.renderer(), 160, 100), red));
  EXPECT_THROW(
      { Session unknown(def, SessionSettings{.width = 320, .height = 200, .follow = "nobody"}); },
      std::invalid_argument);
}

TEST(Camera, ZoomMagnifiesAboutTheCentre) {
  const auto owner = quiet_session({ball({1.0, 0.0}, {}, red)});
  Session& s = *owner;
  s.set_view({0.0, 0.0}, 10.0);  // the ball 32 px right of the centre (160, 100)
  s.zoom(2.0);                   // 5 m across: 64 px
  EXPECT_EQ(s.view().width, 5.0);
  EXPECT_EQ(s.view().center.x, 0.0);
  s.draw();
  EXPECT_TRUE(is(at(s.renderer(), 224, 100), red));
  EXPECT_FALSE(is(at(s.renderer(), 192, 100), red));  // where it was before the zoom
  EXPECT_THROW(s.zoom(0.0), std::invalid_argument);
  EXPECT_THROW(s.zoom(-2.0), std::invalid_argument);
  EXPECT_THROW(s.zoom(std::nan("")), std::invalid_argument);
  EXPECT_THROW(s.zoom(1e-320), std::invalid_argument);  // the width would overflow
  EXPECT_EQ(s.view().width, 5.0);
}

TEST(Camera, TheFollowedBodyStaysAtTheCentreAndItsTrailShowsItsPath) {
  // A red ball moving right at 6 m/s along y = 0.5 m (between grid lines) and a yellow marker
  // resting 2 m below its start.
  const auto owner =
      quiet_session({ball({0.0, 0.5}, {6.0, 0.0}, red), ball({0.0, -1.5}, {}, yellow)});
  Session& s = *owner;
  const Entity red_ball = s.simulation().defined_bodies()[0];
  s.set_view({0.0, 0.0}, 10.0);
  s.follow(red_ball);
  EXPECT_EQ(s.followed(), red_ball);
  const VirtualClock clock(60.0);
  for (int f = 1; f <= 30; ++f) {
    s.advance(clock.frame_seconds());
    s.draw();
    ASSERT_TRUE(is(at(s.renderer(), 160, 100), red)) << "frame " << f;
  }
  // About 0.5 s at 6 m/s (the loop draws up to one tick behind): the ball is about 3 m (96 px)
  // right of where it started, the view with it, so the marker (at the origin's x) is drawn
  // about 96 px left of the centre.
  EXPECT_NEAR(s.view().center.x, 3.0, 6.0 / 60 + 1e-6);
  EXPECT_EQ(s.view().width, 10.0);
  const auto marker = s.renderer().to_pixel(0.0, -1.5);
  EXPECT_NEAR(marker[0], 160.0 - 96.0, 3.3);
  EXPECT_NEAR(marker[1], 100.0 + 64.0, 1e-3);
  EXPECT_TRUE(is(at(s.renderer(), int(marker[0]), int(marker[1])), yellow));
  // The trail is kept in m: it shows where the ball went (to the left of the centre in this
  // view), not where it was on the screen (always the centre).
  int trail = 0;
  for (int x = 115; x < 145; ++x) trail += reddish(at(s.renderer(), x, 100));
  EXPECT_GT(trail, 25);
  // Zooming keeps following; a destroyed body stops it, and the view stays.
  s.zoom(2.0);
  s.advance(clock.frame_seconds());
  s.draw();
  EXPECT_TRUE(is(at(s.renderer(), 160, 100), red));
  const Vec2 last = s.view().center;
  s.simulation().destroy(red_ball);
  s.advance(clock.frame_seconds());
  s.draw();
  EXPECT_EQ(s.followed(), null_entity);
  EXPECT_EQ(s.view().center.x, last.x);
  EXPECT_THROW(s.follow(red_ball), std::invalid_argument);  // stale
  s.follow(s.simulation().defined_bodies()[1]);
  s.follow(null_entity);  // stops
  s.draw();
  EXPECT_EQ(s.view().center.x, last.x);
}

TEST(Camera, ClearTrailsForgetsEveryTrail) {
  const auto owner = quiet_session({ball({-3.0, 0.5}, {6.0, 0.0}, red)});  // between grid lines
  Session& s = *owner;
  s.set_view({0.0, 0.0}, 10.0);
  const VirtualClock clock(60.0);
  auto trail_pixels = [&] {
    const auto p =
        s.renderer().to_pixel(s.simulation().body(s.simulation().bodies()[0]).position.x, 0.5);
    int n = 0;
    for (int x = int(p[0]) - 45; x < int(p[0]) - 16; ++x)
      n += reddish(at(s.renderer(), x, int(p[1])));
    return n;
  };
  for (int f = 0; f < 20; ++f) s.advance(clock.frame_seconds()), s.draw();
  EXPECT_GT(trail_pixels(), 20);  // 2 m of path: 64 px behind the ball
  s.clear_trails();
  s.advance(clock.frame_seconds());
  s.draw();
  EXPECT_EQ(trail_pixels(), 0);
}

// The automatic view and the HUD: four balls at the corners of a 20 m x 10 m box, drawn at
// 640 x 360 with the engine's HUD (4 lines: 108 px at scale 2). Fitted to the whole frame, the
// top-left ball sat under the HUD's panel.
int red_pixels_in_rows(const Renderer& r, int rows) {
  int n = 0;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < r.width(); ++x) n += reddish(at(r, x, y));
  return n;
}

TEST(Camera, TheAutomaticViewKeepsTheBodiesItFitsOutFromUnderTheHud) {
  WorldDef def;
  def.settings.dt = 1.0 / 60;
  for (const Vec2 p : {Vec2{-10, 5}, Vec2{10, 5}, Vec2{-10, -5}, Vec2{10, -5}})
    def.bodies.push_back(ball(p, {}, red));
  Session s(def, SessionSettings{.width = 640, .height = 360, .title = "corners"});
  s.draw();
  const Renderer& r = s.renderer();
  const int band = int(std::ceil(Renderer::hud_height(4, 2.0f)));
  EXPECT_EQ(red_pixels_in_rows(r, band), 0);
  // Every ball is in the frame, below the band.
  for (const BodyDef& b : def.bodies) {
    const auto p = r.to_pixel(b.body.position.x, b.body.position.y);
    EXPECT_GT(p[1], band + 5.0);
    EXPECT_LT(p[1], 360.0);
    EXPECT_TRUE(reddish(at(r, int(p[0]), int(p[1]))));
  }
  // Two more lines (the window's key help): the band grows with them.
  s.set_show_controls(true);
  s.draw();
  EXPECT_EQ(red_pixels_in_rows(r, int(std::ceil(Renderer::hud_height(6, 2.0f)))), 0);
  // A line wrapped to the frame's width (a game's status line, three lines of it at 480 px):
  // the band holds the lines as drawn, not as given.
  Session narrow(def, SessionSettings{
                          .width = 480, .height = 360, .title = "corners", .hud_lines = hud_title});
  const std::string status =
      "player 1 of 2  rollback  tick 123456  rtt 48 ms  delay 2  window 8  rollbacks 1234  "
      "stalled 12.5 s";
  narrow.set_status_lines(std::vector<std::string>{status});
  narrow.draw();
  const HudLayout drawn =
      layout_hud(std::vector<std::string>{"fixstep  corners  (4 bodies)", status}, 2.0f,
                 HudCorner::top_left, 480, 360);
  ASSERT_EQ(drawn.lines.size(), 4u);
  const int wrapped_band = int(std::ceil(drawn.y1));
  EXPECT_EQ(wrapped_band, int(std::ceil(Renderer::hud_height(4, 2.0f))));
  EXPECT_EQ(red_pixels_in_rows(narrow.renderer(), wrapped_band), 0);
  for (const BodyDef& b : def.bodies) {
    const auto p = narrow.renderer().to_pixel(b.body.position.x, b.body.position.y);
    EXPECT_GT(p[1], wrapped_band + 5.0);
  }
  // A view the program sets is left alone: the top-left ball under the HUD again.
  Session mine(def,
               SessionSettings{
                   .width = 640, .height = 360, .title = "corners", .view_center = Vec2{0.0, 0.0}});
  mine.draw();
  EXPECT_GT(red_pixels_in_rows(mine.renderer(), band), 100);
}

// Draws a frame with each camera, however far out or narrow, then exits: 0 when every one
// was drawn and a centre 10^300 m out shows no grid line, else 1.
[[noreturn]] void draw_every_camera() {
  alarm(60);  // a hang fails in 60 s instead of holding the suite
  Renderer r(96, 64);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Camera cameras[] = {{{1e300, 0.0}, 1.0},  {{0.0, -1e300}, 1.0}, {{1.0, 0.0}, 1e-300},
                            {{0x1p50, 0.0}, 1.0}, {{0.0, 0x1p50}, 1.0}, {{0.0, 0.0}, 1e-320},
                            {{nan, 0.0}, 1.0},    {{0.0, 0.0}, inf}};
  for (const Camera& c : cameras) {
    r.set_camera(c);
    r.draw(RenderFrame{}, {});
  }
  // A centre 10^300 m out: no grid line (they would all fall on the centre column).
  r.set_camera(cameras[0]);
  r.draw(RenderFrame{}, {});
  const Rgb p = at(r, 48, 8);
  if (!is(p, Rgba8{18, 21, 28, 255}, 2)) {
    std::fprintf(stderr, "a grid line at 10^300 m: (%d, %d, %d)\n", p.r, p.g, p.b);
    std::exit(1);
  }
  std::fprintf(stderr, "every camera drawn\n");
  std::exit(0);
}

// Any camera draws its frame: the grid's lines are bounded (Renderer::max_grid_lines) before
// any is made, and a spacing below the coordinates' resolution draws none. Before, a centre
// 10^300 m out (spacing 0.1 m: x + 0.1 == x) looped forever appending each line's vertices
// until std::bad_alloc, and so would a centre at 2^50 m, where x + 0.1 advances by an ulp
// below 2^50 and not at all past it. In a child process, with an alarm.
TEST(Camera, AnyCameraDrawsItsFrameWithBoundedGridLines) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(draw_every_camera(), ::testing::ExitedWithCode(0), "every camera drawn");
}

}  // namespace
}  // namespace fixstep
