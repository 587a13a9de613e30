// The OSMesa context and GL objects of a Renderer (gl_pipeline.hpp): creation in acquisition
// order, the shader builder (gl_shaders.hpp), release in reverse.
#include "gl_pipeline.hpp"  // GL through OSMesa only, never libGL: see gl_objects.hpp

#include <fmt/format.h>

#include <array>
#include <cstdlib>
#include <string>

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

}  // namespace fixstep
