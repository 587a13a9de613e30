// Per-body input: what a player does to one body, given as that tick's input (TickInput::bodies)
// so that a recording carries it. A kinematic paddle moved by velocity input knocks a ball along
// the ground; a thruster force lifts a ship for one second; an impulse kicks a ball up
// (Δv = J/m). The script is the game's prepare(), which fixstep::app::run calls before each live
// tick; a replay steps the recorded input.
//
//   08_body_input --frames 96 --last-frame OUT.png    1.6 s headless
//   08_body_input --frames 96 --record input.rec      ... recorded; --replay input.rec verifies
//   08_body_input --help                              the rest
#include <fixstep/app/app.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <string>

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

struct BodyInputs {
  Entity paddle = null_entity, ship = null_entity,
         kick = null_entity;  // the handles the world gives them (WorldDef::add_body)

  void setup(WorldDef& level) {
    level.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
    level.settings.contacts = ContactSettings{.restitution = 0.5, .friction = 0.0};
    paddle = level.add_body(
        disc("paddle", BodyType::kinematic, 1.0, {-7.0, 0.6}, 0.6, {90, 160, 230, 255}));
    level.add_body(disc("ball", BodyType::dynamic, 1.0, {-5.0, 0.35}, 0.35, {230, 70, 60, 255}));
    ship = level.add_body(
        disc("ship", BodyType::dynamic, ship_mass, {1.0, 0.5}, 0.5, {250, 200, 60, 255}));
    kick = level.add_body(
        disc("kick", BodyType::dynamic, kick_mass, {4.5, 0.3}, 0.3, {120, 200, 110, 255}));
    level.planes.push_back({.normal = {0, 1}, .offset = 0, .restitution = 0.3, .friction = 0.1});
  }
  void rules(World&, const TickInput&) {}

  // The player's script, by tick: velocity (m/s, kept until changed), force (N, this tick),
  // impulse (N·s, once).
  void prepare(TickInput& in, const World&) const {
    const std::uint64_t t = in.tick;
    if (t == 0) in.bodies.push_back({paddle, BodyInputKind::velocity, {3.0, 0.0}});
    if (t == 80) in.bodies.push_back({paddle, BodyInputKind::velocity, {0.0, 0.0}});
    if (t >= 20 && t < 140) {
      in.bodies.push_back({ship, BodyInputKind::force, {0.0, 1.3 * ship_mass * g}});
    }
    if (t == 30) in.bodies.push_back({kick, BodyInputKind::impulse, kick_impulse});
  }
  void draw(app::Overlay& overlay) const {
    overlay.text("blue: velocity input 3 m/s (kinematic), ticks 0-79");
    overlay.text("yellow: thruster force 1.3 m g, ticks 20-139");
    overlay.text("green: impulse (0.6, 3.5) N s at tick 30: dv = J/m");
  }
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(BodyInputs{},
                  {.name = "08_body_input",
                   .description = "velocity, force and impulse input on single bodies",
                   .width = 640,
                   .height = 360,
                   .view_center = Vec2{0.0, 3.5},
                   .view_width = 17.0},
                  argc, argv);
}
