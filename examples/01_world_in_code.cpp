// A world built in code: bodies and springs as definitions (BodyDef in a WorldDef), stepped at
// a fixed dt and drawn. The world is a game without rules, run by fixstep::app::run, which
// gives it the window, headless frames, recording, replay and --help.
//
//   01_world_in_code --frames 73 --last-frame OUT.png    1.2 s headless, the last frame
//   01_world_in_code                                     in a window
#include <cmath>
#include <fixstep/app/app.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>

namespace {

using namespace fixstep;

struct WorldInCode {
  void setup(WorldDef& level) {
    level.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
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
      level.add_body(bob);
    }
    // A ball thrown across them under gravity (m/s²).
    BodyDef ball;
    ball.name = "ball";
    ball.body = Body{.mass = 0.5, .position = {-10.0, -8.0}, .velocity = {6.0, 11.0}};
    ball.gravity = Gravity{.acceleration = {0.0, -9.81}};
    ball.appearance = Appearance{.radius = 0.5, .color = {76, 175, 240, 255}};
    level.add_body(ball);
  }
  void rules(World&, const TickInput&) {}  // nothing happens but the physics
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(WorldInCode{},
                  {.name = "01_world_in_code",
                   .description = "three damped springs and a thrown ball, built in code",
                   .width = 640,
                   .height = 360,
                   .view_center = Vec2{0.0, 0.5},
                   .view_width = 26.0,
                   .show_energy = true},
                  argc, argv);
}
