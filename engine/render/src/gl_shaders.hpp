// The renderer's GLSL programs: their sources (what each draws, and how its vertices are laid
// out) and the builder that compiles them into owning handles (whatever a failed step created is
// deleted before it throws). Internal to fixstep::render (not installed);
// tests/render/test_resources.cpp compiles broken sources through the builder. The builder is
// defined in gl_pipeline.cpp.
#pragma once

#include "gl_api.hpp"
#include "gl_objects.hpp"
#include "gl_pipeline.hpp"

namespace fixstep::gl {

/// Compiles `source` (GLSL, NUL-terminated) as a shader of `type` (GL_VERTEX_SHADER or
/// GL_FRAGMENT_SHADER) in the context current on this thread. Throws RenderError
/// "render: shader compilation failed: LOG" (LOG: the compiler's info log).
[[nodiscard]] Shader compile_shader(GLenum type, const char* source);

/// Links `vertex` and `fragment` (compiled shaders of the current context) into a program of
/// that context. Throws RenderError "render: shader program failed to link: LOG".
[[nodiscard]] Program link_program(const Shader& vertex, const Shader& fragment);

// --- the renderer's programs (Renderer, render.cpp) -------------------------------------------
// Every vertex is {a_pos, a_uv, a_color, a_fill} (Renderer::Vertex). The shapes program draws
// triangles (a_fill: a circle's hole, see below), the ring program points (one vertex per disc:
// a_pos its centre, a_uv = (point size px, shape coordinate at the square's edge), a_fill the
// fill's radius). Varyings are
// `noperspective` (w is always 1, so this only spares llvmpipe the perspective division; GLSL ES
// has no such qualifier, so the sources say NOPERSPECTIVE, which FIXSTEP_GLSL_PROLOGUE defines) and
// `flat` where they are constant over a primitive; each fragment shader reads v_color
// (interpolated: polylines fade along their length) or v_flat_color (constant: the outlined
// discs), and the linker drops what a program does not read.

/// Shared by both programs: pixel coordinates into the viewport, which reaches u_margin px beyond
/// every edge of the frame (Renderer::finish()).
inline constexpr const char* vertex_shader = FIXSTEP_GLSL_PROLOGUE R"(
layout(location = 0) in vec2 a_pos;    // pixels, origin top-left, y down
layout(location = 1) in vec2 a_uv;     // shape coordinates; points: (size px, scale)
layout(location = 2) in vec4 a_color;
layout(location = 3) in float a_fill;  // points: the fill's radius in shape coordinates
uniform vec2 u_size;    // pixels, the frame
uniform float u_margin; // pixels of viewport beyond each edge of the frame
uniform float u_flip;   // 1, or -1 upside down (drawing into the backdrop: Renderer::finish())
NOPERSPECTIVE out vec2 v_uv;
NOPERSPECTIVE out vec4 v_color;
flat out vec4 v_flat_color;
flat out float v_fill;
flat out float v_point_scale;
void main() {
  vec2 p = (a_pos + u_margin) / (u_size + 2.0 * u_margin);
  gl_Position = vec4(p.x * 2.0 - 1.0, (1.0 - p.y * 2.0) * u_flip, 0.0, 1.0);
  gl_PointSize = a_uv.x;  // points only
  v_uv = a_uv;
  v_color = a_color;
  v_flat_color = a_color;
  v_fill = a_fill;
  v_point_scale = a_uv.y;  // points only
}
)";

/// Solids, lines, polylines, plain discs, circles (rings), text, in one branch-free shader. Discs
/// and lines are anti-aliased analytically: coverage falls from 1 to 0 over one pixel at the
/// shape's edge, where the distance d = |uv| from the centre (a disc's centre, a line's middle: a
/// line has uv = (0, v)) is 1, measured with fwidth. A circle (Renderer::circle) is a disc with a
/// hole: v_fill is the hole's radius in the same units, and its coverage (anti-aliased likewise)
/// is taken away, so a ring is the picture a disc of its colour leaves outside the hole; every
/// other vertex has v_fill = Renderer::no_hole (-1e30), whose coverage is 0 everywhere (unless
/// fwidth exceeds 1e30: a line narrower than 1e-30 px), so that outer - inner is the disc's or
/// line's own coverage, bit for bit. Solids have uv = 0
/// everywhere, hence full coverage (fwidth is 0 and w its floor). Both programs output
/// premultiplied colour (rgb * a, a), which Renderer::finish() blends "over" the frame with
/// (1, 1 - a): the same picture as straight alpha blended with (a, 1 - a), and one multiplication
/// fewer per pixel for llvmpipe. Circles were GL points of a program of their own (cheaper alone:
/// one primitive instead of two triangles), but a game interleaves them with other shapes, and
/// every change of program is a batch and a draw call of its own, which cost llvmpipe more than
/// the second triangle does (docs/perf/overlay.md).
inline constexpr const char* shapes_fragment_shader = FIXSTEP_GLSL_PROLOGUE R"(
NOPERSPECTIVE in vec2 v_uv;
NOPERSPECTIVE in vec4 v_color;
flat in float v_fill;
out vec4 frag;
void main() {
  float d = length(v_uv);
  float w = max(fwidth(d), 1e-6);
  float outer = clamp((1.0 - d) / w + 0.5, 0.0, 1.0);
  float inner = clamp((v_fill - d) / w + 0.5, 0.0, 1.0);
  float a = v_color.a * max(outer - inner, 0.0);
  frag = vec4(v_color.rgb * a, a);
}
)";

/// Outlined discs (Renderer::disc with an outline) in one pass, drawn as points: a disc is one
/// vertex and one square primitive, its shape coordinates uv run from -v_point_scale to
/// +v_point_scale across the square (from gl_PointCoord) and are 1 at the outer edge; v_fill is
/// the fill's radius in the same units, u_ring the outline's colour. The fill is composited over
/// the outline in the shader, so the result is that of drawing the outline disc and then the
/// fill disc "over" it: alpha a = af + (1 - af) ao and premultiplied colour
/// f af + o (1 - af) ao.
inline constexpr const char* ring_fragment_shader = FIXSTEP_GLSL_PROLOGUE R"(
flat in vec4 v_flat_color;
flat in float v_fill;
flat in float v_point_scale;
uniform vec4 u_ring;
out vec4 frag;
void main() {
  float d = length((gl_PointCoord * 2.0 - 1.0) * v_point_scale);
  float w = max(fwidth(d), 1e-6);
  float ao = u_ring.a * clamp((1.0 - d) / w + 0.5, 0.0, 1.0);
  float af = v_flat_color.a * clamp((v_fill - d) / w + 0.5, 0.0, 1.0);
  float a = af + (1.0 - af) * ao;
  frag = vec4(v_flat_color.rgb * af + u_ring.rgb * ((1.0 - af) * ao), a);
}
)";

/// Images (Renderer::image, sprites, background tiles) on triangles: v_uv is the position in
/// the image in image widths and heights from its top-left corner, and each fragment takes the
/// one texel under its centre, by integer index (texelFetch: no filtering, no mipmaps, so
/// llvmpipe and WebGL agree on every texel they pick). v_fill > 0 tiles the image beyond
/// [0, 1) (the background); otherwise its edge texels stretch. The texel's colour times v_color
/// (a tint), premultiplied as the other programs' output.
inline constexpr const char* image_fragment_shader = FIXSTEP_GLSL_PROLOGUE R"(
NOPERSPECTIVE in vec2 v_uv;
NOPERSPECTIVE in vec4 v_color;
flat in float v_fill;
uniform sampler2D u_image;
out vec4 frag;
void main() {
  vec2 size = vec2(textureSize(u_image, 0));
  vec2 t = v_uv * size;
  t = v_fill > 0.0 ? t - floor(t / size) * size : t;
  t = clamp(t, vec2(0.0), size - 0.5);
  vec4 c = texelFetch(u_image, ivec2(t), 0) * v_color;
  frag = vec4(c.rgb * c.a, c.a);
}
)";

/// The programs, in the order of Renderer::shapes, Renderer::outlined_discs and
/// Renderer::images_program.
inline constexpr ShaderSources shader_sources{
    vertex_shader, {shapes_fragment_shader, ring_fragment_shader, image_fragment_shader}};

}  // namespace fixstep::gl
