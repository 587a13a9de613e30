// A rope: 16 bodies joined by spring-dampers between bodies (links), pinned at one end to an
// anchored spring, released horizontally under gravity. Links join the handles WorldDef::add_body
// returns, the same form a scene's [[chain]] produces; the guard is the program's explicit call.
//
//   05_rope [OUT.png]
#include <cstdio>
#include <exception>
#include <fixstep/capture.hpp>
#include <fixstep/definition_checks.hpp>
#include <fixstep/session.hpp>
#include <string>
#include <vector>

#include "fixstep/summary.hpp"

int main(int argc, char** argv) {
  using namespace fixstep;
  const std::string png = argc > 1 ? argv[1] : "05_rope.png";
  try {
    constexpr int count = 16;
    constexpr double spacing = 0.5, mass = 0.1;  // m, kg per body
    WorldDef world;
    world.settings = {.dt = 1.0 / 240.0, .integrator = Integrator::semi_implicit_euler};
    std::vector<Entity> rope;
    for (int i = 0; i < count; ++i) {
      BodyDef b;
      b.name = "rope_" + std::to_string(i);
      b.body = Body{.mass = mass, .position = {spacing * i, 0.0}, .velocity = {}};
      b.gravity = Gravity{.acceleration = {0.0, -9.81}};  // m/s²
      b.appearance = Appearance{.radius = 0.12, .color = {230, 87, 46, 255}};
      if (i == 0) {  // the pin: a stiff anchored spring at the rope's first body
        b.spring = SpringDamper{.anchor = {0.0, 0.0}, .stiffness = 2000.0, .damping = 5.0};
        b.appearance->color = {250, 200, 60, 255};
      }
      rope.push_back(world.add_body(b));
    }
    // Each link: k = 500 N/m, b = 0.5 N·s/m, rest length = the spacing, so the rope stretches
    // only under load. Stable for semi-implicit Euler at this dt: the guard checks the network
    // (it throws, naming the stiffest link and the substeps that would be stable, if not).
    for (std::size_t i = 0; i + 1 < count; ++i) {
      world.add_link(rope[i], rope[i + 1],
                     {.stiffness = 500.0, .damping = 0.5, .rest_length = spacing});
    }
    for (const std::string& w : check_definition(world)) std::printf("warning: %s\n", w.c_str());

    Session session(world, SessionSettings{.width = 640,
                                           .height = 360,
                                           .title = "rope",
                                           .view_center = Vec2{3.2, -1.0},
                                           .view_width = 13.0});
    const VirtualClock clock(60.0);
    for (int frame = 1; frame <= 48; ++frame) {  // 0.8 s: the rope halfway down its swing
      session.advance(clock.frame_seconds());
      session.draw();  // every frame, so the trails show the swing
    }
    write_png(png, 640, 360, session.renderer().pixels());
    std::printf("%s\nwrote %s\n",
                summary_line(session.simulation(), session.initial_energy()).c_str(), png.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "05_rope: %s\n", e.what());
    return 1;
  }
  return 0;
}
