// The scene view's colours and sizes, shared by render_frame.cpp (bodies, springs, grid),
// render_trails.cpp and render_hud.cpp. Internal.
#pragma once

#include <algorithm>
#include <cstddef>
#include <iterator>

#include "fixstep/render/frame_data.hpp"

namespace fixstep::scene_palette {

inline constexpr Rgba8 grid_minor{32, 37, 48, 255};
inline constexpr Rgba8 grid_axis{62, 70, 90, 255};
inline constexpr Rgba8 spring_color{170, 180, 200, 255};
inline constexpr Rgba8 link_color{170, 180, 200, 200};
inline constexpr Rgba8 anchor_color{120, 130, 150, 255};
inline constexpr Rgba8 outline{8, 10, 14, 255};
inline constexpr Rgba8 text_color{235, 238, 245, 255};
inline constexpr Rgba8 panel{0, 0, 0, 150};
inline constexpr Rgba8 palette[] = {
    {230, 87, 46, 255},   {76, 175, 240, 255},  {250, 200, 60, 255}, {120, 210, 110, 255},
    {200, 120, 230, 255}, {240, 140, 170, 255}, {90, 220, 200, 255}, {240, 240, 240, 255}};
inline constexpr Rgba8 plane_solid{120, 132, 160, 60};
inline constexpr Rgba8 plane_line{150, 162, 190, 255};
inline constexpr float default_radius_px = 9.0f;
inline constexpr float min_radius_px = 3.0f;
inline constexpr float outline_px = 1.5f;      // bodies' outline, beyond their radius
inline constexpr float anchor_half_px = 5.0f;  // anchors are squares of twice this side

inline constexpr Rgba8 sleep_grey{128, 132, 140, 255};
// Joints (render_joints.cpp): light marks edged in `outline`, to read over bodies of any colour;
// their limits in a warm red.
inline constexpr Rgba8 joint_color{245, 248, 255, 255};
inline constexpr Rgba8 joint_limit_color{255, 96, 80, 255};

/// Body j's colour: `own` (a shape's colour) unless its alpha is 0, else its Appearance's, or
/// a palette colour without one (alpha 0); halfway to sleep_grey while it sleeps
/// (RenderFrame::asleep).
inline Rgba8 body_color(const RenderFrame& s, std::size_t j, Rgba8 own = {0, 0, 0, 0}) {
  const Rgba8 c = own.a != 0          ? own
                  : s.color[j].a == 0 ? palette[j % std::size(palette)]
                                      : s.color[j];
  if (s.asleep.empty() || s.asleep[j] == 0) return c;
  auto mid = [](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>((unsigned(a) + unsigned(b) + 1u) / 2u);
  };
  return Rgba8{mid(c.r, sleep_grey.r), mid(c.g, sleep_grey.g), mid(c.b, sleep_grey.b), c.a};
}

/// Bodies are outlined discs of the body's radius (at least min_radius_px; `scale` px per m),
/// drawn last: what the other shapes draw right below a disc's centre or an anchor is hidden
/// (Renderer::hidden_under_disc), and they stop short there.
inline float body_radius_px(const RenderFrame& s, std::size_t j, double scale) {
  return s.radius[j] > 0.0f ? std::max(float(s.radius[j] * scale), min_radius_px)
                            : default_radius_px;
}

/// Whether body j is drawn (RenderFrame::visible; a frame without flags draws every body).
inline bool body_visible(const RenderFrame& s, std::size_t j) {
  return s.visible.empty() || s.visible[j] != 0;
}

}  // namespace fixstep::scene_palette
