// gl::Context natively: an OSMesa context (Mesa's software GL, OpenGL 3.3 core profile) drawing
// into the caller's pixel buffer.
#include <fmt/format.h>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <utility>

#include "fixstep/render/render.hpp"
#include "gl_context.hpp"
#include "osmesa_library.hpp"

namespace fixstep::gl {

namespace {

// Mesa 22's OSMesa dereferences a null screen when GALLIUM_DRIVER names a driver it cannot
// load (seen: GALLIUM_DRIVER=foo crashes inside OSMesaCreateContextAttribs). OSMesa runs on
// the software rasterisers only, so refuse any other name before calling it.
void check_gallium_driver() {
  const char* driver = std::getenv("GALLIUM_DRIVER");
  if (!driver || !*driver) return;
  const std::string d = driver;
  if (d != "llvmpipe" && d != "softpipe") {
    throw RenderError(fmt::format(
        "render: GALLIUM_DRIVER={} is not a driver OSMesa can use (llvmpipe or softpipe); "
        "unset it or choose one of those",
        d));
  }
}

// True when the environment already sets glibc's malloc trim or mmap threshold (the user's
// choice wins over keep_freed_heap_memory()).
bool malloc_thresholds_set_by_user() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && (std::strstr(tunables, "malloc.trim_threshold") ||
                   std::strstr(tunables, "malloc.mmap_threshold"))) {
    return true;
  }
  return std::getenv("MALLOC_TRIM_THRESHOLD_") || std::getenv("MALLOC_MMAP_THRESHOLD_");
}

// llvmpipe bins every frame into 64 KiB blocks it mallocs while binning and frees once the frame
// is rasterised (lp_scene.c: all but the first block of a scene). With glibc's defaults the
// blocks sit at the top of the heap when they are freed, so free() returns them to the kernel
// (trimming above 128 KiB) and the next frame faults the same pages in again, zero-filled: with
// 1000 bodies about 380 page faults per frame, a third of the drawing thread's CPU time
// (docs/perf/capture.md). Raising the trim threshold keeps them; the mmap threshold is set too
// (setting either fixes the other, which glibc would otherwise raise as large blocks come and
// go), to glibc's own upper limit for it. Process-wide, once, and only when the environment does
// not set them.
void keep_freed_heap_memory() {
#ifdef __GLIBC__
  static std::once_flag once;
  std::call_once(once, [] {
    if (malloc_thresholds_set_by_user()) return;
    constexpr int mmap_threshold = 32 << 20;  // bytes: glibc's maximum (HEAP_MAX_SIZE / 2)
    constexpr int trim_threshold = 64 << 20;  // bytes of free heap top kept before trimming
    mallopt(M_MMAP_THRESHOLD, mmap_threshold);
    mallopt(M_TRIM_THRESHOLD, trim_threshold);
  });
#endif
}

OSMesaContext as_osmesa(std::uintptr_t handle) {
  return reinterpret_cast<OSMesaContext>(handle);
}

}  // namespace

Context::Context(int width, int height, std::uint8_t* pixels)
    : width_(width), height_(height), pixels_(pixels) {
  check_gallium_driver();
  keep_freed_heap_memory();
  // Attributes as key, value pairs, one pair a line.
  // clang-format off
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                         OSMESA_DEPTH_BITS, 0,
                         OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 3,
                         OSMESA_CONTEXT_MINOR_VERSION, 3,
                         0};
  // clang-format on
  handle_ = reinterpret_cast<std::uintptr_t>(osmesa().OSMesaCreateContextAttribs(attribs, nullptr));
  if (handle_ == 0) {
    throw RenderError(
        "render: OSMesaCreateContextAttribs failed to create an OpenGL 3.3 core context "
        "(is libosmesa6 from Mesa >= 17 installed?)");
  }
}

void Context::release() noexcept {
  if (handle_ == 0) return;
  const OSMesaContext context = as_osmesa(std::exchange(handle_, 0));
  if (osmesa().OSMesaGetCurrentContext() == context)
    osmesa().OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  osmesa().OSMesaDestroyContext(context);
}

bool Context::try_make_current() const noexcept {
  // Several renderers may live in one process (tests): bind ours before drawing. Y_UP = 0
  // makes row 0 of the buffer the top of the image.
  if (!osmesa().OSMesaMakeCurrent(as_osmesa(handle_), pixels_, GL_UNSIGNED_BYTE, width_, height_)) {
    return false;
  }
  osmesa().OSMesaPixelStore(OSMESA_Y_UP, 0);
  return true;
}

void Context::make_current() const {
  if (!try_make_current()) throw RenderError("render: OSMesaMakeCurrent failed");
}

}  // namespace fixstep::gl
