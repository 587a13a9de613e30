// Plots: tick values and labels, the data-to-pixel mapping, and what draw_plot() puts where
// (pixels read back from the OSMesa renderer).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "fixstep/plot.hpp"

namespace fixstep {
namespace {

using Values = std::vector<double>;
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// --- ticks ---------------------------------------------------------------------------------

TEST(NiceTicks, LinearRangesGiveOneTwoFiveSteps) {
  EXPECT_EQ(nice_ticks(0, 10, false).major, (Values{0, 2, 4, 6, 8, 10}));
  // Each value is the double nearest its decimal (0.6, not 3 * 0.2 = 0.6000000000000001).
  EXPECT_EQ(nice_ticks(0, 1, false).major, (Values{0, 0.2, 0.4, 0.6, 0.8, 1}));
  EXPECT_EQ(nice_ticks(-1000, 1000, false).major, (Values{-1000, -500, 0, 500, 1000}));
  EXPECT_EQ(nice_ticks(3.7, 9.2, false).major, (Values{4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(nice_ticks(-0.3, 0.3, false).major, (Values{-0.3, -0.2, -0.1, 0, 0.1, 0.2, 0.3}));
  EXPECT_EQ(nice_ticks(0.1, 0.15, false).major, (Values{0.1, 0.11, 0.12, 0.13, 0.14, 0.15}));
  EXPECT_EQ(nice_ticks(0, 90, false).major, (Values{0, 20, 40, 60, 80}));
  EXPECT_EQ(nice_ticks(0, 90, false, 10).major, (Values{0, 10, 20, 30, 40, 50, 60, 70, 80, 90}));
  EXPECT_EQ(nice_ticks(1e6, 5e6, false).major, (Values{1e6, 2e6, 3e6, 4e6, 5e6}));
}

TEST(NiceTicks, LinearMinorTicksSubdivideTheStep) {
  // Step 2: minors every 0.5, none on a major.
  const Ticks t = nice_ticks(0, 4, false, 3);
  EXPECT_EQ(t.major, (Values{0, 2, 4}));
  EXPECT_EQ(t.minor, (Values{0.5, 1, 1.5, 2.5, 3, 3.5}));
  // Step 5: minors every 1.
  EXPECT_EQ(nice_ticks(0, 10, false, 3).minor, (Values{1, 2, 3, 4, 6, 7, 8, 9}));
}

TEST(NiceTicks, LogTicksAreDecades) {
  const Ticks t = nice_ticks(1e-3, 100, true);
  EXPECT_EQ(t.major, (Values{1e-3, 1e-2, 0.1, 1, 10, 100}));
  // Minors: 2..9 in each of the 5 decades between, none equal to a major.
  ASSERT_EQ(t.minor.size(), 40u);
  EXPECT_DOUBLE_EQ(t.minor.front(), 2e-3);
  EXPECT_DOUBLE_EQ(t.minor.back(), 90);
  for (double m : t.minor)
    for (double M : t.major) EXPECT_NE(m, M);
  // Twelve decades do not fit in 8 labels: every second decade, the others as minors.
  const Ticks wide = nice_ticks(1e-12, 1, true);
  EXPECT_EQ(wide.major, (Values{1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-2, 1}));
  EXPECT_EQ(wide.minor, (Values{1e-11, 1e-9, 1e-7, 1e-5, 1e-3, 1e-1}));
  for (double v : wide.major) EXPECT_EQ(std::pow(10.0, std::round(std::log10(v))), v);
}

TEST(NiceTicks, NarrowLogRangesUseOneTwoFiveInTheDecade) {
  const Ticks t = nice_ticks(2, 30, true);
  EXPECT_EQ(t.major, (Values{2, 5, 10, 20}));
  EXPECT_EQ(t.minor, (Values{3, 4, 6, 7, 8, 9, 30}));
  // Less than one 1-2-5 step apart: linear ticks.
  EXPECT_EQ(nice_ticks(1.1, 1.4, true).major, (Values{1.1, 1.15, 1.2, 1.25, 1.3, 1.35, 1.4}));
}

TEST(NiceTicks, RejectsBadRanges) {
  EXPECT_THROW((void)nice_ticks(1, 1, false), std::invalid_argument);
  EXPECT_THROW((void)nice_ticks(2, 1, false), std::invalid_argument);
  EXPECT_THROW((void)nice_ticks(0, inf, false), std::invalid_argument);
  EXPECT_THROW((void)nice_ticks(nan, 1, false), std::invalid_argument);
  EXPECT_THROW((void)nice_ticks(0, 10, true), std::invalid_argument);
  EXPECT_THROW((void)nice_ticks(-1, 10, true), std::invalid_argument);
  EXPECT_THROW((void)nice_ticks(0, 10, false, 1), std::invalid_argument);
  EXPECT_THROW((void)nice_ticks(-1e308, 1e308, false), std::invalid_argument);  // span overflows
}

TEST(TickLabels, ShortestCommonDecimalsAndTidyExponents) {
  using S = std::vector<std::string>;
  EXPECT_EQ(tick_labels(Values{0, 0.2, 0.4, 0.6, 0.8, 1}),
            (S{"0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
  EXPECT_EQ(tick_labels(Values{0.1, 0.15, 0.2}), (S{"0.10", "0.15", "0.20"}));
  EXPECT_EQ(tick_labels(Values{-1000, -500, 0, 500, 1000}),
            (S{"-1000", "-500", "0", "500", "1000"}));
  EXPECT_EQ(tick_labels(Values{-0.0, 1}), (S{"0", "1"}));
  EXPECT_EQ(tick_labels(Values{-0.5, 0, 0.5}), (S{"-0.5", "0", "0.5"}));
  EXPECT_EQ(tick_labels(Values{-2e-17, 0.5}), (S{"0", "0.5"}));  // rounding noise at zero
  EXPECT_EQ(tick_labels(Values{1e6, 2e6, 2.5e6}), (S{"1e6", "2e6", "2.5e6"}));
  EXPECT_EQ(tick_labels(Values{1e-5, 2e-5}), (S{"1e-5", "2e-5"}));
  EXPECT_EQ(tick_labels(Values{1e-6, 1e-3, 0.01, 1, 100, 1e5, 2e8}, true),
            (S{"1e-6", "0.001", "0.01", "1", "100", "1e5", "2e8"}));
}

// --- mapping -------------------------------------------------------------------------------

TEST(AxisMap, LinearAndLogMapping) {
  const AxisMap lin{0, 10, 100, 600, false};
  EXPECT_DOUBLE_EQ(lin.to_pixel(0), 100);
  EXPECT_DOUBLE_EQ(lin.to_pixel(5), 350);
  EXPECT_DOUBLE_EQ(lin.to_pixel(12), 700);  // extrapolated
  EXPECT_TRUE(std::isnan(lin.to_pixel(nan)));
  EXPECT_TRUE(std::isnan(lin.to_pixel(inf)));
  // y axes run upwards: pixel_min is the bottom.
  const AxisMap logy{1e-3, 1e3, 500, 20, true};
  EXPECT_DOUBLE_EQ(logy.to_pixel(1e-3), 500);
  EXPECT_DOUBLE_EQ(logy.to_pixel(1), 260);
  EXPECT_DOUBLE_EQ(logy.to_pixel(1e3), 20);
  EXPECT_TRUE(std::isnan(logy.to_pixel(0)));
  EXPECT_TRUE(std::isnan(logy.to_pixel(-1)));
}

TEST(Layout, AutomaticRangesCoverTheDataWithAMargin) {
  PlotSpec s;
  s.series.push_back({.label = "a", .x = {0, 10}, .y = {-2, 8}});
  s.series.push_back({.label = "b", .x = {5, nan, inf}, .y = {100, 1, 1e300}});  // skipped
  s.series.back().y[0] = nan;
  const PlotLayout L = layout_plot(s, PixelBox{0, 0, 640, 360});
  EXPECT_DOUBLE_EQ(L.x.min, -0.5);
  EXPECT_DOUBLE_EQ(L.x.max, 10.5);
  EXPECT_DOUBLE_EQ(L.y.min, -2.5);
  EXPECT_DOUBLE_EQ(L.y.max, 8.5);
  EXPECT_DOUBLE_EQ(L.x.pixel_min, L.area.x0);
  EXPECT_DOUBLE_EQ(L.y.pixel_min, L.area.y1);  // y grows upwards
  // Only x inside the given x range counts for y; log axes drop values <= 0.
  PlotSpec z;
  z.x.min = 0;
  z.x.max = 1;
  z.y.log = true;
  z.y.margin = 0;
  z.series.push_back({.x = {0.5, 0.6, 0.7, 5}, .y = {1e-2, 0, 1e2, 1e9}});
  const PlotLayout Z = layout_plot(z, PixelBox{0, 0, 640, 360});
  EXPECT_DOUBLE_EQ(Z.y.min, 1e-2);
  EXPECT_NEAR(Z.y.max, 1e2, 1e-12);
}

TEST(Layout, ErrorsNameTheAxisOrSeries) {
  PlotSpec s;
  s.y.label = "energy (J)";
  s.y.log = true;
  s.y.max = 0;
  try {
    (void)layout_plot(s, PixelBox{0, 0, 640, 360});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("y axis 'energy (J)'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("max = 0"), std::string::npos) << e.what();
  }
  PlotSpec x;
  x.x.log = true;
  x.x.min = -1;
  EXPECT_THROW((void)layout_plot(x, PixelBox{0, 0, 640, 360}), std::invalid_argument);
  PlotSpec r;
  r.x.min = 2;
  r.x.max = 1;
  EXPECT_THROW((void)layout_plot(r, PixelBox{0, 0, 640, 360}), std::invalid_argument);
  PlotSpec n;
  n.series.push_back({.label = "RK4", .x = {1, 2}, .y = {1}});
  try {
    (void)layout_plot(n, PixelBox{0, 0, 640, 360});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'RK4'"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)layout_plot(PlotSpec{}, PixelBox{0, 0, 30, 20}), std::invalid_argument);
}

// --- drawing -------------------------------------------------------------------------------

struct Pixel {
  int r, g, b;
};
Pixel at(const Renderer& r, int x, int y) {
  const auto p = r.pixels().subspan((static_cast<std::size_t>(y) * r.width() + x) * 4, 4);
  return {p[0], p[1], p[2]};
}
bool near(Pixel p, Rgba8 c, int tol) {
  return std::abs(p.r - c.r) <= tol && std::abs(p.g - c.g) <= tol && std::abs(p.b - c.b) <= tol;
}
// Pure red and pure magenta appear nowhere in the plot's own chrome (greys, white, palette).
constexpr Rgba8 red{255, 0, 0, 255};
constexpr Rgba8 magenta{255, 0, 255, 255};
bool reddish(Pixel p) {
  return p.r > 150 && p.g < 110 && p.b < 110;
}

PlotSpec unit_square() {
  PlotSpec s;
  s.x = {.label = "x", .min = 0, .max = 10};
  s.y = {.label = "y", .min = 0, .max = 10};
  s.legend = LegendPlacement::none;
  return s;
}

TEST(DrawPlot, ALineLandsOnItsMappedPixelsAndNowhereElse) {
  Renderer r(640, 400);
  PlotSpec s = unit_square();
  // y = 5 (horizontal) and y = x (diagonal), both red, 3 px wide.
  s.series.push_back({.x = {0, 10}, .y = {5, 5}, .color = red, .line_width = 3});
  s.series.push_back({.x = {0, 10}, .y = {0, 10}, .color = red, .line_width = 3});
  const PlotLayout L = draw_plot(r, s);
  ASSERT_EQ(r.pixels().size(), 640u * 400u * 4u);
  // Data (0, 0) is the area's bottom-left corner, (10, 10) its top-right (y grows upwards).
  EXPECT_DOUBLE_EQ(L.to_pixel(0, 0)[0], L.area.x0);
  EXPECT_DOUBLE_EQ(L.to_pixel(0, 0)[1], L.area.y1);
  EXPECT_DOUBLE_EQ(L.to_pixel(10, 10)[0], L.area.x1);
  EXPECT_DOUBLE_EQ(L.to_pixel(10, 10)[1], L.area.y0);
  const int row = static_cast<int>(L.y.to_pixel(5));
  for (double x : {1.0, 3.0, 7.0, 9.0}) {
    const int col = static_cast<int>(L.x.to_pixel(x));
    EXPECT_TRUE(near(at(r, col, row), red, 40)) << "x = " << x;
  }
  for (double v : {1.0, 2.5, 7.5, 9.0}) {
    const auto p = L.to_pixel(v, v);
    EXPECT_TRUE(near(at(r, int(p[0]), int(p[1])), red, 40)) << "v = " << v;
  }
  // No red pixel farther than 3 px from either line, and none outside the plot area.
  int stray = 0, outside = 0;
  for (int y = 0; y < r.height(); ++y)
    for (int x = 0; x < r.width(); ++x) {
      if (!reddish(at(r, x, y))) continue;
      const double dh = std::abs(y + 0.5 - L.y.to_pixel(5));
      // Distance to the diagonal through the mapped (0,0) and (10,10).
      const auto a = L.to_pixel(0, 0), b = L.to_pixel(10, 10);
      const double dx = b[0] - a[0], dy = b[1] - a[1];
      const double dd =
          std::abs((x + 0.5 - a[0]) * dy - (y + 0.5 - a[1]) * dx) / std::hypot(dx, dy);
      stray += dh > 3.5 && dd > 3.5;
      outside += !L.area.contains(x + 0.5, y + 0.5);
    }
  EXPECT_EQ(stray, 0);
  EXPECT_EQ(outside, 0);
}

TEST(DrawPlot, DataBeyondFixedRangesIsCutAtTheAxes) {
  Renderer r(400, 300);
  PlotSpec s = unit_square();
  s.series.push_back({.x = {-50, 60},
                      .y = {-40, 70},
                      .color = red,
                      .marker = Marker::square,
                      .line_width = 4,
                      .marker_size = 6});
  s.series.push_back({.x = {-5, 15}, .y = {5, 5}, .color = red, .line_width = 4});
  const PlotLayout L = draw_plot(r, s);
  int inside = 0, outside = 0;
  for (int y = 0; y < r.height(); ++y)
    for (int x = 0; x < r.width(); ++x)
      if (reddish(at(r, x, y))) (L.area.contains(x + 0.5, y + 0.5) ? inside : outside)++;
  EXPECT_GT(inside, 200);
  EXPECT_EQ(outside, 0);
}

TEST(DrawPlot, LegendShowsASwatchPerLabelledSeries) {
  Renderer r(640, 400);
  PlotSpec s = unit_square();
  s.legend = LegendPlacement::top_left;
  s.series.push_back({.label = "red", .x = {6, 9}, .y = {1, 2}, .color = red});
  s.series.push_back({.label = "magenta", .x = {6, 9}, .y = {2, 3}, .color = magenta});
  s.series.push_back({.x = {6, 9}, .y = {3, 4}});  // no label: no entry
  const PlotLayout L = draw_plot(r, s);
  ASSERT_EQ(L.legend, LegendPlacement::top_left);
  const PixelBox& b = L.legend_box;
  EXPECT_LT(b.x0 - L.area.x0, 20);
  EXPECT_LT(b.y0 - L.area.y0, 20);
  int red_px = 0, magenta_px = 0;
  const int mid_x = int((b.x0 + b.x1) / 2);
  for (int y = int(b.y0); y < int(b.y1); ++y)
    for (int x = int(b.x0); x < int(b.x1); ++x) {
      red_px += near(at(r, x, y), red, 30);
      magenta_px += near(at(r, x, y), magenta, 30);
      // Swatches sit at the legend's left, the text to their right.
      if (near(at(r, x, y), red, 30) || near(at(r, x, y), magenta, 30)) {
        EXPECT_LT(x, mid_x);
      }
    }
  EXPECT_GT(red_px, 10);
  EXPECT_GT(magenta_px, 10);
  // The swatches are in order, red above magenta, one text line apart.
  double red_y = 0, magenta_y = 0;
  for (int y = int(b.y0); y < int(b.y1); ++y)
    for (int x = int(b.x0); x < int(b.x1); ++x) {
      if (near(at(r, x, y), red, 30)) red_y = y;
      if (near(at(r, x, y), magenta, 30)) magenta_y = y;
    }
  EXPECT_NEAR(magenta_y - red_y, 12 * L.text_scale, 2);
  // Dark legend text is there too.
  int text_px = 0;
  for (int y = int(b.y0); y < int(b.y1); ++y)
    for (int x = mid_x; x < int(b.x1); ++x) text_px += at(r, x, y).r < 80;
  EXPECT_GT(text_px, 20);
}

TEST(DrawPlot, AutomaticLegendAvoidsTheData) {
  // Data crowds the top right and top left: the legend goes to a bottom corner.
  PlotSpec s = unit_square();
  s.legend = LegendPlacement::automatic;
  s.series.push_back({.label = "a", .x = {0, 10}, .y = {9, 9}});
  s.series.push_back({.label = "b", .x = {0, 10}, .y = {8, 10}});
  const PlotLayout L = layout_plot(s, PixelBox{0, 0, 640, 400});
  EXPECT_EQ(L.legend, LegendPlacement::bottom_right);
  // Data everywhere: the legend moves outside, right of the area.
  PlotSpec full = unit_square();
  full.legend = LegendPlacement::automatic;
  PlotSeries zig{.label = "zigzag"};
  for (int i = 0; i <= 40; ++i) {
    zig.x.push_back(i * 0.25);
    zig.y.push_back(i % 2 ? 10 : 0);
  }
  full.series.push_back(zig);
  const PlotLayout F = layout_plot(full, PixelBox{0, 0, 640, 400});
  EXPECT_EQ(F.legend, LegendPlacement::outside_right);
  EXPECT_GE(F.legend_box.x0, F.area.x1);
  EXPECT_LE(F.legend_box.x1, 640);
}

TEST(DrawPlot, NonFiniteAndNonPositiveLogPointsAreSkippedAndBreakTheLine) {
  Renderer r(640, 400);
  PlotSpec s = unit_square();
  // (1,5) - (3,5) drawn; (5, NaN) breaks the line; (7,5) - (9,5) drawn.
  s.series.push_back({.x = {1, 3, 5, 7, 9}, .y = {5, 5, nan, 5, 5}, .color = red});
  s.series.push_back({.x = {inf, -inf, nan}, .y = {1, 2, 3}, .color = red});
  const PlotLayout L = draw_plot(r, s);
  const int row = int(L.y.to_pixel(5));
  EXPECT_TRUE(reddish(at(r, int(L.x.to_pixel(2)), row)));
  EXPECT_TRUE(reddish(at(r, int(L.x.to_pixel(8)), row)));
  EXPECT_FALSE(reddish(at(r, int(L.x.to_pixel(5)), row)));  // the gap
  // On log axes, values <= 0 are skipped the same way; the automatic range ignores them.
  PlotSpec g;
  g.x.log = g.y.log = true;
  g.legend = LegendPlacement::none;
  g.series.push_back({.x = {1, 10, 0, 100, -5, 1000},
                      .y = {1, 10, 5, 100, 7, -1},
                      .color = red,
                      .marker = Marker::circle});
  const PlotLayout G = draw_plot(r, g);
  EXPECT_GT(G.x.min, 0);
  EXPECT_LT(G.x.max, 200);  // 1000 has y = -1: not shown, not counted
  EXPECT_TRUE(reddish(at(r, int(G.x.to_pixel(5)), int(G.y.to_pixel(5)))));
  EXPECT_TRUE(std::isfinite(G.y.min) && std::isfinite(G.y.max));
}

TEST(DrawPlot, DashedLinesHaveGaps) {
  Renderer r(640, 400);
  PlotSpec s = unit_square();
  s.series.push_back({.x = {0, 10}, .y = {5, 5}, .color = red, .dashed = true});
  const PlotLayout L = draw_plot(r, s);
  const int row = int(L.y.to_pixel(5));
  int runs = 0;
  bool was = false;
  for (int x = int(L.area.x0) + 2; x < int(L.area.x1) - 2; ++x) {
    const bool is = reddish(at(r, x, row));
    runs += is && !was;
    was = is;
  }
  EXPECT_GT(runs, 10);
}

TEST(DrawPlot, TitleAxisLabelsTicksAndCaptionAreDrawnOutsideTheArea) {
  Renderer r(640, 400);
  PlotSpec s = unit_square();
  s.title = "TITLE";
  s.caption = {"caption line"};
  const PlotLayout L = draw_plot(r, s);
  const auto dark_in = [&](double x0, double y0, double x1, double y1) {
    int n = 0;
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = int(x0); x < int(x1); ++x) n += at(r, x, y).r < 100;
    return n;
  };
  EXPECT_GT(dark_in(0, 0, 640, L.area.y0 - 2), 30);                  // title
  EXPECT_GT(dark_in(0, L.area.y0, L.area.x0 - 2, L.area.y1), 30);    // y ticks and label
  EXPECT_GT(dark_in(L.area.x0, L.area.y1 + 2, L.area.x1, 400), 30);  // x ticks, label, caption
  ASSERT_EQ(L.caption_lines.size(), 1u);
  ASSERT_EQ(L.x_tick_labels.size(), L.x_ticks.major.size());
  EXPECT_EQ(L.x_tick_labels.front(), "0");
  EXPECT_EQ(L.x_tick_labels.back(), "10");
}

}  // namespace
}  // namespace fixstep
