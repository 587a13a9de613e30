// Building GLSL programs into owning handles: whatever a failed step created is deleted before
// it throws. Internal to fixstep::render (not installed); tests/test_resources.cpp compiles
// broken sources through it. Defined in render.cpp.
#pragma once

#include "gl_objects.hpp"

namespace fixstep::gl {

/// Compiles `source` (GLSL, NUL-terminated) as a shader of `type` (GL_VERTEX_SHADER or
/// GL_FRAGMENT_SHADER) in the context current on this thread. Throws RenderError
/// "render: shader compilation failed: LOG" (LOG: the compiler's info log).
[[nodiscard]] Shader compile_shader(GLenum type, const char* source);

/// Links `vertex` and `fragment` (compiled shaders of the current context) into a program of
/// that context. Throws RenderError "render: shader program failed to link: LOG".
[[nodiscard]] Program link_program(const Shader& vertex, const Shader& fragment);

}  // namespace fixstep::gl
