// A test game whose rules are not deterministic across peers, as a game's bug would make them:
// they read the environment. With DESYNC_GAME_NUDGE set, after tick 95 they nudge the second
// disc's vx by 1e-9 m/s, so a peer started with it desyncs from one started without it at
// tick 96 (tests/net_desync.sh). Three discs crossing a box; no input.
#include <cstdlib>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/net_app/run.hpp>

namespace {

using namespace fixstep;

struct DesyncGame {
  bool nudge = std::getenv("DESYNC_GAME_NUDGE") != nullptr;

  void setup(WorldDef& level) {
    level.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
    level.settings.contacts = ContactSettings{.restitution = 0.9, .friction = 0.0};
    const char* names[] = {"left", "puck", "right"};
    for (int i = 0; i < 3; ++i) {
      BodyDef b;
      b.name = names[i];
      b.body = Body{.mass = 1.0, .position = {-2.0 + 2.0 * i, 0.5 * i}, .velocity = {1.0, -0.7}};
      b.collider = Collider{.radius = 0.3};
      level.add_body(b);
    }
    for (const Vec2 n : {Vec2{1, 0}, Vec2{-1, 0}, Vec2{0, 1}, Vec2{0, -1}}) {
      level.planes.push_back({.normal = n, .offset = -4.0, .restitution = 0.9});
    }
  }
  void rules(World& world, const TickInput& input) {
    if (!nudge || input.tick != 95) return;
    const Entity puck = world.find("puck");
    const Vec2 v = world.body(puck).velocity;
    world.set_velocity(puck, {v.x + 1e-9, v.y});
  }
  void autopilot(std::int64_t, const World&, InputSampler&) {}
};

}  // namespace

int main(int argc, char** argv) {
  return net::run(DesyncGame{},
                  {.name = "desync_game",
                   .description = "a test game that desyncs on purpose",
                   .width = 320,
                   .height = 320,
                   .view_center = Vec2{0.0, 0.0},
                   .view_width = 9.0},
                  argc, argv);
}
