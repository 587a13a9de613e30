// The GL context and objects of a Renderer (gl_pipeline.hpp): creation in acquisition order, the
// shader builder (gl_shaders.hpp), release in reverse.
#include "gl_pipeline.hpp"  // GL through OSMesa only, never libGL: see gl_api.hpp

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "fixstep/render/render.hpp"
#include "gl_shaders.hpp"

namespace fixstep {

namespace gl {

namespace {

// `log` without the line break Mesa ends its info logs with.
std::string trimmed(const char* log) {
  std::string s = log;
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// GL_RENDERER of the current context.
std::string query_renderer_name() {
  const auto* name = reinterpret_cast<const char*>(gl::api().glGetString(GL_RENDERER));
  if (!name) {
    throw RenderError(
        "render: GL_RENDERER is null: GL calls are not reaching OSMesa. Link libOSMesa only; a "
        "libGL linked before it captures every gl* call and frames come out black.");
  }
  return name;
}

std::array<Pipeline::LinkedProgram, 3> link_programs(const ShaderSources& sources) {
  const Shader vertex = compile_shader(GL_VERTEX_SHADER, sources.vertex);
  std::array<Pipeline::LinkedProgram, 3> programs;
  for (std::size_t i = 0; i < programs.size(); ++i) {
    const Shader fragment = compile_shader(GL_FRAGMENT_SHADER, sources.fragments[i]);
    Pipeline::LinkedProgram& p = programs[i];
    p.program = link_program(vertex, fragment);
    p.size = gl::api().glGetUniformLocation(p.program.get(), "u_size");
    p.margin = gl::api().glGetUniformLocation(p.program.get(), "u_margin");
    p.flip = gl::api().glGetUniformLocation(p.program.get(), "u_flip");
    p.ring = gl::api().glGetUniformLocation(p.program.get(), "u_ring");
  }
  return programs;
}

VertexArray create_vertex_array() {
  GLuint name = 0;
  gl::api().glGenVertexArrays(1, &name);
  return VertexArray(name);
}

Buffer create_buffer() {
  GLuint name = 0;
  gl::api().glGenBuffers(1, &name);
  return Buffer(name);
}

// px of viewport beyond each edge of a width x height frame (see Renderer::finish()).
int viewport_margin(int width, int height) {
  GLint max_dims[2] = {0, 0};
  gl::api().glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_dims);
  // (llvmpipe reports 16384 x 16384, viewport bounds -32768..32767: the full 256 px even at
  // max_frame_size.)
  return std::clamp((std::min(max_dims[0] - width, max_dims[1] - height)) / 2, 0, 256);
}

// The widest point (px) to draw as a point with a viewport `margin` px beyond the frame.
float widest_point(int margin) {
  GLfloat range[2] = {0.0f, 0.0f};
  gl::api().glGetFloatv(point_size_range, range);  // llvmpipe: 1..255
  return std::min(range[1], 2.0f * float(margin));
}

}  // namespace

Shader compile_shader(GLenum type, const char* source) {
  Shader shader(gl::api().glCreateShader(type));
  gl::api().glShaderSource(shader.get(), 1, &source, nullptr);
  gl::api().glCompileShader(shader.get());
  GLint ok = 0;
  gl::api().glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    gl::api().glGetShaderInfoLog(shader.get(), sizeof log, nullptr, log);
    throw RenderError(fmt::format("render: shader compilation failed: {}", trimmed(log)));
  }
  return shader;
}

Program link_program(const Shader& vertex, const Shader& fragment) {
  Program program(gl::api().glCreateProgram());
  gl::api().glAttachShader(program.get(), vertex.get());
  gl::api().glAttachShader(program.get(), fragment.get());
  gl::api().glLinkProgram(program.get());
  GLint linked = 0;
  gl::api().glGetProgramiv(program.get(), GL_LINK_STATUS, &linked);
  if (!linked) {
    char log[2048] = {};
    gl::api().glGetProgramInfoLog(program.get(), sizeof log, nullptr, log);
    throw RenderError(fmt::format("render: shader program failed to link: {}", trimmed(log)));
  }
  return program;
}

Pipeline::Pipeline(int width, int height, std::uint8_t* pixels, const ShaderSources& sources)
    : width(width), height(height), pixels(pixels) {
  // Each step below either leaves its resource in a member or throws; members already filled
  // release theirs on the way out, the context last.
  context = Context(width, height, pixels);
  make_current();
  renderer_name = query_renderer_name();
  programs = link_programs(sources);
  vao = create_vertex_array();
  vbo = create_buffer();
  ibo = create_buffer();
  margin = viewport_margin(width, height);
  max_point_size = widest_point(margin);
}

namespace {

Texture create_texture(int width, int height) {
  GLuint name = 0;
  gl::api().glGenTextures(1, &name);
  Texture texture(name);
  gl::api().glBindTexture(GL_TEXTURE_2D, name);
  gl::api().glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                         nullptr);
  gl::api().glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl::api().glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl::api().glBindTexture(GL_TEXTURE_2D, 0);
  return texture;
}

// A framebuffer drawing into `texture`, left bound to GL_FRAMEBUFFER.
Framebuffer create_framebuffer(const Texture& texture) {
  GLuint name = 0;
  gl::api().glGenFramebuffers(1, &name);
  Framebuffer framebuffer(name);
  gl::api().glBindFramebuffer(GL_FRAMEBUFFER, name);
  gl::api().glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                                   texture.get(), 0);
  if (const GLenum status = gl::api().glCheckFramebufferStatus(GL_FRAMEBUFFER);
      status != GL_FRAMEBUFFER_COMPLETE) {
    gl::api().glBindFramebuffer(GL_FRAMEBUFFER, 0);
    throw RenderError(fmt::format("render: backdrop framebuffer incomplete (0x{:x})", status));
  }
  return framebuffer;
}

}  // namespace

void Pipeline::draw_into_backdrop() {
  if (backdrop_framebuffer.get()) {
    gl::api().glBindFramebuffer(GL_FRAMEBUFFER, backdrop_framebuffer.get());
    return;
  }
  Texture texture = create_texture(width, height);
  backdrop_framebuffer = create_framebuffer(texture);
  backdrop = std::move(texture);
}

void Pipeline::bind_image(std::size_t index, int w, int h, const std::uint8_t* rgba) {
  if (index < images.size() && images[index].get()) {
    gl::api().glBindTexture(GL_TEXTURE_2D, images[index].get());
    return;
  }
  if (images.size() <= index) images.resize(index + 1);
  GLuint name = 0;
  gl::api().glGenTextures(1, &name);
  images[index] = Texture(name);
  gl::api().glBindTexture(GL_TEXTURE_2D, name);
  // Rows of 4-byte pixels: any row length meets the default unpack alignment (4).
  gl::api().glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  // Complete without mipmaps (the shader reads texels with texelFetch: no filtering at all).
  gl::api().glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl::api().glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

void Pipeline::draw_into_frame() {
  gl::api().glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Pipeline::copy_backdrop_to_frame() {
  // Upside down in GL terms (see draw_into_backdrop), same size and format, no scissor: llvmpipe
  // copies the rows (a copy of the resource's region), without drawing.
  gl::api().glBindFramebuffer(GL_READ_FRAMEBUFFER, backdrop_framebuffer.get());
  gl::api().glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl::api().glBlitFramebuffer(0, 0, width, height, 0, height, width, 0, GL_COLOR_BUFFER_BIT,
                              GL_NEAREST);
  gl::api().glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Pipeline::~Pipeline() {
  // GL deletes names in the context current on this thread, by now perhaps another renderer's.
  // Should binding ours fail (it succeeded with the same arguments before), its names are left
  // to the context's destruction, which frees every object of the context.
  if (context.try_make_current()) return;
  for (LinkedProgram& p : programs) p.program.abandon();
  vao.abandon();
  vbo.abandon();
  ibo.abandon();
  backdrop.abandon();
  backdrop_framebuffer.abandon();
  for (Texture& t : images) t.abandon();
}

}  // namespace gl

}  // namespace fixstep
