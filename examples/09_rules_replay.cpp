// Rules in replay: a game whose rule runs after every tick (a ball that rolls off the right
// edge is put back at the top left, and counted). fixstep::app::run runs the rule live, in a
// replay and in the sync test alike, so a recording of the game replays with every state hash
// verified; a build whose rule differs (edit the edge and rebuild) diverges, and --replay exits
// 4 naming the first tick.
//
//   09_rules_replay --frames 361 --record rules.rec     6 s headless, recorded
//   09_rules_replay --replay rules.rec --last-frame OUT.png
//                                                       re-simulated with the rule, verified
//   09_rules_replay --frames 361 --sync-test 8          every tick rolled back 8 ticks
#include <array>
#include <fixstep/app/app.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <string>

namespace {

using namespace fixstep;

constexpr double edge = 8.5;    // m: past it a ball has fallen off
const Vec2 respawn{-7.0, 5.0};  // m

struct Respawns {
  int respawns = 0;  // the rule's state: kept in the game, so copied, saved and restored
  std::array<Entity, 3> balls{};

  void setup(WorldDef& level) {
    level.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
    level.settings.contacts = ContactSettings{.restitution = 0.6, .friction = 0.0};
    const Rgba8 colors[3] = {{230, 70, 60, 255}, {250, 200, 60, 255}, {90, 160, 230, 255}};
    for (int i = 0; i < 3; ++i) {
      BodyDef b;
      b.name = "ball" + std::to_string(i);
      b.body = Body{.mass = 1.0, .position = {-6.0 + 2.5 * i, 3.0 + i}, .velocity = {}};
      b.gravity = Gravity{};
      b.collider = Collider{.radius = 0.4};
      b.appearance = Appearance{.radius = 0.4, .color = colors[i]};
      balls[i] = level.add_body(b);
    }
    // A slope falling to the right: n = (0.25, 1) normalised, through (0, 0).
    level.planes.push_back(
        {.normal = {0.25, 1.0}, .offset = 0, .restitution = 0.3, .friction = 0.1});
  }

  // The rule: a ball past the edge starts again from the top left, at rest.
  void rules(World& world, const TickInput&) {
    for (const Entity e : balls) {
      if (world.body(e).position.x <= edge) continue;
      world.set_position(e, respawn);
      world.set_velocity(e, {});
      ++respawns;
    }
  }

  // The player: an upward kick (impulse, N·s) for one of the three balls every 1.5 s.
  void prepare(TickInput& in, const World&) const {
    if (in.tick % 180 == 90) {
      in.bodies.push_back({balls[in.tick / 180 % 3], BodyInputKind::impulse, {1.0, 5.0}});
    }
  }
  void draw(app::Overlay& overlay) const { overlay.text("respawns: " + std::to_string(respawns)); }
  [[nodiscard]] std::string summary() const { return "respawns=" + std::to_string(respawns); }
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(Respawns{},
                  {.name = "09_rules_replay",
                   .description = "balls respawned by a rule that a replay runs too",
                   .width = 640,
                   .height = 360,
                   .view_center = Vec2{0.0, 1.5},
                   .view_width = 19.0},
                  argc, argv);
}
