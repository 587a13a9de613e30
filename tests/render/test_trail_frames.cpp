// Trails keyed by body handle, drawn: creating and destroying bodies in any order never joins
// two unrelated bodies with a line, while a steadily moving body keeps its trail.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/render/render.hpp"
#include "fixstep/render/trails.hpp"
#include "pixels.hpp"

namespace fixstep {
namespace {
// --- drawn: no streak between a destroyed body and a new one ------------------------------------

using testing::at;
using testing::Rgb;

// A trail's colour over the dark background: one channel well above another (the background
// and the grid are near grey: their channels differ by at most 28).
bool coloured(Rgb c) {
  return std::max({c.r, c.g, c.b}) - std::min({c.r, c.g, c.b}) > 40;
}

constexpr int frame_w = 400, frame_h = 200;  // 20 m wide: 20 px per m, origin at (200, 100)
constexpr double px_per_m = 20.0;
using testing::red;
constexpr Rgba8 blue{40, 80, 255, 255}, green{0, 255, 0, 255};

BodyDef body_at(Vec2 p, Rgba8 color, Vec2 v = {}) {
  BodyDef d;
  d.body.position = p;
  d.body.velocity = v;
  d.appearance = Appearance{.radius = 0.4, .color = color};  // 8 px
  return d;
}

// How one frame replaces bodies: destroy `gone`, create `born` (in either order).
enum class Order { destroy_first, create_first };

/// Draws 30 frames of a world with a green body moving right along y = -3.5 m (its trail must
/// be drawn) and the `gone` bodies resting, then one frame after the `gone` bodies were
/// destroyed and the `born` bodies created, in `order`. Returns the number of coloured pixels
/// outside the discs of the bodies alive in the last frame and outside the green body's path,
/// and sets `green_trail` to the coloured pixels along that path.
int streak_pixels(const std::vector<Vec2>& gone, const std::vector<Vec2>& born, Order order,
                  int& green_trail) {
  Renderer r(frame_w, frame_h);
  r.set_camera(Camera{.center = {0, 0}, .width = frame_w / px_per_m});
  World sim(WorldDef::empty(Precision::f64, WorldSettings{.dt = 1.0 / 60}));
  sim.create_body(body_at({-8.0, -3.5}, green, {4.0, 0.0}));  // 1.33 px per frame
  std::vector<Entity> old;
  for (const Vec2 p : gone) old.push_back(sim.create_body(body_at(p, blue)));
  RenderFrame s;
  for (int f = 0; f < 30; ++f) {
    sim.step();
    fill_render_frame(sim, 1.0, s);
    r.draw(s, {});
  }
  auto destroy = [&] {
    for (const Entity e : old) sim.destroy(e);
  };
  auto create = [&] {
    for (const Vec2 p : born) sim.create_body(body_at(p, red));
  };
  if (order == Order::destroy_first) destroy(), create();
  if (order == Order::create_first) create(), destroy();
  sim.step();
  fill_render_frame(sim, 1.0, s);
  r.draw(s, {});

  int stray = 0;
  green_trail = 0;
  const double gx = s.x[0], gy = s.y[0];
  for (int y = 0; y < frame_h; ++y) {
    for (int x = 0; x < frame_w; ++x) {
      if (!coloured(at(r, x, y))) continue;
      bool on_a_body = false;
      for (std::size_t j = 0; j < s.x.size(); ++j) {
        const auto p = r.to_pixel(s.x[j], s.y[j]);
        on_a_body |= std::hypot(x + 0.5 - p[0], y + 0.5 - p[1]) < 8.0 + 1.5 + 2.0;
      }
      const auto g = r.to_pixel(gx, gy);
      const bool on_green_path = std::abs(y + 0.5 - g[1]) < 3.0 && x + 0.5 < g[0];
      green_trail += on_green_path && !on_a_body;
      stray += !on_a_body && !on_green_path;
    }
  }
  return stray;
}

TEST(Trails, DestroyingAndCreatingInOneFrameDrawsNoStreak) {
  // Body A rests at (-5, 2.5) m; in one frame it is destroyed and body B created at (5, 2.5) m:
  // 200 px apart. Keyed by dense index (the old renderer), B took A's trail and a line joined
  // them across the frame.
  for (const Order order : {Order::destroy_first, Order::create_first}) {
    SCOPED_TRACE(order == Order::destroy_first ? "destroy, then create" : "create, then destroy");
    int green_trail = 0;
    EXPECT_EQ(streak_pixels({{-5.0, 2.5}}, {{5.0, 2.5}}, order, green_trail), 0);
    EXPECT_GT(green_trail, 30);  // the steady body's trail is drawn: ~40 px long
  }
}

TEST(Trails, ReplacingSeveralBodiesInOneFrameDrawsNoStreak) {
  for (const Order order : {Order::destroy_first, Order::create_first}) {
    SCOPED_TRACE(order == Order::destroy_first ? "destroy, then create" : "create, then destroy");
    int green_trail = 0;
    EXPECT_EQ(streak_pixels({{-7.0, 2.5}, {-3.0, 0.5}, {0.5, 3.5}},
                            {{7.0, 0.5}, {3.0, 3.5}, {5.5, -1.5}}, order, green_trail),
              0);
    EXPECT_GT(green_trail, 30);
  }
}

}  // namespace
}  // namespace fixstep
