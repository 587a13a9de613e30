// gl::api() in the browser: emscripten's WebGL2 (OpenGL ES 3.0) functions, linked.
#include "gl_api.hpp"

namespace fixstep::gl {

const Functions& api() {
#define FIXSTEP_GL_ADDRESS(function) &::function,
  static const Functions functions{FIXSTEP_GL_FUNCTIONS(FIXSTEP_GL_ADDRESS)};
#undef FIXSTEP_GL_ADDRESS
  return functions;
}

}  // namespace fixstep::gl
