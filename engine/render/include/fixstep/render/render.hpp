// Headless rendering through OSMesa: every frame, headless or windowed, is drawn here into a
// CPU-side RGBA8 buffer (one render path; the window only presents these pixels); what a frame
// draws over its scene view (a game's overlay, the HUD) is rasterised there by the CPU
// (OverlayPath).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/types.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/render/frame_data.hpp"
#include "fixstep/render/image.hpp"
#include "fixstep/render/trails.hpp"

namespace fixstep {

/// Rendering could not start or failed (OSMesa context, GL binding, shader compilation).
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The part of the world shown: world point `center` maps to the middle of the frame and
/// `width` metres span the frame's width (y points up, pixels are square).
struct Camera {
  Vec2 center{};        ///< m
  double width = 10.0;  ///< m, > 0
};

/// The world point (m) under pixel (px, py) of a width x height frame shown through `camera`
/// (px to the right and py down from the top-left corner, as SDL reports the mouse; pixel
/// centres at +0.5). The inverse of the renderer's projection: the view is camera.width wide
/// and camera.width * height / width tall, centred on camera.center, y up.
[[nodiscard]] Vec2 screen_to_world(const Camera& camera, double px, double py, int width,
                                   int height);

/// The scene view's default background colour.
inline constexpr Rgba8 default_background{18, 21, 28, 255};

/// How the scene view draws the world's joints (ViewStyle::joints).
enum class JointView : std::uint8_t {
  off,      ///< not at all
  anchors,  ///< a mark at each anchor: a ring, an axis, a distance joint's line (the default)
  limits,   ///< the marks and each joint's limits: a revolute joint's arc, ticks along an axis
};

/// What the scene view draws besides the world (Renderer::set_view_style).
struct ViewStyle {
  Rgba8 background = default_background;  ///< the frame's colour (its alpha is ignored: opaque)
  bool grid = true;                       ///< grid lines every power of ten metres
  bool axes = true;                       ///< the lines x = 0 and y = 0, brighter than the grid
  /// The scale bar (a length of 1, 2 or 5 times a power of ten metres), in the bottom corner
  /// the HUD does not take: bottom right, or bottom left when the HUD is there.
  bool scale_bar = true;
  /// The joints (RenderFrame::joints), over the bodies: marks at their anchors by default; their
  /// limits too with JointView::limits.
  JointView joints = JointView::anchors;
  /// A PNG image (a path, ImageCache) tiled over the background, under the grid (empty: none),
  /// anchored to the world: tile (i, j) covers [i t, (i + 1) t] x [j t, (j + 1) t] m, t =
  /// background_tile, so it scrolls and zooms with the camera; nearest texel, its alpha
  /// blended over the background colour.
  std::string background_image{};
  double background_tile = 1.0;  ///< m, a tile's width and height, finite and > 0
  friend bool operator==(const ViewStyle&, const ViewStyle&) = default;
};

/// A corner of the frame (the HUD panel's place: Renderer::set_hud_corner).
enum class HudCorner : std::uint8_t { top_left, top_right, bottom_left, bottom_right };

/// Frame sizes accepted by Renderer, pixels (OSMesa's own limit is larger).
inline constexpr int min_frame_size = 16;
inline constexpr int max_frame_size = 8192;

namespace detail {
/// A vertex of the renderer's GL programs (gl_shaders.hpp) and of its CPU rasteriser
/// (soft_shapes.hpp): position px, shape coordinates (a point's size px and scale for outlined
/// discs), colour (straight alpha), and an outlined disc's fill radius or a circle's hole radius
/// in shape coordinates (Renderer::no_hole elsewhere). Internal to the renderer.
struct CanvasVertex {
  float x, y, u, v;
  std::uint8_t r, g, b, a;
  float fill;
};
class SoftRasteriser;  // soft_shapes.hpp
}  // namespace detail

/// Who rasterises what a frame draws after its scene view (a game's overlay, the HUD).
enum class OverlayPath : std::uint8_t {
  /// fixstep's CPU rasteriser, straight into pixels() after GL has drawn the scene: the same
  /// picture (the shader's coverage and blending), without llvmpipe's cost per triangle.
  /// Shapes of the outlined-disc program, or beyond 2^20 px, fall back to GL for the frame.
  cpu,
  /// GL, like the scene view (the browser page always draws this way).
  gl,
};

/// Draws RenderFrames with OSMesa (Mesa's software GL, core profile 3.3+).
///
/// Shapes: pixels() is height rows of width RGBA8 pixels (4 bytes each, straight alpha,
/// alpha = 255 everywhere), the TOP row first — ready for PNG and SDL textures.
class Renderer {
 public:
  /// Creates the OSMesa context, its shader programs and vertex buffers for width x height
  /// pixels. Throws RenderError if the size is outside [min_frame_size, max_frame_size], if
  /// GALLIUM_DRIVER names a driver OSMesa cannot use, if OSMesa cannot create a core-profile
  /// context or make it current, if GL calls do not reach OSMesa (GL_RENDERER is null, e.g.
  /// when libGL was linked first) or if a shader fails to compile or link; whatever was
  /// acquired before the failure is released first.
  ///
  /// Process-wide: the first Renderer raises glibc's malloc trim and mmap thresholds (mallopt)
  /// so that the blocks llvmpipe allocates and frees every frame stay in the heap instead of
  /// being returned to the kernel and faulted in again; not when GLIBC_TUNABLES,
  /// MALLOC_TRIM_THRESHOLD_ or MALLOC_MMAP_THRESHOLD_ set them (docs/perf/capture.md).
  Renderer(int width, int height);
  /// Releases the GL objects, then the context. Never throws.
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }
  /// GL_RENDERER of the context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  [[nodiscard]] const std::string& gl_renderer() const { return gl_renderer_; }

  void set_camera(const Camera& camera) { camera_ = camera; }
  [[nodiscard]] const Camera& camera() const { return camera_; }
  /// Pixel coordinates (x right, y down, continuous: pixel (i, j) covers [i, i+1) x [j, j+1))
  /// of world point (x, y) in m under the current camera.
  [[nodiscard]] std::array<double, 2> to_pixel(double x, double y) const;

  /// Draws the scene view of `frame` (see draw_scene()) and the HUD text lines (draw_hud()) into
  /// pixels(): draw_scene(frame), draw_hud(hud_lines), finish().
  void draw(const RenderFrame& frame, std::span<const std::string> hud_lines);
  /// Starts a picture (begin()) of the scene view of `frame`: background, grid, axes and scale
  /// bar as view_style() says (over its background image, tiled), the planes, segments (in
  /// their colours and widths), trails, links, springs, the visible bodies (those with a
  /// sprite as their image, RenderFrame::sprites; those with shapes as their shapes,
  /// RenderFrame::shapes, each in its own colour or the body's; the others as discs; an image
  /// the cache refuses throws ImageError) and, over them, the
  /// joints as ViewStyle::joints says (none that broke, nor one whose body is hidden). With
  /// at most max_zigzag_links links, links are zigzags like the anchored springs; with more (a
  /// cloth) they are thin straight lines and no trails are drawn. A body hidden by its
  /// Appearance (RenderFrame::visible 0) is not drawn, nor its trail, nor the springs and links
  /// that end at it. Prepares the trails first (Trails::prepare: throws std::invalid_argument for
  /// a frame it refuses). Canvas primitives recorded after it are drawn over the bodies (a
  /// game's overlay, rasterised as overlay_path() says); draw_hud() and finish() complete the
  /// picture.
  void draw_scene(const RenderFrame& frame);
  /// The HUD panel with `lines` (none: nothing) in the corner hud_corner() names, at
  /// hud_text_scale(), over whatever was recorded before.
  void draw_hud(std::span<const std::string> lines);
  /// Samples the trails after a tick of `world` (Trails::sample; Session calls it after every
  /// tick). A world with more than max_zigzag_links links, whose trails are not drawn, is not
  /// sampled.
  void sample_trails(const World& world);
  /// Size of draw()'s HUD text, px per font pixel: the font (stb_easy_font) is about 7 font
  /// pixels tall and HUD lines are 11 apart, so 2 (the default) gives 22 px lines. Narrow
  /// frames take less (`fixstep compare`'s tiles). Throws std::invalid_argument unless
  /// `scale` is finite and in [min_hud_text_scale, max_hud_text_scale].
  void set_hud_text_scale(float scale);
  [[nodiscard]] float hud_text_scale() const { return hud_text_scale_; }
  static constexpr float min_hud_text_scale = 1.0f;
  static constexpr float max_hud_text_scale = 4.0f;
  /// The frame's corner the HUD panel sits in (top_left by default).
  void set_hud_corner(HudCorner corner) { hud_corner_ = corner; }
  [[nodiscard]] HudCorner hud_corner() const { return hud_corner_; }
  /// What the scene view draws besides the world (background, grid, axes, scale bar).
  void set_view_style(const ViewStyle& style) { style_ = style; }
  /// How finish() rasterises what is recorded after draw_scene() (OverlayPath; cpu by default
  /// natively, gl in the browser, where this setting is ignored).
  void set_overlay_path(OverlayPath path) { overlay_path_ = path; }
  [[nodiscard]] OverlayPath overlay_path() const { return overlay_path_; }
  [[nodiscard]] const ViewStyle& view_style() const { return style_; }
  /// Height in px of draw()'s HUD panel holding `lines` lines at scale `scale`, margin included.
  [[nodiscard]] static float hud_height(std::size_t lines, float scale);
  /// Width in px of draw()'s HUD panel for `line` (its widest line) at scale `scale`, margin
  /// included: the HUD fits a frame at least this wide.
  [[nodiscard]] static float hud_width(const std::string& line, float scale);
  /// Most links drawn as zigzags, with trails (see draw()).
  static constexpr std::size_t max_zigzag_links = 40;
  /// Most grid lines draw() draws across each axis of the frame: the grid's power-of-ten
  /// spacing gives 4..40 across the view's width and 40·height/width across its height, at
  /// most 40 · max_frame_size / min_frame_size. A camera whose centre is too far out for its
  /// width to be resolved (centre + spacing == centre), or that is not finite, gets no grid
  /// lines: no camera makes a frame's memory grow without bound.
  static constexpr int max_grid_lines = 40 * max_frame_size / min_frame_size + 1;
  /// Forgets the trails (after a restart or a jump): each body starts a new one.
  void clear_trails() { trails_.clear(); }
  /// The trails draw() draws, each body's own (see Trails: kept per handle, sampled per tick).
  [[nodiscard]] const Trails& trails() const { return trails_; }

  [[nodiscard]] std::span<const std::uint8_t> pixels() const { return pixels_; }

  // --- canvas: 2D drawing in pixel coordinates ---------------------------------------------
  // The one GL pipeline of the renderer, shared by draw() and by plots (plot.hpp). Coordinates
  // are pixels, x right and y down, origin at the top-left corner of the frame, continuous
  // (pixel (i, j) covers [i, i+1) x [j, j+1), so its centre is (i + 0.5, j + 0.5)); sizes are
  // pixels. Colours blend "over" what was drawn before in call order; alpha stays 255.
  // Primitives only record vertices: nothing reaches pixels() until finish().

  /// An axis-aligned pixel rectangle [x0, x1) x [y0, y1).
  struct ClipRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };

  /// Starts a new picture that finish() fills with `background` before drawing the
  /// primitives recorded in between. Forgets primitives recorded since the last finish().
  void begin(Rgba8 background);
  /// Rasterises everything recorded since begin() into pixels() (one upload, one draw call per
  /// clip change); what was recorded after draw_scene() (the overlay, the HUD) as
  /// overlay_path() says: by default natively the CPU draws it into pixels() once GL has drawn
  /// the rest (the same coverage, derivatives and blending as the shader under llvmpipe, to a
  /// level or two), on a second thread too where the machine has a second core. Throws
  /// RenderError if GL reports an error.
  void finish();
  /// Primitives recorded after this call are cut to `clip` (GL scissor: exact to the pixel)
  /// until the next set_clip(); std::nullopt draws on the whole frame again.
  void set_clip(std::optional<ClipRect> clip);

  /// A filled axis-aligned rectangle from corner (x0, y0) to corner (x1, y1), not smoothed.
  void rect(float x0, float y0, float x1, float y1, Rgba8 c);
  /// A filled triangle (any winding), not smoothed.
  void triangle(float x0, float y0, float x1, float y1, float x2, float y2, Rgba8 c);
  /// An anti-aliased straight line of `width` px from (x0, y0) to (x1, y1) with flat ends
  /// (no caps); lines shorter than 1e-3 px are skipped.
  void line(float x0, float y0, float x1, float y1, float width, Rgba8 c);
  /// One point of a polyline: position in px and its colour (straight alpha).
  struct PolylinePoint {
    float x = 0, y = 0;
    Rgba8 c{};
  };
  /// An anti-aliased polyline of `width` px through `points` in order, drawn as one strip of
  /// shared vertices: joins turning by up to 90° are mitred (no gap, no double blending),
  /// sharper ones end one strip and start the next with flat ends, exactly like two line()s;
  /// the two ends are flat. Colours (alpha included) are interpolated linearly along each
  /// segment. Points closer than 1e-3 px to the previous one are skipped; fewer than two
  /// distinct points draw nothing. Cheaper than one line() per segment: 2 vertices per point
  /// instead of 4 per segment.
  void polyline(std::span<const PolylinePoint> points, float width);
  /// An anti-aliased filled disc of radius r px centred on (cx, cy).
  void disc(float cx, float cy, float r, Rgba8 c);
  /// The same disc inside an outline ring `outline_width` px wide of colour `outline_c` (outer
  /// radius r + outline_width px): the picture of disc(cx, cy, r + outline_width, outline_c)
  /// followed by disc(cx, cy, r, c), drawn in one pass over the pixels instead of two, as one
  /// GL point (the cheapest primitive for llvmpipe); a disc wider than GL's largest point (255 px
  /// with llvmpipe) is drawn as those two discs. outline_width <= 0 draws the plain disc.
  void disc(float cx, float cy, float r, Rgba8 c, float outline_width, Rgba8 outline_c);
  /// A point of a closed polyline or polygon, px.
  struct Point {
    float x = 0, y = 0;
  };
  /// An anti-aliased closed polyline of `width` px through `points` and back to the first, joins
  /// as polyline()'s (all mitred up to 90°, the first point's included); fewer than two distinct
  /// points draw nothing.
  void closed_polyline(std::span<const Point> points, float width, Rgba8 c);
  /// An anti-aliased circle (an outline, not filled) of radius r px centred on (cx, cy), its
  /// line `width` px wide centred on the radius (a ring from r - width/2, at least 0, to
  /// r + width/2): one quad of two triangles, drawn with the lines and discs (in the same draw
  /// call as the shapes around it); wider than 255 px (outer diameter and anti-aliasing), a
  /// closed polyline of enough sides that no chord strays 0.05 px from the circle (8 to 1024
  /// sides), which shades fewer pixels than the quad would. r <= 0 or width <= 0: nothing.
  void circle(float cx, float cy, float r, float width, Rgba8 c);
  /// A filled convex polygon (a triangle fan from points[0]; any winding), not smoothed. The
  /// caller ensures convexity; fewer than 3 points draw nothing.
  void polygon(std::span<const Point> points, Rgba8 c);
  /// An anti-aliased filled convex polygon through `points` (either winding) rounded by
  /// `radius` px: every pixel within `radius` of the polygon (its Minkowski sum with a disc),
  /// so one point draws a disc and two a capsule. Drawn as one mesh that does not overlap
  /// itself (the polygon, a band outside each edge and a wedge at each corner), whose shape
  /// coordinates are the distance to the polygon over `radius`: the shapes program smooths
  /// its edge as it does a disc's. A radius of 0 (a sharp polygon) draws the polygon shrunk by
  /// 1 px and rounded by 1 px, smoothed alike (corners 1 px round), or, smaller than that, the
  /// polygon unsmoothed. Points closer than 1e-3 px to the one before (and the last to the
  /// first) are dropped; the caller ensures convexity; a negative or non-finite radius, or no
  /// point, draws nothing.
  void rounded_polygon(std::span<const Point> points, float radius, Rgba8 c);
  /// The PNG image at `path` (images(): loaded on first use) stretched over the quad with
  /// corners `corners` (px): the image's top-left corner at corners[0], then its top-right,
  /// bottom-right and bottom-left; each pixel takes the texel under its centre (nearest, no
  /// smoothing, no mipmaps: the same pixels in every renderer), its alpha blended "over" and
  /// multiplied by tint's (and its colour by tint's). Throws ImageError (image.hpp) for an
  /// image the cache refuses. A frame with an image after its scene view (a game's overlay)
  /// is drawn all by GL (OverlayPath::cpu falls back for it).
  void image(const std::string& path, std::span<const Point, 4> corners,
             Rgba8 tint = {255, 255, 255, 255});
  /// The images loaded so far (image(), sprites, the background).
  [[nodiscard]] const ImageCache& images() const { return images_; }
  /// An arrow from (x0, y0) to (x1, y1): an anti-aliased shaft `width` px wide and a filled
  /// triangular head, not smoothed, `head` px long and as wide, whose tip is (x1, y1). An arrow
  /// shorter than its head is all head (scaled down to its length); shorter than 1e-3 px draws
  /// nothing.
  void arrow(float x0, float y0, float x1, float y1, float width, float head, Rgba8 c);
  /// Text in stb_easy_font's bitmap font (printable ASCII: any other character, e.g. a UTF-8
  /// "ω", is drawn as one '?'; '\n' starts a new line), `scale` px per font
  /// unit, with the top-left corner of the first glyph cell at (x, y). A line of capitals is
  /// about 7·scale px tall; lines are 12·scale px apart. At most max_text_chars characters of
  /// `s` are drawn (the font's vertices take about 1 kB a character: the rest would lie far
  /// beyond the largest frame at any scale >= 1/8).
  void text(float x, float y, const std::string& s, float scale, Rgba8 c);
  /// Most characters text() draws of one string (its vertex scratch: 1024 bytes a character).
  static constexpr std::size_t max_text_chars = 65536;
  /// The same text turned 90° counter-clockwise (reading upwards), the top-left corner of the
  /// unrotated glyph cell at (x, y): the text ends text_width() px above y and occupies
  /// [x, x + text_height()) horizontally.
  void text_vertical(float x, float y, const std::string& s, float scale, Rgba8 c);
  /// Advance width of `s` drawn at `scale`, px (the longest line when s has several).
  [[nodiscard]] static float text_width(const std::string& s, float scale);
  /// Height of one line of text at `scale` (the glyph cell, capitals and descenders), px.
  [[nodiscard]] static float text_height(float scale) { return 9.0f * scale; }

 private:
  /// Rolling discs' marks: a line from each visible disc's centre to its rim at its angle
  /// (RenderFrame::angle), over the discs; none for a body with shapes.
  void draw_spin_marks(const RenderFrame& frame);
  /// The visible bodies' shapes (RenderFrame::shapes): each filled in its body's colour over
  /// an outline as wide as the discs', and its mark (render_body_shapes.cpp). Marks
  /// shaped_bodies_ for the frame's bodies (1: drawn as shapes, not as a disc).
  void draw_body_shapes(const RenderFrame& frame);
  /// The visible bodies' sprites (RenderFrame::sprites), after their shapes
  /// (render_images.cpp). Marks them in shaped_bodies_ (2: drawn as an image).
  void draw_sprites(const RenderFrame& frame);
  /// style_.background_image tiled over the frame (render_images.cpp).
  void background_tiles();
  /// The quad of image `index` of images_ with corners `p` (px) and texture coordinates `uv`
  /// (image widths and heights from its top-left corner); `repeat`: the image tiles beyond
  /// [0, 1], else its edge texels stretch.
  void image_quad(std::size_t index, const float (&p)[4][2], const float (&uv)[4][2], Rgba8 tint,
                  bool repeat);
  /// The joints (RenderFrame::joints) as style_.joints says, over the bodies
  /// (render_joints.cpp).
  void draw_joints(const RenderFrame& frame);
  /// A revolute joint's limit arc round its anchor `at` (px), the limits' lines and the angle
  /// now (render_joints.cpp).
  void draw_hinge_limits(const RenderFrame::JointMark& m, Point at);
  /// rounded_polygon()'s mesh for the points in rounded_points_ (distinct, at least one):
  /// the polygon and, for radius > 0, the bands and wedges reaching `radius` px beyond it.
  void rounded_mesh(float radius, Rgba8 c);
  using Vertex = detail::CanvasVertex;
  // Fragment programs; each batch uses one.
  static constexpr int shapes = 0;  // triangles: solids, discs, circles, lines, polylines, text
  static constexpr int outlined_discs = 1;  // points: disc() with an outline
  static constexpr int images_program = 2;  // triangles: image(), sprites, background tiles
  // A shapes vertex's `fill` when its shape has no hole (every shape but circle()'s rings): the
  // shader's hole coverage is 0 everywhere (gl_shaders.hpp).
  static constexpr float no_hole = -1e30f;
  /// Makes sure what is recorded next goes into a batch drawn with `program` (and, for
  /// outlined_discs, outline colour `ring`), starting a new batch if needed.
  void use(int program, Rgba8 ring, std::uint32_t texture = 0);
  void quad(const float (&p)[4][2], const float (&uv)[4][2], Rgba8 c, float fill = no_hole);
  void vertex(float x, float y, float u, float v, Rgba8 c, float fill = no_hole) {
    vertices_.push_back({x, y, u, v, c.r, c.g, c.b, c.a, fill});
  }
  template <class Transform>
  void glyphs(const std::string& s, float scale, Rgba8 c, Transform&& to_pixel);
  // Occlusion by what draw() draws later, fully opaque (so what lies below does not matter):
  /// px by which a line of `width` px ending at the centre of an outlined disc of outer radius
  /// `outer` px (drawn over it later) can stop short without changing the picture.
  [[nodiscard]] static float hidden_under_disc(float outer, float width);
  /// px by which a line of `width` px leaving the centre of an opaque solid square of half-side
  /// `half` px (drawn over it later) in unit direction (ux, uy) can start late, likewise.
  [[nodiscard]] static float hidden_under_square(float half, float width, float ux, float uy);
  /// Moves the first of `points` along the first segment by `cut_start` px and the last back
  /// along the last segment by `cut_end` px, colours interpolated (and rounded to 8 bits); an
  /// end whose segment is not longer than its cut + 0.01 px stays. A single segment shorter than
  /// both cuts together (wholly hidden) is the caller's to skip.
  static void shorten(std::span<PolylinePoint> points, float cut_start, float cut_end);
  /// The grid, axes and scale bar, as style_ says.
  void grid();
  /// The scale bar for grid spacing `step` m.
  void scale_bar(double step);
  /// draw()'s trails: one fading polyline per body (few_links scenes only).
  void draw_trails(const RenderFrame& s, double scale);
  /// A pair of strip vertices at (x, y) offset by +-(nx, ny) px (shape coordinate v = +-e) in
  /// colour c, joined to the pair before it by two triangles when `join`.
  void strip_pair(float x, float y, float nx, float ny, float e, Rgba8 c, bool join);
  /// Sets every program's uniforms for this frame, drawn upside down with flip = -1 (finish()).
  void set_flip(float flip);
  /// Draws batches_[from, to) (finish()).
  void draw_batches(std::size_t from, std::size_t to);
  /// draw(): whether the backdrop holds this frame's grid and planes (same background, camera
  /// and planes as when it was recorded); if so, this frame starts from a copy of it.
  bool reuse_backdrop(std::span<const PlaneDef> planes);
  /// draw(): what was recorded since begin() (the grid and `planes`) is drawn into the backdrop
  /// first, and the frame starts from a copy of it.
  void record_backdrop(std::span<const PlaneDef> planes);

  int width_, height_;
  std::vector<std::uint8_t> pixels_;
  struct Gl;                // the OSMesa context and GL objects drawing into pixels_
  std::unique_ptr<Gl> gl_;  // after pixels_: released before them
  std::string gl_renderer_;
  Camera camera_;
  float hud_text_scale_ = 2.0f;  ///< px per font pixel in draw()'s HUD
  HudCorner hud_corner_ = HudCorner::top_left;
  ViewStyle style_;
  std::vector<Vertex> vertices_;
  std::vector<std::uint32_t> indices_;  // triangles (3 indices each) or points (1 each)
  // Draw batches: indices [first, next batch's first) share one clip rectangle.
  struct Batch {
    std::size_t first = 0;
    std::optional<ClipRect> clip;
    int program = shapes;
    Rgba8 ring{};               // outline colour of outlined_discs
    std::uint32_t texture = 0;  // images_program: the image's index in images_
  };
  std::vector<Batch> batches_;
  // What draw_scene() recorded ends where batches_[overlay_batch_] and vertices_[overlay_vertex_]
  // start (npos: no scene view this frame); finish() rasterises the rest as overlay_path_ says.
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  std::size_t overlay_batch_ = npos;
  std::size_t overlay_vertex_ = 0;
  OverlayPath overlay_path_ = OverlayPath::cpu;
  std::unique_ptr<detail::SoftRasteriser> soft_;  // made on the first frame that needs it
  /// The first batch finish() leaves to the CPU rasteriser (batches_.size(): none).
  [[nodiscard]] std::size_t first_soft_batch() const;
  /// Rasterises batches_[from, end) on the CPU into pixels_ (finish()).
  void draw_soft_batches(std::size_t from);
  Rgba8 background_{};
  // How this frame starts (finish()): cleared to background_; from a copy of the backdrop
  // (gl::Pipeline), drawn first from batches_[0, backdrop_batches_) (record) or as it is (reuse).
  enum class Backdrop { none, record, reuse };
  Backdrop backdrop_ = Backdrop::none;
  std::size_t backdrop_batches_ = 0;
  // What the backdrop shows, once recorded: draw()'s grid and planes for these.
  bool backdrop_recorded_ = false;
  ViewStyle backdrop_style_;
  HudCorner backdrop_hud_corner_ = HudCorner::top_left;
  Camera backdrop_camera_;
  std::vector<PlaneDef> backdrop_planes_;
  std::vector<char> font_scratch_;
  std::string text_scratch_;                     // glyphs(): the printable copy of a text
  std::vector<PolylinePoint> polyline_scratch_;  // one trail or spring, reused every frame
  std::vector<Point> point_scratch_;             // closed_polyline()'s distinct points
  std::vector<Point> circle_scratch_;            // circle()'s sides
  std::vector<Point> rounded_points_;            // rounded_polygon()'s distinct points
  std::vector<Point> rounded_normals_;           // rounded_polygon()'s outward edge normals
  std::vector<Point> shape_scratch_;             // draw_body_shapes(): one shape's points, px
  /// Per body of the frame drawn last: 1 when draw_body_shapes() drew it as its shapes (empty:
  /// no body has shapes).
  std::vector<std::uint8_t> shaped_bodies_;
  Trails trails_;      // world coordinates, m: drawn through the camera of each frame
  ImageCache images_;  // each image's texture: gl_->images[index], made on first use
};

}  // namespace fixstep
