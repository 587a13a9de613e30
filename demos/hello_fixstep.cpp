// hello_fixstep: the smallest complete fixstep program — a world built in code (no scene
// file), stepped at a fixed dt by the accumulator loop, captured headless as PNG frames.
// Start a prototype by copying this file.
//
//   build/release/bin/hello_fixstep [OUT_DIR]     (default: hello_frames)
#include <cstdio>
#include <string>
#include <vector>

#include <fixstep/capture.hpp>
#include <fixstep/loop.hpp>
#include <fixstep/render.hpp>
#include <fixstep/simulation.hpp>
#include <fmt/format.h>

int main(int argc, char** argv) {
  using namespace fixstep;
  const std::string out = argc > 1 ? argv[1] : "hello_frames";
  try {
    // 1. A world stepped at dt = 1/100 s with semi-implicit Euler, in double precision.
    const WorldSettings settings{.dt = 0.01, .integrator = Integrator::semi_implicit_euler};
    Simulation sim(Precision::f64, settings);

    // 2. A 1 kg bob on a spring (k = 15 N/m, b = 0.1 N*s/m) anchored at the origin...
    BodyDef bob;
    bob.name = "bob";
    bob.body = Body{.mass = 1.0, .position = {8.0, 0.0}, .velocity = {0.0, 0.0}};
    bob.spring = SpringDamper{.anchor = {0.0, 0.0}, .stiffness = 15.0, .damping = 0.1};
    bob.appearance = Appearance{.radius = 0.6, .color = {230, 87, 46, 255}};
    sim.create_body(bob);

    // ...and a ball thrown at 12 m/s, 60 degrees up, under gravity with a little drag.
    BodyDef ball;
    ball.name = "ball";
    ball.body = Body{.mass = 0.5, .position = {-12.0, -6.0}, .velocity = {6.0, 10.39}};
    ball.gravity = Gravity{.acceleration = {0.0, -9.81}};
    ball.drag = LinearDrag{.coefficient = 0.05};
    ball.appearance = Appearance{.radius = 0.4, .color = {76, 175, 240, 255}};
    sim.create_body(ball);
    sim.set_keep_previous(true);  // keep the last tick's positions for interpolation

    // 3. The renderer (OSMesa) and a camera 32 m wide centred on the origin.
    Renderer renderer(640, 360);
    renderer.set_camera(Camera{.center = {0.0, 0.0}, .width = 32.0});
    prepare_output_dir(out);

    // 4. "Fix Your Timestep!": frames of exactly 1/60 s feed the accumulator, which runs
    //    whole ticks of dt; each frame draws the state interpolated by alpha.
    FixedStepLoop loop(LoopSettings{.dt = settings.dt});
    const VirtualClock clock(60.0);
    RenderFrame drawn;
    for (int frame = 0; frame < 90; ++frame) {
      if (frame > 0) loop.advance(clock.frame_seconds(), {}, [&](const TickInput& in) { sim.step(in); });
      sim.fill_render_frame(loop.alpha(), drawn);
      const std::vector<std::string> hud = {
          fmt::format("hello_fixstep   tick {}   t = {:.2f} s", sim.tick(), sim.time()),
          fmt::format("energy {:.3f} J", sim.energy().total())};
      renderer.draw(drawn, hud);
      write_png(frame_path(out, frame), renderer.width(), renderer.height(), renderer.pixels());
    }
    fmt::print("wrote 90 frames to {}/ (ticks={}, t={:.2f} s)\n", out, sim.tick(), sim.time());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hello_fixstep: %s\n", e.what());
    return 1;
  }
  return 0;
}
