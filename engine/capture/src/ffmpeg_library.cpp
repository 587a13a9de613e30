// Loading FFmpeg's libraries on first use (ffmpeg_library.hpp).
#include "ffmpeg_library.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <string>

#include "fixstep/capture/capture.hpp"

namespace fixstep::av {
namespace {

#define FIXSTEP_SONAME(name, major) "lib" #name ".so." AV_STRINGIFY(major)
// The sonames of the libraries the headers describe: a library of another major version has
// another ABI, and would be refused by name rather than called with the wrong layouts.
struct Sonames {
  const char* avutil = FIXSTEP_SONAME(avutil, LIBAVUTIL_VERSION_MAJOR);
  const char* avcodec = FIXSTEP_SONAME(avcodec, LIBAVCODEC_VERSION_MAJOR);
  const char* avformat = FIXSTEP_SONAME(avformat, LIBAVFORMAT_VERSION_MAJOR);
  const char* avfilter = FIXSTEP_SONAME(avfilter, LIBAVFILTER_VERSION_MAJOR);
  const char* swscale = FIXSTEP_SONAME(swscale, LIBSWSCALE_VERSION_MAJOR);
};
#undef FIXSTEP_SONAME

// The loaded table, or why it could not be loaded (the first failure). The libraries stay
// loaded until the process ends (never dlclose'd: frames and codecs may outlive any owner here).
struct Loaded {
  FfmpegFunctions functions;
  std::string error;
};

void* open_library(const char* soname, std::string& error) {
  void* handle = dlopen(soname, RTLD_NOW | RTLD_LOCAL);
  if (!handle && error.empty()) {
    const char* why = dlerror();
    error = fmt::format("video needs FFmpeg's {}, which could not be loaded: {}", soname,
                        why ? why : "unknown reason");
  }
  return handle;
}

template <class Function>
void find(void* library, const char* soname, const char* name, Function& to, std::string& error) {
  if (!library) return;  // its dlopen failed: error says so
  void* address = dlsym(library, name);
  if (!address && error.empty()) {
    error = fmt::format("video needs {} from FFmpeg's {}, which lacks it", name, soname);
  }
  to = reinterpret_cast<Function>(address);  // dlsym's documented use for functions (POSIX)
}

Loaded load() {
  constexpr Sonames soname;
  Loaded l;
  const struct {
    void *avutil, *avcodec, *avformat, *avfilter, *swscale;
  } library{open_library(soname.avutil, l.error), open_library(soname.avcodec, l.error),
            open_library(soname.avformat, l.error), open_library(soname.avfilter, l.error),
            open_library(soname.swscale, l.error)};
#define FIXSTEP_FFMPEG_FIND(lib, function) \
  find(library.lib, soname.lib, #function, l.functions.function, l.error);
  FIXSTEP_FFMPEG_FUNCTIONS(FIXSTEP_FFMPEG_FIND)
#undef FIXSTEP_FFMPEG_FIND
  return l;
}

}  // namespace

const FfmpegFunctions& ffmpeg() {
  static const Loaded loaded = load();  // once, thread-safe (C++11 static initialisation)
  if (!loaded.error.empty()) throw CaptureError(loaded.error);
  return loaded.functions;
}

}  // namespace fixstep::av
