// The shapes program (gl_shaders.hpp) on the CPU: triangles of canvas vertices rasterised
// straight into the frame's RGBA8 pixels, with the fragment shader's coverage and finish()'s
// "over" blending. Renderer::finish() draws a frame's overlay and HUD this way natively
// (Renderer::set_overlay_path); the browser's WebGL2 page keeps drawing them with GL.
// Internal to fixstep::render (not installed).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "fixstep/render/render.hpp"
#include "soft_piece.hpp"

namespace fixstep::detail {

/// Farthest a vertex may lie from the frame's origin for SoftRasteriser, px (either axis).
/// Its edge functions are exact 64-bit integers over 1/256 px steps up to this distance;
/// DrawList never passes more than 10^6 px (a disc's quad), the HUD stays in the frame.
inline constexpr double soft_reach_px = 1 << 20;

/// Whether every vertex of `vertices` is finite and within soft_reach_px of the origin.
[[nodiscard]] bool within_soft_reach(std::span<const CanvasVertex> vertices);

/// Rasterises triangles of the shapes program into an RGBA8 frame (height rows of width
/// pixels, the top row first) as GL draws them with finish()'s blending:
/// - coverage: a pixel belongs to a triangle when its centre (i + 0.5, j + 0.5) does, positions
///   snapped to 1/256 px as llvmpipe's are, ties on a shared edge to exactly one triangle;
/// - colour: the shader's, with shape coordinates (u, v) and colour interpolated affinely over
///   the triangle, its coverage clamp((1 - d) / w + 0.5, 0, 1) minus the hole's
///   clamp((fill - d) / w + 0.5, 0, 1), d = |(u, v)|, w = max(|ddx d| + |ddy d|, 1e-6), the
///   derivatives taken as llvmpipe takes them: differences within each 2x2 pixel quad of the
///   GL framebuffer (whose rows count from the bottom of the frame);
/// - blending: premultiplied colour rounded to 8 bits, then dst = src + dst (255 - a) / 255 in
///   8-bit arithmetic, rounded; alpha stays 255.
/// The frame is drawn in bands of rows, each band's triangles in their order, so that a band's
/// pixels stay in cache, shared between the calling thread and a second one (started on the
/// first large frame where there is a second core, if the system gives it a thread); the result
/// is the same as drawing triangle after triangle, whichever thread draws a band. Two triangles
/// (a, b, c), (a, c, d) that make one convex quad with one affine map of their attributes are
/// drawn as that quad (the same pixels, set up once). Keeps its scratch between frames:
/// allocates nothing once it has drawn its largest frame.
class SoftRasteriser {
 public:
  SoftRasteriser();
  ~SoftRasteriser();
  SoftRasteriser(const SoftRasteriser&) = delete;
  SoftRasteriser& operator=(const SoftRasteriser&) = delete;

  /// Forgets the triangles added since the last draw().
  void clear();
  /// Adds the triangles `indices` (3 each, into `vertices`, all within soft_reach_px), cut to
  /// `box` (within the frame draw() is given), after those added before.
  void add(std::span<const CanvasVertex> vertices, std::span<const std::uint32_t> indices,
           PixelBox box);
  /// Draws every triangle added into `pixels` (width x height RGBA8), then clear()s.
  void draw(std::span<std::uint8_t> pixels, int width, int height);

 private:
  struct Crew;  // the second thread
  /// Frames of fewer pieces are drawn by the calling thread alone.
  static constexpr std::size_t min_pieces_for_crew = 256;
  /// Starts the second thread, if there is a second core and none yet; whether it runs.
  bool start_crew();
  /// Draws bands of frame_ until none is left (both threads).
  void run_bands();
  /// Asks for the cache lines piece t covers in rows [first, last] of the frame.
  void ahead(const SoftPiece& t, int first, int last) const;
  std::vector<SoftPiece> pieces_;
  std::vector<std::uint32_t> band_start_, band_list_, band_next_;  // pieces by band (counting sort)
  std::span<std::uint8_t> frame_;  // the frame being drawn, width_ x height_, in bands_ bands
  int width_ = 0, height_ = 0, bands_ = 0;
  std::atomic<int> next_band_{0};  // the next band a thread takes
  std::unique_ptr<Crew> crew_;
};

}  // namespace fixstep::detail
