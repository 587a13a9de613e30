// The HUD's lines fit the frame (layout_hud): wrapped at the gaps between their fields, then at
// their words, a word wider than a line broken, the lines past the frame's height dropped with
// "..."; a line that fits is kept as it was; and the panel drawn stays inside the frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "fixstep/render/hud_layout.hpp"
#include "fixstep/render/render.hpp"

namespace fixstep {
namespace hud_layout_test {

/// The HUD line of a networked game (net_app's MatchView::status): fields two spaces apart.
const std::string net_line =
    "player 1 of 2  rollback  tick 123456  rtt 48 ms  delay 2  window 8  rollbacks 1234 "
    "(longest 7)  stalled 12.5 s  (match over)";

constexpr HudCorner corners[] = {HudCorner::top_left, HudCorner::top_right, HudCorner::bottom_left,
                                 HudCorner::bottom_right};

/// `s` without its spaces: what must survive any wrapping.
std::string ink(const std::string& s) {
  std::string out;
  std::copy_if(s.begin(), s.end(), std::back_inserter(out), [](char c) { return c != ' '; });
  return out;
}

/// Every line's glyph box [x, x + text_width) x [y, y + text_height) and the panel inside the
/// frame, each line inside the panel.
void expect_inside(const HudLayout& hud, int width, int height, const std::string& what) {
  EXPECT_GE(hud.x0, 0.0f) << what;
  EXPECT_GE(hud.y0, 0.0f) << what;
  EXPECT_LE(hud.x1, float(width)) << what;
  EXPECT_LE(hud.y1, float(height)) << what;
  for (const HudTextLine& l : hud.lines) {
    EXPECT_GE(l.x, hud.x0) << what << ": " << l.text;
    EXPECT_GE(l.y, hud.y0) << what << ": " << l.text;
    EXPECT_LE(l.x + Renderer::text_width(l.text, hud.scale), hud.x1) << what << ": " << l.text;
    EXPECT_LE(l.y + Renderer::text_height(hud.scale), hud.y1) << what << ": " << l.text;
  }
}

/// A frame with room for the margins: the panel keeps 10 px from every edge.
void expect_margins(const HudLayout& hud, int width, int height) {
  EXPECT_GE(hud.x0, 10.0f);
  EXPECT_GE(hud.y0, 10.0f);
  EXPECT_LE(hud.x1, float(width - 10));
  EXPECT_LE(hud.y1, float(height - 10));
}

std::string joined_ink(const HudLayout& hud) {
  std::string all;
  for (const HudTextLine& l : hud.lines) all += ink(l.text);
  return all;
}

TEST(HudLayout, ALineThatFitsIsKeptWhereTheHudAlwaysDrewIt) {
  const std::string lines[] = {"score 0", "tick 150   t = 1.500 s"};
  const HudLayout hud = layout_hud(lines, 2.0f, HudCorner::top_left, 640, 360);
  ASSERT_EQ(hud.lines.size(), 2u);
  EXPECT_FALSE(hud.cut);
  EXPECT_EQ(hud.lines[0].text, "score 0");
  EXPECT_EQ(hud.lines[1].text, "tick 150   t = 1.500 s");  // its spaces as they were
  // 10 px margin, 4 font px of padding, 11 font px a line (Renderer::hud_width, hud_height).
  EXPECT_FLOAT_EQ(hud.lines[0].x, 18.0f);
  EXPECT_FLOAT_EQ(hud.lines[0].y, 18.0f);
  EXPECT_FLOAT_EQ(hud.lines[1].y, 40.0f);
  EXPECT_FLOAT_EQ(hud.x1, Renderer::hud_width(lines[1], 2.0f));
  EXPECT_FLOAT_EQ(hud.y1, Renderer::hud_height(2, 2.0f));
  EXPECT_TRUE(layout_hud({}, 2.0f, HudCorner::top_left, 640, 360).lines.empty());
}

TEST(HudLayout, TheNetworkLineWrapsAtItsFieldsInsideA640PxFrame) {
  const std::string lines[] = {"score 3 : 2", net_line};
  for (const HudCorner corner : corners) {
    const HudLayout hud = layout_hud(lines, 2.0f, corner, 640, 360);
    expect_inside(hud, 640, 360, "640x360");
    expect_margins(hud, 640, 360);
    EXPECT_FALSE(hud.cut);
    EXPECT_GE(hud.lines.size(), 3u);  // one line of it is wider than the frame
    EXPECT_EQ(joined_ink(hud), ink(lines[0]) + ink(net_line));
    // Broken only between fields: each field whole on one line.
    for (const char* field : {"player 1 of 2", "tick 123456", "rtt 48 ms",
                              "rollbacks 1234 (longest 7)", "stalled 12.5 s", "(match over)"}) {
      EXPECT_TRUE(std::any_of(hud.lines.begin(), hud.lines.end(), [&](const HudTextLine& l) {
        return l.text.find(field) != std::string::npos;
      })) << field;
    }
    for (const HudTextLine& l : hud.lines) {
      EXPECT_NE(l.text.front(), ' ') << l.text;
      EXPECT_NE(l.text.back(), ' ') << l.text;
    }
  }
}

TEST(HudLayout, ANarrowFrameWrapsAtWordsAndBreaksAWordWiderThanALine) {
  const std::string lines[] = {net_line,
                               "--scene assets/scenes/a_level_with_a_very_long_name.toml"};
  for (const float scale : {1.0f, 2.0f})
    for (const HudCorner corner : corners) {
      const HudLayout hud = layout_hud(lines, scale, corner, 160, 720);
      expect_inside(hud, 160, 720, "160x720");
      expect_margins(hud, 160, 720);
      EXPECT_FALSE(hud.cut) << scale;
      EXPECT_EQ(joined_ink(hud), ink(lines[0]) + ink(lines[1])) << scale;
      // The path is wider than 160 px at either scale: broken, its first piece a line's width.
      const auto piece = std::find_if(hud.lines.begin(), hud.lines.end(),
                                      [](const auto& l) { return l.text.starts_with("assets/"); });
      ASSERT_NE(piece, hud.lines.end()) << scale;
      EXPECT_GT(Renderer::text_width(piece->text + "_", scale), 160.0f - 20.0f - 8.0f * scale);
    }
}

TEST(HudLayout, WordsArePackedGreedily) {
  // Words one space apart: each line broken only where its next word would not fit beside it.
  const std::string lines[] = {
      "the runtime guard stopped the simulation because a body's speed left the finite range "
      "of its precision after the spring between it and the anchor was stretched too far"};
  for (const int width : {160, 333, 640})
    for (const float scale : {1.0f, 1.75f, 2.0f}) {
      const HudLayout hud = layout_hud(lines, scale, HudCorner::top_right, width, 2000);
      expect_inside(hud, width, 2000, std::to_string(width));
      expect_margins(hud, width, 2000);
      EXPECT_EQ(joined_ink(hud), ink(lines[0]));
      const float room = float(width) - 20.0f - 8.0f * scale;
      for (std::size_t i = 0; i + 1 < hud.lines.size(); ++i) {
        const std::string& next = hud.lines[i + 1].text;
        const std::string word = next.substr(0, next.find(' '));
        EXPECT_GT(Renderer::text_width(hud.lines[i].text + " " + word, scale), room)
            << '"' << hud.lines[i].text << "\" could take \"" << word << '"';
      }
    }
}

TEST(HudLayout, LinesPastTheFramesHeightAreDroppedAndTheLastShownEndsInAnEllipsis) {
  const std::string lines[] = {net_line, net_line, net_line};
  const HudLayout hud = layout_hud(lines, 2.0f, HudCorner::bottom_left, 160, 90);
  expect_inside(hud, 160, 90, "160x90");
  EXPECT_TRUE(hud.cut);
  // (90 - 20 - 8 - 2) / 22: two lines.
  ASSERT_EQ(hud.lines.size(), 2u);
  EXPECT_TRUE(hud.lines.back().text.ends_with("...")) << hud.lines.back().text;
  EXPECT_TRUE(ink(net_line).starts_with(ink(hud.lines[0].text)));
}

// A runtime guard's message may name a body with a 2 MB name: only the lines the frame can show
// are made (the wrapping stops past them), each a piece of the name, the last cut with "...".
TEST(HudLayout, AHugeWordIsBrokenOnlyIntoTheLinesShown) {
  const std::string lines[] = {"STOPPED: body " + std::string(2000000, 'x') + " left the range"};
  const HudLayout hud = layout_hud(lines, 2.0f, HudCorner::top_left, 640, 360);
  expect_inside(hud, 640, 360, "640x360");
  EXPECT_TRUE(hud.cut);
  ASSERT_EQ(hud.lines.size(), 15u);  // (360 - 20 - 8 - 2) / 22
  EXPECT_EQ(hud.lines[0].text, "STOPPED: body");
  EXPECT_EQ(hud.lines[1].text, std::string(hud.lines[1].text.size(), 'x'));
  EXPECT_TRUE(hud.lines.back().text.ends_with("xx...")) << hud.lines.back().text;
}

TEST(HudLayout, AFrameTooSmallForTheMarginsKeepsTheTextInsideIt) {
  const std::string lines[] = {"W@M tick 1"};
  for (const float scale : {1.0f, 2.0f, 4.0f})
    for (const HudCorner corner : corners)
      for (const int size : {min_frame_size, 24, 40}) {
        const HudLayout hud = layout_hud(lines, scale, corner, size, size);
        expect_inside(hud, size, size, std::to_string(size) + " px");
        ASSERT_FALSE(hud.lines.empty());
        EXPECT_LE(hud.scale, scale);
        EXPECT_GE(hud.scale, 1.0f);  // a glyph of scale 1 fits the smallest frame
      }
  EXPECT_THROW((void)layout_hud(lines, 0.0f, HudCorner::top_left, 64, 64), std::invalid_argument);
  EXPECT_THROW((void)layout_hud(lines, 2.0f, HudCorner::top_left, 0, 64), std::invalid_argument);
}

TEST(HudLayout, UnprintableCharactersAndNewLinesAreLaidOutAsDrawn) {
  const std::string lines[] = {"ω = 2\nsecond"};
  const HudLayout hud = layout_hud(lines, 2.0f, HudCorner::top_left, 640, 360);
  ASSERT_EQ(hud.lines.size(), 2u);
  EXPECT_EQ(hud.lines[0].text, "? = 2");
  EXPECT_EQ(hud.lines[1].text, "second");
}

// The HUD drawn: its panel ends a margin short of the frame's right edge, however long the
// line (it ran to the edge and past it before the lines were wrapped).
TEST(HudLayout, TheDrawnPanelStaysInsideTheFrame) {
  for (const int width : {160, 640}) {
    Renderer r(width, 200);
    r.set_camera(Camera{.center = {0, 0}, .width = 20.0});
    r.set_view_style(ViewStyle{.grid = false, .axes = false, .scale_bar = false});
    r.draw(RenderFrame{}, {});
    const std::vector<std::uint8_t> without(r.pixels().begin(), r.pixels().end());
    const std::string hud[] = {net_line};
    r.draw(RenderFrame{}, hud);
    int rightmost = -1, rows = 0;
    for (int y = 0; y < r.height(); ++y) {
      bool row = false;
      for (int x = 0; x < width; ++x) {
        const std::size_t i = (std::size_t(y) * width + x) * 4;
        if (r.pixels()[i] != without[i] || r.pixels()[i + 1] != without[i + 1]) {
          rightmost = std::max(rightmost, x);
          row = true;
        }
      }
      rows += row;
    }
    EXPECT_GE(rightmost, width / 2) << width;  // the panel is there
    EXPECT_LT(rightmost, width - 10) << width;
    const HudLayout layout = layout_hud(hud, 2.0f, HudCorner::top_left, width, 200);
    EXPECT_NEAR(rightmost + 1, layout.x1, 1.0) << width;
    EXPECT_NEAR(rows, layout.y1 - layout.y0, 1.0) << width;
  }
}

}  // namespace hud_layout_test
}  // namespace fixstep
