// Renderer: the GL frame buffer (OSMesa's pixels, or the page's WebGL2 canvas) and the canvas
// (rectangles, lines, discs, text) batched into one upload and one draw call per clip; polylines,
// circles, polygons and arrows are in render_shapes.cpp, the scene view in render_frame.cpp.
#include "fixstep/render/render.hpp"

#include <fmt/format.h>
#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "aa_pad.hpp"
#include "font_chars.hpp"
#include "gl_pipeline.hpp"  // GL through OSMesa only, never libGL: see gl_api.hpp
#include "gl_shaders.hpp"
#include "occlusion.hpp"
#include "renderer_gl.hpp"
#include "soft_shapes.hpp"

namespace fixstep {

Vec2 screen_to_world(const Camera& camera, double px, double py, int width, int height) {
  const double scale = camera.width / double(width);  // m per pixel, both axes
  return {camera.center.x + (px - 0.5 * double(width)) * scale,
          camera.center.y - (py - 0.5 * double(height)) * scale};
}

namespace {

std::string printable(const std::string& s) {
  std::string out;
  detail::font_chars_into(s, out);
  return out;
}

}  // namespace

Renderer::Renderer(int width, int height) : width_(width), height_(height) {
  if (width < min_frame_size || height < min_frame_size || width > max_frame_size ||
      height > max_frame_size) {
    throw RenderError(fmt::format("render: frame size {}x{} is outside {}..{} pixels", width,
                                  height, min_frame_size, max_frame_size));
  }
  pixels_.assign(static_cast<std::size_t>(width) * height * 4, 0);
  gl_ = std::make_unique<Gl>(width, height, pixels_.data(), gl::shader_sources);
  gl_renderer_ = gl_->renderer_name;

  gl::api().glBindVertexArray(gl_->vao.get());
  gl::api().glBindBuffer(GL_ARRAY_BUFFER, gl_->vbo.get());
  gl::api().glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gl_->ibo.get());  // part of the VAO's state
  const auto stride = static_cast<GLsizei>(sizeof(Vertex));
  gl::api().glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride,
                                  reinterpret_cast<void*>(offsetof(Vertex, x)));
  gl::api().glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                                  reinterpret_cast<void*>(offsetof(Vertex, u)));
  gl::api().glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride,
                                  reinterpret_cast<void*>(offsetof(Vertex, r)));
  gl::api().glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, stride,
                                  reinterpret_cast<void*>(offsetof(Vertex, fill)));
  for (GLuint i = 0; i < 4; ++i) gl::api().glEnableVertexAttribArray(i);
  font_scratch_.resize(std::size_t{64} * 1024);
}

Renderer::~Renderer() = default;

std::array<double, 2> Renderer::to_pixel(double x, double y) const {
  const double scale = width_ / camera_.width;  // px per m
  return {(x - camera_.center.x) * scale + width_ * 0.5,
          height_ * 0.5 - (y - camera_.center.y) * scale};
}

void Renderer::quad(const float (&p)[4][2], const float (&uv)[4][2], Rgba8 c, float fill) {
  const auto base = static_cast<std::uint32_t>(vertices_.size());
  for (int i = 0; i < 4; ++i) vertex(p[i][0], p[i][1], uv[i][0], uv[i][1], c, fill);
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices_.push_back(base + i);
}

void Renderer::rect(float x0, float y0, float x1, float y1, Rgba8 c) {
  use(shapes, {});
  quad({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {{0, 0}, {0, 0}, {0, 0}, {0, 0}}, c);
}

void Renderer::line(float x0, float y0, float x1, float y1, float width, Rgba8 c) {
  const float dx = x1 - x0, dy = y1 - y0;
  const float len = std::sqrt(dx * dx + dy * dy);
  if (len < 1e-3f) return;
  use(shapes, {});
  const float h = 0.5f * width, pad = h + detail::aa_pad_px;  // room for the anti-aliased edge
  const float nx = -dy / len * pad, ny = dx / len * pad;
  const float e = pad / h;
  quad({{x0 + nx, y0 + ny}, {x1 + nx, y1 + ny}, {x1 - nx, y1 - ny}, {x0 - nx, y0 - ny}},
       {{0, e}, {0, e}, {0, -e}, {0, -e}}, c);
}

void Renderer::disc(float cx, float cy, float r, Rgba8 c) {
  use(shapes, {});
  const float pad = r + detail::aa_pad_px, e = pad / r;
  quad({{cx - pad, cy - pad}, {cx + pad, cy - pad}, {cx + pad, cy + pad}, {cx - pad, cy + pad}},
       {{-e, -e}, {e, -e}, {e, e}, {-e, e}}, c);
}

void Renderer::disc(float cx, float cy, float r, Rgba8 c, float outline_width, Rgba8 outline_c) {
  if (!(outline_width > 0.0f)) {
    disc(cx, cy, r, c);
    return;
  }
  const float outer = r + outline_width, pad = outer + detail::aa_pad_px;
  if (2.0f * pad > gl_->max_point_size) {  // too wide for a point: the two discs it stands for
    disc(cx, cy, outer, outline_c);
    disc(cx, cy, r, c);
    return;
  }
  // One vertex, one square primitive: llvmpipe shades each 4x4 pixel block the square touches
  // once, where the two triangles of a quad both shade the blocks along their shared diagonal.
  use(outlined_discs, outline_c);
  indices_.push_back(static_cast<std::uint32_t>(vertices_.size()));
  vertex(cx, cy, 2.0f * pad, pad / outer, c, r / outer);
}

void Renderer::use(int program, Rgba8 ring, std::uint32_t texture) {
  if (batches_.empty()) batches_.push_back(Batch{});  // primitives before the first begin()
  Batch& b = batches_.back();
  if (b.program == program && (program == shapes || (program == outlined_discs && b.ring == ring) ||
                               (program == images_program && b.texture == texture))) {
    return;
  }
  if (b.first == indices_.size()) {  // nothing recorded in this batch yet
    b.program = program;
    b.ring = ring;
    b.texture = texture;
  } else {
    batches_.push_back(Batch{indices_.size(), b.clip, program, ring, texture});
  }
}

void Renderer::triangle(float x0, float y0, float x1, float y1, float x2, float y2, Rgba8 c) {
  use(shapes, {});
  const float p[3][2] = {{x0, y0}, {x1, y1}, {x2, y2}};
  const auto base = static_cast<std::uint32_t>(vertices_.size());
  for (const auto& v : p) vertex(v[0], v[1], 0.0f, 0.0f, c);
  for (std::uint32_t i = 0; i < 3; ++i) indices_.push_back(base + i);
}

namespace detail {

float hidden_under_disc(float outer, float width) {
  // The outlined disc (outline opaque) covers every pixel within outer - 1 px of its centre with
  // coverage 1 (the shader's coverage is 1 up to half a fwidth, at most 1 px, inside the edge), so
  // its colour replaces whatever lies below there. A line ending at the centre can stop `cut` px
  // short, with a flat end, when its quad's part beyond, reaching `pad` px to either side, lies
  // within that radius: cut^2 + pad^2 <= (outer - 1)^2.
  const float opaque = outer - 1.0f, pad = 0.5f * width + detail::aa_pad_px;
  return opaque > pad ? std::sqrt(opaque * opaque - pad * pad) : 0.0f;
}

float hidden_under_square(float half, float width, float ux, float uy) {
  // The square (solid, opaque) replaces every pixel whose centre lies strictly inside it. The
  // quad of a line leaving its centre in direction (ux, uy) (a unit vector) reaches s |ux| +
  // pad |uy| along x and s |uy| + pad |ux| along y over its first s px; both must stay inside.
  const float pad = 0.5f * width + detail::aa_pad_px, inside = half - 0.01f;
  const float ax = std::abs(ux), ay = std::abs(uy);
  float cut = std::numeric_limits<float>::max();
  if (ax > 0.0f) cut = std::min(cut, (inside - pad * ay) / ax);
  if (ay > 0.0f) cut = std::min(cut, (inside - pad * ax) / ay);
  return std::max(cut, 0.0f);
}

namespace {

// Moves `moved` towards `fixed` by `cut` px along the segment joining them, its colour
// interpolated (and rounded to 8 bits); nothing when the segment is not longer than cut + 0.01 px.
void pull_towards(const Renderer::PolylinePoint& fixed, Renderer::PolylinePoint& moved, float cut) {
  const float dx = moved.x - fixed.x, dy = moved.y - fixed.y;
  const float len = std::sqrt(dx * dx + dy * dy);
  if (!(cut > 0.0f) || !(len > cut + 0.01f)) return;
  const float f = (len - cut) / len;  // of the way from `fixed` to `moved`
  auto lerp = [f](std::uint8_t u, std::uint8_t v) {
    return static_cast<std::uint8_t>(std::lround(float(u) + (float(v) - float(u)) * f));
  };
  const Rgba8 a = fixed.c, b = moved.c;
  moved = {fixed.x + dx * f, fixed.y + dy * f,
           Rgba8{lerp(a.r, b.r), lerp(a.g, b.g), lerp(a.b, b.b), lerp(a.a, b.a)}};
}

}  // namespace

void shorten(std::span<Renderer::PolylinePoint> points, float cut_start, float cut_end) {
  const std::size_t n = points.size();
  if (n < 2) return;
  if (n == 2 && cut_start + cut_end > 0.0f) {  // one segment: both ends move along it
    const Renderer::PolylinePoint a = points[0], b = points[1];
    pull_towards(b, points[0], cut_start);
    pull_towards(a, points[1], cut_end);
    return;
  }
  pull_towards(points[1], points[0], cut_start);
  pull_towards(points[n - 2], points[n - 1], cut_end);
}

}  // namespace detail

float Renderer::hidden_under_disc(float outer, float width) {
  return detail::hidden_under_disc(outer, width);
}

float Renderer::hidden_under_square(float half, float width, float ux, float uy) {
  return detail::hidden_under_square(half, width, ux, uy);
}

void Renderer::shorten(std::span<PolylinePoint> points, float cut_start, float cut_end) {
  detail::shorten(points, cut_start, cut_end);
}

template <class Transform>
void Renderer::glyphs(const std::string& s, float scale, Rgba8 c, Transform&& to_pixel) {
  // stb_easy_font emits quads of 4 vertices {x, y, z, rgba8} (16 bytes each) in font units,
  // at most ~270 bytes per character on average (its documentation); give it room for long
  // strings rather than letting it truncate them.
  std::string& copy = text_scratch_;  // kept: no allocation once it has held the longest text
  detail::font_chars_into(s, copy);
  // The scratch grows with the text: a body name of megabytes in a guard's message asked for
  // gigabytes. Past max_text_chars the characters lie beyond any frame.
  if (copy.size() > max_text_chars) copy.resize(max_text_chars);
  font_scratch_.resize(std::max(font_scratch_.size(), copy.size() * 1024));
  unsigned char rgba[4] = {c.r, c.g, c.b, c.a};
  const int quads = stb_easy_font_print(0, 0, copy.data(), rgba, font_scratch_.data(),
                                        static_cast<int>(font_scratch_.size()));
  const char* base = font_scratch_.data();
  use(shapes, {});
  for (int q = 0; q < quads; ++q) {
    float p[4][2];
    for (int k = 0; k < 4; ++k) {
      float v[2];
      std::memcpy(v, base + static_cast<std::ptrdiff_t>(q * 4 + k) * 16, sizeof v);
      const std::array<float, 2> px = to_pixel(v[0] * scale, v[1] * scale);
      p[k][0] = px[0];
      p[k][1] = px[1];
    }
    quad(p, {{0, 0}, {0, 0}, {0, 0}, {0, 0}}, c);
  }
}

void Renderer::text(float x, float y, const std::string& s, float scale, Rgba8 c) {
  glyphs(s, scale, c, [&](float u, float v) { return std::array<float, 2>{x + u, y + v}; });
}

void Renderer::text_vertical(float x, float y, const std::string& s, float scale, Rgba8 c) {
  // Turned 90° counter-clockwise about (x, y) and moved right by nothing: font x (along the
  // text) goes up the frame, font y (down the glyph) goes right.
  glyphs(s, scale, c, [&](float u, float v) { return std::array<float, 2>{x + v, y - u}; });
}

float Renderer::text_width(const std::string& s, float scale) {
  std::string copy = printable(s);
  return float(stb_easy_font_width(copy.data())) * scale;
}

void Renderer::begin(Rgba8 background) {
  gl_->make_current();
  vertices_.clear();
  indices_.clear();
  batches_.assign(1, Batch{});
  background_ = background;
  backdrop_ = Backdrop::none;
  overlay_batch_ = npos;
}

void Renderer::set_clip(std::optional<ClipRect> clip) {
  if (batches_.empty()) batches_.push_back(Batch{});
  if (batches_.back().first == indices_.size()) {
    batches_.back().clip = clip;  // nothing drawn under the previous clip yet
  } else {
    batches_.push_back(Batch{indices_.size(), clip, batches_.back().program, batches_.back().ring,
                             batches_.back().texture});
  }
}

namespace {

// Fills the buffer bound to `target` with `bytes` bytes of `data`, growing its store (to at
// least twice its old size) only when they do not fit. `capacity` is the store's size.
void upload(GLenum target, std::size_t& capacity, const void* data, std::size_t bytes) {
  if (bytes > capacity) {
    capacity = std::max(bytes, 2 * capacity);
    gl::api().glBufferData(target, static_cast<GLsizeiptr>(capacity), nullptr, GL_DYNAMIC_DRAW);
  }
  if (bytes > 0) gl::api().glBufferSubData(target, 0, static_cast<GLsizeiptr>(bytes), data);
}

}  // namespace

void Renderer::finish() {
  gl_->make_current();
  // The viewport reaches gl_->margin px beyond every edge of the frame (the vertex shader maps
  // pixel coordinates into it, so pixels land where they did with a frame-sized viewport;
  // whatever falls outside the frame is simply not rasterised). Without the margin, any vertex
  // just outside the frame (a disc or trail at the edge) sends the whole chunk of up to 4096
  // vertices it belongs to through Mesa's clipping pipeline, whose vbuf stage re-marks every
  // vertex of the chunk on each small flush: that was a third of the drawing thread's time with
  // 1000 bodies (measured with perf; docs/perf/capture.md). Vertices farther than the margin
  // out still take the clipping path, correctly.
  gl::api().glViewport(-gl_->margin, -gl_->margin, width_ + 2 * gl_->margin,
                       height_ + 2 * gl_->margin);
  gl::api().glDisable(GL_SCISSOR_TEST);
  gl::api().glClearColor(background_.r / 255.0f, background_.g / 255.0f, background_.b / 255.0f,
                         1.0f);
  gl::api().glEnable(GL_BLEND);
  gl::enable_program_point_size();  // outlined discs: the vertex shader sets each point's size
  // Colour blends "over" (the shaders output premultiplied colour); alpha keeps 1, so every pixel
  // of the PNG is opaque.
  gl::api().glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  set_flip(1.0f);
  gl::api().glBindVertexArray(gl_->vao.get());
  gl::api().glBindBuffer(GL_ARRAY_BUFFER, gl_->vbo.get());
  // What the CPU rasterises (the overlay and HUD, first_soft_batch()) never reaches GL.
  const std::size_t soft = first_soft_batch();
  const bool gl_all = soft == batches_.size();
  const std::size_t gl_vertices = gl_all ? vertices_.size() : overlay_vertex_;
  const std::size_t gl_indices = gl_all ? indices_.size() : batches_[soft].first;
  upload(GL_ARRAY_BUFFER, gl_->vbo_bytes, vertices_.data(), gl_vertices * sizeof(Vertex));
  upload(GL_ELEMENT_ARRAY_BUFFER, gl_->ibo_bytes, indices_.data(),
         gl_indices * sizeof(std::uint32_t));
  std::size_t first_batch = 0;
  if (backdrop_ == Backdrop::record) {  // its batches into the backdrop, then copied
    gl_->draw_into_backdrop();
    set_flip(-1.0f);  // upside down: see gl::Pipeline::draw_into_backdrop
    gl::api().glClear(GL_COLOR_BUFFER_BIT);
    draw_batches(0, backdrop_batches_);
    gl_->draw_into_frame();
    set_flip(1.0f);
    first_batch = backdrop_batches_;
  }
  if (backdrop_ == Backdrop::none) {
    gl::api().glClear(GL_COLOR_BUFFER_BIT);
  } else {
    gl_->copy_backdrop_to_frame();
  }
  draw_batches(first_batch, soft);
  gl::api().glFinish();
  if (const GLenum err = gl::api().glGetError(); err != GL_NO_ERROR) {
    throw RenderError(fmt::format("render: GL error 0x{:x} while drawing", err));
  }
  draw_soft_batches(soft);
}

std::size_t Renderer::first_soft_batch() const {
#ifdef __EMSCRIPTEN__
  return batches_.size();  // the picture is WebGL's canvas, not pixels_
#else
  if (overlay_path_ != OverlayPath::cpu || overlay_batch_ == npos) return batches_.size();
  for (std::size_t b = overlay_batch_; b < batches_.size(); ++b) {
    if (batches_[b].program != shapes) return batches_.size();
  }
  if (!detail::within_soft_reach(std::span(vertices_).subspan(overlay_vertex_))) {
    return batches_.size();
  }
  return overlay_batch_;
#endif
}

void Renderer::draw_soft_batches(std::size_t from) {
  if (from == batches_.size()) return;
  if (!soft_) soft_ = std::make_unique<detail::SoftRasteriser>();
  for (std::size_t b = from; b < batches_.size(); ++b) {
    const std::size_t first = batches_[b].first;
    const std::size_t end = b + 1 < batches_.size() ? batches_[b + 1].first : indices_.size();
    detail::PixelBox box{0, 0, width_, height_};
    if (const auto& c = batches_[b].clip) {  // as draw_batches() cuts it
      box.x0 = std::clamp(c->x0, 0, width_);
      box.x1 = std::clamp(c->x1, box.x0, width_);
      box.y0 = std::clamp(c->y0, 0, height_);
      box.y1 = std::clamp(c->y1, box.y0, height_);
    }
    soft_->add(vertices_, std::span(indices_).subspan(first, end - first), box);
  }
  soft_->draw(pixels_, width_, height_);
}

void Renderer::set_flip(float flip) {
  for (const gl::Pipeline::LinkedProgram& p : gl_->programs) {
    gl::api().glUseProgram(p.program.get());
    gl::api().glUniform2f(p.size, float(width_), float(height_));
    gl::api().glUniform1f(p.margin, float(gl_->margin));
    gl::api().glUniform1f(p.flip, flip);
  }
}

void Renderer::draw_batches(std::size_t from, std::size_t to) {
  int program = -1;
  for (std::size_t b = from; b < to; ++b) {
    const std::size_t first = batches_[b].first;
    const std::size_t end = b + 1 < batches_.size() ? batches_[b + 1].first : indices_.size();
    if (end == first) continue;
    if (batches_[b].program != program) {
      program = batches_[b].program;
      gl::api().glUseProgram(gl_->programs[program].program.get());
    }
    if (program == images_program) {
      const Image& im = images_.at(batches_[b].texture);
      gl_->bind_image(batches_[b].texture, im.width, im.height, im.rgba.data());
    }
    if (program == outlined_discs) {
      const Rgba8 r = batches_[b].ring;
      gl::api().glUniform4f(gl_->programs[program].ring, r.r / 255.0f, r.g / 255.0f, r.b / 255.0f,
                            r.a / 255.0f);
    }
    if (const auto& c = batches_[b].clip) {
      // GL's scissor box has its origin at the bottom-left; pixels() rows run top down.
      const int x0 = std::clamp(c->x0, 0, width_), x1 = std::clamp(c->x1, x0, width_);
      const int y0 = std::clamp(c->y0, 0, height_), y1 = std::clamp(c->y1, y0, height_);
      gl::api().glEnable(GL_SCISSOR_TEST);
      gl::api().glScissor(x0, height_ - y1, x1 - x0, y1 - y0);
    } else {
      gl::api().glDisable(GL_SCISSOR_TEST);
    }
    gl::api().glDrawElements(program == outlined_discs ? GL_POINTS : GL_TRIANGLES,
                             static_cast<GLsizei>(end - first), GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
  }
  gl::api().glDisable(GL_SCISSOR_TEST);
}

}  // namespace fixstep
