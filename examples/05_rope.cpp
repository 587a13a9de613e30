// A rope: 16 bodies joined by spring-dampers between bodies (links), pinned at one end to an
// anchored spring, released horizontally under gravity. Links join the handles WorldDef::add_body
// returns, the same form a scene's [[chain]] produces. The rope is a game with no rules, run by
// fixstep::app::run, which checks the level (the stability guard: it would name the stiffest
// link and the substeps that are stable), and gives it the window, headless frames, recording
// and replay.
//
//   05_rope --frames 48 --last-frame OUT.png    0.8 s headless: the rope halfway down its swing
//   05_rope                                     in a window
//   05_rope --help                              the rest
#include <fixstep/app/app.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>
#include <vector>

namespace {

using namespace fixstep;

struct Rope {
  void setup(WorldDef& level) {
    constexpr int count = 16;
    constexpr double spacing = 0.5, mass = 0.1;  // m, kg per body
    level.settings = {.dt = 1.0 / 240.0, .integrator = Integrator::semi_implicit_euler};
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
      rope.push_back(level.add_body(b));
    }
    // Each link: k = 500 N/m, b = 0.5 N·s/m, rest length = the spacing, so the rope stretches
    // only under load; stable for semi-implicit Euler at this dt.
    for (std::size_t i = 0; i + 1 < rope.size(); ++i) {
      level.add_link(rope[i], rope[i + 1],
                     {.stiffness = 500.0, .damping = 0.5, .rest_length = spacing});
    }
  }
  void rules(World&, const TickInput&) {}  // the rope only falls
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(Rope{},
                  {.name = "05_rope",
                   .description = "a rope of 16 linked bodies, pinned at one end, released",
                   .width = 640,
                   .height = 360,
                   .view_center = Vec2{3.2, -1.0},
                   .view_width = 13.0,
                   .show_energy = true},
                  argc, argv);
}
