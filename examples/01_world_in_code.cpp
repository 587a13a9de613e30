// A world built in code: bodies and springs as definitions (BodyDef, WorldDef), stepped at a
// fixed dt, its state read back, one frame drawn through the same Session the CLI uses.
//
//   01_world_in_code [OUT.png]
#include <cmath>
#include <cstdio>
#include <exception>
#include <fixstep/capture.hpp>
#include <fixstep/session.hpp>
#include <string>

#include "fixstep/summary.hpp"

int main(int argc, char** argv) {
  using namespace fixstep;
  const std::string png = argc > 1 ? argv[1] : "01_world_in_code.png";
  try {
    WorldDef world;
    world.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
    // Three bobs on springs of the same stiffness k = 40 N/m and rising damping b (N·s/m):
    // damping ratio ζ = b / (2 sqrt(k m)) = 0, 0.2 and 1 (critical).
    const double zetas[] = {0.0, 0.2, 1.0};
    const Rgba8 colors[] = {{230, 87, 46, 255}, {250, 200, 60, 255}, {90, 220, 200, 255}};
    for (int i = 0; i < 3; ++i) {
      const double m = 1.0, k = 40.0, y = 2.0 - 3.5 * i;
      BodyDef bob;
      bob.name = "zeta_" + std::to_string(i);
      bob.body = Body{.mass = m, .position = {7.0, y}, .velocity = {}};
      bob.spring = SpringDamper{
          .anchor = {0.0, y}, .stiffness = k, .damping = zetas[i] * 2.0 * std::sqrt(k * m)};
      bob.appearance = Appearance{.radius = 0.7, .color = colors[i]};
      world.bodies.push_back(bob);
    }
    // A ball thrown across them under gravity (m/s²).
    BodyDef ball;
    ball.name = "ball";
    ball.body = Body{.mass = 0.5, .position = {-10.0, -8.0}, .velocity = {6.0, 11.0}};
    ball.gravity = Gravity{.acceleration = {0.0, -9.81}};
    ball.appearance = Appearance{.radius = 0.5, .color = {76, 175, 240, 255}};
    world.bodies.push_back(ball);

    // The frame pipeline: loop, interpolation, renderer. 1.2 s of 60 Hz frames.
    Session session(world, SessionSettings{.width = 640,
                                           .height = 360,
                                           .title = "world in code",
                                           .view_center = Vec2{0.0, 0.5},
                                           .view_width = 26.0});
    const VirtualClock clock(60.0);
    for (int frame = 1; frame <= 72; ++frame) session.advance(clock.frame_seconds());
    session.draw();
    write_png(png, 640, 360, session.renderer().pixels());

    // The state, read back: body i in creation order.
    const World& sim = session.simulation();
    for (std::size_t i = 0; i < sim.body_count(); ++i) {
      const Body b = sim.body(sim.bodies()[i]);
      std::printf("%-8s x = %7.3f m  y = %7.3f m\n", sim.name(sim.bodies()[i]).c_str(),
                  b.position.x, b.position.y);
    }
    std::printf("%s\nwrote %s\n", summary_line(sim, session.initial_energy()).c_str(), png.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "01_world_in_code: %s\n", e.what());
    return 1;
  }
  return 0;
}
