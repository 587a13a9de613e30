// A camera that follows a body: a ball thrown along a 120 m level bounces off the ground past a
// row of posts, and the view, 16 m wide, keeps it at the centre of the frame
// (Session::follow). Trails are kept in metres, so the ball's trail is its path through the
// level, not a smear at the centre of the screen.
//
//   07_camera_follow [OUT.png]
#include <cstdio>
#include <exception>
#include <fixstep/capture.hpp>
#include <fixstep/session.hpp>
#include <string>

int main(int argc, char** argv) {
  using namespace fixstep;
  const std::string png = argc > 1 ? argv[1] : "07_camera_follow.png";
  try {
    WorldDef world;
    world.settings = {.dt = 1.0 / 120.0};
    world.planes.push_back(PlaneDef{.normal = {0.0, 1.0},
                                    .offset = 0.0,
                                    .restitution = 0.75,
                                    .friction = 0.2});  // the ground, y = 0
    BodyDef ball;
    ball.name = "ball";
    ball.body = Body{.mass = 0.5, .position = {0.0, 1.0}, .velocity = {11.0, 9.0}};  // m, m/s
    ball.gravity = Gravity{.acceleration = {0.0, -9.81}};                            // m/s²
    ball.collider = Collider{.radius = 0.4};
    ball.appearance = Appearance{.radius = 0.4, .color = {76, 175, 240, 255}};
    world.bodies.push_back(ball);
    for (int post = 1; post <= 24; ++post) {  // static markers every 5 m, to see the level move
      BodyDef p;
      p.type = BodyType::static_body;
      p.body.position = {5.0 * post, 0.25};
      p.appearance = Appearance{.radius = 0.25, .color = {250, 200, 60, 255}};
      world.bodies.push_back(p);
    }

    Session session(world, SessionSettings{.width = 640, .height = 360, .title = "camera follow"});
    session.set_view({0.0, 3.0}, 16.0);  // m: 40 px per m
    session.follow(session.simulation().find("ball"));
    const VirtualClock clock(60.0);
    for (int frame = 1; frame <= 150; ++frame) {  // 2.5 s: the ball some 25 m down the level
      session.advance(clock.frame_seconds());
      session.draw();  // every frame: the view moves with the ball, trails grow
    }
    write_png(png, 640, 360, session.renderer().pixels());
    const Body b = session.simulation().body(session.followed());
    std::printf("ball at x = %.2f m, y = %.2f m; view centre x = %.2f m\nwrote %s\n", b.position.x,
                b.position.y, session.view().center.x, png.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "07_camera_follow: %s\n", e.what());
    return 1;
  }
  return 0;
}
