// hello_fixstep: the smallest complete fixstep program. A world built in code (no scene file)
// goes through the same frame pipeline as `fixstep render`: a fixed-step accumulator loop,
// interpolation, the OSMesa renderer and PNG capture. Start a prototype by copying this file.
//
//   build/release/bin/hello_fixstep [OUT_DIR]     (default: hello_frames)
#include <cstdio>
#include <exception>
#include <fixstep/app/session.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/world_def.hpp>
#include <string>

#include "fixstep/io/summary.hpp"

int main(int argc, char** argv) {
  using namespace fixstep;
  const std::string out = argc > 1 ? argv[1] : "hello_frames";
  try {
    // 1. A world stepped at dt = 1/100 s with semi-implicit Euler, in double precision.
    WorldDef world;
    world.settings = {.dt = 0.01, .integrator = Integrator::semi_implicit_euler};

    // 2. A 1 kg bob on a spring (k = 15 N/m, b = 0.1 N*s/m) anchored at the origin...
    BodyDef bob;
    bob.name = "bob";
    bob.body = Body{.mass = 1.0, .position = {8.0, 0.0}, .velocity = {0.0, 0.0}};
    bob.spring = SpringDamper{.anchor = {0.0, 0.0}, .stiffness = 15.0, .damping = 0.1};
    bob.appearance = Appearance{.radius = 0.6, .color = {230, 87, 46, 255}};
    world.bodies.push_back(bob);

    // ...and a ball thrown at 12 m/s, 60 degrees up, under gravity with a little drag.
    BodyDef ball;
    ball.name = "ball";
    ball.body = Body{.mass = 0.5, .position = {-12.0, -6.0}, .velocity = {6.0, 10.39}};
    ball.gravity = Gravity{.acceleration = {0.0, -9.81}};
    ball.drag = LinearDrag{.coefficient = 0.05};
    ball.appearance = Appearance{.radius = 0.4, .color = {76, 175, 240, 255}};
    world.bodies.push_back(ball);

    // 3. The frame pipeline: 640x360 frames of a view 32 m wide centred on the origin.
    Session session(world, SessionSettings{.width = 640,
                                           .height = 360,
                                           .title = "hello_fixstep",
                                           .view_center = Vec2{0.0, 0.0},
                                           .view_width = 32.0});
    prepare_output_dir(out);
    FrameWriter writer(out, 640, 360);  // encodes PNGs on a worker thread

    // 4. "Fix Your Timestep!": frames of exactly 1/60 s feed the accumulator, which runs whole
    //    ticks of dt; each frame draws the state interpolated by alpha.
    const VirtualClock clock(60.0);
    for (int frame = 0; frame < 90; ++frame) {
      if (frame > 0) session.advance(clock.frame_seconds());
      session.draw();
      writer.submit(session.renderer().pixels());
    }
    writer.finish();
    std::printf("wrote 90 frames to %s/ (%s)\n", out.c_str(),
                summary_line(session.simulation(), session.initial_energy()).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hello_fixstep: %s\n", e.what());
    return 1;
  }
  return 0;
}
