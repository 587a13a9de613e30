// Hand-filled RenderFrames of bodies with shapes (RenderFrame::Shape), shared by the render
// tests (test_shape_frames.cpp) and the shapes' golden frame (test_golden_frames.cpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <numbers>

#include "fixstep/core/types.hpp"
#include "fixstep/render/frame_data.hpp"

namespace fixstep::testing {

/// Adds a body at (x, y) m turned by `angle` rad, of colour `color` (alpha 0: the palette's),
/// and returns its entry.
inline std::uint32_t add_shaped_body(RenderFrame& s, float x, float y, float angle, Rgba8 color) {
  s.x.push_back(x);
  s.y.push_back(y);
  s.ids.push_back(Entity{static_cast<std::uint32_t>(s.x.size()), 1});
  s.radius.push_back(0.0f);
  s.color.push_back(color);
  s.angle.push_back(angle);
  return static_cast<std::uint32_t>(s.x.size() - 1);
}

/// A shape of body `body` through `points` (body-local, relative to its centre of mass, m),
/// radius `radius` m; its mark at the first point, or for a circle on its rim along +x.
inline void add_shape(RenderFrame& s, std::uint32_t body, std::initializer_list<Vec2> points,
                      float radius) {
  RenderFrame::Shape shape;
  shape.body = body;
  shape.radius = radius;
  for (const Vec2 p : points) {
    shape.px[shape.count] = float(p.x);
    shape.py[shape.count] = float(p.y);
    ++shape.count;
  }
  shape.mark_x = shape.px[0] + (shape.count == 1 ? radius : 0.0f);
  shape.mark_y = shape.py[0];
  s.shapes.push_back(shape);
}

/// A box of half-extents hx, hy (m) centred on its body's centre of mass, rounded by
/// `rounding` m, its vertices counter-clockwise from (-hx, -hy) (b2MakeBox's order) and its
/// mark min(hx, hy) along its +x axis (fill_render_frame's: a square's reaches its side, a
/// long box's stays as short).
inline void add_box(RenderFrame& s, std::uint32_t body, float hx, float hy, float rounding = 0) {
  add_shape(s, body, {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}}, rounding);
  s.shapes.back().mark_x = hx < hy ? hx : hy;
  s.shapes.back().mark_y = 0.0f;
}

/// Pure colours of the shape tests' bodies.
inline constexpr Rgba8 shape_red{255, 0, 0, 255};
inline constexpr Rgba8 shape_green{0, 255, 0, 255};
inline constexpr Rgba8 shape_blue{0, 0, 255, 255};
inline constexpr Rgba8 shape_yellow{255, 255, 0, 255};

/// Four bodies on a 10 m wide view centred on the origin: a box 2 x 0.5 m turned 45° at
/// (-3, 1.5) (red), a capsule from (-0.75, 0) to (0.75, 0) of radius 0.3 m at (0, 1.5) (green),
/// the triangle (0, 0), (1.2, 0), (0, 1.2) less its centroid at (3, 1.5) (blue) and a box
/// 1.5 x 1 m rounded by 0.25 m at (0, -1.5) (yellow).
inline RenderFrame shape_test_frame() {
  RenderFrame s;
  add_box(s, add_shaped_body(s, -3.0f, 1.5f, std::numbers::pi_v<float> / 4, shape_red), 1.0f,
          0.25f);
  add_shape(s, add_shaped_body(s, 0.0f, 1.5f, 0.0f, shape_green), {{-0.75, 0}, {0.75, 0}}, 0.3f);
  add_shape(s, add_shaped_body(s, 3.0f, 1.5f, 0.0f, shape_blue),
            {{-0.4, -0.4}, {0.8, -0.4}, {-0.4, 0.8}}, 0.0f);
  add_box(s, add_shaped_body(s, 0.0f, -1.5f, 0.0f, shape_yellow), 0.75f, 0.5f, 0.25f);
  return s;
}

/// Every kind of shape in the scene view's own colours for the golden frame (640 x 360 px, a
/// view 16 m wide centred on (0, 1)): a ground box, a stack of boxes one turned, one asleep
/// (greyed), capsules standing and lying, a circle with its mark, a rounded pentagon, a thin
/// sharp triangle, a body of two shapes (an L of two boxes at poses of their own), beside a
/// plain disc, a rolling-style disc without mark (spin_marks off) and a spring to a shape.
inline RenderFrame shape_card_frame() {
  RenderFrame s;
  s.spin_marks = false;
  const Rgba8 palette{0, 0, 0, 0};
  const auto ground = add_shaped_body(s, 0.0f, -1.5f, 0.0f, Rgba8{120, 132, 160, 255});
  add_box(s, ground, 7.0f, 0.3f);
  add_box(s, add_shaped_body(s, -5.0f, -0.7f, 0.0f, palette), 0.5f, 0.5f);
  add_box(s, add_shaped_body(s, -5.0f, 0.3f, 0.3f, palette), 0.5f, 0.5f, 0.05f);
  const auto sleeping = add_shaped_body(s, -3.6f, -0.7f, 0.0f, Rgba8{230, 87, 46, 255});
  add_box(s, sleeping, 0.5f, 0.5f);
  add_shape(s, add_shaped_body(s, -2.0f, -0.2f, 1.2f, palette), {{-0.6, 0}, {0.6, 0}}, 0.25f);
  add_shape(s, add_shaped_body(s, -0.6f, -0.95f, 0.0f, palette), {{-0.6, 0}, {0.6, 0}}, 0.25f);
  add_shape(s, add_shaped_body(s, 1.0f, -0.5f, 2.0f, palette), {{0, 0}}, 0.6f);
  std::initializer_list<Vec2> pentagon = {
      {0.6, 0}, {0.185, 0.571}, {-0.485, 0.353}, {-0.485, -0.353}, {0.185, -0.571}};
  add_shape(s, add_shaped_body(s, 2.8f, -0.4f, 0.4f, palette), pentagon, 0.15f);
  add_shape(s, add_shaped_body(s, 4.6f, -0.6f, -0.2f, palette),
            {{-0.8, -0.2}, {0.9, -0.3}, {0, 0.6}}, 0.0f);
  const auto l_body = add_shaped_body(s, 5.5f, 2.5f, 0.6f, palette);
  add_box(s, l_body, 0.8f, 0.15f);
  add_box(s, l_body, 0.15f, 0.6f);  // then moved: the L's upright at its right end
  for (int k = 0; k < 4; ++k) {
    auto& p = s.shapes.back();
    p.px[k] += 0.65f;
    p.py[k] += 0.45f;
  }
  s.shapes.back().mark_x += 0.65f;  // (0.15, 0) + the offset
  s.shapes.back().mark_y += 0.45f;
  // Bodies without shapes: a disc and one with an angle that spin_marks off leaves unmarked.
  add_shaped_body(s, -1.0f, 3.0f, 0.0f, palette);
  s.radius.back() = 0.4f;
  add_shaped_body(s, 1.0f, 3.0f, 1.0f, palette);
  s.radius.back() = 0.4f;
  s.springs.push_back({-2.0f, 4.5f, 4});  // to the standing capsule's centre
  s.asleep.assign(s.x.size(), 0);
  s.asleep[sleeping] = 1;
  return s;
}

}  // namespace fixstep::testing
