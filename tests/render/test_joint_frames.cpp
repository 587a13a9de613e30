// Joints in the scene view (RenderFrame::joints, ViewStyle::joints): what fill_render_frame takes
// of each (anchors and axis at the frame's moment, type, limits), the marks and limits drawn
// where they belong, nothing for a broken joint or with JointView::off.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "fixstep/core/joint.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/render/frame_data.hpp"
#include "fixstep/render/render.hpp"
#include "fixstep/scene/scene.hpp"
#include "pixels.hpp"
#include "scene_palette.hpp"

namespace fixstep {
namespace {

using testing::at;
using testing::near;

/// A rod (a 2 m x 0.2 m box from x = 0 to 2, with `rod_keys`) on a hinge to the world at the
/// origin with limits [-1, 0.5] rad, and `more` (TOML) after it.
std::string hinge_scene(const std::string& rod_keys, const std::string& more = "") {
  return "[world]\ndt = 0.01\n[[body]]\nname = \"rod\"\nposition = [1.0, 0.0]\n" + rod_keys +
         "\n"
         "shape = { box = [1.0, 0.1], density = 1.0 }\ncolor = \"#ff0000\"\n"
         "[[joint]]\ntype = \"revolute\"\nbody_b = \"rod\"\nanchor = [0.0, 0.0]\n"
         "lower = -1.0\nupper = 0.5\nname = \"a hinge with a name longer than a short string\"\n" +
         more;
}

World world_of(const std::string& text) {
  return World(parse_scene(text, "joints.toml").def);
}

/// Draws `s` on 320 x 200 px, 10 m wide on the origin (32 px per m; the origin on the corner of
/// pixels (159, 99) and (160, 100)), no grid, axes or scale bar, joints as `joints` says.
std::unique_ptr<Renderer> draw_with_joints(const RenderFrame& s, JointView joints) {
  auto r = std::make_unique<Renderer>(320, 200);
  r->set_camera(Camera{.center = {0, 0}, .width = 10.0});
  r->set_view_style(ViewStyle{.grid = false, .axes = false, .scale_bar = false, .joints = joints});
  r->draw(s, {});
  return r;
}

TEST(JointFrames, AFrameTakesEachJointsAnchorsTypeAndLimits) {
  World w = world_of(hinge_scene("gravity = [0.0, -9.81]", R"(
[[body]]
name = "slider"
position = [0.0, 3.0]
gravity = [0.0, -9.81]
shape = { box = [0.3, 0.2], density = 1.0 }
[[joint]]
type = "prismatic"
body_b = "slider"
anchor = [0.0, 3.0]
axis = [3.0, -4.0]
upper = 1.0
)"));
  RenderFrame s;
  fill_render_frame(w, 1.0, s);
  ASSERT_EQ(s.joints.size(), 2u);
  for (int t = 0; t < 20; ++t) w.step();
  fill_render_frame(w, 1.0, s);
  ASSERT_EQ(s.joints.size(), 2u);
  const RenderFrame::JointMark& hinge = s.joints[0];
  const RenderFrame::JointMark& slider = s.joints[1];
  EXPECT_EQ(hinge.joint, w.joints()[0]);
  EXPECT_EQ(hinge.type, JointType::revolute);
  EXPECT_EQ(hinge.body_a, RenderFrame::JointMark::world);
  EXPECT_EQ(s.ids[hinge.body_b], w.find("rod"));
  EXPECT_TRUE(hinge.has_lower && hinge.has_upper);
  EXPECT_EQ(hinge.lower, -1.0f);
  EXPECT_EQ(hinge.upper, 0.5f);
  EXPECT_EQ(slider.type, JointType::prismatic);
  EXPECT_FALSE(slider.has_lower);
  EXPECT_TRUE(slider.has_upper);
  EXPECT_EQ(slider.upper, 1.0f);
  EXPECT_FALSE(slider.rope);
  // At alpha 1 the frame is the tick: the anchors and axis are JointState's.
  for (std::size_t i = 0; i < 2; ++i) {
    const JointState st = w.joint_state(w.joints()[i]);
    const RenderFrame::JointMark& m = s.joints[i];
    EXPECT_NEAR(m.ax, st.anchor_a.x, 1e-5);
    EXPECT_NEAR(m.ay, st.anchor_a.y, 1e-5);
    EXPECT_NEAR(m.bx, st.anchor_b.x, 1e-5);
    EXPECT_NEAR(m.by, st.anchor_b.y, 1e-5);
    EXPECT_NEAR(m.axis_x, st.axis.x, 1e-6);
    EXPECT_NEAR(m.axis_y, st.axis.y, 1e-6);
    EXPECT_NEAR(m.value, st.value, 1e-6);
  }
  EXPECT_NEAR(slider.axis_x, 0.6, 1e-6);
  EXPECT_NEAR(slider.axis_y, -0.8, 1e-6);
  // The hinge's angle 0 lies where the rod pointed at the start (+x, the world's frame: A is
  // the world), and zero_angle + sense · value points at the rod's centre now.
  EXPECT_NEAR(hinge.zero_angle, 0.0, 1e-5);
  EXPECT_EQ(hinge.sense, 1.0f);
  const std::uint32_t rod = hinge.body_b;
  EXPECT_NEAR(hinge.zero_angle + hinge.sense * hinge.value,
              std::atan2(s.y[rod] - hinge.by, s.x[rod] - hinge.bx), 1e-5);
  EXPECT_LT(hinge.value, -0.1) << "the rod has swung down under gravity";
}

TEST(JointFrames, AnEndOnABodyMovesWithItBetweenTicks) {
  World w = world_of(hinge_scene("",
                                 "[[body]]\nname = \"anchor\"\nposition = [0.0, 3.0]\n"
                                 "gravity = [0.0, -9.81]\nshape = { circle = 0.2, density = 1.0 }\n"
                                 "[[joint]]\ntype = \"distance\"\nbody_a = \"anchor\"\n"
                                 "body_b = \"rod\"\nanchor_b = [2.0, 0.0]\nupper = 4.0\n"));
  w.set_keep_previous(true);
  for (int t = 0; t < 10; ++t) w.step();
  RenderFrame s;
  fill_render_frame(w, 0.5, s);
  ASSERT_EQ(s.joints.size(), 2u);
  const RenderFrame::JointMark& rope = s.joints[1];
  EXPECT_TRUE(rope.rope);
  // The rope's end on the rod keeps its distance from the rod's drawn centre, and its end on
  // the falling disc sits on the disc's drawn centre (its anchor), half a tick back.
  const JointState st = w.joint_state(w.joints()[1]);
  const Entity rod_e = w.find("rod");
  const Body rod = w.body(rod_e);
  const double c = std::cos(rod.angle), sn = std::sin(rod.angle);
  const Vec2 lc = w.local_center(rod_e);
  const Vec2 centre{rod.position.x + c * lc.x - sn * lc.y, rod.position.y + sn * lc.x + c * lc.y};
  const std::uint32_t j = rope.body_b;
  EXPECT_NEAR(std::hypot(rope.bx - s.x[j], rope.by - s.y[j]),
              std::hypot(st.anchor_b.x - centre.x, st.anchor_b.y - centre.y), 1e-5);
  EXPECT_NEAR(rope.ax, s.x[rope.body_a], 1e-5);
  EXPECT_NEAR(rope.ay, s.y[rope.body_a], 1e-5);
  EXPECT_GT(rope.ay, st.anchor_a.y) << "half a tick before the tick, the disc was higher";
}

TEST(JointFrames, AWorldWithoutJointsHasNone) {
  World w(parse_scene("[world]\ndt = 0.01\n[[body]]\nposition = [0.0, 0.0]\nmass = 1.0\n"
                      "shape = { circle = 0.5 }\n",
                      "plain.toml")
              .def);
  RenderFrame s;
  fill_render_frame(w, 1.0, s);
  EXPECT_TRUE(s.joints.empty());
}

TEST(JointFrames, MarksAndLimitsAreDrawnWhereTheyBelong) {
  World w = world_of(hinge_scene(""));  // no gravity: the rod stays level
  RenderFrame s;
  fill_render_frame(w, 1.0, s);
  const auto off = draw_with_joints(s, JointView::off);
  const auto anchors = draw_with_joints(s, JointView::anchors);
  const auto limits = draw_with_joints(s, JointView::limits);
  // The ring round the hinge (5 px), left of the rod: the background without joints.
  const Rgba8 bg = default_background;
  EXPECT_TRUE(near(at(*off, 155, 99), bg, 2));
  EXPECT_TRUE(near(at(*anchors, 155, 99), scene_palette::joint_color, 40));
  EXPECT_TRUE(near(at(*limits, 155, 99), scene_palette::joint_color, 40));
  // The limits' arc (22 px) at -0.5 rad, below the rod: only when the limits are asked for.
  const int ax = int(160 + 22 * std::cos(-0.5)), ay = int(100 + 22 * std::sin(0.5));
  EXPECT_TRUE(near(at(*anchors, ax, ay), bg, 2));
  EXPECT_TRUE(near(at(*limits, ax, ay), scene_palette::joint_limit_color, 60));
  // Away from the joint the three frames are the same.
  EXPECT_TRUE(near(at(*limits, 250, 150), bg, 0));
  EXPECT_EQ(
      std::vector<std::uint8_t>(off->pixels().begin(), off->pixels().begin() + 4 * 320 * 40),
      std::vector<std::uint8_t>(limits->pixels().begin(), limits->pixels().begin() + 4 * 320 * 40));
}

TEST(JointFrames, ABrokenJointIsNotDrawn) {
  World w =
      world_of(hinge_scene("",
                           "[[body]]\nname = \"weight\"\nposition = [-2.0, 2.0]\n"
                           "gravity = [0.0, -9.81]\nshape = { circle = 0.3, density = 1.0 }\n"
                           "[[joint]]\ntype = \"weld\"\nbody_b = \"weight\"\nanchor = [-2.0, 2.5]\n"
                           "break_force = 0.001\n"));
  w.step();
  ASSERT_TRUE(w.joint_state(w.joints()[1]).broken);
  RenderFrame s;
  fill_render_frame(w, 1.0, s);
  ASSERT_EQ(s.joints.size(), 2u);
  EXPECT_TRUE(s.joints[1].broken);
  EXPECT_FALSE(s.joints[0].broken);
  // The weld's ring would be round (-2, 2.5) m: px (96, 20). Drawn as without the joint.
  RenderFrame without = s;
  without.joints.pop_back();
  const auto a = draw_with_joints(s, JointView::limits),
             b = draw_with_joints(without, JointView::limits);
  EXPECT_TRUE(std::equal(a->pixels().begin(), a->pixels().end(), b->pixels().begin()));
}

}  // namespace
}  // namespace fixstep
