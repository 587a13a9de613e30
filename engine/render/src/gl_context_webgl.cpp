// gl::Context in the browser: a WebGL2 context (OpenGL ES 3.0) on the page's canvas, made
// through emscripten's html5.h. The renderer draws on the canvas itself (its default
// framebuffer), so the page shows each frame as drawn, without a read-back.
#include <emscripten/html5.h>
#include <fmt/format.h>

#include <utility>

#include "fixstep/render/render.hpp"
#include "gl_context.hpp"

namespace fixstep::gl {

namespace {

EMSCRIPTEN_WEBGL_CONTEXT_HANDLE as_webgl(std::uintptr_t handle) {
  return static_cast<EMSCRIPTEN_WEBGL_CONTEXT_HANDLE>(handle);
}

}  // namespace

Context::Context(int width, int height, std::uint8_t* pixels)
    : width_(width), height_(height), pixels_(pixels) {
  if (emscripten_set_canvas_element_size(canvas_selector, width, height) !=
      EMSCRIPTEN_RESULT_SUCCESS) {
    throw RenderError(fmt::format("render: the page has no canvas {}", canvas_selector));
  }
  EmscriptenWebGLContextAttributes attrs;
  emscripten_webgl_init_context_attributes(&attrs);
  attrs.majorVersion = 2;  // WebGL2 = OpenGL ES 3.0
  attrs.minorVersion = 0;
  attrs.alpha = false;  // every pixel is opaque, as in the PNG frames
  attrs.depth = false;
  attrs.stencil = false;
  // No multisampling: the shaders anti-alias analytically, as with OSMesa, and the backdrop's
  // copy (glBlitFramebuffer) into a multisampled canvas would be an error.
  attrs.antialias = false;
  // Keep the frame after it is composited, so a screenshot taken between frames shows it.
  attrs.preserveDrawingBuffer = true;
  const EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context =
      emscripten_webgl_create_context(canvas_selector, &attrs);
  if (context <= 0) {
    throw RenderError(fmt::format(
        "render: could not create a WebGL2 context on canvas {} (error {}): does this browser "
        "have WebGL2?",
        canvas_selector, static_cast<long>(context)));
  }
  handle_ = static_cast<std::uintptr_t>(context);
}

void Context::release() noexcept {
  if (handle_ == 0) return;
  const EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context = as_webgl(std::exchange(handle_, 0));
  if (emscripten_webgl_get_current_context() == context) emscripten_webgl_make_context_current(0);
  emscripten_webgl_destroy_context(context);
}

bool Context::try_make_current() const noexcept {
  return emscripten_webgl_make_context_current(as_webgl(handle_)) == EMSCRIPTEN_RESULT_SUCCESS;
}

void Context::make_current() const {
  if (!try_make_current()) {
    throw RenderError("render: emscripten_webgl_make_context_current failed");
  }
}

}  // namespace fixstep::gl
