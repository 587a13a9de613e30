// What every fixstep loop does with its user's events (key_bindings.hpp).
#include "fixstep/app/key_bindings.hpp"

#include <algorithm>
#include <cmath>

#include "fixstep/core/input.hpp"

namespace fixstep {

void feed(const UserEvents& ev, InputSampler& sampler, const Camera& camera, int width,
          int height) {
  for (const UserEvents::ButtonEdge& edge : ev.edges) {
    edge.press ? sampler.press(edge.buttons) : sampler.release(edge.buttons);
  }
  for (std::size_t i = 0; i < max_axes; ++i) sampler.set_axis(i, ev.axes[i]);
  if (ev.pointer_seen) {
    sampler.set_pointer(screen_to_world(camera, ev.pointer_x, ev.pointer_y, width, height));
  }
}

void apply_loop_keys(const UserEvents& ev, FixedStepLoop& loop, double max_time_scale) {
  if (ev.toggle_pause) loop.set_paused(!loop.paused());
  if (ev.single_step) {
    loop.set_paused(true);
    loop.request_single_step();
  }
  if (ev.time_scale_steps != 0) {
    loop.set_time_scale(std::clamp(loop.time_scale() * std::pow(2.0, ev.time_scale_steps),
                                   1.0 / 16.0, max_time_scale));
  }
}

Vec2 arrow_push(std::uint32_t held, double view_width) {
  const double a = 0.5 * view_width;
  auto axis = [&](std::uint32_t plus, std::uint32_t minus) {
    return (held & plus ? a : 0.0) - (held & minus ? a : 0.0);
  };
  return {axis(button_right, button_left), axis(button_up, button_down)};
}

}  // namespace fixstep
