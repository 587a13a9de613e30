// Every GL resource of a Renderer (OSMesa natively, WebGL2 in the browser), owned through the
// handles of gl_objects.hpp. Internal to fixstep::render (not installed);
// tests/render/test_resources.cpp builds it from broken shader sources and a missing pixel buffer
// to provoke each failure of its construction. Defined in render.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gl_context.hpp"
#include "gl_objects.hpp"

namespace fixstep::gl {

/// GLSL sources of the renderer's programs: one vertex shader, shared by the programs, and one
/// fragment shader per program.
struct ShaderSources {
  const char* vertex = nullptr;
  std::array<const char*, 3> fragments{};
};

/// The GL context of one frame (gl_context.hpp) and the GL objects drawn with it. The members are
/// declared in the order the constructor acquires them and so are released in reverse: if the
/// constructor throws, the members built so far release what they hold (the GL names while the
/// context is still current, then the context).
struct Pipeline {
  /// A linked program and its uniform locations (-1 where the program has no such uniform).
  struct LinkedProgram {
    Program program;
    GLint size = -1, margin = -1, flip = -1, ring = -1;  // u_size, u_margin, u_flip, u_ring
  };

  /// Creates the context (Context(width, height, pixels): OSMesa draws into `pixels`, width x
  /// height RGBA8 pixels, top row first, which the caller keeps alive and in place while the
  /// Pipeline lives; WebGL2 on the page's canvas), makes it current, builds programs[i] from
  /// sources.vertex and sources.fragments[i], and creates the vertex array and its two buffers.
  /// Throws RenderError, having released whatever it acquired, when: the context cannot be
  /// created (see Context) or made current (OSMesaMakeCurrent fails, e.g. no pixels);
  /// GL_RENDERER is null (GL calls do not reach OSMesa); a shader fails to compile or a program
  /// to link.
  Pipeline(int width, int height, std::uint8_t* pixels, const ShaderSources& sources);
  /// Makes the context current (so the GL names are deleted in it), then releases everything.
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  /// Makes the context current on this thread (OSMesa: drawing into the pixels, row 0 at the
  /// top). Throws RenderError (see Context::make_current).
  void make_current() const { context.make_current(); }

  // The backdrop: an offscreen width x height picture that a frame starts from instead of a
  // clear (Renderer::draw keeps its grid and planes there while the view does not change). It is
  // drawn upside down (u_flip = -1), so that its rows lie in memory as the frame's do: OSMesa's
  // framebuffer is a window-system one, whose rows Mesa stores top first (GL's y is flipped on
  // the way), where a texture's row 0 is GL's bottom row. The copy then flips it back in GL
  // terms, which for llvmpipe is no flip at all but a plain copy of the rows; drawing the
  // backdrop the right way up would make the copy a flip, which llvmpipe draws as a textured
  // quad (and rasterises the backdrop's edges slightly differently).
  /// Makes the backdrop the framebuffer drawn into, creating it on first use. Throws RenderError
  /// if GL cannot complete it.
  void draw_into_backdrop();
  /// Makes the frame (OSMesa's framebuffer, which is the pixels; in the browser the canvas)
  /// the one drawn into.
  void draw_into_frame();
  /// Copies the backdrop over the whole frame.
  void copy_backdrop_to_frame();

  int width, height;
  std::uint8_t* pixels;
  // --- resources, in acquisition order ---
  Context context;
  std::array<LinkedProgram, 3> programs;
  VertexArray vao;
  Buffer vbo, ibo;  // vertices; triangles (3 indices each), part of vao's state
  // --- state ---
  std::string renderer_name;  // GL_RENDERER
  int margin = 0;             // px of viewport beyond each edge of the frame (Renderer::finish)
  // The widest point drawn as a point, px: GL's limit, and at most twice the margin (GL drops a
  // point whose centre is clipped away, so a point must not reach the frame from beyond it).
  float max_point_size = 0.0f;
  // Bytes allocated for vbo and ibo: they grow (glBufferData) only when a frame needs more and
  // are otherwise refilled in place (glBufferSubData), so a steady scene allocates nothing.
  std::size_t vbo_bytes = 0, ibo_bytes = 0;
  // --- the backdrop, created by the first draw_into_backdrop() ---
  Texture backdrop;                  // RGBA8, width x height
  Framebuffer backdrop_framebuffer;  // its colour attachment: backdrop
  // --- images (Renderer::image): texture i holds the renderer's image i, made on first use ---
  std::vector<Texture> images;
  /// Binds the texture of image `index` (of `width` x `height` RGBA8 pixels at `rgba`, top row
  /// first), creating and filling it first when it is new (nearest texel, no mipmaps).
  void bind_image(std::size_t index, int width, int height, const std::uint8_t* rgba);
};

}  // namespace fixstep::gl
