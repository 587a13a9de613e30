// Loading libOSMesa on first use: its own functions and the GL ones (osmesa_library.hpp).
#include "osmesa_library.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <string>

#include "fixstep/render/render.hpp"

namespace fixstep::gl {
namespace {

// Both tables, or why they could not be loaded (the first failure).
struct Loaded {
  OsmesaFunctions osmesa;
  Functions gl;
  std::string error;
};

template <class Function>
void find(void* library, const char* name, Function& to, std::string& error) {
  if (!library) return;  // its dlopen failed: error says so
  void* address = dlsym(library, name);
  if (!address && error.empty()) {
    error = fmt::format("render: {} lacks {}, which rendering needs", osmesa_soname, name);
  }
  to = reinterpret_cast<Function>(address);  // dlsym's documented use for functions (POSIX)
}

Loaded load() {
  Loaded l;
  // RTLD_LOCAL: its gl* symbols stay out of the global scope (see gl_api.hpp).
  void* library = dlopen(osmesa_soname, RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char* why = dlerror();
    l.error = fmt::format(
        "render: rendering needs OSMesa ({}, Debian's libosmesa6), which could "
        "not be loaded: {}",
        osmesa_soname, why ? why : "unknown reason");
  }
#define FIXSTEP_OSMESA_FIND(function) find(library, #function, l.osmesa.function, l.error);
  FIXSTEP_OSMESA_FUNCTIONS(FIXSTEP_OSMESA_FIND)
#undef FIXSTEP_OSMESA_FIND
#define FIXSTEP_GL_FIND(function) find(library, #function, l.gl.function, l.error);
  FIXSTEP_GL_FUNCTIONS(FIXSTEP_GL_FIND)
#undef FIXSTEP_GL_FIND
  return l;
}

const Loaded& loaded() {
  static const Loaded once = load();  // once, thread-safe (C++11 static initialisation)
  if (!once.error.empty()) throw RenderError(once.error);
  return once;
}

}  // namespace

const OsmesaFunctions& osmesa() {
  return loaded().osmesa;
}

const Functions& api() {
  return loaded().gl;
}

}  // namespace fixstep::gl
