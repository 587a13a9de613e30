// The GL context a Renderer's pipeline (gl_pipeline.hpp) draws with. Natively an OSMesa context
// drawing into a CPU-side pixel buffer (gl_context_osmesa.cpp); in the browser a WebGL2 context
// drawing on the page's canvas (gl_context_webgl.cpp). Exactly one of the two is built. Internal
// to fixstep::render (not installed).
#pragma once

#include <cstdint>

#include "gl_api.hpp"

namespace fixstep::gl {

/// The CSS selector of the canvas a browser Renderer draws on (the page's
/// `<canvas id="canvas">`); unused natively.
inline constexpr const char* canvas_selector = "#canvas";

/// Owns one GL context. Movable, not copyable; the destructor only releases (noexcept).
class Context {
 public:
  /// No context.
  Context() = default;
  /// Creates an OpenGL 3.3 core (OSMesa) or OpenGL ES 3.0 (WebGL2, on canvas_selector, resized
  /// to width x height px, no depth, stencil or multisampling, its drawing buffer preserved for
  /// screenshots) context for a width x height frame. OSMesa draws into `pixels` (width x height
  /// RGBA8, top row first; the caller keeps them alive and in place); WebGL2 ignores them. Not
  /// made current. Throws RenderError: OSMesa when GALLIUM_DRIVER names a driver other than
  /// llvmpipe or softpipe (Mesa 22 would crash on it) or OSMesaCreateContextAttribs fails;
  /// WebGL2 when the page has no such canvas or the browser no WebGL2.
  Context(int width, int height, std::uint8_t* pixels);
  /// Unbinds the context if it is current on this thread, then destroys it (which also frees
  /// every GL object left in it).
  ~Context();
  Context(Context&& other) noexcept;
  Context& operator=(Context&& other) noexcept;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Makes the context current on this thread (OSMesa: drawing into the pixels, row 0 at the
  /// top). Throws RenderError "render: OSMesaMakeCurrent failed" (natively, e.g. no pixels) or
  /// "render: emscripten_webgl_make_context_current failed".
  void make_current() const;
  /// make_current() without throwing: whether it succeeded.
  [[nodiscard]] bool try_make_current() const noexcept;
  /// Whether this owns a context.
  [[nodiscard]] explicit operator bool() const noexcept { return handle_ != 0; }

 private:
  void release() noexcept;

  std::uintptr_t handle_ = 0;  // OSMesaContext, or EMSCRIPTEN_WEBGL_CONTEXT_HANDLE
  int width_ = 0, height_ = 0;
  std::uint8_t* pixels_ = nullptr;
};

}  // namespace fixstep::gl
