// Two projectiles thrown alike (1 kg, 20 m/s at 55°), one in vacuum and one with linear drag
// c = 0.4 N·s/m, stepped by semi-implicit Euler at dt = 1/20 s. The lines are the exact paths
// (a parabola; with drag, x = x0 + v0 τ (1 - e^{-t/τ}), τ = m/c, and y likewise with the
// terminal speed g τ: Taylor, Classical Mechanics §2.2-2.3); the dots are the ticks.
//
//   04_projectile_drag [OUT.png]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/exact.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/render/render.hpp>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace fixstep;
  const std::string png = argc > 1 ? argv[1] : "04_projectile_drag.png";
  constexpr int width = 800, height = 450;
  constexpr double dt = 1.0 / 20.0, duration = 3.2;  // s
  try {
    std::vector<BodyDef> throws(2);
    for (BodyDef& d : throws) {
      d.body = Body{.mass = 1.0,
                    .position = {-16.0, -6.0},
                    .velocity = {20.0 * std::cos(0.96), 20.0 * std::sin(0.96)}};
      d.gravity = Gravity{.acceleration = {0.0, -9.81}};  // m/s²
    }
    throws[1].drag = LinearDrag{.coefficient = 0.4};  // N·s/m
    const Rgba8 colors[] = {{76, 175, 240, 255}, {250, 200, 60, 255}};
    const char* names[] = {"vacuum", "drag c = 0.4 N*s/m"};

    World sim(WorldDef::empty(Precision::f64, WorldSettings{.dt = dt}));
    for (const BodyDef& d : throws) sim.create_body(d);
    std::vector<std::vector<Vec2>> ticks(2);
    double worst[2] = {0.0, 0.0};
    for (int n = 0; n * dt <= duration + 1e-9; ++n) {
      if (n > 0) sim.step();
      for (std::size_t i = 0; i < 2; ++i) {
        const Vec2 p = sim.body(sim.bodies()[i]).position,
                   q = exact::solve(throws[i], sim.time())->position;
        ticks[i].push_back(p);
        worst[i] = std::max(worst[i], std::hypot(p.x - q.x, p.y - q.y));
      }
    }

    Renderer r(width, height);
    r.set_camera(Camera{.center = {1.0, 2.0}, .width = 44.0});
    r.begin({18, 22, 30, 255});
    for (std::size_t i = 0; i < 2; ++i) {
      std::vector<Renderer::PolylinePoint> path;
      for (int s = 0; s <= 400; ++s) {
        const Vec2 q = exact::solve(throws[i], duration * s / 400.0)->position;
        const auto [px, py] = r.to_pixel(q.x, q.y);
        path.push_back({static_cast<float>(px), static_cast<float>(py), colors[i]});
      }
      r.polyline(path, 2.0f);
      for (const Vec2 p : ticks[i]) {
        const auto [px, py] = r.to_pixel(p.x, p.y);
        r.disc(static_cast<float>(px), static_cast<float>(py), 4.0f, {235, 235, 235, 255});
      }
      char label[120];
      std::snprintf(label, sizeof label, "%s: largest error %.2f m", names[i], worst[i]);
      r.text(20.0f, 20.0f + 28.0f * i, label, 2.0f, colors[i]);
    }
    r.text(20.0f, height - 30.0f,
           "lines: exact paths   dots: ticks of semi-implicit Euler, dt = 1/20 s", 1.5f,
           {150, 160, 175, 255});
    r.finish();
    write_png(png, width, height, r.pixels());
    std::printf("largest error: vacuum %.4f m, drag %.4f m; wrote %s\n", worst[0], worst[1],
                png.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "04_projectile_drag: %s\n", e.what());
    return 1;
  }
  return 0;
}
