// A minimal window: the frame pipeline (Session) presented in an SDL2 window at the real
// clock, the loop keys of every fixstep window (space pause, '.' single tick, +/- time scale),
// Esc or the close button to quit. The window shows the very pixels headless capture writes.
//
//   06_window                       until closed
//   06_window FRAMES OUT.png        FRAMES frames on a virtual 60 Hz clock, then the last frame
//                                   as a PNG (how CI runs it, under xvfb-run)
#include <chrono>
#include <cstdio>
#include <exception>
#include <fixstep/app/session.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/window/window.hpp>
#include <optional>
#include <string>
#include <thread>

#include "fixstep/io/summary.hpp"

int main(int argc, char** argv) {
  using namespace fixstep;
  const long frames = argc > 1 ? std::stol(argv[1]) : 0;  // 0: until the window is closed
  const std::string png = argc > 2 ? argv[2] : "";
  try {
    WorldDef world;
    world.settings = {.dt = 0.01};
    BodyDef bob;
    bob.body = Body{.mass = 1.0, .position = {3.0, -1.0}, .velocity = {0.0, 1.0}};
    bob.spring = SpringDamper{.anchor = {0.0, -1.0}, .stiffness = 12.0, .damping = 0.2};
    bob.appearance = Appearance{.radius = 0.4, .color = {230, 87, 46, 255}};
    world.bodies.push_back(bob);

    Window window("fixstep - 06_window", 640, 360);
    Session session(world, SessionSettings{.width = 640,
                                           .height = 360,
                                           .title = "06_window",
                                           .view_center = Vec2{0.0, 0.8},
                                           .view_width = 10.0});
    session.set_show_controls(true);
    RealClock real;
    std::optional<VirtualClock> virtual_clock;
    if (frames > 0) virtual_clock.emplace(60.0);
    for (long frame = 0; frames == 0 || frame < frames; ++frame) {
      const auto start = std::chrono::steady_clock::now();
      const WindowEvents ev = window.poll();
      if (ev.quit) break;
      apply_loop_keys(ev, session.loop());
      if (ev.restart) session.restart();
      const double seconds = virtual_clock ? virtual_clock->frame_seconds() : real.frame_seconds();
      if (frame > 0) session.advance(seconds);
      session.draw();
      window.present(session.renderer().pixels());
      if (!virtual_clock) std::this_thread::sleep_until(start + std::chrono::milliseconds(16));
    }
    if (!png.empty()) write_png(png, 640, 360, session.renderer().pixels());
    std::printf("driver=%s %s\n", window.driver().c_str(),
                summary_line(session.simulation(), session.initial_energy()).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "06_window: %s\n", e.what());
    return 1;
  }
  return 0;
}
