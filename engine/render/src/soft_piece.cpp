// SoftPiece (soft_piece.hpp): set-up from the corners, each row's span from exact integer edge
// functions, and the rows drawn: solid pieces a span at a time, the rest a 2x2 quad at a time
// (one vector lane a pixel), so that the shader's derivatives are the differences llvmpipe
// takes. The quads' loop is soft_quads.hpp's, compiled here for 4 lanes (one quad a vector);
// where the CPU has AVX2, shaded pieces are drawn by its 8-lane copy (two quads a vector,
// soft_piece_avx2.cpp) instead, with the same pixels.
#include "soft_piece.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "soft_lanes.hpp"
#define FIXSTEP_QUADS_FN  // the baseline instruction set: no attributes
#include "soft_quads.hpp"

namespace fixstep::detail {

namespace {

using namespace lanes;
constexpr std::int64_t sub = soft_subpixels;

/// Exact: whether pixel i of the row whose centre is at subpixel Y is inside edge e.
inline bool inside(const SoftEdge& e, std::int64_t i, std::int64_t Y) {
  return e.a * (i * sub + sub / 2) + e.b * Y + e.c >= 0;
}

/// floor(n / d) for d > 0.
inline std::int64_t floor_div(std::int64_t n, std::int64_t d) {
  const std::int64_t q = n / d;
  return (n % d != 0 && n < 0) ? q - 1 : q;
}

/// The half-plane of the edge from corner `from` to corner `to` (SoftEdge), the tie rule folded
/// into c; at and per_row are set only where the edge is not horizontal (a != 0).
SoftEdge make_edge(const std::int64_t (&from)[2], const std::int64_t (&to)[2]) {
  SoftEdge e;
  e.a = from[1] - to[1];
  e.b = to[0] - from[0];
  e.c = -(e.a * from[0] + e.b * from[1]);
  // A pixel centre on an edge shared by two pieces belongs to exactly one: the edge's
  // direction is reversed in the other, and only one of (a, b), (-a, -b) passes this.
  if (!(e.a > 0 || (e.a == 0 && e.b > 0))) e.c -= 1;
  if (e.a == 0) return e;
  // a (i sub + sub/2) + b (j sub + sub/2) + c = 0
  const double inv_step = 1.0 / (double(e.a) * sub);
  const double half = 0.5 * double(sub);
  e.at = -(double(e.b) * half + double(e.c) + double(e.a) * half) * inv_step;
  e.per_row = -double(e.b) * sub * inv_step;
  return e;
}

/// The bounding box of corners p[0, corners).
SoftCornerBox corner_box(const std::int64_t (*p)[2], int corners) {
  SoftCornerBox b{p[0][0], p[0][0], p[0][1], p[0][1]};
  for (int k = 1; k < corners; ++k) {
    b.x_min = std::min(b.x_min, p[k][0]), b.x_max = std::max(b.x_max, p[k][0]);
    b.top = std::min(b.top, p[k][1]), b.bottom = std::max(b.bottom, p[k][1]);
  }
  return b;
}

}  // namespace

bool SoftPiece::set_up(const CanvasVertex* const* v, const std::int64_t (*p)[2], int corners,
                       const PixelBox& cut) {
  const std::int64_t area = soft_cross(p[0], p[1], p[2]);
  if (area == 0) return false;
  std::int64_t first_row = INT32_MIN, last_row = INT32_MAX;  // as the horizontal edges allow
  set_edges(p, corners, area < 0, first_row, last_row);
  set_planes(v, p);
  set_coverage(v, corners);
  box = cut;
  const SoftCornerBox b = corner_box(p, corners);
  set_rows_and_columns(b, first_row, last_row);
  rect = solid && corners == 4;
  for (int k = 0; k < corners && rect; ++k) {  // every corner on the bounding box's corners
    rect = (p[k][0] == b.x_min || p[k][0] == b.x_max) && (p[k][1] == b.top || p[k][1] == b.bottom);
  }
  if (rect) return set_up_rect(*v[0], b.x_min, b.top, b.x_max, b.bottom, cut);
  return row0 <= row1 && box.x0 < box.x1;
}

void SoftPiece::set_edges(const std::int64_t (*p)[2], int corners, bool flip,
                          std::int64_t& first_row, std::int64_t& last_row) {
  SoftEdge left[4], right[4];
  lefts = rights = 0;
  for (int k = 0; k < corners; ++k) {
    const int from = flip ? (corners - k) % corners : k;
    const int to = flip ? (corners - k - 1) % corners : (k + 1) % corners;
    const SoftEdge e = make_edge(p[from], p[to]);
    if (e.a == 0) {  // rows j with b (j sub + sub/2) + c >= 0
      const std::int64_t n = e.b * (sub / 2) + e.c;
      if (e.b > 0) {
        first_row = std::max(first_row, -floor_div(n, e.b * sub));
      } else {
        last_row = std::min(last_row, floor_div(n, -e.b * sub));
      }
    } else if (e.a > 0) {
      left[lefts++] = e;
    } else {
      right[rights++] = e;
    }
  }
  for (int k = 0; k < lefts; ++k) edge[k] = left[k];
  for (int k = 0; k < rights; ++k) edge[lefts + k] = right[k];
}

void SoftPiece::set_planes(const CanvasVertex* const* v, const std::int64_t (*p)[2]) {
  // The planes, from the first three corners (a quad's fourth lies on them: add()).
  double x[3], y[3];
  for (int k = 0; k < 3; ++k) x[k] = double(p[k][0]) / sub, y[k] = double(p[k][1]) / sub;
  x0 = x[0];
  y0 = y[0];
  const double inv_det = 1.0 / ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]));
  auto plane = [&](double f0, double f1, double f2) {
    return SoftPlane{f0, ((f1 - f0) * (y[2] - y[0]) - (f2 - f0) * (y[1] - y[0])) * inv_det,
                     ((f2 - f0) * (x[1] - x[0]) - (f1 - f0) * (x[2] - x[0])) * inv_det};
  };
  u = plane(v[0]->u, v[1]->u, v[2]->u);
  this->v = plane(v[0]->v, v[1]->v, v[2]->v);
  const std::uint8_t* c[3] = {&v[0]->r, &v[1]->r, &v[2]->r};
  flat_color = true;
  for (int ch = 0; ch < 4; ++ch) {
    flat_color = flat_color && c[0][ch] == c[1][ch] && c[0][ch] == c[2][ch];
  }
  for (int ch = 0; ch < 4; ++ch) {
    const auto value = [&](int k) { return double(float(c[k][ch]) / 255.0f); };
    color[ch] = flat_color ? SoftPlane{value(0), 0, 0} : plane(value(0), value(1), value(2));
  }
}

void SoftPiece::set_coverage(const CanvasVertex* const* v, int corners) {
  fill = v[corners - 1]->fill;  // flat: GL's provoking vertex is the last (one per shape)
  solid = flat_color && !has_hole();
  hole_r = reach_r = -1;
  if (!solid && !is_line()) find_round();
  for (int k = 0; k < corners && solid; ++k) solid = v[k]->u == 0.0f && v[k]->v == 0.0f;
}

void SoftPiece::set_rows_and_columns(const SoftCornerBox& c, std::int64_t first_row,
                                     std::int64_t last_row) {
  // Rows whose centres lie within [top, bottom] (and within the horizontal edges' rows).
  row0 = static_cast<int>(
      std::max({std::int64_t(box.y0), floor_div(c.top - sub / 2, sub), first_row}));
  row1 = static_cast<int>(
      std::min({std::int64_t(box.y1 - 1), -floor_div(sub / 2 - c.bottom, sub), last_row}));
  col0 = static_cast<int>(std::max(std::int64_t(box.x0), floor_div(c.x_min - sub / 2, sub)));
  col1 =
      static_cast<int>(std::min(std::int64_t(box.x1 - 1), floor_div(c.x_max - sub / 2, sub) + 1));
}

bool SoftPiece::set_up_rect(const CanvasVertex& c, std::int64_t x_min, std::int64_t y_min,
                            std::int64_t x_max, std::int64_t y_max, const PixelBox& cut) {
  lefts = rights = 0;
  const std::uint8_t* rgba = &c.r;
  for (int ch = 0; ch < 4; ++ch) color[ch] = SoftPlane{double(float(rgba[ch]) / 255.0f), 0, 0};
  fill = c.fill;
  flat_color = solid = rect = true;
  hole_r = reach_r = -1;
  box = cut;
  // Pixel (i, j) is inside where x_min <= i sub + sub/2 < x_max and y_min <= j sub + sub/2 <
  // y_max: the tie rule of the edges (the left and top edges own their centres).
  auto first_from = [](std::int64_t edge) { return floor_div(edge - sub / 2 + sub - 1, sub); };
  col0 = static_cast<int>(std::max<std::int64_t>(box.x0, first_from(x_min)));
  col1 = static_cast<int>(std::min<std::int64_t>(box.x1, first_from(x_max)) - 1);
  row0 = static_cast<int>(std::max<std::int64_t>(box.y0, first_from(y_min)));
  row1 = static_cast<int>(std::min<std::int64_t>(box.y1, first_from(y_max)) - 1);
  return row0 <= row1 && col0 <= col1;
}

void SoftPiece::find_round() {
  // uv = 0 at the centre. A step of ρ px changes uv by at most σ_max ρ and at least σ_min ρ,
  // σ the singular values of the map's Jacobian J, and d's fwidth w is at most w_max. Alpha is
  // 0 where d >= 1 + w / 2 (outside the shape) and, for a circle, where d <= fill - w / 2
  // (inside its hole). σ_max² = (S + √(S² - 4 det²)) / 2 with S = |J|² (Frobenius), the
  // eigenvalues of JᵀJ, and σ_min = |det| / σ_max; σ_max is taken a part in 10⁶ large, and
  // the radii get a further 0.01 px margin, against the rounding of these doubles and of the
  // floats the quads compute d in.
  const double det = u.dx * v.dy - u.dy * v.dx;
  if (!(std::abs(det) > 1e-12)) return;
  const double du = -u.at, dv = -v.at;  // solve the planes for uv = 0
  centre_x = x0 + (du * v.dy - u.dy * dv) / det;
  centre_y = y0 + (u.dx * dv - du * v.dx) / det;
  const double frobenius2 = u.dx * u.dx + u.dy * u.dy + v.dx * v.dx + v.dy * v.dy;
  const double gap = std::sqrt(std::max(0.0, frobenius2 * frobenius2 - 4.0 * det * det));
  const double sigma_max = std::sqrt(0.5 * (frobenius2 + gap)) * (1.0 + 1e-6);
  const double sigma_min = std::abs(det) / sigma_max;
  const double w_max = std::sqrt(u.dx * u.dx + v.dx * v.dx) + std::sqrt(u.dy * u.dy + v.dy * v.dy);
  reach_r = (1.0 + 0.5 * w_max) / sigma_min + 0.01;
  if (has_hole()) hole_r = (double(fill) - 0.5 * w_max) / sigma_max - 0.01;
}

void SoftPiece::span(int j, int& lo, int& hi) const {
  // The tightest bound of each side, in double (within 1e-9 px of the exact one), rounded
  // inwards; decided exactly where it is a hair from a whole pixel (only a pixel centre on an
  // edge itself can go either way).
  const SoftEdge* end = edge + lefts + rights;
  double from = double(box.x0), to = double(box.x1 - 1);
  for (const SoftEdge* e = edge; e != edge + lefts; ++e)
    from = std::max(from, e->at + e->per_row * j);
  for (const SoftEdge* e = edge + lefts; e != end; ++e) to = std::min(to, e->at + e->per_row * j);
  if (!(from <= double(box.x1)) || !(to >= double(box.x0 - 1))) {  // none inside the box
    lo = box.x0;
    hi = lo - 1;
    return;
  }
  auto first = static_cast<std::int64_t>(from);  // from >= box.x0 >= 0: towards zero is floor
  const double rest_first = from - double(first);
  if (rest_first > 0.0) ++first;                        // ceil
  auto last = static_cast<std::int64_t>(to + 1.0) - 1;  // floor (to >= -1)
  const double rest_last = to - double(last);
  const std::int64_t Y = std::int64_t(j) * sub + sub / 2;
  auto inside_all = [&](const SoftEdge* b, const SoftEdge* e, std::int64_t i) {
    for (; b != e; ++b) {
      if (!inside(*b, i, Y)) return false;
    }
    return true;
  };
  constexpr double hair = 1e-6;
  if (lefts > 0 && (rest_first < hair || rest_first > 1.0 - hair)) {
    while (!inside_all(edge, edge + lefts, first)) ++first;
    while (first > box.x0 && inside_all(edge, edge + lefts, first - 1)) --first;
  }
  if (rights > 0 && (rest_last < hair || rest_last > 1.0 - hair)) {
    while (!inside_all(edge + lefts, end, last)) --last;
    while (last < box.x1 - 1 && inside_all(edge + lefts, end, last + 1)) ++last;
  }
  lo = static_cast<int>(first);
  hi = static_cast<int>(std::max(last, first - 1));
}

void SoftPiece::draw_solid(std::uint8_t* pixels, int width, int first, int last) const {
  const float ca = float(color[3].at);
  const int a = to8(ca);
  if (a == 0) return;
  const int r = to8(float(color[0].at) * ca), g = to8(float(color[1].at) * ca),
            b = to8(float(color[2].at) * ca);
  for (int j = std::max(first, row0); j <= std::min(last, row1); ++j) {
    int lo = col0, hi = col1;
    if (!rect) span(j, lo, hi);
    blend_span(pixels + (std::size_t(j) * std::size_t(width) + std::size_t(lo)) * 4, hi - lo + 1, r,
               g, b, a);
  }
}

namespace {

bool cpu_has_wide_lanes() {
#if FIXSTEP_SOFT_WIDE
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") != 0;
#else
  return false;
#endif
}

std::atomic<bool> wide_lanes{cpu_has_wide_lanes()};

}  // namespace

bool soft_wide_lanes() {
  return wide_lanes.load(std::memory_order_relaxed);
}

void set_soft_wide_lanes(bool wide) {
  wide_lanes.store(wide && cpu_has_wide_lanes(), std::memory_order_relaxed);
}

void SoftPiece::draw_shaded(std::uint8_t* pixels, int width, int first, int last) const {
#if FIXSTEP_SOFT_WIDE
  if (soft_wide_lanes()) {
    draw_shaded_wide(*this, pixels, width, first, last);
    return;
  }
#endif
  draw_shaded_lanes<lanes::Lanes4>(*this, pixels, width, first, last);
}

bool SoftPiece::quad_row(int top, int width, std::uint8_t* pixels, SoftQuadRow& q) const {
  for (int r = 0; r < 2; ++r) {
    q.lo[r] = 0, q.hi[r] = -1;
    if (top + r >= row0 && top + r <= row1) span(top + r, q.lo[r], q.hi[r]);
  }
  int x_first = width, x_last = -1;  // the columns either row covers
  for (int r = 0; r < 2; ++r) {
    if (q.lo[r] > q.hi[r]) continue;
    x_first = std::min(x_first, q.lo[r]);
    x_last = std::max(x_last, q.hi[r]);
  }
  if (x_first > x_last) return false;
  q.x_start = x_first & ~1;
  q.cx = q.x_start + 0.5;
  q.cy = top + 0.5;
  // In a frame of odd height the top row's quad pairs it with row -1, outside the frame: no
  // lane there is drawn (its span is empty), and the quad is blended lane by lane.
  q.whole = top >= 0;
  q.rows[0] = q.whole ? pixels + std::size_t(top) * std::size_t(width) * 4 : nullptr;
  q.rows[1] = pixels + std::size_t(top + 1) * std::size_t(width) * 4;
  // Quads wholly outside a round shape, or inside a circle's hole (their alpha 0
  // everywhere), are skipped.
  q.skip_from = x_last + 1, q.skip_to = x_last;  // quads x in [skip_from, skip_to)
  q.x_begin = q.x_start;
  const double cy = q.cy;
  if (reach_r > 0.0) {
    const double near = centre_y >= cy && centre_y <= cy + 1.0
                            ? 0.0
                            : std::min(std::abs(cy - centre_y), std::abs(cy + 1.0 - centre_y));
    if (near >= reach_r) return false;
    const double half = std::sqrt(reach_r * reach_r - near * near);
    x_last = std::min(x_last, static_cast<int>(std::floor(centre_x + half - 0.5)));
    const int from = static_cast<int>(std::ceil(centre_x - half - 0.5));
    if (from > q.x_begin) q.x_begin = from & ~1;
  }
  q.x_last = x_last;
  if (hole_r > 0.0) {
    const double dy = std::max(std::abs(cy - centre_y), std::abs(cy + 1.0 - centre_y));
    if (dy < hole_r) {
      const double half = std::sqrt(hole_r * hole_r - dy * dy);
      int from = static_cast<int>(std::ceil(centre_x - half - 0.5));
      int to = static_cast<int>(std::floor(centre_x + half - 0.5));  // last column inside
      from += from & 1;                                              // whole quads only
      to = to - 1 - ((to - 1) & 1) + 2;                              // one past the last whole quad
      q.skip_from = from;
      q.skip_to = std::max(to, from);
    }
  }
  return q.x_begin <= q.x_last;
}

}  // namespace fixstep::detail
