// The GL API the renderer draws with, and the few places where its two dialects differ: desktop
// OpenGL 3.3 core through OSMesa natively, OpenGL ES 3.0 through WebGL2 in the browser
// (emscripten). Internal to fixstep::render (not installed). The draw code is the same for both;
// the context that backs it is gl_context.hpp's.
//
// Natively, GL entry points are resolved against libOSMesa, which exports every GL function
// (checked: `nm -D libOSMesa.so | grep glCreateShader`). The engine links OSMesa and never libGL:
// with -lGL first, the same symbols would bind to libGL's dispatch, which has no current context
// in an OSMesa program, and every call would silently do nothing (black frames).
#pragma once

#ifdef __EMSCRIPTEN__
#include <GLES3/gl3.h>
#else
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/osmesa.h>
#endif

namespace fixstep::gl {

#ifdef __EMSCRIPTEN__
/// The first lines of every shader of the renderer (gl_shaders.hpp): GLSL ES 3.00 for WebGL2,
/// floats at high precision (ES has no default in fragment shaders), and no `noperspective`
/// (ES has none; every w is 1, so perspective-correct interpolation is the same).
#define FIXSTEP_GLSL_PROLOGUE "#version 300 es\nprecision highp float;\n#define NOPERSPECTIVE\n"
/// glGetFloatv's name for the range of point sizes (GL ES 3.0, table 6.18).
inline constexpr GLenum point_size_range = GL_ALIASED_POINT_SIZE_RANGE;
#else
/// The first lines of every shader of the renderer (gl_shaders.hpp): GLSL 3.30 core.
#define FIXSTEP_GLSL_PROLOGUE "#version 330 core\n#define NOPERSPECTIVE noperspective\n"
/// glGetFloatv's name for the range of point sizes (GL 3.3 core, table 6.16).
inline constexpr GLenum point_size_range = GL_POINT_SIZE_RANGE;
#endif

/// Lets the vertex shader set each point's size (gl_PointSize): desktop GL needs
/// GL_PROGRAM_POINT_SIZE enabled; OpenGL ES 3.0 always takes it from the shader and has no such
/// capability (enabling it would be GL_INVALID_ENUM).
inline void enable_program_point_size() {
#ifndef __EMSCRIPTEN__
  glEnable(GL_PROGRAM_POINT_SIZE);
#endif
}

}  // namespace fixstep::gl
