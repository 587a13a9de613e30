// A program's drawing over the scene view: the canvas's circles, closed polylines, polygons and
// arrows; DrawList shapes in world and screen coordinates, and refused arguments; the order
// bodies < overlay < HUD in a Session; the view style (background, grid, axes, scale bar) and
// the HUD's corner; no streak where a body teleports.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/app/session.hpp"
#include "fixstep/capture/capture.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/render/draw_list.hpp"
#include "fixstep/render/render.hpp"
#include "pixels.hpp"

namespace fixstep {
namespace overlay_test {

using testing::at;
using testing::near;
using testing::Rgb;
constexpr Rgba8 black{0, 0, 0, 255}, red{255, 0, 0, 255}, blue{0, 0, 255, 255},
    green{0, 255, 0, 255}, white{255, 255, 255, 255};

TEST(CanvasShapes, CircleIsARingOfItsRadiusClosedAllRound) {
  Renderer r(100, 100);
  r.begin(black);
  r.circle(50, 50, 20, 3, red);
  r.finish();
  // Every pixel centre on the radius, all round (the seam included), is red; inside and outside
  // the 3 px line, black.
  for (int k = 0; k < 360; ++k) {
    const double a = k * std::numbers::pi / 180.0;
    const int x = int(std::floor(50 + 20 * std::cos(a))),
              y = int(std::floor(50 + 20 * std::sin(a)));
    EXPECT_GT(at(r, x, y).r, 150) << "angle " << k;
  }
  EXPECT_TRUE(near(at(r, 50, 50), black, 0));
  EXPECT_TRUE(near(at(r, 60, 50), black, 0));
  EXPECT_TRUE(near(at(r, 75, 50), black, 0));
}

TEST(CanvasShapes, ClosedPolylineBlendsItsSeamOnceLikeItsOtherCorners) {
  // A translucent square loop: a doubled seam would be brighter at the first corner than at the
  // other three.
  Renderer r(100, 100);
  r.begin(black);
  const Renderer::Point square[] = {{20, 20}, {80, 20}, {80, 80}, {20, 80}};
  r.closed_polyline(square, 4.0f, Rgba8{255, 255, 255, 128});
  r.finish();
  const int corner = at(r, 20, 20).r;
  EXPECT_NEAR(corner, 128, 3);
  EXPECT_EQ(at(r, 79, 79).r, corner);
  EXPECT_EQ(at(r, 20, 79).r, corner);
  EXPECT_NEAR(at(r, 50, 20).r, 128, 3);  // an edge's middle
  EXPECT_TRUE(near(at(r, 50, 50), black, 0));
}

TEST(CanvasShapes, PolygonFillsItsInsideAndArrowEndsInAHeadAtItsTip) {
  Renderer r(100, 100);
  r.begin(black);
  const Renderer::Point hexagon[] = {{30, 10}, {50, 10}, {60, 25}, {50, 40}, {30, 40}, {20, 25}};
  r.polygon(hexagon, red);
  r.arrow(10, 70, 90, 70, 2.0f, 12.0f, white);
  r.finish();
  EXPECT_TRUE(near(at(r, 40, 25), red, 0));
  EXPECT_TRUE(near(at(r, 22, 12), black, 0));  // outside the cut corner
  EXPECT_TRUE(near(at(r, 40, 70), white, 8));  // the shaft
  EXPECT_TRUE(near(at(r, 40, 74), black, 0));  // 2 px wide
  EXPECT_TRUE(near(at(r, 80, 74), white, 0));  // the head, 12 px wide at its base (x = 78)
  EXPECT_TRUE(near(at(r, 92, 70), black, 0));  // nothing beyond the tip
}

TEST(DrawList, WorldShapesMoveWithTheCameraScreenShapesStay) {
  DrawList list;
  list.disc({2.0, 1.0}, 0.5, red);                   // world: 10 px
  list.rect({5, 5}, {15, 15}, blue, Space::screen);  // screen
  list.label({150, 80}, "ok", 2.0, white, Space::screen);
  for (const Vec2 center : {Vec2{0, 0}, Vec2{-2, 1}}) {
    Renderer r(200, 100);
    r.set_camera(Camera{.center = center, .width = 10.0});
    r.begin(black);
    list.draw(r);
    r.finish();
    const auto p = r.to_pixel(2.0, 1.0);
    EXPECT_TRUE(near(at(r, int(p[0]), int(p[1])), red, 0)) << center.x;
    EXPECT_TRUE(near(at(r, int(p[0]) + 12, int(p[1])), black, 0)) << center.x;
    EXPECT_TRUE(near(at(r, 10, 10), blue, 0)) << center.x;
  }
}

TEST(DrawList, FarAwayShapesAreCulledOrClippedWithoutHugeCoordinates) {
  // A line from far off the frame through it, a polygon mostly outside, a disc 10^9 m away:
  // the visible parts are drawn, nothing else, and nothing throws.
  Renderer r(200, 100);  // 10 m across: 20 px per m, centred on the origin
  r.set_camera(Camera{.center = {0, 0}, .width = 10.0});
  DrawList list;
  const std::vector<Vec2> tri{{-1e9, -1e9}, {1e9, -1e9}, {0.0, 2.0}};
  list.polygon(tri, blue);
  list.line({-1e12, 0.0}, {1e12, 0.0}, 0.2, red);
  list.disc({1e9, 0.0}, 1.0, green);
  r.begin(black);
  list.draw(r);
  r.finish();
  EXPECT_TRUE(near(at(r, 100, 50), red, 8));   // the line, through the middle
  EXPECT_TRUE(near(at(r, 100, 40), blue, 0));  // inside the triangle, above the line
  EXPECT_TRUE(near(at(r, 100, 5), black, 0));  // above its apex (y = 2 m: 40 px up)
}

TEST(DrawList, RefusesBadArgumentsNamingTheFieldAndKeepsTheList) {
  DrawList list;
  list.line({0, 0}, {1, 1}, 1.0, red);
  auto message = [&](auto&& call) {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message([&] {
              list.line({nan, 0}, {1, 1}, 1.0, red);
            }),
            "DrawList::line: a.x must be finite, got nan");
  EXPECT_EQ(message([&] {
              list.circle({0, 0}, 1.0, -2.0, red);
            }),
            "DrawList::circle: width must be finite and >= 0, got -2");
  EXPECT_EQ(message([&] {
              list.disc({0, inf}, 1.0, red);
            }),
            "DrawList::disc: center.y must be finite, got inf");
  const std::vector<Vec2> bow{{0, 0}, {1, 1}, {1, 0}, {0, 1}};  // crosses itself
  EXPECT_EQ(message([&] { list.polygon(bow, red); }),
            "DrawList::polygon: points must bound a convex polygon");
  const std::vector<Vec2> two{{0, 0}, {1, 1}};
  EXPECT_EQ(message([&] { list.polygon(two, red); }),
            "DrawList::polygon: points must hold at least 3 points, got 2");
  const std::vector<Vec2> bad{{0, 0}, {0, nan}};
  EXPECT_EQ(message([&] { list.polyline(bad, 1.0, red); }),
            "DrawList::polyline: points[1] must be finite, got (0, nan)");
  EXPECT_EQ(message([&] {
              list.label({0, 0}, "x", 0.1, red);
            }),
            "DrawList::label: scale must be in [0.5, 16], got 0.1");
  EXPECT_EQ(message([&] {
              list.arrow({0, 0}, {1, 0}, 1.0, nan, red);
            }),
            "DrawList::arrow: head must be finite and >= 0, got nan");
  EXPECT_EQ(list.size(), 1u);
}

/// A 200 x 100 session, 10 m wide around the origin, with a red body there (radius 1 m).
Session red_body_session(SessionSettings settings = {}) {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef b;
  b.appearance = Appearance{.radius = 1.0, .color = red};
  def.bodies.push_back(b);
  settings.width = 200, settings.height = 100;
  settings.view_center = Vec2{0, 0}, settings.view_width = 10.0;
  return Session(def, settings);
}

TEST(OverlayOrder, OverTheBodiesUnderTheHud) {
  Session s = red_body_session();
  s.set_show_engine_hud(false);
  const std::vector<std::string> lines{"HUD"};
  s.set_status_lines(lines);
  DrawList list;
  list.disc({0, 0}, 0.25, blue);                      // over the body's centre
  list.rect({0, 0}, {60, 60}, green, Space::screen);  // under the HUD's panel
  s.draw(list);
  const Renderer& r = s.renderer();
  EXPECT_TRUE(near(at(r, 100, 50), blue, 0));      // overlay over the body
  EXPECT_TRUE(near(at(r, 100, 50 + 12), red, 8));  // the body around it
  // The HUD's panel (black, alpha 150) darkens the green rectangle below it: 255 * 105 / 255.
  EXPECT_NEAR(at(r, 12, 40).g, 105, 3);
  EXPECT_TRUE(near(at(r, 55, 55), green, 0));  // beyond the panel
}

TEST(OverlayOrder, DrawnPositionIsTheInterpolatedOne) {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef b;
  b.body.velocity = {10.0, 0.0};
  def.bodies.push_back(b);
  Session s(def, SessionSettings{.width = 100, .height = 100});
  s.advance(0.0125);                                           // one tick and a quarter: alpha 0.25
  EXPECT_FALSE(s.drawn_position(s.simulation().bodies()[0]));  // no frame prepared
  s.prepare_frame();
  const auto p = s.drawn_position(s.simulation().bodies()[0]);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->x, 0.025, 1e-6);  // a quarter of the way from 0 to 0.1 m
  EXPECT_FALSE(s.drawn_position(null_entity));
}

TEST(ViewStyle, BackgroundGridAxesAndScaleBarAreSwitchable) {
  // 10 m across 200 px: grid lines every metre (20 px), the axes through the centre.
  auto frame_of = [](ViewStyle style) {
    Session s = red_body_session(SessionSettings{.style = style, .show_hud = false});
    s.draw();
    std::vector<std::uint8_t> p(s.renderer().pixels().begin(), s.renderer().pixels().end());
    return std::make_pair(p, s.renderer().width());
  };
  auto pixel = [](const std::pair<std::vector<std::uint8_t>, int>& f, int x, int y) {
    const std::size_t i = (std::size_t(y) * f.second + x) * 4;
    return Rgb{f.first[i], f.first[i + 1], f.first[i + 2]};
  };
  const Rgba8 bg{40, 10, 60, 255};
  const auto all = frame_of(ViewStyle{.background = bg});
  const auto none =
      frame_of(ViewStyle{.background = bg, .grid = false, .axes = false, .scale_bar = false});
  const auto axes = frame_of(ViewStyle{.background = bg, .grid = false, .scale_bar = false});
  EXPECT_TRUE(near(pixel(none, 5, 5), bg, 0));
  EXPECT_FALSE(near(pixel(all, 120, 5), bg, 0));  // the grid line x = 1 m
  EXPECT_TRUE(near(pixel(none, 120, 5), bg, 0));
  EXPECT_TRUE(near(pixel(axes, 120, 5), bg, 0));
  EXPECT_FALSE(near(pixel(axes, 100, 5), bg, 0));  // the axis x = 0
  EXPECT_TRUE(near(pixel(none, 100, 5), bg, 0));
  EXPECT_FALSE(near(pixel(all, 179, 80), bg, 0));  // the scale bar's right end, bottom right
  EXPECT_TRUE(near(pixel(none, 179, 80), bg, 0));
}

TEST(ViewStyle, TheHudSitsInTheCornerAskedOrNowhere) {
  const Rgba8 bg{200, 200, 200, 255};
  const ViewStyle plain{.background = bg, .grid = false, .axes = false, .scale_bar = false};
  const std::vector<std::string> lines{"x"};
  struct Case {
    HudCorner corner;
    int x, y;  // a pixel of the panel (its padding, no text)
  };
  for (const Case c :
       {Case{HudCorner::top_left, 11, 11}, Case{HudCorner::top_right, 188, 11},
        Case{HudCorner::bottom_left, 11, 88}, Case{HudCorner::bottom_right, 188, 88}}) {
    Session s = red_body_session(SessionSettings{.style = plain, .hud_corner = c.corner});
    s.set_show_engine_hud(false);
    s.set_status_lines(lines);
    s.draw();
    const Renderer& r = s.renderer();
    EXPECT_LT(at(r, c.x, c.y).r, 120) << int(c.corner);  // darkened by the panel
    for (const Case other :
         {Case{HudCorner::top_left, 11, 11}, Case{HudCorner::bottom_right, 188, 88}}) {
      if (other.corner != c.corner) {
        EXPECT_TRUE(near(at(r, other.x, other.y), bg, 0)) << int(c.corner);
      }
    }
  }
  Session off = red_body_session(SessionSettings{.style = plain, .show_hud = false});
  off.set_status_lines(lines);
  off.draw();
  EXPECT_TRUE(near(at(off.renderer(), 11, 11), bg, 0));
}

TEST(TrailCuts, ATeleportedBodyDrawsNoStreakAcrossTheFrame) {
  // A blue body flies right along y = -2 m; the program moves it to y = +2 m. Drawn every 3rd
  // frame, no pixel between the two rows is coloured (the old renderer joined the places), and
  // the trail since the jump (1 m) is drawn.
  WorldDef def;
  def.settings.dt = 1.0 / 120;
  BodyDef b;
  b.body.velocity = {4.0, 0.0};
  b.body.position = {-3.0, -2.0};
  b.appearance = Appearance{.radius = 0.2, .color = blue};
  def.bodies.push_back(b);
  Session s(def, SessionSettings{.width = 200,
                                 .height = 100,
                                 .view_center = Vec2{0, 0},
                                 .view_width = 10.0,
                                 .show_hud = false});
  for (int f = 0; f < 30; ++f) s.advance(1.0 / 60);
  s.simulation().set_position(s.simulation().bodies()[0], {-1.0, 2.0});
  for (int f = 0; f < 15; ++f) {
    s.advance(1.0 / 60);
    if (f % 3 == 2) s.draw();  // every 3rd frame drawn
  }
  const Renderer& r = s.renderer();
  if (std::getenv("FIXSTEP_TEST_PNG")) write_png("/tmp/trail_cut.png", 200, 100, r.pixels());
  int streak = 0;
  for (int y = 62; y > 38; --y)  // rows between y = -1.1 m and +1.1 m
    for (int x = 0; x < 200; ++x) streak += at(r, x, y).b > 150 && at(r, x, y).r < 100;
  EXPECT_EQ(streak, 0);
  int trail = 0;  // the trail since the jump: to the left of the body, on its row
  const auto p = r.to_pixel(s.frame().x[0], s.frame().y[0]);
  for (int x = int(p[0]) - 12; x > int(p[0]) - 30; --x) {
    trail += at(r, x, int(p[1])).b > 60 && at(r, x, int(p[1])).r < 60;
  }
  EXPECT_GT(trail, 3);
}

}  // namespace overlay_test
}  // namespace fixstep
