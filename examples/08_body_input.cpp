// Per-body input: what a player does to one body, given as that tick's input (TickInput::
// bodies, through an InputSampler) so that a recording carries it. A kinematic paddle moved by
// velocity input knocks a ball along the ground; a thruster force lifts a ship for one second;
// an impulse kicks a ball up (Δv = J/m).
//
//   08_body_input [OUT.png]
#include <cstdio>
#include <exception>
#include <fixstep/capture.hpp>
#include <fixstep/session.hpp>
#include <string>

#include "fixstep/summary.hpp"

namespace {

using namespace fixstep;

constexpr double g = 9.81;                          // m/s²
constexpr double ship_mass = 2.0, kick_mass = 0.5;  // kg
constexpr Vec2 kick_impulse{0.6, 3.5};              // N·s: Δv = (1.2, 7) m/s on 0.5 kg

BodyDef disc(const char* name, BodyType type, double mass, Vec2 at, double r, Rgba8 color) {
  BodyDef b;
  b.name = name;
  b.type = type;
  b.body = Body{.mass = mass, .position = at, .velocity = {}};
  if (type == BodyType::dynamic) b.gravity = Gravity{{0.0, -g}};
  b.collider = Collider{.radius = r};
  b.appearance = Appearance{.radius = r, .color = color};
  return b;
}

WorldDef world() {
  WorldDef def;
  def.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
  def.settings.contacts = ContactSettings{.restitution = 0.5, .friction = 0.0};
  def.bodies = {
      disc("paddle", BodyType::kinematic, 1.0, {-7.0, 0.6}, 0.6, {90, 160, 230, 255}),
      disc("ball", BodyType::dynamic, 1.0, {-5.0, 0.35}, 0.35, {230, 70, 60, 255}),
      disc("ship", BodyType::dynamic, ship_mass, {1.0, 0.5}, 0.5, {250, 200, 60, 255}),
      disc("kick", BodyType::dynamic, kick_mass, {4.5, 0.3}, 0.3, {120, 200, 110, 255}),
  };
  def.planes.push_back({.normal = {0, 1}, .offset = 0, .restitution = 0.3, .friction = 0.1});
  return def;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string png = argc > 1 ? argv[1] : "08_body_input.png";
  try {
    Session session(world(), SessionSettings{.width = 640,
                                             .height = 360,
                                             .title = "per-body input",
                                             .view_center = Vec2{0.0, 3.5},
                                             .view_width = 17.0});
    session.set_show_engine_hud(false);  // the status lines only
    const World& sim = session.simulation();
    const Entity paddle = sim.find("paddle"), ship = sim.find("ship"), kick = sim.find("kick");
    InputSampler sampler;
    const VirtualClock clock(60.0);
    for (int frame = 1; frame <= 96; ++frame) {  // 1.6 s
      session.advance_with(clock.frame_seconds(), [&](std::uint64_t t, World& s) {
        if (t == 0) sampler.set_velocity(paddle, {3.0, 0.0});  // m/s, kept until changed
        if (t == 80) sampler.set_velocity(paddle, {0.0, 0.0});
        if (t == 20) sampler.set_force(ship, {0.0, 1.3 * ship_mass * g});  // N, held
        if (t == 140) sampler.set_force(ship, {0.0, 0.0});                 // released
        if (t == 30) sampler.apply_impulse(kick, kick_impulse);            // N·s, once
        s.step(sampler.sample(t));
      });
      session.set_status_lines({"blue: velocity input 3 m/s (kinematic), ticks 0-79",
                                "yellow: thruster force 1.3 m g, ticks 20-139",
                                "green: impulse (0.6, 3.5) N s at tick 30: dv = J/m"});
      session.draw();  // every frame, so the trails show the paths
    }
    write_png(png, 640, 360, session.renderer().pixels());
    const Body b = sim.body(sim.find("ball")), s = sim.body(ship);
    std::printf("ball v = (%.3f, %.3f) m/s, ship y = %.3f m\n%s\nwrote %s\n", b.velocity.x,
                b.velocity.y, s.position.y, summary_line(sim, session.initial_energy()).c_str(),
                png.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "08_body_input: %s\n", e.what());
    return 1;
  }
  return 0;
}
