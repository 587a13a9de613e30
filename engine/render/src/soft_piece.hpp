// One convex piece of the CPU rasteriser (soft_shapes.hpp): a triangle, or a quad of two that
// share one affine map, with its exact edges, its interpolated planes and the drawing of its
// rows. Internal to fixstep::render (not installed).
#pragma once

#include <cstdint>

#include "fixstep/render/render.hpp"

// Where the rasteriser has an 8-lane (AVX2) path beside its 4-lane one, chosen at run time.
#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
#define FIXSTEP_SOFT_WIDE 1
#else
#define FIXSTEP_SOFT_WIDE 0
#endif

namespace fixstep::detail {

/// Subpixel steps per px of the edges (llvmpipe's precision).
inline constexpr std::int64_t soft_subpixels = 256;
/// A fill below this is Renderer::no_hole (no circle's hole).
inline constexpr float soft_no_hole = -1e29f;

/// An axis-aligned pixel rectangle [x0, x1) x [y0, y1) that drawing is cut to.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// One edge's half-plane over subpixel coordinates: a pixel centre (X, Y) is inside where
/// a X + b Y + c >= 0 (the tie rule folded into c). In pixel terms, row j's pixels i satisfy
/// i >= bound (a > 0) or i <= bound (a < 0), bound = at + per_row j, kept in double to decide
/// quickly and checked exactly where it is within a hair of a whole pixel.
struct SoftEdge {
  std::int64_t a = 0, b = 0, c = 0;
  double at = 0, per_row = 0;
};

/// A value interpolated affinely over a piece: at px (x, y), at + dx (x - x0) + dy (y - y0).
struct SoftPlane {
  double at = 0, dx = 0, dy = 0;
};

/// x (px, within soft_reach_px) in subpixel steps, rounded to nearest, halves away from zero
/// (std::llround's rounding, inline: x 256 is exact in double, and so is the added half).
inline std::int64_t soft_snap(float x) {
  const double s = double(x) * double(soft_subpixels);
  return static_cast<std::int64_t>(s >= 0.0 ? s + 0.5 : s - 0.5);
}

/// (q - p) x (r - p), exact over subpixel coordinates.
inline std::int64_t soft_cross(const std::int64_t (&p)[2], const std::int64_t (&q)[2],
                               const std::int64_t (&r)[2]) {
  return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
}

/// The bounding box of a piece's corners, subpixels.
struct SoftCornerBox {
  std::int64_t x_min = 0, x_max = 0, top = 0, bottom = 0;
};

/// One row of a piece's 2x2 quads (SoftPiece::quad_row()): the rows' spans, the columns to draw
/// and the rows' pixels.
struct SoftQuadRow {
  int lo[2] = {0, 0}, hi[2] = {-1, -1};  ///< each row's span of pixels [lo, hi] (lo > hi: none)
  int x_start = 0;  ///< the even column the planes are taken at (with cx, cy: its centre, px)
  int x_begin = 0, x_last = -1;    ///< quads from column x_begin (even) to x_last
  int skip_from = 0, skip_to = 0;  ///< quads x in [skip_from, skip_to) have alpha 0
  double cx = 0, cy = 0;
  std::uint8_t* rows[2] = {nullptr, nullptr};  ///< the rows' pixels (row -1: nullptr)
  bool whole = false;                          ///< both rows are in the frame
};

/// One convex piece (a triangle, or a quad of two), set up for drawing.
struct SoftPiece {
  SoftEdge edge[4];           ///< left edges (a > 0), then right edges (a < 0)
  int lefts = 0, rights = 0;  ///< horizontal edges only limit the rows
  double x0 = 0, y0 = 0;      ///< the first vertex, px (snapped): the planes' origin
  SoftPlane u, v, color[4];
  PixelBox box;
  float fill = 0;
  bool solid = false;       ///< coverage 1 everywhere: no shape coordinates, no hole
  bool flat_color = false;  ///< one colour: the vertices'
  bool rect = false;        ///< solid and axis-aligned: columns [col0, col1] on every row
  int row0 = 0, row1 = -1;  ///< rows it may cover, within the box
  int col0 = 0, col1 = -1;  ///< columns it may cover, within the box (a rect: exactly these)
  /// A disc's or circle's centre (uv = 0), px: pixel centres within hole_r px of it (a
  /// circle's hole) or beyond reach_r px (outside the shape) are sure to get alpha 0
  /// (reach_r < 0: not round; hole_r < 0: no hole).
  double centre_x = 0, centre_y = 0, hole_r = -1, reach_r = -1;
  /// Sets centre_x, centre_y, hole_r and reach_r (set_up()).
  void find_round();

  /// Sets up the piece with corners v (3 or 4, convex, in order), snapped to p (soft_snap); false
  /// when it covers no pixel centre (no area, or outside the box).
  bool set_up(const CanvasVertex* const* v, const std::int64_t (*p)[2], int corners,
              const PixelBox& cut);
  /// set_up()'s steps, in the order it takes them. The edges of corners p (reversed when
  /// `flip`), left ones then right ones; horizontal edges narrow rows [first_row, last_row].
  void set_edges(const std::int64_t (*p)[2], int corners, bool flip, std::int64_t& first_row,
                 std::int64_t& last_row);
  /// The planes (u, v, colours) from the first three corners, and flat_color.
  void set_planes(const CanvasVertex* const* v, const std::int64_t (*p)[2]);
  /// fill, solid, and a round shape's centre and radii (find_round()).
  void set_coverage(const CanvasVertex* const* v, int corners);
  /// Rows and columns within the box whose centres the corners' box `c` and rows [first_row,
  /// last_row] may cover.
  void set_rows_and_columns(const SoftCornerBox& c, std::int64_t first_row, std::int64_t last_row);
  /// Sets up a solid axis-aligned rectangle of colour c from subpixel corner (x0, y0) to
  /// (x1, y1) (x0 < x1, y0 < y1) without edges or planes; false when it covers no pixel centre.
  bool set_up_rect(const CanvasVertex& c, std::int64_t x0, std::int64_t y0, std::int64_t x1,
                   std::int64_t y1, const PixelBox& cut);
  /// Pixels [lo, hi] of row j whose centres are inside, within the box (lo > hi: none).
  void span(int j, int& lo, int& hi) const;
  /// A line's piece: its shape coordinate u is 0 everywhere, so d = |v| (no root needed).
  [[nodiscard]] bool is_line() const { return u.at == 0.0 && u.dx == 0.0 && u.dy == 0.0; }
  /// A circle's piece: the coverage of its hole (radius `fill`) is taken away.
  [[nodiscard]] bool has_hole() const { return fill >= soft_no_hole; }
  [[nodiscard]] double at(const SoftPlane& p, double x, double y) const {
    return p.at + p.dx * (x - x0) + p.dy * (y - y0);
  }
  /// Rows [first, last] of a solid piece of one colour.
  void draw_solid(std::uint8_t* pixels, int width, int first, int last) const;
  /// Rows [first, last] of any piece, `first` the top row of one of the GL framebuffer's 2x2
  /// quads (soft_quads.hpp's loop, in 4 or 8 lanes as soft_wide_lanes() says).
  void draw_shaded(std::uint8_t* pixels, int width, int first, int last) const;
  /// The quads of rows top and top + 1 of a frame `width` px wide: false when none is drawn.
  bool quad_row(int top, int width, std::uint8_t* pixels, SoftQuadRow& row) const;
};

/// Whether shaded pieces are drawn two quads at a time in 8-lane vectors (AVX2, where the CPU
/// has it; the pixels are the same as with 4 lanes). The setter is for tests and benchmarks.
bool soft_wide_lanes();
void set_soft_wide_lanes(bool wide);

/// SoftPiece::draw_shaded() in 8 lanes (soft_piece_avx2.cpp; only where soft_wide_lanes()).
void draw_shaded_wide(const SoftPiece& piece, std::uint8_t* pixels, int width, int first, int last);

}  // namespace fixstep::detail
