// What both GL contexts (gl_context_osmesa.cpp natively, gl_context_webgl.cpp in the browser)
// share: ownership of the handle. Each backend defines its constructor and release().
#include "gl_context.hpp"

#include <utility>

namespace fixstep::gl {

Context::~Context() {
  release();
}

Context::Context(Context&& other) noexcept
    : handle_(std::exchange(other.handle_, 0)),
      width_(other.width_),
      height_(other.height_),
      pixels_(other.pixels_) {}

Context& Context::operator=(Context&& other) noexcept {
  if (this != &other) {
    release();
    handle_ = std::exchange(other.handle_, 0);
    width_ = other.width_, height_ = other.height_, pixels_ = other.pixels_;
  }
  return *this;
}

}  // namespace fixstep::gl
