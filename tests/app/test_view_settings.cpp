// The scene's [view] look (background, grid, axes, scale_bar, hud, hud_scale, hud_lines, joints):
// parsed into SceneView, refused with file:line:column and the key, and applied to a Session's
// settings (scene_view_settings.hpp) and so to its frames.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "fixstep/app/scene_view_settings.hpp"
#include "fixstep/app/session.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "pixels.hpp"

namespace fixstep {
namespace view_settings_tests {

const std::string body =
    "[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, 0.0]\nradius = 0.5\n";

Scene scene_with_view(const std::string& view) {
  return parse_scene(body + "[view]\n" + view, "view.toml");
}

std::string error_of(const std::string& view) {
  try {
    (void)scene_with_view(view);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneViewStyle, EveryKeyIsReadAndAbsentKeysStayUnset) {
  const Scene s = scene_with_view(
      "background = \"#102030\"\ngrid = false\naxes = true\nscale_bar = false\n"
      "hud = \"bottom_right\"\nhud_scale = 1.5\nhud_lines = [\"time\", \"energy\"]\n");
  ASSERT_TRUE(s.view.background);
  EXPECT_EQ(*s.view.background, (Rgba8{16, 32, 48, 255}));
  EXPECT_EQ(s.view.grid, false);
  EXPECT_EQ(s.view.axes, true);
  EXPECT_EQ(s.view.scale_bar, false);
  EXPECT_EQ(s.view.hud, SceneHud::bottom_right);
  EXPECT_EQ(s.view.hud_scale, 1.5);
  EXPECT_EQ(s.view.hud_lines, scene_hud_time | scene_hud_energy);
  const Scene plain = scene_with_view("width = 10.0\n");
  EXPECT_FALSE(plain.view.background || plain.view.grid || plain.view.axes ||
               plain.view.scale_bar || plain.view.hud || plain.view.hud_scale ||
               plain.view.hud_lines);
  EXPECT_EQ(scene_with_view("hud_lines = []\n").view.hud_lines, 0u);
  EXPECT_EQ(scene_with_view("hud = \"off\"\n").view.hud, SceneHud::off);
}

TEST(SceneViewStyle, BadValuesAreRefusedAtTheirKey) {
  // [view] is on line 7: its keys from line 8 on.
  EXPECT_EQ(error_of("background = \"#12\"\n"),
            "view.toml:8:14: view.background: expected \"#rrggbb\" or \"#rrggbbaa\", found "
            "\"#12\"");
  EXPECT_EQ(error_of("grid = 1\n"),
            "view.toml:8:8: view.grid: expected true or false, found an "
            "integer (1)");
  EXPECT_EQ(error_of("axes = \"yes\"\n"),
            "view.toml:8:8: view.axes: expected true or false, found a string (\"yes\")");
  EXPECT_EQ(error_of("scale_bar = 2.0\n"),
            "view.toml:8:13: view.scale_bar: expected true or false, found a float (2.0)");
  EXPECT_EQ(error_of("hud = \"middle\"\n"),
            "view.toml:8:7: view.hud: expected \"top_left\", \"top_right\", \"bottom_left\", "
            "\"bottom_right\" or \"off\", found \"middle\"");
  EXPECT_EQ(error_of("hud = true\n"),
            "view.toml:8:7: view.hud: expected a string, found a boolean (true)");
  EXPECT_EQ(error_of("hud_scale = 5\n"),
            "view.toml:8:13: view.hud_scale: must be 1 .. 4 (px per font pixel) (got 5)");
  EXPECT_EQ(error_of("hud_scale = \"2\"\n"),
            "view.toml:8:13: view.hud_scale: expected a number, found a string (\"2\"); write the "
            "number without quotes: 2");
  EXPECT_EQ(error_of("hud_lines = \"title\"\n"),
            "view.toml:8:13: view.hud_lines: expected an array of line names (\"title\", "
            "\"time\", \"integrator\", \"energy\" or \"controls\"), found a string (\"title\")");
  EXPECT_EQ(error_of("hud_lines = [\"title\", \"tick\"]\n"),
            "view.toml:8:23: view.hud_lines[1]: expected \"title\", \"time\", \"integrator\", "
            "\"energy\" or \"controls\", found \"tick\"");
  EXPECT_EQ(error_of("hud_lines = [\"title\", \"title\"]\n"),
            "view.toml:8:23: view.hud_lines[1]: \"title\" is named twice");
  EXPECT_EQ(error_of("hud_lines = [3]\n"),
            "view.toml:8:14: view.hud_lines[0]: expected a string, found an integer (3)");
}

TEST(SceneViewStyle, AppliedToASessionItShapesTheFrame) {
  const Scene s = scene_with_view(
      "center = [0.0, 0.0]\nwidth = 10.0\nbackground = \"#c8c8c8\"\ngrid = false\naxes = "
      "false\nscale_bar = false\nhud = \"bottom_left\"\nhud_scale = 1\nhud_lines = [\"time\"]\n");
  SessionSettings settings{
      .width = 200, .height = 100, .view_center = s.view.center, .view_width = s.view.width};
  apply_scene_view_style(s.view, settings);
  EXPECT_EQ(settings.style.background, (Rgba8{200, 200, 200, 255}));
  EXPECT_FALSE(settings.style.grid || settings.style.axes || settings.style.scale_bar);
  EXPECT_EQ(settings.hud_corner, HudCorner::bottom_left);
  EXPECT_TRUE(settings.show_hud);
  EXPECT_EQ(settings.hud_text_scale, 1.0f);
  EXPECT_EQ(settings.hud_lines, unsigned(hud_time));
  Session session(s.def, settings);
  session.draw();
  const Renderer& r = session.renderer();
  EXPECT_TRUE(testing::near(testing::at(r, 190, 5), Rgba8{200, 200, 200, 255}, 0));
  EXPECT_TRUE(testing::near(testing::at(r, 11, 5), Rgba8{200, 200, 200, 255}, 0));  // not top
  EXPECT_LT(testing::at(r, 11, 89).r, 120);  // the one-line panel, bottom left

  SessionSettings off;
  apply_scene_view_style(scene_with_view("hud = \"off\"\n").view, off);
  EXPECT_FALSE(off.show_hud);
}

TEST(SceneViewStyle, JointsAreDrawnAsTheViewSays) {
  EXPECT_FALSE(scene_with_view("width = 10.0\n").view.joints);
  const std::pair<const char*, JointView> cases[] = {
      {"off", JointView::off}, {"anchors", JointView::anchors}, {"limits", JointView::limits}};
  for (const auto& [name, view] : cases) {
    const Scene s = scene_with_view(std::string("joints = \"") + name + "\"\n");
    ASSERT_TRUE(s.view.joints) << name;
    SessionSettings settings;
    EXPECT_EQ(settings.style.joints, JointView::anchors) << "the default";
    apply_scene_view_style(s.view, settings);
    EXPECT_EQ(settings.style.joints, view) << name;
  }
  EXPECT_EQ(error_of("joints = \"all\"\n"),
            "view.toml:8:10: view.joints: expected \"off\", \"anchors\" or \"limits\", found "
            "\"all\"");
  EXPECT_EQ(error_of("joints = true\n"),
            "view.toml:8:10: view.joints: expected a string, found a boolean (true)");
}

}  // namespace view_settings_tests
}  // namespace fixstep
