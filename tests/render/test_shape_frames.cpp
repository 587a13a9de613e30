// Bodies' shapes in the scene view (RenderFrame::shapes) and the canvas's rounded polygons
// (Renderer::rounded_polygon) that draw them: which pixels they fill, how they turn, that their
// pieces cover each pixel once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <vector>

#include "fixstep/app/session.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/render/render.hpp"
#include "pixels.hpp"
#include "scene_palette.hpp"
#include "shape_card.hpp"

namespace fixstep {
namespace {

using testing::at;
using testing::near;
using testing::Rgb;

const ViewStyle plain{.grid = false, .axes = false, .scale_bar = false};

/// The pixel under world point (x, y) m.
Rgb at_world(const Renderer& r, double x, double y) {
  const auto p = r.to_pixel(x, y);
  return at(r, int(std::floor(p[0])), int(std::floor(p[1])));
}

/// Renders `s` on 320 x 200 px through a camera 10 m wide on the origin (32 px per m, the
/// origin on the corner of pixels (159, 99) and (160, 100)), without grid, axes or scale bar.
std::unique_ptr<Renderer> draw_shape_frame(const RenderFrame& s) {
  auto r = std::make_unique<Renderer>(320, 200);
  r->set_camera(Camera{.center = {0, 0}, .width = 10.0});
  r->set_view_style(plain);
  r->draw(s, {});
  return r;
}

// Tolerances: a pixel well inside a shape (its centre over 2 px from the edge) is the body's
// colour within 2 levels of 255; one well outside the shape and its outline is the background
// within 2; a pixel where a wrong shape (a square capsule end, a sharp corner) would be the
// body's colour is more than 60 levels from it (here 1.5 to 2.6 px beyond the true edge: the
// outline, or the background).
TEST(ShapeFrames, ShapesFillWhatTheyCoverAndNoMore) {
  using namespace testing;
  const auto r = draw_shape_frame(shape_test_frame());
  const Rgba8 bg = default_background;
  // The red box, 2 x 0.5 m turned 45° at (-3, 1.5): along its long axis u, across it v.
  const double cx = -3.0, cy = 1.5, h = std::sqrt(0.5);
  auto red_at = [&](double a, double b) {  // a along u, b along v
    return at_world(*r, cx + h * a - h * b, cy + h * a + h * b);
  };
  EXPECT_TRUE(near(red_at(-0.8, 0.0), shape_red, 2));
  EXPECT_TRUE(near(red_at(-0.3, 0.15), shape_red, 2));
  EXPECT_TRUE(near(red_at(0.0, 0.45), bg, 2));           // beyond its long side
  EXPECT_TRUE(near(red_at(-1.2, 0.0), bg, 2));           // beyond its short side
  EXPECT_TRUE(near(at_world(*r, cx - 0.8, cy), bg, 2));  // inside it were it not turned
  // The green capsule, the segment (-0.75, 0)..(0.75, 0) at (0, 1.5) swept by 0.3 m.
  EXPECT_TRUE(near(at_world(*r, 0.5, 1.7), shape_green, 2));
  EXPECT_TRUE(near(at_world(*r, 0.9, 1.5), shape_green, 2));  // in its round end
  // 10 px from its centre: the ring of the 9 px disc drawn for a body without shapes.
  EXPECT_TRUE(near(at_world(*r, 0.3, 1.6), shape_green, 2));
  EXPECT_FALSE(near(at_world(*r, 1.0, 1.77), shape_green, 60));  // a square end's corner
  EXPECT_TRUE(near(at_world(*r, 1.3, 1.5), bg, 2));
  EXPECT_TRUE(near(at_world(*r, 0.0, 1.95), bg, 2));
  // The blue triangle (-0.4, -0.4), (0.8, -0.4), (-0.4, 0.8) at (3, 1.5), sharp.
  EXPECT_TRUE(near(at_world(*r, 3.1, 1.25), shape_blue, 2));
  EXPECT_TRUE(near(at_world(*r, 3.35, 1.85), bg, 2));  // beyond its long side, in its box
  EXPECT_TRUE(near(at_world(*r, 3.0, 1.0), bg, 2));    // below it
  // The yellow box 1.5 x 1 m rounded by 0.25 m at (0, -1.5).
  EXPECT_TRUE(near(at_world(*r, -0.9, -1.5), shape_yellow, 2));     // in the rounding
  EXPECT_TRUE(near(at_world(*r, 0.85, -0.9), shape_yellow, 2));     // in a round corner
  EXPECT_FALSE(near(at_world(*r, 0.97, -0.78), shape_yellow, 60));  // a sharp corner's
  EXPECT_TRUE(near(at_world(*r, 1.15, -1.5), bg, 2));
  // The outline: dark, just beyond the fill's edge (1 px beyond the rounded box's side).
  EXPECT_TRUE(near(at_world(*r, 0.0, -0.75 + 0.5 / 32), scene_palette::outline, 12));
}

TEST(ShapeFrames, TurningABodyBy90DegreesTurnsItsPixels) {
  // A box 2 x 0.5 m reaching from -0.5 to 1.5 m along its body's x axis (its centre of mass at
  // the origin, off the box's middle so that a turn the wrong way shows), at 0 and at 90°. The
  // origin lies on a pixel corner, so the turn maps pixel centres onto pixel centres: the pixel
  // at offset (dx, dy) px from it at 0° is the pixel at (dy, -dx) at 90° (y down). Edges may
  // round differently (positions snap to 1/256 px, cos(pi/2) is not 0 in float): at most 1 % of
  // the 120 x 120 px around it may differ by more than 24 levels, where a turn the wrong way
  // or none differs on hundreds.
  auto frame = [](float angle) {
    RenderFrame s;
    const auto body = testing::add_shaped_body(s, 0, 0, angle, testing::shape_red);
    testing::add_shape(s, body, {{-0.5, -0.25}, {1.5, -0.25}, {1.5, 0.25}, {-0.5, 0.25}}, 0.0f);
    return s;
  };
  const auto flat = draw_shape_frame(frame(0.0f));
  const auto turned = draw_shape_frame(frame(std::numbers::pi_v<float> / 2));
  const Rgba8 bg = default_background;
  EXPECT_TRUE(near(at_world(*flat, 1.2, 0.0), testing::shape_red, 2));
  EXPECT_TRUE(near(at_world(*flat, -1.2, 0.0), bg, 2));
  EXPECT_TRUE(near(at_world(*flat, 0.0, 1.2), bg, 2));
  EXPECT_TRUE(near(at_world(*turned, 0.0, 1.2), testing::shape_red, 2));
  EXPECT_TRUE(near(at_world(*turned, 0.0, -1.2), bg, 2));
  EXPECT_TRUE(near(at_world(*turned, 1.2, 0.0), bg, 2));
  int differ = 0, red = 0;
  for (int dy = -60; dy < 60; ++dy) {
    for (int dx = -60; dx < 60; ++dx) {
      // Pixel (160 + dx, 100 + dy) has its centre at offset (dx + 0.5, dy + 0.5); turned, at
      // (dy + 0.5, -dx - 0.5): pixel (160 + dy, 100 - dx - 1).
      const Rgb a = at(*flat, 160 + dx, 100 + dy), b = at(*turned, 160 + dy, 99 - dx);
      differ += !near(a, Rgba8{std::uint8_t(b.r), std::uint8_t(b.g), std::uint8_t(b.b), 255}, 24);
      red += near(a, testing::shape_red, 2);
    }
  }
  EXPECT_GT(red, 800);  // 64 x 16 px, less the mark and the edges
  EXPECT_LE(differ, 144) << differ << " of 14400 pixels differ";
}

TEST(ShapeFrames, ASleepingShapedBodyIsGreyedAndADiscBodyKeepsItsDisc) {
  RenderFrame s = testing::shape_test_frame();
  s.asleep.assign(s.x.size(), 0);
  s.asleep[0] = 1;  // the red box
  // A body without shapes beside them: its disc, 0.25 m (8 px), at (3, -1.5).
  testing::add_shaped_body(s, 3.0f, -1.5f, 0.0f, testing::shape_blue);
  s.radius.back() = 0.25f;
  s.asleep.push_back(0);
  const auto r = draw_shape_frame(s);
  const double h = std::sqrt(0.5);
  // Halfway from red to sleep_grey {128, 132, 140}, as a sleeping disc.
  EXPECT_TRUE(near(at_world(*r, -3.0 - 0.8 * h, 1.5 - 0.8 * h), Rgba8{192, 66, 70, 255}, 2));
  EXPECT_TRUE(near(at_world(*r, 0.5, 1.7), testing::shape_green, 2));  // awake
  EXPECT_TRUE(near(at_world(*r, 3.0, -1.5 + 0.15), testing::shape_blue, 2));
  // Its spin mark is drawn (spin_marks, the default): the line from its centre along +x, 1.5 px
  // wide across the boundary of two rows of pixels, darkens both.
  EXPECT_FALSE(near(at_world(*r, 3.15, -1.5), testing::shape_blue, 60));
  s.spin_marks = false;
  EXPECT_TRUE(near(at_world(*draw_shape_frame(s), 3.15, -1.5), testing::shape_blue, 2));
}

/// Signed distance (px) from (x, y) to the convex polygon through `points` (one: a point, two:
/// a segment), less `radius`: negative inside the rounded polygon.
double rounded_distance(std::span<const Renderer::Point> points, double radius, double x,
                        double y) {
  const std::size_t n = points.size();
  double nearest = std::numeric_limits<double>::max();
  bool inside = n >= 3;
  double turn = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto a = points[i], b = points[(i + 1) % n];
    const double ex = b.x - a.x, ey = b.y - a.y, len2 = ex * ex + ey * ey;
    const double t = len2 > 0 ? std::clamp(((x - a.x) * ex + (y - a.y) * ey) / len2, 0.0, 1.0) : 0;
    nearest = std::min(nearest, std::hypot(x - a.x - t * ex, y - a.y - t * ey));
    const double cross = ex * (y - a.y) - ey * (x - a.x);
    if (i == 0) turn = cross;
    inside = inside && cross * turn > 0.0;
  }
  return (inside ? -nearest : nearest) - radius;
}

TEST(RoundedPolygon, ShadesEveryPixelOnceByItsDistanceToTheShape) {
  // Each shape (apart from the others) in a half-transparent colour: a pixel whose centre lies over
  // 1 px inside is the colour blended once over the background, within 1 level (a piece drawn twice
  // would blend it twice: 3/4 of the way); over 1 px outside, the background exactly. Sharp
  // polygons (radius 0) are rounded by 1 px at their corners: pixels within 8 px of a vertex are
  // left out (1 / sin(half the sharpest corner, 17°) px and 1 more).
  struct Case {
    std::vector<Renderer::Point> points;
    float radius;
  };
  const std::vector<Case> cases = {
      {{{60, 60}}, 23.3f},                                       // disc
      {{{40, 130}, {150, 100}}, 17.0f},                          // capsule
      {{{150, 20}, {200, 70}, {180, 90}, {120, 60}}, 0.0f},      // sharp, clockwise
      {{{260, 40}, {300, 120}, {220, 100}}, 9.5f},               // rounded
      {{{200, 150}, {290, 150}, {290, 185}, {200, 185}}, 6.0f},  // rounded box
      {{{30, 190}, {120, 188}, {31, 160}}, 0.0f},                // thin, sharp
  };
  const Rgba8 bg{10, 20, 30, 255}, c{250, 200, 40, 128};
  Renderer r(320, 200);
  r.begin(bg);
  for (const Case& k : cases) r.rounded_polygon(k.points, k.radius, c);
  r.finish();
  auto once = [&](int ch_c, int ch_bg) { return (ch_c * 128 + ch_bg * 127 + 127) / 255; };
  const Rgba8 blended{std::uint8_t(once(c.r, bg.r)), std::uint8_t(once(c.g, bg.g)),
                      std::uint8_t(once(c.b, bg.b)), 255};
  int inside = 0, outside = 0, edge = 0;
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 320; ++x) {
      double d = std::numeric_limits<double>::max();
      bool near_corner = false, sharp = false;
      for (const Case& k : cases) {
        const double dk = rounded_distance(k.points, k.radius, x + 0.5, y + 0.5);
        if (dk < d) d = dk, sharp = k.radius == 0;
        for (const auto& p : k.points) {
          near_corner =
              near_corner || (k.radius == 0 && std::hypot(x + 0.5 - p.x, y + 0.5 - p.y) < 8);
        }
      }
      const Rgb p = at(r, x, y);
      if (sharp && !near_corner && std::abs(d) < 0.25) {  // on a sharp edge: smoothed
        edge += !near(p, blended, 1) && !near(p, bg, 1);
      }
      if (near_corner || std::abs(d) <= 1.0) continue;
      if (d < 0) {
        ++inside;
        ASSERT_TRUE(near(p, blended, 1))
            << "inside at " << x << ", " << y << ": " << p.r << " " << p.g << " " << p.b;
      } else {
        ++outside;
        ASSERT_TRUE(near(p, bg, 0))
            << "outside at " << x << ", " << y << ": " << p.r << " " << p.g << " " << p.b;
      }
    }
  }
  EXPECT_GT(inside, 12000);
  EXPECT_GT(outside, 30000);
  // Pixels whose centre lies within 1/4 px of a sharp polygon's edge are partly covered
  // (a polygon drawn as bare triangles would cover each wholly or not at all).
  EXPECT_GT(edge, 40) << edge;
}

TEST(ShapeFrames, AWorldsBoxBodyIsDrawnTurnedAboutItsCentreOfMass) {
  // A box 2 x 0.5 m whose centre sits 0.5 m along its body's x axis from the body's origin,
  // the origin at (0, 0) turned 90°: its centre of mass (World::x, y) is at (0, 0.5) and it
  // covers x in [-0.25, 0.25], y in [-0.5, 1.5].
  World sim(WorldDef::empty(Precision::f64, WorldSettings{}));
  BodyDef d;
  d.body.angle = std::numbers::pi / 2;
  // 0.5 x 2 m turned 90° in the body: 2 m along the body's x axis.
  d.shapes = {make_box(0.25, 1.0, {0.5, 0.0}, std::numbers::pi / 2)};
  d.appearance = Appearance{.color = testing::shape_red};
  const Entity e = sim.create_body(d);
  ASSERT_NEAR(sim.local_center(e).x, 0.5, 1e-12);
  RenderFrame s;
  fill_render_frame(sim, 1.0, s);
  EXPECT_FALSE(s.spin_marks);  // no rolling discs
  ASSERT_EQ(s.angle.size(), 1u);
  EXPECT_NEAR(s.angle[0], std::numbers::pi / 2, 1e-6);
  EXPECT_NEAR(s.x[0], 0.0, 1e-6);
  EXPECT_NEAR(s.y[0], 0.5, 1e-6);
  ASSERT_EQ(s.shapes.size(), 1u);
  const RenderFrame::Shape& box = s.shapes[0];
  EXPECT_EQ(box.body, 0u);
  // About the centre of mass, counter-clockwise from (-hx, -hy) turned 90°: (1, -0.25).
  ASSERT_EQ(box.count, 4u);
  EXPECT_NEAR(box.px[0], 1.0f, 1e-6f);
  EXPECT_NEAR(box.py[0], -0.25f, 1e-6f);
  EXPECT_NEAR(box.px[2], -1.0f, 1e-6f);
  EXPECT_NEAR(box.py[2], 0.25f, 1e-6f);
  EXPECT_NEAR(box.mark_x, 0.0f, 1e-6f);  // min(hx, hy) along the box's x axis (turned: y)
  EXPECT_NEAR(box.mark_y, 0.25f, 1e-6f);
  const auto r = draw_shape_frame(s);
  const Rgba8 bg = default_background;
  EXPECT_TRUE(near(at_world(*r, -0.15, 1.3), testing::shape_red, 2));
  EXPECT_TRUE(near(at_world(*r, 0.15, -0.3), testing::shape_red, 2));
  EXPECT_TRUE(near(at_world(*r, 0.0, -0.8), bg, 2));  // unturned about the origin, it would be
  EXPECT_TRUE(near(at_world(*r, 1.2, 0.0), bg, 2));   // red here
  EXPECT_TRUE(near(at_world(*r, 0.45, 0.5), bg, 2));
}

TEST(ShapeFrames, AWorldWithoutShapesFillsNoShapesAndKeepsItsSpinMarks) {
  WorldSettings settings;
  settings.contacts = ContactSettings{.rolling = true};
  World sim(WorldDef::empty(Precision::f64, settings));
  BodyDef d;
  d.collider = Collider{.radius = 0.5};
  sim.create_body(d);
  RenderFrame s;
  fill_render_frame(sim, 1.0, s);
  EXPECT_TRUE(s.shapes.empty());
  EXPECT_TRUE(s.spin_marks);
  EXPECT_EQ(s.angle.size(), 1u);
}

TEST(ShapeFrames, TheAutomaticViewIncludesEveryShape) {
  // A ground box 20 m wide (x in [-10, 10]) whose body's origin is at its left end, and a
  // capsule turned upright reaching y = 6: the view's box is x in [-10, 10], y in [-0.5, 6].
  WorldDef def = WorldDef::empty(Precision::f64, WorldSettings{});
  BodyDef ground;
  ground.type = BodyType::static_body;
  ground.body.position = {-10.0, 0.0};
  ground.shapes = {make_box(10.0, 0.5, {10.0, 0.0})};
  def.add_body(ground);
  BodyDef upright;
  upright.body.position = {0.0, 3.0};
  upright.body.angle = std::numbers::pi / 2;
  upright.shapes = {make_capsule({-2.5, 0.0}, {2.5, 0.0}, 0.5)};
  def.add_body(upright);
  const Camera c = fit_camera(def, 1600, 800);
  EXPECT_NEAR(c.center.x, 0.0, 1e-9);
  EXPECT_NEAR(c.center.y, 2.75, 1e-9);
  EXPECT_NEAR(c.width, 20.0 * 1.15, 1e-9);  // the width sets it: 6.5 m tall fits in 11.5
}

}  // namespace
}  // namespace fixstep
