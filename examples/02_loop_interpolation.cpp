// The accumulator loop of "Fix Your Timestep!" at a deliberately low tick rate (10 ticks/s)
// under 60 frames/s: what each frame draws, frame by frame, with and without interpolation.
// Without it a frame shows the last tick's state, which holds for 6 frames and then jumps (the
// stutter); with it a frame shows lerp(previous tick, current tick, alpha), alpha =
// accumulator / dt, which is smooth (one tick behind).
//
//   02_loop_interpolation [OUT.png]
#include <cstdio>
#include <exception>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/loop.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/render/render.hpp>
#include <string>
#include <vector>

namespace {

constexpr int width = 800, height = 450, frames = 90;  // 1.5 s at 60 frames/s

/// Draws the drawn positions x (m, in [-1, 1]) of every frame as a curve of dots in the band
/// [top, top + band) px, with a title.
void panel(fixstep::Renderer& r, const std::vector<float>& x, float top, float band,
           const std::string& title, fixstep::Rgba8 color) {
  r.text(24.0f, top, title, 2.0f, {235, 235, 235, 255});
  const float y0 = top + 30.0f, h = band - 50.0f, left = 40.0f, step = (width - 80.0f) / frames;
  r.line(left, y0 + 0.5f * h, width - 40.0f, y0 + 0.5f * h, 1.0f, {70, 80, 95, 255});
  std::vector<fixstep::Renderer::PolylinePoint> curve;
  for (std::size_t f = 0; f < x.size(); ++f) {
    const float px = left + step * static_cast<float>(f), py = y0 + 0.5f * h * (1.0f - x[f]);
    curve.push_back({px, py, {color.r, color.g, color.b, 120}});
  }
  r.polyline(curve, 1.5f);
  for (const auto& p : curve) r.disc(p.x, p.y, 3.0f, color);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fixstep;
  const std::string png = argc > 1 ? argv[1] : "02_loop_interpolation.png";
  try {
    // A 1 kg bob on a spring k = 4π² N/m (1 Hz), released 1 m from its anchor.
    World sim(WorldDef::empty(Precision::f64,
                              WorldSettings{.dt = 0.1}));  // s: 10 ticks per second, on purpose
    BodyDef bob;
    bob.body = Body{.mass = 1.0, .position = {1.0, 0.0}, .velocity = {}};
    bob.spring = SpringDamper{.anchor = {}, .stiffness = 4.0 * 3.14159265358979 * 3.14159265358979};
    sim.create_body(bob);
    sim.set_keep_previous(true);  // keep the last tick's positions for interpolation

    FixedStepLoop loop(sim);  // ticks of the world's dt
    const VirtualClock clock(60.0);
    std::vector<float> x(1), y(1);    // the drawn position, m
    std::vector<float> held, smooth;  // the bob's drawn x in each frame
    for (int frame = 0; frame < frames; ++frame) {
      if (frame > 0)
        loop.advance(clock.frame_seconds(), {}, [&](const TickInput& in) { sim.step(in); });
      sim.interpolate_positions(1.0, x, y);  // alpha = 1: the current tick, as is
      held.push_back(x[0]);
      sim.interpolate_positions(loop.alpha(), x, y);  // between the last two ticks
      smooth.push_back(x[0]);
    }

    Renderer r(width, height);
    r.begin({18, 22, 30, 255});
    panel(r, held, 16.0f, 215.0f, "no interpolation: each tick held for 6 frames",
          {230, 87, 46, 255});
    panel(r, smooth, 231.0f, 215.0f, "interpolated by alpha = accumulator / dt",
          {90, 220, 200, 255});
    r.text(24.0f, height - 20.0f, "x of a 1 Hz spring, drawn each frame (60 frames/s, 10 ticks/s)",
           1.5f, {150, 160, 175, 255});
    r.finish();
    write_png(png, width, height, r.pixels());
    std::printf("%llu ticks in %d frames; wrote %s\n", static_cast<unsigned long long>(sim.tick()),
                frames, png.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "02_loop_interpolation: %s\n", e.what());
    return 1;
  }
  return 0;
}
