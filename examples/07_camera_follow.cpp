// A camera that follows a body: a ball thrown along a 120 m level bounces off the ground past a
// row of posts, and the view, 16 m wide, keeps it at the centre of the frame (app::Settings'
// follow, Session::follow underneath). Trails are kept in metres, so the ball's trail is its
// path through the level, not a smear at the centre of the screen. A game with no rules, run by
// fixstep::app::run.
//
//   07_camera_follow --frames 151 --last-frame OUT.png   2.5 s headless: some 25 m down the level
//   07_camera_follow                                     in a window
//   07_camera_follow --help                              the rest
#include <fixstep/app/app.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>

namespace {

using namespace fixstep;

struct BouncingBall {
  void setup(WorldDef& level) {
    level.settings = {.dt = 1.0 / 120.0};
    level.planes.push_back(PlaneDef{.normal = {0.0, 1.0},
                                    .offset = 0.0,
                                    .restitution = 0.75,
                                    .friction = 0.2});  // the ground, y = 0
    BodyDef ball;
    ball.name = "ball";
    ball.body = Body{.mass = 0.5, .position = {0.0, 1.0}, .velocity = {11.0, 9.0}};  // m, m/s
    ball.gravity = Gravity{.acceleration = {0.0, -9.81}};                            // m/s²
    ball.collider = Collider{.radius = 0.4};
    ball.appearance = Appearance{.radius = 0.4, .color = {76, 175, 240, 255}};
    level.bodies.push_back(ball);
    for (int post = 1; post <= 24; ++post) {  // static markers every 5 m, to see the level move
      BodyDef p;
      p.type = BodyType::static_body;
      p.body.position = {5.0 * post, 0.25};
      p.appearance = Appearance{.radius = 0.25, .color = {250, 200, 60, 255}};
      level.bodies.push_back(p);
    }
  }
  void rules(World&, const TickInput&) {}  // the ball only flies and bounces
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(BouncingBall{},
                  {.name = "07_camera_follow",
                   .description = "a ball bouncing along a long level, the view following it",
                   .width = 640,
                   .height = 360,
                   .view_center = Vec2{0.0, 3.0},  // m: where the view starts, 40 px per m
                   .view_width = 16.0,
                   .follow = "ball"},
                  argc, argv);
}
