// The GL API the renderer draws with, and the few places where its two dialects differ: desktop
// OpenGL 3.3 core through OSMesa natively, OpenGL ES 3.0 through WebGL2 in the browser
// (emscripten). Internal to fixstep::render (not installed). The draw code is the same for both
// and calls GL through api(), a table of the functions it uses; the context that backs it is
// gl_context.hpp's.
//
// Natively the table's addresses come from libOSMesa, loaded when the first context is created
// (osmesa_library.hpp): a program that never renders never maps OSMesa, nor the LLVM it pulls in
// (most of a process's start-up time when linked). OSMesa exports every GL function itself
// (checked: `nm -D libOSMesa.so.8 | grep glCreateShader`); it is opened with RTLD_LOCAL, so a
// libGL loaded into the same process (by SDL, say) can neither take over these calls (its
// dispatch has no current context in an OSMesa program: every call would silently do nothing)
// nor be taken over by them. The headers give the signatures only.
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

// X(function): every GL function the renderer calls, by its GL name.
#define FIXSTEP_GL_FUNCTIONS(X) \
  X(glAttachShader)             \
  X(glBindBuffer)               \
  X(glBindFramebuffer)          \
  X(glBindTexture)              \
  X(glBindVertexArray)          \
  X(glBlendFunc)                \
  X(glBlitFramebuffer)          \
  X(glBufferData)               \
  X(glBufferSubData)            \
  X(glCheckFramebufferStatus)   \
  X(glClear)                    \
  X(glClearColor)               \
  X(glCompileShader)            \
  X(glCreateProgram)            \
  X(glCreateShader)             \
  X(glDeleteBuffers)            \
  X(glDeleteFramebuffers)       \
  X(glDeleteProgram)            \
  X(glDeleteShader)             \
  X(glDeleteTextures)           \
  X(glDeleteVertexArrays)       \
  X(glDisable)                  \
  X(glDrawElements)             \
  X(glEnable)                   \
  X(glEnableVertexAttribArray)  \
  X(glFinish)                   \
  X(glFramebufferTexture2D)     \
  X(glGenBuffers)               \
  X(glGenFramebuffers)          \
  X(glGenTextures)              \
  X(glGenVertexArrays)          \
  X(glGetError)                 \
  X(glGetFloatv)                \
  X(glGetIntegerv)              \
  X(glGetProgramInfoLog)        \
  X(glGetProgramiv)             \
  X(glGetShaderInfoLog)         \
  X(glGetShaderiv)              \
  X(glGetString)                \
  X(glGetUniformLocation)       \
  X(glLinkProgram)              \
  X(glScissor)                  \
  X(glShaderSource)             \
  X(glTexImage2D)               \
  X(glTexParameteri)            \
  X(glUniform1f)                \
  X(glUniform2f)                \
  X(glUniform4f)                \
  X(glUseProgram)               \
  X(glVertexAttribPointer)      \
  X(glViewport)

/// One pointer per function of FIXSTEP_GL_FUNCTIONS, with the header's exact type.
struct Functions {
// (`function` names a declaration here: it cannot be parenthesised.)
// NOLINTNEXTLINE(bugprone-macro-parentheses)
#define FIXSTEP_GL_MEMBER(function) decltype(&::function) function = nullptr;
  FIXSTEP_GL_FUNCTIONS(FIXSTEP_GL_MEMBER)
#undef FIXSTEP_GL_MEMBER
};

/// The GL functions the renderer draws with. Natively loaded from libOSMesa on the first call
/// (osmesa_library.hpp; from any thread, once per process); in the browser, emscripten's WebGL2
/// functions. Throws RenderError naming the library and dlopen's or dlsym's reason when
/// libOSMesa cannot be loaded or lacks a function (every later call throws the same). The
/// renderer creates its context (which loads the library, or throws) before any GL call.
const Functions& api();

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
  api().glEnable(GL_PROGRAM_POINT_SIZE);
#endif
}

}  // namespace fixstep::gl
