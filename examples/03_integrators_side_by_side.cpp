// The six integrators on one undamped spring (1 kg, 1 Hz) at a coarse step, ω·dt = 0.21:
// each strip plots the bob's x over 4 s (its colour) on the exact solution (grey), with the
// largest error and the energy after 4 s relative to the start. Explicit Euler gains energy
// every step, implicit Euler loses it, the symplectic methods keep it bounded, RK4 is close.
//
//   03_integrators_side_by_side [OUT.png]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/exact.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/render/render.hpp>
#include <string>
#include <vector>

namespace {

constexpr int width = 900, height = 600, ticks = 120;  // 4 s of dt = 1/30 s
constexpr double dt = 1.0 / 30.0, k = 4.0 * 3.141592653589793 * 3.141592653589793;

/// One strip: curves of x (m, |x| <= 1.6 shown) against t in the band [top, top + h) px.
void strip(fixstep::Renderer& r, float top, float h, const std::vector<double>& exact,
           const std::vector<double>& x, fixstep::Rgba8 color, const std::string& label) {
  const float left = 250.0f, right = width - 20.0f, mid = top + 0.5f * h;
  auto point = [&](std::size_t i, double v, fixstep::Rgba8 c) {
    const float px = left + (right - left) * static_cast<float>(i) / ticks;
    return fixstep::Renderer::PolylinePoint{px, mid - 0.5f * h * static_cast<float>(v / 1.6), c};
  };
  std::vector<fixstep::Renderer::PolylinePoint> grey, mine;
  for (std::size_t i = 0; i < x.size(); ++i) {
    grey.push_back(point(i, exact[i], {120, 125, 135, 255}));
    mine.push_back(point(i, x[i], color));
  }
  r.set_clip(fixstep::Renderer::ClipRect{static_cast<int>(left), static_cast<int>(top),
                                         static_cast<int>(right), static_cast<int>(top + h)});
  r.line(left, mid, right, mid, 1.0f, {55, 62, 75, 255});
  r.polyline(grey, 3.0f);
  r.polyline(mine, 2.0f);
  r.set_clip(std::nullopt);
  r.text(16.0f, top + 0.5f * h - 14.0f, label, 1.6f, color);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fixstep;
  const std::string png = argc > 1 ? argv[1] : "03_integrators_side_by_side.png";
  const Rgba8 colors[] = {{230, 87, 46, 255},  {250, 200, 60, 255},  {90, 220, 200, 255},
                          {76, 175, 240, 255}, {200, 120, 230, 255}, {150, 230, 90, 255}};
  try {
    BodyDef bob;
    bob.body = Body{.mass = 1.0, .position = {1.0, 0.0}, .velocity = {}};
    bob.spring = SpringDamper{.anchor = {}, .stiffness = k};
    std::vector<double> exact;
    for (int i = 0; i <= ticks; ++i) exact.push_back(exact::solve(bob, i * dt)->position.x);

    Renderer r(width, height);
    r.begin({18, 22, 30, 255});
    const float band = (height - 40.0f) / 6.0f;
    int row = 0;
    for (const Integrator method : all_integrators) {
      World world(WorldDef::empty(Precision::f64, WorldSettings{.dt = dt, .integrator = method}));
      const Entity body = world.create_body(bob);
      const double e0 = world.energy().total();
      std::vector<double> x{world.body(body).position.x};
      double worst = 0.0;
      for (int i = 1; i <= ticks; ++i) {
        world.step();
        x.push_back(world.body(body).position.x);
        worst = std::max(worst, std::abs(x.back() - exact[i]));
      }
      char label[160];
      std::snprintf(label, sizeof label, "%s\nmax error %.3g m\nE/E0 = %.3f",
                    std::string(integrator_name(method)).c_str(), worst,
                    world.energy().total() / e0);
      strip(r, 10.0f + band * row, band - 8.0f, exact, x, colors[row], label);
      std::printf("%-20s max error %.3e m  E/E0 = %.4f\n",
                  std::string(integrator_name(method)).c_str(), worst, world.energy().total() / e0);
      ++row;
    }
    r.text(250.0f, height - 24.0f, "x(t), 0 to 4 s, dt = 1/30 s; grey: exact", 1.5f,
           {150, 160, 175, 255});
    r.finish();
    write_png(png, width, height, r.pixels());
    std::printf("wrote %s\n", png.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "03_integrators_side_by_side: %s\n", e.what());
    return 1;
  }
  return 0;
}
