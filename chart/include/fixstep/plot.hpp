// Charts drawn by fixstep itself: line and marker plots with linear or log10 axes, ticks at
// nice values, labels, legend and caption, rasterised through the Renderer's canvas (OSMesa,
// the same GL pipeline as the scene) into its RGBA8 pixels, ready for write_png().
//
// Coordinates: data values are in the units the caller chose (the axis labels say which);
// pixels are as on the Renderer canvas (x right, y down, origin at the frame's top-left).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fixstep/core/types.hpp"
#include "fixstep/render/render.hpp"

namespace fixstep {

/// The shape drawn at each data point of a series.
enum class Marker { none, circle, square, diamond, triangle };

/// One data series: x[i], y[i] pairs joined in order. Every member has a default, so
/// designated initializers may name only what they set (in declaration order).
///
/// Points with a non-finite coordinate, or a coordinate <= 0 on a log axis, are skipped and
/// break the polyline there (no segment is drawn across them). Segments and markers are cut
/// exactly at the plot area's border.
struct PlotSeries {
  std::string label{};           ///< legend text; empty: the series is not in the legend
  std::vector<double> x{}, y{};  ///< data, equal lengths (else std::invalid_argument)
  std::optional<Rgba8> color{};  ///< default: plot_palette()[series index % palette size]
  bool lines = true;             ///< join consecutive points
  Marker marker = Marker::none;
  float line_width = 2.0f;   ///< px, > 0
  float marker_size = 4.0f;  ///< marker radius (half the side of a square), px, > 0
  bool dashed = false;       ///< dashes of 5 and gaps of 3 text-scale units, along the polyline
};

/// A horizontal (constant y) or vertical (constant x) reference line across the plot area.
struct ReferenceLine {
  enum class Orientation { horizontal, vertical };
  Orientation orientation = Orientation::horizontal;
  double value = 0.0;   ///< in the data units of the y (horizontal) or x (vertical) axis
  std::string label{};  ///< legend text; empty: not in the legend
  Rgba8 color{110, 110, 110, 255};
  bool dashed = true;
  float line_width = 1.5f;  ///< px
};

/// One axis. Unset ends are chosen from the data (automatic range, see layout_plot).
struct PlotAxis {
  std::string label{};                 ///< e.g. "t (s)"; may be empty
  bool log = false;                    ///< log10 scale: every value shown must be > 0
  std::optional<double> min{}, max{};  ///< fixed ends in data units; finite, min < max
  /// Fraction of the data's span (log axes: of its decades) added beyond each automatic end.
  double margin = 0.05;
};

/// Where the legend goes. `automatic` takes the first inside corner (top right, top left,
/// bottom right, bottom left) whose legend box no line, marker or reference line of the plot
/// touches, and otherwise puts the legend outside, right of the plot area (which then
/// narrows): the legend never covers data.
enum class LegendPlacement {
  automatic,
  top_right,
  top_left,
  bottom_right,
  bottom_left,
  outside_right,
  none,
};

/// Everything one chart shows.
struct PlotSpec {
  std::string title{};
  PlotAxis x{}, y{};
  std::vector<PlotSeries> series{};  ///< drawn in order: later series on top
  std::vector<ReferenceLine> references{};
  /// Lines of text under the plot (the measured numbers), word-wrapped to the frame's width.
  std::vector<std::string> caption{};
  LegendPlacement legend = LegendPlacement::automatic;
  /// px per font unit of tick labels, axis labels, legend and caption (the title is one step
  /// larger); 0 = plot_text_scale() of the frame. Integer values keep the bitmap font crisp.
  float text_scale = 0.0f;
};

/// Tick positions of one axis, in data units, ascending.
struct Ticks {
  std::vector<double> major;  ///< labelled
  std::vector<double> minor;  ///< unlabelled, none at a major position
};

/// Tick values inside [min, max] (both included, up to a relative 1e-9 of the step).
///
/// Linear axes: multiples k·s of the finest step s in {1, 2, 5}·10^e giving at most
/// `max_major` major ticks; each value is k·m·10^e rounded once (so 0.6 is the double nearest
/// 0.6, not 3·0.2). Minor ticks divide each step into 5 (steps 1 and 5) or 4 (step 2).
/// Log axes (log = true): major ticks at decades 10^k, every 1, 2, 5, 10, 20, ... decades so
/// that at most `max_major` show; minor ticks at 2..9·10^k when every decade is labelled,
/// otherwise at the unlabelled decades. When fewer than two decades fall inside the range, the
/// majors are 1, 2 and 5·10^k (minors the other digits), and when even those give fewer than
/// two, the linear rule is used.
/// Throws std::invalid_argument when min or max is not finite, min >= max, max - min overflows,
/// max_major < 2, or (log) min <= 0.
[[nodiscard]] Ticks nice_ticks(double min, double max, bool log, int max_major = 8);

/// Labels for major tick values, one per value.
/// Linear axes: the shortest fixed-point text (same number of decimals for all) that tells
/// every value apart and reads back to within 1e-9 of the spacing, e.g. "0", "0.5", "1.0";
/// scientific ("1e-6", "2.5e10") when the largest |value| is >= 1e6 or below 1e-4. Zero prints
/// as "0", never "-0".
/// Log axes (log = true): each value's own shortest exact text, plain from 0.001 up to 1e5
/// ("0.01", "1", "2000") and scientific beyond ("1e-6", "5e8").
[[nodiscard]] std::vector<std::string> tick_labels(std::span<const double> values,
                                                   bool log = false);

/// Maps data values along one axis to pixels, linearly in the value or in log10 of it.
struct AxisMap {
  double min = 0.0, max = 1.0;              ///< data range shown
  double pixel_min = 0.0, pixel_max = 1.0;  ///< pixel coordinates of min and max
  bool log = false;
  /// Pixel coordinate of v; NaN when v is not finite or (log) v <= 0. Values outside
  /// [min, max] map outside [pixel_min, pixel_max] (extrapolated).
  [[nodiscard]] double to_pixel(double v) const;
};

/// A rectangle in pixels: [x0, x1) x [y0, y1), y down.
struct PixelBox {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  [[nodiscard]] double width() const { return x1 - x0; }
  [[nodiscard]] double height() const { return y1 - y0; }
  [[nodiscard]] bool contains(double x, double y) const {
    return x >= x0 && x < x1 && y >= y0 && y < y1;
  }
};

/// Where everything of a chart goes in pixels; layout_plot() computes it, draw_plot() draws it.
struct PlotLayout {
  PixelBox frame;  ///< the whole chart
  PixelBox area;   ///< inside the axes: data is drawn only here
  AxisMap x, y;    ///< y.pixel_min is the area's bottom edge (y grows upwards)
  Ticks x_ticks, y_ticks;
  std::vector<std::string> x_tick_labels, y_tick_labels;  ///< one per major tick
  LegendPlacement legend = LegendPlacement::none;         ///< resolved: never automatic
  PixelBox legend_box;                                    ///< empty unless a legend is shown
  std::vector<std::string> caption_lines;                 ///< after word wrapping
  float text_scale = 2.0f;                                ///< px per font unit
  /// Pixel coordinates of data point (x, y); NaN components where AxisMap::to_pixel gives NaN.
  [[nodiscard]] std::array<double, 2> to_pixel(double x, double y) const {
    return {this->x.to_pixel(x), this->y.to_pixel(y)};
  }
};

/// The default text scale for a frame of width x height px: 1 per 640x360 (rounded, >= 1),
/// so 1280x720 gives 2.
[[nodiscard]] float plot_text_scale(int width, int height);

/// The fixed series palette: 8 colours chosen to stay apart for colour-blind readers and to
/// read on the white plot background (Okabe & Ito's set, with a dark grey for black).
[[nodiscard]] std::span<const Rgba8> plot_palette();

/// Lays out `spec` in `frame`: resolves the axis ranges, ticks, labels, plot area, legend and
/// caption. Automatic ranges span the finite data (for y, only points whose x is inside the x
/// range) and the reference lines, widened by the axis margin; with no data, [0, 1] (log:
/// [1, 10]); a single value v gets v ± max(|v|, 1)/2 (log: half a decade each way). When only
/// one end is given and the data lies wholly beyond it, the other end is set one unit (log:
/// one decade) away. Ticks are thinned until their labels do not touch.
/// Throws std::invalid_argument naming the axis or series for: a given min or max that is not
/// finite, min >= max, a log axis with a given min or max <= 0, a negative or non-finite
/// margin, a series whose x and y lengths differ or whose line width or marker size is not
/// > 0, a non-finite reference value, a range whose span overflows a double (data from -1e308
/// to 1e308), and a frame too small to leave a plot area.
[[nodiscard]] PlotLayout layout_plot(const PlotSpec& spec, PixelBox frame);

/// Records the chart into the picture `renderer` is composing (between Renderer::begin() and
/// Renderer::finish()), inside `frame`; several charts can share one picture. Returns the
/// layout used. Throws as layout_plot().
PlotLayout add_plot(Renderer& renderer, const PlotSpec& spec, PixelBox frame);

/// Draws the chart over the renderer's whole frame on a white background: begin(), add_plot(),
/// finish(). The result is in renderer.pixels() (write it with write_png()). Throws as
/// layout_plot(), and RenderError if GL fails.
PlotLayout draw_plot(Renderer& renderer, const PlotSpec& spec);

}  // namespace fixstep
