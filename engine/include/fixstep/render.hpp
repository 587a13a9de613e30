// Headless rendering through OSMesa: every frame, headless or windowed, is drawn here into a
// CPU-side RGBA8 buffer (one render path; the window only presents these pixels).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/simulation.hpp"
#include "fixstep/types.hpp"

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

/// Frame sizes accepted by Renderer, pixels (OSMesa's own limit is larger).
inline constexpr int min_frame_size = 16;
inline constexpr int max_frame_size = 8192;

/// Draws Snapshots with OSMesa (Mesa's software GL, core profile 3.3+).
///
/// Shapes: pixels() is height rows of width RGBA8 pixels (4 bytes each, straight alpha,
/// alpha = 255 everywhere), the TOP row first — ready for PNG and SDL textures.
class Renderer {
 public:
  /// Creates the OSMesa context. Throws RenderError if the size is outside
  /// [min_frame_size, max_frame_size], if OSMesa cannot create a core-profile context, or if
  /// GL calls do not reach OSMesa (GL_RENDERER is null, e.g. when libGL was linked first).
  Renderer(int width, int height);
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

  /// Draws grid, trails, springs, bodies and the HUD text lines into pixels(). Each call also
  /// appends the bodies' positions to their trails (one sample per frame).
  void draw(const Snapshot& snapshot, std::span<const std::string> hud_lines);
  /// Forgets the trails (after a restart or a jump).
  void clear_trails();
  /// Number of frames a trail spans.
  static constexpr int trail_frames = 45;

  [[nodiscard]] std::span<const std::uint8_t> pixels() const { return pixels_; }

 private:
  struct Vertex {
    float x, y, u, v;
    std::uint8_t r, g, b, a;
    float kind;
  };
  void make_current();
  void quad(const float (&p)[4][2], const float (&uv)[4][2], Rgba8 c, float kind);
  void rect(float x0, float y0, float x1, float y1, Rgba8 c);
  void line(float x0, float y0, float x1, float y1, float width, Rgba8 c);
  void disc(float cx, float cy, float r, Rgba8 c);
  void text(float x, float y, const std::string& s, float scale, Rgba8 c);
  void grid();
  void record_trails(const Snapshot& s);

  int width_, height_;
  std::vector<std::uint8_t> pixels_;
  struct Gl;
  std::unique_ptr<Gl> gl_;
  std::string gl_renderer_;
  Camera camera_;
  std::vector<Vertex> vertices_;
  std::vector<char> font_scratch_;
  // trails: ring buffers of trail_frames samples per body, pixel coordinates
  std::vector<float> trail_x_, trail_y_;
  std::size_t trail_bodies_ = 0;
  int trail_head_ = 0, trail_count_ = 0;
};

}  // namespace fixstep
