// The OSMesa context and GL objects of a Renderer (gl_pipeline.hpp): creation in acquisition
// order, the shader builder (gl_shaders.hpp), release in reverse.
#include "gl_pipeline.hpp"  // GL through OSMesa only, never libGL: see gl_objects.hpp

#include <fmt/format.h>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <utility>

#include "fixstep/render.hpp"
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

// True when the environment already sets glibc's malloc trim or mmap threshold (the user's
// choice wins over keep_freed_heap_memory()).
bool malloc_thresholds_set_by_user() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && (std::strstr(tunables, "malloc.trim_threshold") ||
                   std::strstr(tunables, "malloc.mmap_threshold"))) {
    return true;
  }
  return std::getenv("MALLOC_TRIM_THRESHOLD_") || std::getenv("MALLOC_MMAP_THRESHOLD_");
}

// llvmpipe bins every frame into 64 KiB blocks it mallocs while binning and frees once the frame
// is rasterised (lp_scene.c: all but the first block of a scene). With glibc's defaults the
// blocks sit at the top of the heap when they are freed, so free() returns them to the kernel
// (trimming above 128 KiB) and the next frame faults the same pages in again, zero-filled: with
// 1000 bodies about 380 page faults per frame, a third of the drawing thread's CPU time
// (docs/perf/capture.md). Raising the trim threshold keeps them; the mmap threshold is set too
// (setting either fixes the other, which glibc would otherwise raise as large blocks come and
// go), to glibc's own upper limit for it. Process-wide, once, and only when the environment does
// not set them.
void keep_freed_heap_memory() {
#ifdef __GLIBC__
  static std::once_flag once;
  std::call_once(once, [] {
    if (malloc_thresholds_set_by_user()) return;
    constexpr int mmap_threshold = 32 << 20;  // bytes: glibc's maximum (HEAP_MAX_SIZE / 2)
    constexpr int trim_threshold = 64 << 20;  // bytes of free heap top kept before trimming
    mallopt(M_MMAP_THRESHOLD, mmap_threshold);
    mallopt(M_TRIM_THRESHOLD, trim_threshold);
  });
#endif
}

Context create_context() {
  check_gallium_driver();
  keep_freed_heap_memory();
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
    p.flip = glGetUniformLocation(p.program.get(), "u_flip");
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

// The widest point (px) to draw as a point with a viewport `margin` px beyond the frame.
float widest_point(int margin) {
  GLfloat range[2] = {0.0f, 0.0f};
  glGetFloatv(GL_POINT_SIZE_RANGE, range);  // llvmpipe: 1..255
  return std::min(range[1], 2.0f * float(margin));
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
  max_point_size = widest_point(margin);
}

namespace {

Texture create_texture(int width, int height) {
  GLuint name = 0;
  glGenTextures(1, &name);
  Texture texture(name);
  glBindTexture(GL_TEXTURE_2D, name);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  return texture;
}

// A framebuffer drawing into `texture`, left bound to GL_FRAMEBUFFER.
Framebuffer create_framebuffer(const Texture& texture) {
  GLuint name = 0;
  glGenFramebuffers(1, &name);
  Framebuffer framebuffer(name);
  glBindFramebuffer(GL_FRAMEBUFFER, name);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture.get(), 0);
  if (const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
      status != GL_FRAMEBUFFER_COMPLETE) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    throw RenderError(fmt::format("render: backdrop framebuffer incomplete (0x{:x})", status));
  }
  return framebuffer;
}

}  // namespace

void Pipeline::draw_into_backdrop() {
  if (backdrop_framebuffer.get()) {
    glBindFramebuffer(GL_FRAMEBUFFER, backdrop_framebuffer.get());
    return;
  }
  Texture texture = create_texture(width, height);
  backdrop_framebuffer = create_framebuffer(texture);
  backdrop = std::move(texture);
}

void Pipeline::draw_into_frame() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Pipeline::copy_backdrop_to_frame() {
  // Upside down in GL terms (see draw_into_backdrop), same size and format, no scissor: llvmpipe
  // copies the rows (a copy of the resource's region), without drawing.
  glBindFramebuffer(GL_READ_FRAMEBUFFER, backdrop_framebuffer.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, width, height, 0, height, width, 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
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
  backdrop.abandon();
  backdrop_framebuffer.abandon();
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

}  // namespace fixstep
