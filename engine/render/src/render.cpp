#include "fixstep/render.hpp"

#include <fmt/format.h>
#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>

#include "gl_pipeline.hpp"  // GL through OSMesa only, never libGL: see gl_objects.hpp
#include "gl_shaders.hpp"

namespace fixstep {

namespace {

constexpr Rgba8 background{18, 21, 28, 255};
constexpr Rgba8 grid_minor{32, 37, 48, 255};
constexpr Rgba8 grid_axis{62, 70, 90, 255};
constexpr Rgba8 spring_color{170, 180, 200, 255};
constexpr Rgba8 link_color{170, 180, 200, 200};
constexpr Rgba8 anchor_color{120, 130, 150, 255};
constexpr Rgba8 outline{8, 10, 14, 255};
constexpr Rgba8 text_color{235, 238, 245, 255};
constexpr Rgba8 panel{0, 0, 0, 150};
constexpr Rgba8 palette[] = {{230, 87, 46, 255},   {76, 175, 240, 255},  {250, 200, 60, 255},
                             {120, 210, 110, 255}, {200, 120, 230, 255}, {240, 140, 170, 255},
                             {90, 220, 200, 255},  {240, 240, 240, 255}};
constexpr float default_radius_px = 9.0f;
// How far quads reach beyond the edge of a line or disc, px. The fragment shader's coverage
// (1 - d) / fwidth(d) + 0.5 reaches 0 at half a fwidth beyond the edge: 0.5 px across an
// axis-aligned edge, at most sqrt(2) / 2 = 0.707 px across a diagonal one (fwidth is
// |d/dx| + |d/dy|). Fragments farther out blend with alpha 0, so 0.75 px draws the picture a
// whole pixel of padding drew (checked on 1000-body frames: all but one pixel within 1 level)
// with fewer fragments.
constexpr float aa_pad_px = 0.75f;
constexpr float min_radius_px = 3.0f;

constexpr const char* vertex_shader = R"(#version 330 core
layout(location = 0) in vec2 a_pos;    // pixels, origin top-left, y down
layout(location = 1) in vec2 a_uv;     // shape coordinates (discs, lines)
layout(location = 2) in vec4 a_color;
layout(location = 3) in float a_kind;  // 0 solid, 1 disc, 2 anti-aliased line; see below
uniform vec2 u_size;    // pixels, the frame
uniform float u_margin; // pixels of viewport beyond each edge of the frame (see finish())
out vec2 v_uv;
out vec4 v_color;
out float v_kind;
void main() {
  vec2 p = (a_pos + u_margin) / (u_size + 2.0 * u_margin);
  gl_Position = vec4(p.x * 2.0 - 1.0, 1.0 - p.y * 2.0, 0.0, 1.0);
  v_uv = a_uv;
  v_color = a_color;
  v_kind = a_kind;
}
)";

// Discs and lines are anti-aliased analytically: coverage falls from 1 to 0 over one pixel at
// the shape's edge (distance 1 in shape coordinates), measured with fwidth.
constexpr const char* fragment_shader = R"(#version 330 core
in vec2 v_uv;
in vec4 v_color;
in float v_kind;
out vec4 frag;
void main() {
  float a = v_color.a;
  if (v_kind > 0.5) {
    float d = v_kind < 1.5 ? length(v_uv) : abs(v_uv.y);
    float w = max(fwidth(d), 1e-6);
    a *= clamp((1.0 - d) / w + 0.5, 0.0, 1.0);
  }
  frag = vec4(v_color.rgb, a);
}
)";

// Outlined discs (Renderer::disc with an outline) in one pass, their own program: v_uv is 1 at
// the outer edge, v_kind is the fill's radius in the same units, u_ring the outline's colour.
// The fill is composited over the outline in the shader, so the result is that of drawing the
// outline disc and then the fill disc "over" it: alpha a = af + (1 - af) ao and colour
// (f af + o (1 - af) ao) / a, blended over the frame with GL's straight-alpha "over".
constexpr const char* ring_fragment_shader = R"(#version 330 core
in vec2 v_uv;
in vec4 v_color;
in float v_kind;
uniform vec4 u_ring;
out vec4 frag;
void main() {
  float d = length(v_uv);
  float w = max(fwidth(d), 1e-6);
  float ao = u_ring.a * clamp((1.0 - d) / w + 0.5, 0.0, 1.0);
  float af = v_color.a * clamp((v_kind - d) / w + 0.5, 0.0, 1.0);
  float a = af + (1.0 - af) * ao;
  frag = vec4((v_color.rgb * af + u_ring.rgb * ((1.0 - af) * ao)) / max(a, 1e-6), a);
}
)";

// The programs, in the order of Renderer::shapes and Renderer::outlined_discs.
constexpr gl::ShaderSources shader_sources{vertex_shader, {fragment_shader, ring_fragment_shader}};

// stb_easy_font indexes its glyph table with (char - 32) and has glyphs for ' '..'~' only: any
// other byte would read outside the table. Each UTF-8 sequence (or other byte) outside that
// range becomes one '?'; '\n' is kept (a new line).
std::string printable(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c >= 32 && c <= 126) || c == '\n')
      out.push_back(ch);
    else if ((c & 0xC0) != 0x80)
      out.push_back('?');  // UTF-8 continuation bytes are dropped
  }
  return out;
}

}  // namespace

namespace gl {

namespace {

// `log` without the line break Mesa ends its info logs with.
std::string trimmed(const char* log) {
  std::string s = log;
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// Mesa 22's OSMesa dereferences a null screen when GALLIUM_DRIVER names a driver it cannot
// load (seen: GALLIUM_DRIVER=foo crashes inside OSMesaCreateContextAttribs). OSMesa runs on
// the software rasterisers only, so refuse any other name before calling it.
void check_gallium_driver() {
  const char* driver = std::getenv("GALLIUM_DRIVER");
  if (!driver || !*driver) return;
  const std::string d = driver;
  if (d != "llvmpipe" && d != "softpipe") {
    throw RenderError(fmt::format(
        "render: GALLIUM_DRIVER={} is not a driver OSMesa can use (llvmpipe or softpipe); "
        "unset it or choose one of those",
        d));
  }
}

Context create_context() {
  check_gallium_driver();
  // Attributes as key, value pairs, one pair a line.
  // clang-format off
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                         OSMESA_DEPTH_BITS, 0,
                         OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 3,
                         OSMESA_CONTEXT_MINOR_VERSION, 3,
                         0};
  // clang-format on
  Context context(OSMesaCreateContextAttribs(attribs, nullptr));
  if (!context.get()) {
    throw RenderError(
        "render: OSMesaCreateContextAttribs failed to create an OpenGL 3.3 core context "
        "(is libosmesa6 from Mesa >= 17 installed?)");
  }
  return context;
}

// GL_RENDERER of the current context.
std::string query_renderer_name() {
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (!name) {
    throw RenderError(
        "render: GL_RENDERER is null: GL calls are not reaching OSMesa. Link libOSMesa only; a "
        "libGL linked before it captures every gl* call and frames come out black.");
  }
  return name;
}

std::array<Pipeline::LinkedProgram, 2> link_programs(const ShaderSources& sources) {
  const Shader vertex = compile_shader(GL_VERTEX_SHADER, sources.vertex);
  std::array<Pipeline::LinkedProgram, 2> programs;
  for (std::size_t i = 0; i < programs.size(); ++i) {
    const Shader fragment = compile_shader(GL_FRAGMENT_SHADER, sources.fragments[i]);
    Pipeline::LinkedProgram& p = programs[i];
    p.program = link_program(vertex, fragment);
    p.size = glGetUniformLocation(p.program.get(), "u_size");
    p.margin = glGetUniformLocation(p.program.get(), "u_margin");
    p.ring = glGetUniformLocation(p.program.get(), "u_ring");
  }
  return programs;
}

VertexArray create_vertex_array() {
  GLuint name = 0;
  glGenVertexArrays(1, &name);
  return VertexArray(name);
}

Buffer create_buffer() {
  GLuint name = 0;
  glGenBuffers(1, &name);
  return Buffer(name);
}

// px of viewport beyond each edge of a width x height frame (see Renderer::finish()).
int viewport_margin(int width, int height) {
  GLint max_dims[2] = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_dims);
  // (llvmpipe reports 16384 x 16384, viewport bounds -32768..32767: the full 256 px even at
  // max_frame_size.)
  return std::clamp((std::min(max_dims[0] - width, max_dims[1] - height)) / 2, 0, 256);
}

}  // namespace

Shader compile_shader(GLenum type, const char* source) {
  Shader shader(glCreateShader(type));
  glShaderSource(shader.get(), 1, &source, nullptr);
  glCompileShader(shader.get());
  GLint ok = 0;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader.get(), sizeof log, nullptr, log);
    throw RenderError(fmt::format("render: shader compilation failed: {}", trimmed(log)));
  }
  return shader;
}

Program link_program(const Shader& vertex, const Shader& fragment) {
  Program program(glCreateProgram());
  glAttachShader(program.get(), vertex.get());
  glAttachShader(program.get(), fragment.get());
  glLinkProgram(program.get());
  GLint linked = 0;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &linked);
  if (!linked) {
    char log[2048] = {};
    glGetProgramInfoLog(program.get(), sizeof log, nullptr, log);
    throw RenderError(fmt::format("render: shader program failed to link: {}", trimmed(log)));
  }
  return program;
}

Pipeline::Pipeline(int width, int height, std::uint8_t* pixels, const ShaderSources& sources)
    : width(width), height(height), pixels(pixels) {
  // Each step below either leaves its resource in a member or throws; members already filled
  // release theirs on the way out, the context last.
  context = create_context();
  make_current();
  renderer_name = query_renderer_name();
  programs = link_programs(sources);
  vao = create_vertex_array();
  vbo = create_buffer();
  ibo = create_buffer();
  margin = viewport_margin(width, height);
}

Pipeline::~Pipeline() {
  // GL deletes names in the context current on this thread, by now perhaps another renderer's.
  // Should binding ours fail (it succeeded with the same arguments before), its names are left
  // to OSMesaDestroyContext, which frees every object of the context.
  if (OSMesaMakeCurrent(context.get(), pixels, GL_UNSIGNED_BYTE, width, height)) return;
  for (LinkedProgram& p : programs) p.program.abandon();
  vao.abandon();
  vbo.abandon();
  ibo.abandon();
}

void Pipeline::make_current() const {
  // Several renderers may live in one process (tests): bind ours before drawing. Y_UP = 0
  // makes row 0 of the buffer the top of the image.
  if (!OSMesaMakeCurrent(context.get(), pixels, GL_UNSIGNED_BYTE, width, height)) {
    throw RenderError("render: OSMesaMakeCurrent failed");
  }
  OSMesaPixelStore(OSMESA_Y_UP, 0);
}

}  // namespace gl

struct Renderer::Gl : gl::Pipeline {
  using Pipeline::Pipeline;
};

Renderer::Renderer(int width, int height) : width_(width), height_(height) {
  if (width < min_frame_size || height < min_frame_size || width > max_frame_size ||
      height > max_frame_size) {
    throw RenderError(fmt::format("render: frame size {}x{} is outside {}..{} pixels", width,
                                  height, min_frame_size, max_frame_size));
  }
  pixels_.assign(static_cast<std::size_t>(width) * height * 4, 0);
  gl_ = std::make_unique<Gl>(width, height, pixels_.data(), shader_sources);
  gl_renderer_ = gl_->renderer_name;

  glBindVertexArray(gl_->vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, gl_->vbo.get());
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gl_->ibo.get());  // part of the VAO's state
  const auto stride = static_cast<GLsizei>(sizeof(Vertex));
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(offsetof(Vertex, x)));
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(offsetof(Vertex, u)));
  glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride,
                        reinterpret_cast<void*>(offsetof(Vertex, r)));
  glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(offsetof(Vertex, kind)));
  for (GLuint i = 0; i < 4; ++i) glEnableVertexAttribArray(i);
  font_scratch_.resize(std::size_t{64} * 1024);
}

Renderer::~Renderer() = default;

std::array<double, 2> Renderer::to_pixel(double x, double y) const {
  const double scale = width_ / camera_.width;  // px per m
  return {(x - camera_.center.x) * scale + width_ * 0.5,
          height_ * 0.5 - (y - camera_.center.y) * scale};
}

void Renderer::quad(const float (&p)[4][2], const float (&uv)[4][2], Rgba8 c, float kind) {
  const auto base = static_cast<std::uint32_t>(vertices_.size());
  for (int i = 0; i < 4; ++i) vertex(p[i][0], p[i][1], uv[i][0], uv[i][1], c, kind);
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices_.push_back(base + i);
}

void Renderer::rect(float x0, float y0, float x1, float y1, Rgba8 c) {
  use(shapes, {});
  quad({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {{0, 0}, {0, 0}, {0, 0}, {0, 0}}, c, 0.0f);
}

void Renderer::line(float x0, float y0, float x1, float y1, float width, Rgba8 c) {
  const float dx = x1 - x0, dy = y1 - y0;
  const float len = std::sqrt(dx * dx + dy * dy);
  if (len < 1e-3f) return;
  use(shapes, {});
  const float h = 0.5f * width, pad = h + aa_pad_px;  // room for the anti-aliased edge
  const float nx = -dy / len * pad, ny = dx / len * pad;
  const float e = pad / h;
  quad({{x0 + nx, y0 + ny}, {x1 + nx, y1 + ny}, {x1 - nx, y1 - ny}, {x0 - nx, y0 - ny}},
       {{0, e}, {0, e}, {0, -e}, {0, -e}}, c, 2.0f);
}

void Renderer::disc(float cx, float cy, float r, Rgba8 c) {
  use(shapes, {});
  const float pad = r + aa_pad_px, e = pad / r;
  quad({{cx - pad, cy - pad}, {cx + pad, cy - pad}, {cx + pad, cy + pad}, {cx - pad, cy + pad}},
       {{-e, -e}, {e, -e}, {e, e}, {-e, e}}, c, 1.0f);
}

void Renderer::disc(float cx, float cy, float r, Rgba8 c, float outline_width, Rgba8 outline_c) {
  if (!(outline_width > 0.0f)) {
    disc(cx, cy, r, c);
    return;
  }
  use(outlined_discs, outline_c);
  const float outer = r + outline_width, pad = outer + aa_pad_px, e = pad / outer;
  quad({{cx - pad, cy - pad}, {cx + pad, cy - pad}, {cx + pad, cy + pad}, {cx - pad, cy + pad}},
       {{-e, -e}, {e, -e}, {e, e}, {-e, e}}, c, r / outer);
}

void Renderer::use(int program, Rgba8 ring) {
  if (batches_.empty()) batches_.push_back(Batch{});  // primitives before the first begin()
  Batch& b = batches_.back();
  if (b.program == program && (program == shapes || b.ring == ring)) return;
  if (b.first == indices_.size()) {  // nothing recorded in this batch yet
    b.program = program;
    b.ring = ring;
  } else {
    batches_.push_back(Batch{indices_.size(), b.clip, program, ring});
  }
}

void Renderer::triangle(float x0, float y0, float x1, float y1, float x2, float y2, Rgba8 c) {
  use(shapes, {});
  const float p[3][2] = {{x0, y0}, {x1, y1}, {x2, y2}};
  const auto base = static_cast<std::uint32_t>(vertices_.size());
  for (const auto& v : p) vertex(v[0], v[1], 0.0f, 0.0f, c, 0.0f);
  for (std::uint32_t i = 0; i < 3; ++i) indices_.push_back(base + i);
}

void Renderer::polyline(std::span<const PolylinePoint> points, float width) {
  // The strip is a sequence of vertex pairs: left = point + normal * pad, right = point -
  // normal * pad, shape coordinate v = +e / -e, as in line() (pad includes aa_pad_px for the
  // anti-aliased edge). A pair emitted with `join` is connected to the pair before it by
  // two triangles.
  use(shapes, {});
  const float h = 0.5f * width, pad = h + aa_pad_px, e = pad / h;
  constexpr float min_step = 1e-3f;  // px, as line()
  // cos of the sharpest turn still mitred: 90°, where the mitre is sqrt(2) * pad long.
  constexpr float mitre_limit = 0.0f;
  auto pair = [&](const PolylinePoint& p, float nx, float ny, bool join) {
    const auto base = static_cast<std::uint32_t>(vertices_.size());
    vertex(p.x + nx, p.y + ny, 0.0f, e, p.c, 2.0f);
    vertex(p.x - nx, p.y - ny, 0.0f, -e, p.c, 2.0f);
    if (join) {
      for (std::uint32_t i : {0u, 1u, 3u, 0u, 3u, 2u}) indices_.push_back(base - 2 + i);
    }
  };
  if (points.empty()) return;
  // `prev`: the last distinct point; (dx, dy): unit direction of the segment ending there.
  const PolylinePoint* prev = &points[0];
  float dx = 0, dy = 0;
  bool started = false;  // the first segment (and the pair at its start) has been emitted
  for (std::size_t i = 1; i < points.size(); ++i) {
    const PolylinePoint& p = points[i];
    const float sx = p.x - prev->x, sy = p.y - prev->y;
    const float len = std::sqrt(sx * sx + sy * sy);
    if (len < min_step) continue;
    const float ux = sx / len, uy = sy / len;
    if (!started) {
      pair(*prev, -uy * pad, ux * pad, false);
      started = true;
    } else if (dx * ux + dy * uy >= mitre_limit) {  // mitre: one pair on the bisector
      float mx = dx + ux, my = dy + uy;
      const float ml = std::sqrt(mx * mx + my * my);
      mx /= ml, my /= ml;
      // Offset pad / cos(half the turn) along the bisector's normal: pad from both segments.
      const float scale = pad / (mx * ux + my * uy);
      pair(*prev, -my * scale, mx * scale, true);
    } else {  // too sharp: end this strip flat and start the next one flat
      pair(*prev, -dy * pad, dx * pad, true);
      pair(*prev, -uy * pad, ux * pad, false);
    }
    dx = ux, dy = uy;
    prev = &p;
  }
  if (started) pair(*prev, -dy * pad, dx * pad, true);
}

template <class Transform>
void Renderer::glyphs(const std::string& s, float scale, Rgba8 c, Transform&& to_pixel) {
  // stb_easy_font emits quads of 4 vertices {x, y, z, rgba8} (16 bytes each) in font units,
  // at most ~270 bytes per character on average (its documentation); give it room for long
  // strings rather than letting it truncate them.
  std::string copy = printable(s);
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
    quad(p, {{0, 0}, {0, 0}, {0, 0}, {0, 0}}, c, 0.0f);
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
}

void Renderer::set_clip(std::optional<ClipRect> clip) {
  if (batches_.empty()) batches_.push_back(Batch{});
  if (batches_.back().first == indices_.size()) {
    batches_.back().clip = clip;  // nothing drawn under the previous clip yet
  } else {
    batches_.push_back(Batch{indices_.size(), clip, batches_.back().program, batches_.back().ring});
  }
}

void Renderer::grid() {
  // Grid spacing: the power of ten that gives 4..40 lines across the view.
  const double step = std::pow(10.0, std::floor(std::log10(camera_.width / 4.0)));
  const double half_w = camera_.width * 0.5, half_h = half_w * height_ / width_;
  const double scale = width_ / camera_.width;
  for (double gx = std::ceil((camera_.center.x - half_w) / step) * step;
       gx <= camera_.center.x + half_w; gx += step) {
    const float px = static_cast<float>(to_pixel(gx, 0)[0]);
    const bool axis = std::abs(gx) < step * 1e-6;
    line(px, 0, px, float(height_), axis ? 2.0f : 1.0f, axis ? grid_axis : grid_minor);
  }
  for (double gy = std::ceil((camera_.center.y - half_h) / step) * step;
       gy <= camera_.center.y + half_h; gy += step) {
    const float py = static_cast<float>(to_pixel(0, gy)[1]);
    const bool axis = std::abs(gy) < step * 1e-6;
    line(0, py, float(width_), py, axis ? 2.0f : 1.0f, axis ? grid_axis : grid_minor);
  }
  // Scale bar, bottom right: one grid step.
  const float bar = static_cast<float>(step * scale);
  const float x1 = width_ - 20.0f, x0 = x1 - bar, y = height_ - 20.0f;
  line(x0, y, x1, y, 3.0f, text_color);
  line(x0, y - 5, x0, y + 5, 2.0f, text_color);
  line(x1, y - 5, x1, y + 5, 2.0f, text_color);
  const std::string label = fmt::format("{:g} m", step);
  const float label_w = text_width(label, 2.0f);
  text(x1 - label_w, y - 24, label, 2.0f, text_color);  // right-aligned: never off the frame
}

void Renderer::clear_trails() {
  trail_count_ = 0;
  trail_head_ = 0;
}

void Renderer::record_trails(const RenderFrame& s) {
  const std::size_t n = s.x.size();
  if (n != trail_bodies_) {
    trail_bodies_ = n;
    trail_x_.assign(n * trail_frames, 0.0f);
    trail_y_.assign(n * trail_frames, 0.0f);
    clear_trails();
  }
  for (std::size_t j = 0; j < n; ++j) {
    const auto p = to_pixel(s.x[j], s.y[j]);
    trail_x_[j * trail_frames + trail_head_] = static_cast<float>(p[0]);
    trail_y_[j * trail_frames + trail_head_] = static_cast<float>(p[1]);
  }
  trail_head_ = (trail_head_ + 1) % trail_frames;
  trail_count_ = std::min(trail_count_ + 1, trail_frames);
}

namespace {

// Trail samples may be left up to this far from the drawn polyline, px (see draw()).
constexpr float trail_tolerance_px = 0.2f;

// Drops points of `points` (in place, order kept) greedily: from each kept point, the next one
// kept is the farthest along that leaves every point in between within `tolerance` px of the
// segment joining the two, and at most max_run points on. The first and last points are
// always kept. O(n * max_run) distance computations.
void simplify_polyline(std::vector<Renderer::PolylinePoint>& points, float tolerance) {
  const std::size_t n = points.size();
  if (n < 3) return;
  const float tol2 = tolerance * tolerance;
  constexpr std::size_t max_run = 12;
  // Is every point strictly between points[from] and points[to] within tolerance of the segment
  // joining them?
  auto fits = [&](std::size_t from, std::size_t to) {
    const Renderer::PolylinePoint &a = points[from], &b = points[to];
    const float ux = b.x - a.x, uy = b.y - a.y, len2 = ux * ux + uy * uy;
    const float inv_len2 = len2 > 0.0f ? 1.0f / len2 : 0.0f;
    for (std::size_t i = from + 1; i < to; ++i) {
      const float wx = points[i].x - a.x, wy = points[i].y - a.y;
      const float t = std::clamp((wx * ux + wy * uy) * inv_len2, 0.0f, 1.0f);
      const float dx = wx - t * ux, dy = wy - t * uy;
      if (dx * dx + dy * dy > tol2) return false;
    }
    return true;
  };
  std::size_t kept = 1, anchor = 0;  // points[0] stays where it is
  while (anchor + 1 < n) {
    std::size_t end = anchor + 1;
    while (end + 1 < n && end - anchor < max_run && fits(anchor, end + 1)) ++end;
    points[kept++] = points[end];
    anchor = end;
  }
  points.resize(kept);
}

}  // namespace

void Renderer::draw(const RenderFrame& s, std::span<const std::string> hud_lines) {
  begin(background);
  record_trails(s);
  grid();

  const std::size_t n = s.x.size();
  const double scale = width_ / camera_.width;
  auto color_of = [&](std::size_t j) {
    return s.color[j].a == 0 ? palette[j % std::size(palette)] : s.color[j];
  };

  // Trails: one polyline per body through its samples, fading from transparent (oldest) to
  // 60 % opaque (newest): sample k of count (0 = oldest) has alpha 150 (k + 0.5) / count, so
  // each segment has on average the alpha it had when every segment was a line() of alpha
  // 150 k / count. Samples are then dropped where the polyline can skip them without leaving
  // any of them more than trail_tolerance_px away (simplify_polyline): a trail of 44 sub-pixel
  // segments becomes a few segments of a few pixels, and a projectile's gentle parabola a few
  // long ones.
  // A scene with many links (a cloth, a soft body) draws no trails: hundreds of them would
  // hide the structure the links draw.
  const bool few_links = s.links.size() <= max_zigzag_links;
  for (std::size_t j = 0; j < n && trail_count_ > 1 && few_links; ++j) {
    const Rgba8 c = color_of(j);
    const float* tx = &trail_x_[j * trail_frames];
    const float* ty = &trail_y_[j * trail_frames];
    polyline_scratch_.clear();
    for (int k = 0; k < trail_count_; ++k) {  // oldest first
      const int at = (trail_head_ - trail_count_ + k + trail_frames) % trail_frames;
      Rgba8 ck = c;
      ck.a = static_cast<std::uint8_t>((300 * k + 150) / (2 * trail_count_));
      polyline_scratch_.push_back({tx[at], ty[at], ck});
    }
    simplify_polyline(polyline_scratch_, trail_tolerance_px);
    polyline(polyline_scratch_, 2.0f);
  }

  // Springs: a zigzag of 12 coils from (ax, ay) to (bx, by), with straight leads.
  auto zigzag = [&](float ax, float ay, float bx, float by) {
    const float dx = bx - ax, dy = by - ay, len = std::sqrt(dx * dx + dy * dy);
    if (len < 24.0f) {
      line(ax, ay, bx, by, 2.0f, spring_color);
      return;
    }
    // One polyline: anchor, start of the coils, 2 * coils corners, the body.
    constexpr int coils = 12;
    const float nx = -dy / len * 7.0f, ny = dx / len * 7.0f;
    polyline_scratch_.clear();
    polyline_scratch_.push_back({ax, ay, spring_color});
    polyline_scratch_.push_back({ax + dx * 0.1f, ay + dy * 0.1f, spring_color});
    for (int k = 1; k <= 2 * coils; ++k) {
      const float f = 0.1f + 0.8f * float(k) / (2 * coils);
      const float side = k == 2 * coils ? 0.0f : (k % 2 ? 1.0f : -1.0f);
      polyline_scratch_.push_back({ax + dx * f + nx * side, ay + dy * f + ny * side, spring_color});
    }
    polyline_scratch_.push_back({bx, by, spring_color});
    polyline(polyline_scratch_, 2.0f);
  };

  // Links (springs between bodies): zigzags like the anchored springs when there are few,
  // thin straight lines when there are many (a cloth's zigzags would merge into felt).
  for (const RenderFrame::LinkLine& l : s.links) {
    const auto a = to_pixel(s.x[l.a], s.y[l.a]);
    const auto b = to_pixel(s.x[l.b], s.y[l.b]);
    if (few_links) {
      zigzag(float(a[0]), float(a[1]), float(b[0]), float(b[1]));
    } else {
      line(float(a[0]), float(a[1]), float(b[0]), float(b[1]), 1.25f, link_color);
    }
  }

  for (const RenderFrame::SpringLine& sp : s.springs) {
    const auto a = to_pixel(sp.anchor_x, sp.anchor_y);
    const auto b = to_pixel(s.x[sp.body], s.y[sp.body]);
    const float ax = float(a[0]), ay = float(a[1]);
    zigzag(ax, ay, float(b[0]), float(b[1]));
    rect(ax - 5, ay - 5, ax + 5, ay + 5, anchor_color);
  }

  // Bodies: an outlined disc of the body's radius (at least min_radius_px).
  for (std::size_t j = 0; j < n; ++j) {
    const auto p = to_pixel(s.x[j], s.y[j]);
    const float r = s.radius[j] > 0.0f ? std::max(float(s.radius[j] * scale), min_radius_px)
                                       : default_radius_px;
    disc(float(p[0]), float(p[1]), r, color_of(j), 1.5f, outline);
  }

  // HUD: text lines on a translucent panel, top left.
  if (!hud_lines.empty()) {
    constexpr float scale_text = 2.0f, line_h = 22.0f, margin = 10.0f;
    float widest = 0;
    for (const std::string& l : hud_lines) widest = std::max(widest, text_width(l, scale_text));
    rect(margin, margin, margin + widest + 16, margin + 10 + line_h * hud_lines.size(), panel);
    float y = margin + 8;
    for (const std::string& l : hud_lines) {
      text(margin + 8, y, l, scale_text, text_color);
      y += line_h;
    }
  }

  finish();
}

namespace {

// Fills the buffer bound to `target` with `bytes` bytes of `data`, growing its store (to at
// least twice its old size) only when they do not fit. `capacity` is the store's size.
void upload(GLenum target, std::size_t& capacity, const void* data, std::size_t bytes) {
  if (bytes > capacity) {
    capacity = std::max(bytes, 2 * capacity);
    glBufferData(target, static_cast<GLsizeiptr>(capacity), nullptr, GL_DYNAMIC_DRAW);
  }
  if (bytes > 0) glBufferSubData(target, 0, static_cast<GLsizeiptr>(bytes), data);
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
  glViewport(-gl_->margin, -gl_->margin, width_ + 2 * gl_->margin, height_ + 2 * gl_->margin);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(background_.r / 255.0f, background_.g / 255.0f, background_.b / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  // Colour blends "over"; alpha keeps 1 so every pixel of the PNG is opaque.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  for (const gl::Pipeline::LinkedProgram& p : gl_->programs) {
    glUseProgram(p.program.get());
    glUniform2f(p.size, float(width_), float(height_));
    glUniform1f(p.margin, float(gl_->margin));
  }
  int program = -1;
  glBindVertexArray(gl_->vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, gl_->vbo.get());
  upload(GL_ARRAY_BUFFER, gl_->vbo_bytes, vertices_.data(), vertices_.size() * sizeof(Vertex));
  upload(GL_ELEMENT_ARRAY_BUFFER, gl_->ibo_bytes, indices_.data(),
         indices_.size() * sizeof(std::uint32_t));
  for (std::size_t b = 0; b < batches_.size(); ++b) {
    const std::size_t first = batches_[b].first;
    const std::size_t end = b + 1 < batches_.size() ? batches_[b + 1].first : indices_.size();
    if (end == first) continue;
    if (batches_[b].program != program) {
      program = batches_[b].program;
      glUseProgram(gl_->programs[program].program.get());
    }
    if (program == outlined_discs) {
      const Rgba8 r = batches_[b].ring;
      glUniform4f(gl_->programs[program].ring, r.r / 255.0f, r.g / 255.0f, r.b / 255.0f,
                  r.a / 255.0f);
    }
    if (const auto& c = batches_[b].clip) {
      // GL's scissor box has its origin at the bottom-left; pixels() rows run top down.
      const int x0 = std::clamp(c->x0, 0, width_), x1 = std::clamp(c->x1, x0, width_);
      const int y0 = std::clamp(c->y0, 0, height_), y1 = std::clamp(c->y1, y0, height_);
      glEnable(GL_SCISSOR_TEST);
      glScissor(x0, height_ - y1, x1 - x0, y1 - y0);
    } else {
      glDisable(GL_SCISSOR_TEST);
    }
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(end - first), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
  }
  glDisable(GL_SCISSOR_TEST);
  glFinish();
  if (const GLenum err = glGetError(); err != GL_NO_ERROR) {
    throw RenderError(fmt::format("render: GL error 0x{:x} while drawing", err));
  }
}

}  // namespace fixstep
