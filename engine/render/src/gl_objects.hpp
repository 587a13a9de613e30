// Owning handles for the GL names a Renderer holds: its shaders, programs, vertex arrays,
// buffers, textures and framebuffers (the context is gl_context.hpp's). Internal to
// fixstep::render (not installed).
#pragma once

#include <utility>

#include "gl_api.hpp"  // GL through OSMesa only, never libGL (see there); WebGL2 in the browser

namespace fixstep::gl {

/// Owns one resource `value` (the null value T{} owns nothing) and hands it to Release{} on
/// destruction. Movable, not copyable; the destructor is noexcept and only releases.
template <class T, class Release>
class Owned {
 public:
  static_assert(noexcept(Release{}(T{})), "a release must not throw");

  Owned() = default;
  explicit Owned(T value) noexcept : value_(value) {}
  ~Owned() { reset(); }
  Owned(Owned&& other) noexcept : value_(std::exchange(other.value_, T{})) {}
  Owned& operator=(Owned&& other) noexcept {
    if (this != &other) {
      reset();
      value_ = std::exchange(other.value_, T{});
    }
    return *this;
  }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;

  [[nodiscard]] T get() const noexcept { return value_; }
  /// Gives up ownership without releasing (the resource is freed by someone else).
  void abandon() noexcept { value_ = T{}; }

 private:
  void reset() noexcept {
    if (value_ != T{}) Release{}(std::exchange(value_, T{}));
  }
  T value_{};
};

// GL names are deleted in the context current on this thread: the one that created them must
// be current when they are released (see Pipeline::~Pipeline).
struct DeleteShader {
  void operator()(GLuint name) const noexcept { gl::api().glDeleteShader(name); }
};
struct DeleteProgram {
  void operator()(GLuint name) const noexcept { gl::api().glDeleteProgram(name); }
};
struct DeleteVertexArray {
  void operator()(GLuint name) const noexcept { gl::api().glDeleteVertexArrays(1, &name); }
};
struct DeleteBuffer {
  void operator()(GLuint name) const noexcept { gl::api().glDeleteBuffers(1, &name); }
};
struct DeleteTexture {
  void operator()(GLuint name) const noexcept { gl::api().glDeleteTextures(1, &name); }
};
struct DeleteFramebuffer {
  void operator()(GLuint name) const noexcept { gl::api().glDeleteFramebuffers(1, &name); }
};

using Shader = Owned<GLuint, DeleteShader>;
using Program = Owned<GLuint, DeleteProgram>;
using VertexArray = Owned<GLuint, DeleteVertexArray>;
using Buffer = Owned<GLuint, DeleteBuffer>;
using Texture = Owned<GLuint, DeleteTexture>;
using Framebuffer = Owned<GLuint, DeleteFramebuffer>;

}  // namespace fixstep::gl
