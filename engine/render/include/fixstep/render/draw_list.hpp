// Shapes a program draws over the scene view (a game's aim line, launcher, labels): recorded in a
// DrawList in world or screen coordinates, drawn through the frame's camera by draw().
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/types.hpp"

namespace fixstep {

class Renderer;

/// Where a shape's coordinates and sizes are given.
enum class Space : std::uint8_t {
  /// m, y up, through the frame's camera (moves and zooms with the world); widths, radii and
  /// arrow heads in m.
  world,
  /// px from the frame's top-left corner, x right, y down (continuous: pixel (i, j) covers
  /// [i, i+1) x [j, j+1)); widths, radii and arrow heads in px.
  screen,
};

/// A list of shapes to draw over one frame, in call order (later over earlier), each in world
/// or screen coordinates, colours with straight alpha (0 transparent .. 255 opaque).
///
/// Errors: every call checks its arguments and throws std::invalid_argument naming the call and
/// the field ("DrawList::line: a.x must be finite, got nan") for a coordinate that is not
/// finite, a width, radius or head that is not finite and >= 0, a text scale outside
/// [min_text_scale, max_text_scale], a polygon of fewer than 3 points or not convex; the list
/// is then unchanged.
///
/// Cost: recording copies a few numbers (and a polyline's points, a text's characters); clear()
/// keeps the storage, so a list recorded every frame allocates nothing once it has held its
/// largest frame. Drawing (draw()) is one or a few canvas primitives a shape, culled when they
/// lie wholly outside the frame.
class DrawList {
 public:
  /// Text scale limits, px per font pixel (Renderer::text: capitals about 7 font pixels tall).
  static constexpr double min_text_scale = 0.5;
  static constexpr double max_text_scale = 16.0;

  /// An anti-aliased straight line from a to b, `width` wide, flat ends.
  void line(Vec2 a, Vec2 b, double width, Rgba8 color, Space space = Space::world);
  /// An anti-aliased polyline through `points` in order, `width` wide, mitred joins (see
  /// Renderer::polyline); fewer than 2 points draw nothing.
  void polyline(std::span<const Vec2> points, double width, Rgba8 color,
                Space space = Space::world);
  /// The outline of a circle of `radius` round `center`, its line `width` wide.
  void circle(Vec2 center, double radius, double width, Rgba8 color, Space space = Space::world);
  /// A filled, anti-aliased disc of `radius` round `center`.
  void disc(Vec2 center, double radius, Rgba8 color, Space space = Space::world);
  /// A filled axis-aligned rectangle with opposite corners `a` and `b` (any two), not smoothed.
  void rect(Vec2 a, Vec2 b, Rgba8 color, Space space = Space::world);
  /// A filled convex polygon through `points` (either winding; collinear points allowed), not
  /// smoothed.
  void polygon(std::span<const Vec2> points, Rgba8 color, Space space = Space::world);
  /// An arrow from `from` to `to`: a shaft `width` wide and a triangular head `head` long and as
  /// wide at its base, its tip at `to` (see Renderer::arrow).
  void arrow(Vec2 from, Vec2 to, double width, double head, Rgba8 color,
             Space space = Space::world);
  /// Text in the bitmap font (printable ASCII; other characters drawn as '?', '\n' starts a new
  /// line), the top-left corner of its first glyph at `at`, `scale` px per font pixel in both
  /// spaces (text stays readable at any zoom).
  void label(Vec2 at, std::string_view text, double scale, Rgba8 color, Space space = Space::world);

  /// The PNG image at `path` (loaded once by the renderer, Renderer::image; an image it
  /// refuses throws ImageError from draw()), `size` = (width, height) centred on `center` and
  /// turned by `angle` rad counter-clockwise about it (as seen: in screen space too), its top
  /// row up before the turn; each pixel takes the texel under its centre (nearest), its alpha
  /// blended over. size in m (world) or px (screen), each finite and >= 0 (0: nothing drawn).
  /// An image reaching no pixel of the frame, or more than 10^6 px across, is not drawn.
  void image(std::string_view path, Vec2 center, Vec2 size, double angle = 0.0,
             Space space = Space::world);

  /// Forgets every shape, keeping the storage.
  void clear();
  /// Shapes recorded since the last clear().
  [[nodiscard]] std::size_t size() const { return shapes_.size(); }
  [[nodiscard]] bool empty() const { return shapes_.empty(); }

  /// Draws the shapes on `canvas` through its camera (world shapes) as canvas primitives,
  /// between Renderer::begin() (or draw_scene()) and finish(). A shape wholly outside the frame
  /// is skipped; a world circle or disc more than 10^6 px wide in the frame is not drawn (its
  /// visible part is all but straight: draw a line or polygon instead).
  void draw(Renderer& canvas) const;

 private:
  enum class Kind : std::uint8_t {
    line,
    polyline,
    circle,
    disc,
    rect,
    polygon,
    arrow,
    label,
    image
  };
  /// One shape: its points (points_[first, first + count)), sizes and colour; a label's text (an
  /// image's path) is text_[text_first, text_first + text_count); an image's points are its
  /// corners.
  struct Shape {
    Kind kind = Kind::line;
    Space space = Space::world;
    Rgba8 color{};
    double width = 0.0;  ///< line width; circle's and disc's radius; label's scale
    double size = 0.0;   ///< circle's line width; arrow's head
    std::uint32_t first = 0, count = 0;
    std::uint32_t text_first = 0, text_count = 0;
  };
  void push(Kind kind, Space space, Rgba8 color, double width, double size,
            std::span<const Vec2> points);
  [[nodiscard]] std::span<const Vec2> points_of(const Shape& s) const {
    return std::span(points_).subspan(s.first, s.count);
  }
  std::vector<Shape> shapes_;
  std::vector<Vec2> points_;
  std::string text_;
};

}  // namespace fixstep
