#include "fixstep/plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace fixstep {

namespace {

constexpr Rgba8 paper{255, 255, 255, 255};
constexpr Rgba8 ink{25, 25, 30, 255};
constexpr Rgba8 axis_ink{70, 70, 78, 255};
constexpr Rgba8 grid_major{222, 224, 228, 255};
constexpr Rgba8 grid_minor{240, 241, 243, 255};
constexpr Rgba8 legend_paper{255, 255, 255, 235};
constexpr Rgba8 legend_edge{190, 192, 198, 255};

constexpr Rgba8 palette[] = {
    {0, 114, 178, 255},    // blue
    {230, 159, 0, 255},    // orange
    {0, 158, 115, 255},    // bluish green
    {213, 94, 0, 255},     // vermillion
    {204, 121, 167, 255},  // reddish purple
    {86, 180, 233, 255},   // sky blue
    {70, 70, 70, 255},     // dark grey
    {180, 160, 0, 255},    // dark yellow (Okabe-Ito's yellow darkened to read on white)
};

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// 10^e as the double nearest the decimal value (exact for |e| <= 22).
double pow10(int e) {
  return e >= 0 ? std::pow(10.0, e) : 1.0 / std::pow(10.0, -e);
}
// n·10^e rounded once.
double scaled(double n, int e) {
  return e >= 0 ? n * std::pow(10.0, e) : n / std::pow(10.0, -e);
}

Ticks linear_ticks(double min, double max, int max_major) {
  const double span = max - min;
  int e = static_cast<int>(std::floor(std::log10(span / max_major))) - 1;
  for (;; ++e) {
    for (const int m : {1, 2, 5}) {
      const double step = scaled(m, e);
      const double k0 = std::ceil(min / step - 1e-9), k1 = std::floor(max / step + 1e-9);
      if (k1 - k0 + 1 > max_major) continue;
      Ticks t;
      for (double k = k0; k <= k1; ++k) t.major.push_back(k == 0 ? 0.0 : scaled(k * m, e));
      // Minor ticks: 5 per step for steps 1 and 5 (at 0.2 and 1 of the next decade down), 4
      // per step for 2 (at 0.5).
      const int sub = m == 2 ? 4 : 5;
      const int mm = m == 1 ? 2 : m == 2 ? 5 : 1;
      const int me = m == 5 ? e : e - 1;
      const double minor_step = scaled(mm, me);
      const double j0 = std::ceil(min / minor_step - 1e-9);
      const double j1 = std::floor(max / minor_step + 1e-9);
      for (double j = j0; j <= j1; ++j) {
        if (std::fmod(std::abs(j), sub) != 0) t.minor.push_back(scaled(j * mm, me));
      }
      return t;
    }
  }
}

Ticks log_ticks(double min, double max, int max_major) {
  const double lo = std::log10(min), hi = std::log10(max);
  const int d0 = static_cast<int>(std::ceil(lo - 1e-9)),
            d1 = static_cast<int>(std::floor(hi + 1e-9));
  const auto inside = [&](double v) { return v >= min * (1 - 1e-9) && v <= max * (1 + 1e-9); };
  Ticks t;
  if (d1 - d0 + 1 >= 2) {
    // Decades every p in 1, 2, 5, 10, 20, ... so that at most max_major are labelled.
    int p = 1;
    for (int i = 0;; ++i) {
      p = (i % 3 == 0 ? 1 : i % 3 == 1 ? 2 : 5) * static_cast<int>(std::pow(10, i / 3));
      const int first = static_cast<int>(std::ceil(double(d0) / p)) * p;
      const int count = first > d1 ? 0 : (d1 - first) / p + 1;
      if (count <= max_major) break;
    }
    for (int k = d0; k <= d1; ++k) {
      if (k % p == 0)
        t.major.push_back(pow10(k));
      else
        t.minor.push_back(pow10(k));
    }
    if (p == 1) {
      for (int k = d0 - 1; k <= d1; ++k)
        for (int m = 2; m <= 9; ++m)
          if (const double v = scaled(m, k); inside(v)) t.minor.push_back(v);
      std::sort(t.minor.begin(), t.minor.end());
    }
    return t;
  }
  // Less than two decades: 1-2-5 inside each decade.
  for (int k = d0 - 1; k <= d1; ++k)
    for (int m = 1; m <= 9; ++m) {
      const double v = scaled(m, k);
      if (!inside(v)) continue;
      (m == 1 || m == 2 || m == 5 ? t.major : t.minor).push_back(v);
    }
  if (t.major.size() >= 2 && static_cast<int>(t.major.size()) <= max_major) return t;
  return linear_ticks(min, max, max_major);
}

std::string tidy_exponent(const std::string& s) {
  // "1e+06" -> "1e6", "2.5e-05" -> "2.5e-5"
  const std::string_view all(s);
  const auto e = all.find('e');
  if (e == std::string_view::npos) return s;
  std::string_view exp = all.substr(e + 1);
  const bool negative = !exp.empty() && exp.front() == '-';
  if (!exp.empty() && (exp.front() == '+' || exp.front() == '-')) exp.remove_prefix(1);
  while (exp.size() > 1 && exp.front() == '0') exp.remove_prefix(1);
  return fmt::format("{}e{}{}", all.substr(0, e), negative ? "-" : "", exp);
}

std::string axis_name(const char* which, const PlotAxis& a) {
  return a.label.empty() ? fmt::format("{} axis", which)
                         : fmt::format("{} axis '{}'", which, a.label);
}

struct Range {
  double min, max;
};

// Liang-Barsky: clips the segment p0-p1 to box; false when nothing is left.
bool clip_segment(double& x0, double& y0, double& x1, double& y1, const PixelBox& b) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = x1 - x0, dy = y1 - y0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0 - b.x0, b.x1 - x0, y0 - b.y0, b.y1 - y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  const double ax = x0 + t0 * dx, ay = y0 + t0 * dy;
  x1 = x0 + t1 * dx;
  y1 = y0 + t1 * dy;
  x0 = ax;
  y0 = ay;
  return true;
}

// Visits the pixel segments of a series (already broken at skipped points, not clipped).
template <class F>
void for_each_segment(const PlotSeries& s, const PlotLayout& L, F&& f) {
  bool have = false;
  double px = 0, py = 0;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const auto p = L.to_pixel(s.x[i], s.y[i]);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1])) {
      have = false;
      continue;
    }
    if (have) f(px, py, p[0], p[1]);
    px = p[0];
    py = p[1];
    have = true;
  }
}

template <class F>
void for_each_point(const PlotSeries& s, const PlotLayout& L, F&& f) {
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const auto p = L.to_pixel(s.x[i], s.y[i]);
    if (std::isfinite(p[0]) && std::isfinite(p[1])) f(p[0], p[1]);
  }
}

Rgba8 color_of(const PlotSpec& spec, std::size_t i) {
  return spec.series[i].color.value_or(palette[i % std::size(palette)]);
}

struct LegendEntry {
  std::string label;
  Rgba8 color;
  bool lines, dashed;
  Marker marker;
  float line_width, marker_size;
};

std::vector<LegendEntry> legend_entries(const PlotSpec& spec) {
  std::vector<LegendEntry> out;
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const PlotSeries& s = spec.series[i];
    if (!s.label.empty())
      out.push_back(
          {s.label, color_of(spec, i), s.lines, s.dashed, s.marker, s.line_width, s.marker_size});
  }
  for (const ReferenceLine& r : spec.references) {
    if (!r.label.empty())
      out.push_back({r.label, r.color, true, r.dashed, Marker::none, r.line_width, 0.0f});
  }
  return out;
}

std::vector<std::string> wrap(const std::string& text, double max_width, float scale) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t j = std::min(text.find(' ', i), text.size());
    const std::string word = text.substr(i, j - i);
    const std::string trial = line.empty() ? word : fmt::format("{} {}", line, word);
    if (!line.empty() && Renderer::text_width(trial, scale) > max_width) {
      lines.push_back(line);
      line = word;
    } else {
      line = trial;
    }
    i = j + 1;
  }
  lines.push_back(line);
  return lines;
}

}  // namespace

// --- ticks and labels ----------------------------------------------------------------------

Ticks nice_ticks(double min, double max, bool log, int max_major) {
  if (!std::isfinite(min) || !std::isfinite(max))
    throw std::invalid_argument(fmt::format("nice_ticks: range [{}, {}] is not finite", min, max));
  if (!(min < max))
    throw std::invalid_argument(fmt::format("nice_ticks: min {} is not below max {}", min, max));
  if (max_major < 2)
    throw std::invalid_argument(fmt::format("nice_ticks: max_major {} is below 2", max_major));
  if (!std::isfinite(max - min))
    throw std::invalid_argument(
        fmt::format("nice_ticks: range [{}, {}] is too wide (its span overflows)", min, max));
  if (log && min <= 0)
    throw std::invalid_argument(
        fmt::format("nice_ticks: a log axis needs min > 0, got min = {}", min));
  return log ? log_ticks(min, max, max_major) : linear_ticks(min, max, max_major);
}

std::vector<std::string> tick_labels(std::span<const double> values, bool log) {
  std::vector<std::string> out(values.size());
  if (values.empty()) return out;
  if (log) {
    // Each value on its own, shortest text that reads back exactly.
    for (std::size_t i = 0; i < values.size(); ++i) {
      const double v = values[i];
      const double a = std::abs(v);
      out[i] = a >= 1e-3 && a < 1e5 ? fmt::format("{}", v) : tidy_exponent(fmt::format("{:e}", v));
      if (a < 1e-3 || a >= 1e5) {
        // "{:e}" prints six decimals; keep the fewest that still read back exactly.
        for (int d = 0; d <= 16; ++d) {
          std::string t = tidy_exponent(fmt::format("{:.{}e}", v, d));
          if (std::strtod(t.c_str(), nullptr) == v) {
            out[i] = std::move(t);
            break;
          }
        }
      } else if (out[i].size() > 2 && out[i].ends_with(".0")) {
        out[i].resize(out[i].size() - 2);
      }
    }
    return out;
  }
  double largest = 0.0, smallest_gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < values.size(); ++i) {
    largest = std::max(largest, std::abs(values[i]));
    if (i > 0) smallest_gap = std::min(smallest_gap, std::abs(values[i] - values[i - 1]));
  }
  if (!std::isfinite(smallest_gap) || smallest_gap == 0) smallest_gap = std::max(largest, 1.0);
  const double tolerance = 1e-9 * smallest_gap;
  const bool scientific = largest >= 1e6 || (largest > 0 && largest < 1e-4);
  for (int digits = scientific ? 1 : 0; digits <= 17; ++digits) {
    bool ok = true;
    for (std::size_t i = 0; i < values.size() && ok; ++i) {
      const double v = std::abs(values[i]) <= tolerance ? 0.0 : values[i];
      std::string text = scientific ? tidy_exponent(fmt::format("{:.{}g}", v, digits))
                                    : fmt::format("{:.{}f}", v, digits);
      if (text.find_first_not_of("-0.") == std::string::npos) {  // "0", "-0", "0.00", ...
        text = std::string(1, '0');
        if (std::abs(v) > tolerance) ok = false;
      }
      out[i] = std::move(text);
      ok = ok && std::abs(std::strtod(out[i].c_str(), nullptr) - v) <= tolerance;
    }
    if (ok) return out;
  }
  for (std::size_t i = 0; i < values.size(); ++i) out[i] = fmt::format("{}", values[i]);
  return out;
}

// --- mapping ------------------------------------------------------------------------------

double AxisMap::to_pixel(double v) const {
  if (!std::isfinite(v)) return nan;
  double t;
  if (log) {
    if (v <= 0) return nan;
    t = (std::log10(v) - std::log10(min)) / (std::log10(max) - std::log10(min));
  } else {
    t = (v - min) / (max - min);
  }
  return pixel_min + t * (pixel_max - pixel_min);
}

float plot_text_scale(int width, int height) {
  return static_cast<float>(std::max(1.0, std::round(std::min(width / 640.0, height / 360.0))));
}

std::span<const Rgba8> plot_palette() {
  return palette;
}

// --- layout -------------------------------------------------------------------------------

namespace {

void validate_axis(const char* which, const PlotAxis& a) {
  const std::string name = axis_name(which, a);
  if (a.min && !std::isfinite(*a.min))
    throw std::invalid_argument(fmt::format("plot: {}: min {} is not finite", name, *a.min));
  if (a.max && !std::isfinite(*a.max))
    throw std::invalid_argument(fmt::format("plot: {}: max {} is not finite", name, *a.max));
  if (a.min && a.max && !(*a.min < *a.max))
    throw std::invalid_argument(
        fmt::format("plot: {}: min {} is not below max {}", name, *a.min, *a.max));
  if (a.log && a.min && *a.min <= 0)
    throw std::invalid_argument(
        fmt::format("plot: {} is logarithmic but min = {} (must be > 0)", name, *a.min));
  if (a.log && a.max && *a.max <= 0)
    throw std::invalid_argument(
        fmt::format("plot: {} is logarithmic but max = {} (must be > 0)", name, *a.max));
  if (!std::isfinite(a.margin) || a.margin < 0)
    throw std::invalid_argument(
        fmt::format("plot: {}: margin {} is not finite and >= 0", name, a.margin));
}

bool usable(double v, bool log) {
  return std::isfinite(v) && (!log || v > 0);
}

// Resolves an axis range from the values the automatic ends should cover.
Range resolve(const PlotAxis& a, double lo, double hi, bool any) {
  // Work in the axis's own coordinate (log10 for log axes), then map back.
  const auto fwd = [&](double v) { return a.log ? std::log10(v) : v; };
  const auto back = [&](double u) { return a.log ? std::pow(10.0, u) : u; };
  double u0, u1;
  if (!any) {
    u0 = 0.0;
    u1 = 1.0;
  } else {
    u0 = fwd(lo);
    u1 = fwd(hi);
    if (u0 == u1) {
      const double h = a.log ? 0.5 : std::max(std::abs(u0), 1.0) * 0.5;
      u0 -= h;
      u1 += h;
    } else {
      const double pad = (u1 - u0) * a.margin;
      u0 -= pad;
      u1 += pad;
    }
  }
  if (a.min) u0 = fwd(*a.min);
  if (a.max) u1 = fwd(*a.max);
  if (!(u0 < u1)) {  // one end given and the data lies wholly beyond it
    if (a.min)
      u1 = u0 + 1.0;
    else
      u0 = u1 - 1.0;
  }
  Range r{back(u0), back(u1)};
  if (a.min) r.min = *a.min;
  if (a.max) r.max = *a.max;
  return r;
}

Range x_range(const PlotSpec& spec) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  bool any = false;
  const auto take = [&](double v) {
    if (!usable(v, spec.x.log)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    any = true;
  };
  for (const PlotSeries& s : spec.series)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (usable(s.y[i], spec.y.log)) take(s.x[i]);
  for (const ReferenceLine& r : spec.references)
    if (r.orientation == ReferenceLine::Orientation::vertical) take(r.value);
  return resolve(spec.x, lo, hi, any);
}

Range y_range(const PlotSpec& spec, Range x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  bool any = false;
  const auto take = [&](double v) {
    if (!usable(v, spec.y.log)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    any = true;
  };
  for (const PlotSeries& s : spec.series)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (usable(s.x[i], spec.x.log) && s.x[i] >= x.min && s.x[i] <= x.max) take(s.y[i]);
  for (const ReferenceLine& r : spec.references)
    if (r.orientation == ReferenceLine::Orientation::horizontal) take(r.value);
  return resolve(spec.y, lo, hi, any);
}

// Geometry derived from the text scale s (px per font unit).
struct Metrics {
  float s;
  float title_scale;
  double pad, tick, gap, line;  // px
  double swatch;                // legend swatch length, px
  explicit Metrics(float scale)
      : s(scale),
        title_scale(scale + 1.0f),
        pad(6.0 * scale),
        tick(3.0 * scale),
        gap(3.0 * scale),
        line(12.0 * scale),
        swatch(14.0 * scale) {}
};

// Ticks whose labels fit: fewer majors until neighbouring labels keep a gap.
void fit_ticks(const PlotAxis& a, Range r, double length, bool horizontal, const Metrics& m,
               Ticks& ticks, std::vector<std::string>& labels) {
  for (int max_major = 10; max_major >= 2; --max_major) {
    ticks = nice_ticks(r.min, r.max, a.log, max_major);
    labels = tick_labels(ticks.major, a.log);
    if (ticks.major.size() < 2) return;
    AxisMap map{r.min, r.max, 0.0, length, a.log};
    bool fits = true;
    for (std::size_t i = 1; i < ticks.major.size() && fits; ++i) {
      const double spacing =
          std::abs(map.to_pixel(ticks.major[i]) - map.to_pixel(ticks.major[i - 1]));
      const double need = horizontal ? 0.5 * (Renderer::text_width(labels[i], m.s) +
                                              Renderer::text_width(labels[i - 1], m.s)) +
                                           3 * m.gap
                                     : Renderer::text_height(m.s) + 2 * m.gap;
      fits = spacing >= need;
    }
    if (fits) return;
  }
}

double widest(const std::vector<std::string>& labels, float scale) {
  double w = 0;
  for (const std::string& l : labels) w = std::max(w, double(Renderer::text_width(l, scale)));
  return w;
}

PlotLayout layout_once(const PlotSpec& spec, PixelBox frame, const Metrics& m, Range xr, Range yr,
                       double legend_width) {
  PlotLayout L;
  L.frame = frame;
  L.text_scale = m.s;
  const double text_h = Renderer::text_height(m.s);
  for (const std::string& c : spec.caption)
    for (std::string& l : wrap(c, frame.width() - 2 * m.pad, m.s)) L.caption_lines.push_back(l);

  const double top =
      frame.y0 + m.pad +
      (spec.title.empty() ? 0.0 : Renderer::text_height(m.title_scale) + m.line * 0.75);
  const double bottom = frame.y1 - m.pad - m.line * double(L.caption_lines.size()) -
                        (L.caption_lines.empty() ? 0.0 : m.gap) -
                        (spec.x.label.empty() ? 0.0 : text_h + 2 * m.gap) - text_h - m.gap - m.tick;
  const double y_length = bottom - top;
  if (y_length > 0) fit_ticks(spec.y, yr, y_length, false, m, L.y_ticks, L.y_tick_labels);
  const double left = frame.x0 + m.pad + (spec.y.label.empty() ? 0.0 : text_h + 2 * m.gap) +
                      widest(L.y_tick_labels, m.s) + m.gap + m.tick;
  // Half of the last x label may hang beyond the area's right edge.
  const double right = frame.x1 - m.pad - legend_width - 0.5 * Renderer::text_width("0000000", m.s);
  const double x_length = right - left;
  if (x_length < 8 * m.s || y_length < 8 * m.s) {
    throw std::invalid_argument(fmt::format(
        "plot: a {:.0f}x{:.0f} px frame leaves no room for the plot area (text scale {})",
        frame.width(), frame.height(), m.s));
  }
  fit_ticks(spec.x, xr, x_length, true, m, L.x_ticks, L.x_tick_labels);
  L.area = {left, top, right, bottom};
  L.x = {xr.min, xr.max, left, right, spec.x.log};
  L.y = {yr.min, yr.max, bottom, top, spec.y.log};
  return L;
}

// Legend box size for the entries.
std::array<double, 2> legend_size(const std::vector<LegendEntry>& entries, const Metrics& m) {
  double w = 0;
  for (const LegendEntry& e : entries) w = std::max(w, double(Renderer::text_width(e.label, m.s)));
  return {m.pad + m.swatch + 2 * m.gap + w + m.pad,
          2 * m.gap + m.line * double(entries.size()) + m.gap};
}

// Does anything drawn in the area touch box?
bool touches(const PlotSpec& spec, const PlotLayout& L, const PixelBox& box) {
  PixelBox grown{box.x0 - 2, box.y0 - 2, box.x1 + 2, box.y1 + 2};
  for (const PlotSeries& s : spec.series) {
    const double r = (s.marker == Marker::none ? 0.0 : s.marker_size) + s.line_width;
    const PixelBox b{grown.x0 - r, grown.y0 - r, grown.x1 + r, grown.y1 + r};
    bool hit = false;
    if (s.lines) {
      for_each_segment(s, L, [&](double x0, double y0, double x1, double y1) {
        if (!hit) hit = clip_segment(x0, y0, x1, y1, b);
      });
    }
    // A lone point (or every point of a marker series) counts as well.
    for_each_point(s, L, [&](double x, double y) { hit = hit || b.contains(x, y); });
    if (hit) return true;
  }
  for (const ReferenceLine& r : spec.references) {
    if (r.orientation == ReferenceLine::Orientation::horizontal) {
      const double y = L.y.to_pixel(r.value);
      if (y >= grown.y0 && y < grown.y1) return true;
    } else {
      const double x = L.x.to_pixel(r.value);
      if (x >= grown.x0 && x < grown.x1) return true;
    }
  }
  return false;
}

PixelBox corner_box(LegendPlacement p, const PlotLayout& L, std::array<double, 2> size,
                    const Metrics& m) {
  const PixelBox& a = L.area;
  const bool right = p == LegendPlacement::top_right || p == LegendPlacement::bottom_right;
  const bool top = p == LegendPlacement::top_right || p == LegendPlacement::top_left;
  const double x0 = right ? a.x1 - m.pad - size[0] : a.x0 + m.pad;
  const double y0 = top ? a.y0 + m.pad : a.y1 - m.pad - size[1];
  return {x0, y0, x0 + size[0], y0 + size[1]};
}

}  // namespace

PlotLayout layout_plot(const PlotSpec& spec, PixelBox frame) {
  validate_axis("x", spec.x);
  validate_axis("y", spec.y);
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const PlotSeries& s = spec.series[i];
    const std::string name = s.label.empty() ? fmt::format("#{}", i) : fmt::format("'{}'", s.label);
    if (s.x.size() != s.y.size())
      throw std::invalid_argument(fmt::format("plot: series {}: x has {} values but y has {}", name,
                                              s.x.size(), s.y.size()));
    if (!(s.line_width > 0) || !(s.marker_size > 0) || !std::isfinite(s.line_width) ||
        !std::isfinite(s.marker_size))
      throw std::invalid_argument(
          fmt::format("plot: series {}: line_width {} and marker_size {} must be finite and > 0",
                      name, s.line_width, s.marker_size));
  }
  for (const ReferenceLine& r : spec.references)
    if (!std::isfinite(r.value))
      throw std::invalid_argument(
          fmt::format("plot: reference line '{}' has a non-finite value {}", r.label, r.value));
  if (!(spec.text_scale >= 0) || !std::isfinite(spec.text_scale))
    throw std::invalid_argument(
        fmt::format("plot: text_scale {} is not finite and >= 0", spec.text_scale));

  const Metrics m(spec.text_scale > 0 ? spec.text_scale
                                      : plot_text_scale(int(frame.width()), int(frame.height())));
  const Range xr = x_range(spec);
  const Range yr = y_range(spec, xr);
  const std::vector<LegendEntry> entries = legend_entries(spec);
  const auto size = legend_size(entries, m);

  PlotLayout L = layout_once(spec, frame, m, xr, yr, 0.0);
  LegendPlacement want = entries.empty() ? LegendPlacement::none : spec.legend;
  if (want == LegendPlacement::automatic) {
    want = LegendPlacement::outside_right;
    for (const LegendPlacement p : {LegendPlacement::top_right, LegendPlacement::top_left,
                                    LegendPlacement::bottom_right, LegendPlacement::bottom_left}) {
      const PixelBox b = corner_box(p, L, size, m);
      const bool fits =
          b.x0 >= L.area.x0 && b.x1 <= L.area.x1 && b.y0 >= L.area.y0 && b.y1 <= L.area.y1;
      if (fits && !touches(spec, L, b)) {
        want = p;
        break;
      }
    }
  }
  if (want == LegendPlacement::outside_right) {
    L = layout_once(spec, frame, m, xr, yr, size[0] + m.pad);
    const double x0 = frame.x1 - m.pad - size[0];
    L.legend_box = {x0, L.area.y0, x0 + size[0], L.area.y0 + size[1]};
  } else if (want != LegendPlacement::none) {
    L.legend_box = corner_box(want, L, size, m);
  }
  L.legend = want;
  return L;
}

// --- drawing ------------------------------------------------------------------------------

namespace {

// Draws a clipped polyline segment, dashed when dash > 0; `phase` carries the dash pattern
// from one segment to the next (px travelled along the polyline).
void stroke(Renderer& r, double x0, double y0, double x1, double y1, float width, Rgba8 c,
            double dash, double gap, double& phase) {
  const double len = std::hypot(x1 - x0, y1 - y0);
  if (dash <= 0) {
    r.line(float(x0), float(y0), float(x1), float(y1), width, c);
    return;
  }
  const double period = dash + gap;
  double t = 0;
  while (t < len) {
    const double in = std::fmod(phase + t, period);
    const double run = in < dash ? std::min(dash - in, len - t) : std::min(period - in, len - t);
    if (in < dash) {
      const double a = t / len, b = (t + run) / len;
      r.line(float(x0 + (x1 - x0) * a), float(y0 + (y1 - y0) * a), float(x0 + (x1 - x0) * b),
             float(y0 + (y1 - y0) * b), width, c);
    }
    t += run;
  }
  phase = std::fmod(phase + len, period);
}

void marker(Renderer& r, Marker k, double x, double y, float size, Rgba8 c) {
  const float cx = float(x), cy = float(y), s = size;
  switch (k) {
    case Marker::none:
      return;
    case Marker::circle:
      r.disc(cx, cy, s, c);
      return;
    case Marker::square:
      r.rect(cx - s, cy - s, cx + s, cy + s, c);
      return;
    case Marker::diamond: {
      const float d = s * 1.3f;
      r.triangle(cx - d, cy, cx, cy - d, cx + d, cy, c);
      r.triangle(cx - d, cy, cx + d, cy, cx, cy + d, c);
      return;
    }
    case Marker::triangle: {
      const float d = s * 1.4f;
      r.triangle(cx, cy - d, cx + d * 0.866f, cy + d * 0.5f, cx - d * 0.866f, cy + d * 0.5f, c);
      return;
    }
  }
}

Renderer::ClipRect pixels_of(const PixelBox& b) {
  return {int(std::floor(b.x0)), int(std::floor(b.y0)), int(std::ceil(b.x1)), int(std::ceil(b.y1))};
}

}  // namespace

PlotLayout add_plot(Renderer& r, const PlotSpec& spec, PixelBox frame) {
  PlotLayout L = layout_plot(spec, frame);
  const Metrics m(L.text_scale);
  const PixelBox& a = L.area;
  const float s = m.s;
  const double text_h = Renderer::text_height(s);
  const double dash = 5.0 * s, gap = 3.0 * s;

  r.set_clip(pixels_of(frame));
  r.rect(float(frame.x0), float(frame.y0), float(frame.x1), float(frame.y1), paper);
  // Grid: minor, then major lines across the area.
  for (const auto* ticks : {&L.x_ticks.minor, &L.x_ticks.major}) {
    const Rgba8 c = ticks == &L.x_ticks.minor ? grid_minor : grid_major;
    for (double v : *ticks) {
      const float x = float(L.x.to_pixel(v));
      r.line(x, float(a.y0), x, float(a.y1), 1.0f, c);
    }
  }
  for (const auto* ticks : {&L.y_ticks.minor, &L.y_ticks.major}) {
    const Rgba8 c = ticks == &L.y_ticks.minor ? grid_minor : grid_major;
    for (double v : *ticks) {
      const float y = float(L.y.to_pixel(v));
      r.line(float(a.x0), y, float(a.x1), y, 1.0f, c);
    }
  }

  // Data, cut to the area: reference lines, then series in order.
  r.set_clip(pixels_of(a));
  for (const ReferenceLine& ref : spec.references) {
    double x0 = a.x0, x1 = a.x1, y0 = a.y0, y1 = a.y1;
    if (ref.orientation == ReferenceLine::Orientation::horizontal)
      y0 = y1 = L.y.to_pixel(ref.value);
    else
      x0 = x1 = L.x.to_pixel(ref.value);
    if (!std::isfinite(x0 + y0)) continue;  // e.g. <= 0 on a log axis
    double phase = 0;
    if (clip_segment(x0, y0, x1, y1, a))
      stroke(r, x0, y0, x1, y1, ref.line_width, ref.color, ref.dashed ? dash : 0, gap, phase);
  }
  // Clip a little outside the area so line widths at the border stay whole up to the scissor.
  const PixelBox reach{a.x0 - 8, a.y0 - 8, a.x1 + 8, a.y1 + 8};
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const PlotSeries& ser = spec.series[i];
    const Rgba8 c = color_of(spec, i);
    if (ser.lines) {
      double phase = 0;
      for_each_segment(ser, L, [&](double x0, double y0, double x1, double y1) {
        const double full = std::hypot(x1 - x0, y1 - y0);
        const double sx0 = x0, sy0 = y0;
        if (clip_segment(x0, y0, x1, y1, reach)) {
          double p = phase + std::hypot(x0 - sx0, y0 - sy0);  // dash pattern keeps its place
          stroke(r, x0, y0, x1, y1, ser.line_width, c, ser.dashed ? dash : 0, gap, p);
        }
        if (ser.dashed) phase = std::fmod(phase + full, dash + gap);
      });
    }
    if (ser.marker != Marker::none) {
      for_each_point(ser, L, [&](double x, double y) {
        if (reach.contains(x, y)) marker(r, ser.marker, x, y, ser.marker_size, c);
      });
    }
  }

  // Axes: the area's frame, ticks outside it, tick labels, axis labels.
  r.set_clip(pixels_of(frame));
  const float fx0 = float(a.x0), fy0 = float(a.y0), fx1 = float(a.x1), fy1 = float(a.y1);
  r.rect(fx0 - 1, fy0 - 1, fx1 + 1, fy0, axis_ink);
  r.rect(fx0 - 1, fy1, fx1 + 1, fy1 + 1, axis_ink);
  r.rect(fx0 - 1, fy0, fx0, fy1, axis_ink);
  r.rect(fx1, fy0, fx1 + 1, fy1, axis_ink);
  const float tick = float(m.tick), minor_tick = float(m.tick * 0.5);
  for (double v : L.x_ticks.minor) {
    const float x = float(L.x.to_pixel(v));
    r.line(x, fy1 + 1, x, fy1 + 1 + minor_tick, 1.0f, axis_ink);
  }
  for (std::size_t i = 0; i < L.x_ticks.major.size(); ++i) {
    const float x = float(L.x.to_pixel(L.x_ticks.major[i]));
    r.line(x, fy1 + 1, x, fy1 + 1 + tick, 1.5f, axis_ink);
    const float w = Renderer::text_width(L.x_tick_labels[i], s);
    r.text(std::round(x - w * 0.5f), std::round(fy1 + 1 + tick + float(m.gap)), L.x_tick_labels[i],
           s, ink);
  }
  for (double v : L.y_ticks.minor) {
    const float y = float(L.y.to_pixel(v));
    r.line(fx0 - 1 - minor_tick, y, fx0 - 1, y, 1.0f, axis_ink);
  }
  for (std::size_t i = 0; i < L.y_ticks.major.size(); ++i) {
    const float y = float(L.y.to_pixel(L.y_ticks.major[i]));
    r.line(fx0 - 1 - tick, y, fx0 - 1, y, 1.5f, axis_ink);
    const float w = Renderer::text_width(L.y_tick_labels[i], s);
    // Right-aligned; the font's advance includes one trailing unit of spacing.
    r.text(std::round(fx0 - 1 - tick - float(m.gap) - w + s), std::round(y - float(text_h) * 0.4f),
           L.y_tick_labels[i], s, ink);
  }
  const double x_labels_bottom = a.y1 + 1 + m.tick + m.gap + text_h;
  if (!spec.x.label.empty()) {
    const float w = Renderer::text_width(spec.x.label, s);
    r.text(std::round(float((a.x0 + a.x1) * 0.5) - w * 0.5f),
           float(std::round(x_labels_bottom + 2 * m.gap)), spec.x.label, s, ink);
  }
  if (!spec.y.label.empty()) {
    const float w = Renderer::text_width(spec.y.label, s);
    r.text_vertical(float(std::round(L.frame.x0 + m.pad)),
                    std::round(float((a.y0 + a.y1) * 0.5) + w * 0.5f), spec.y.label, s, ink);
  }
  if (!spec.title.empty()) {
    float ts = m.title_scale;
    if (Renderer::text_width(spec.title, ts) > L.frame.width() - 2 * m.pad) ts = s;
    const float w = Renderer::text_width(spec.title, ts);
    r.text(std::round(float((L.frame.x0 + L.frame.x1) * 0.5) - w * 0.5f),
           float(std::round(L.frame.y0 + m.pad)), spec.title, ts, ink);
  }

  // Caption under everything, left-aligned.
  double cy = L.frame.y1 - m.pad - m.line * double(L.caption_lines.size()) + (m.line - text_h);
  for (const std::string& line : L.caption_lines) {
    r.text(float(std::round(L.frame.x0 + m.pad)), float(std::round(cy)), line, s, ink);
    cy += m.line;
  }

  // Legend.
  if (L.legend != LegendPlacement::none) {
    const PixelBox& b = L.legend_box;
    r.rect(float(b.x0) - 1, float(b.y0) - 1, float(b.x1) + 1, float(b.y1) + 1, legend_edge);
    r.rect(float(b.x0), float(b.y0), float(b.x1), float(b.y1), legend_paper);
    double y = b.y0 + 2 * m.gap;
    for (const LegendEntry& e : legend_entries(spec)) {
      const double mid = y + text_h * 0.4;
      const double x0 = b.x0 + m.pad, x1 = x0 + m.swatch;
      if (e.lines) {
        double phase = 0;
        stroke(r, x0, mid, x1, mid, std::max(e.line_width, 2.0f), e.color,
               e.dashed ? dash * 0.6 : 0, gap * 0.6, phase);
      }
      if (e.marker != Marker::none)
        marker(r, e.marker, (x0 + x1) * 0.5, mid, e.marker_size, e.color);
      r.text(float(std::round(x1 + 2 * m.gap)), float(std::round(y)), e.label, s, ink);
      y += m.line;
    }
  }
  r.set_clip(std::nullopt);
  return L;
}

PlotLayout draw_plot(Renderer& r, const PlotSpec& spec) {
  r.begin(paper);
  PlotLayout L = add_plot(r, spec, PixelBox{0, 0, double(r.width()), double(r.height())});
  r.finish();
  return L;
}

}  // namespace fixstep
