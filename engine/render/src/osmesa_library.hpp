// OSMesa's own functions as the native gl::Context calls them, loaded with the GL table
// (gl_api.hpp's api()) from libOSMesa the first time a context is created. Internal to
// fixstep::render (not installed); native builds only.
#pragma once

#include "gl_api.hpp"

namespace fixstep::gl {

// X(function): every OSMesa function gl_context_osmesa.cpp calls.
#define FIXSTEP_OSMESA_FUNCTIONS(X) \
  X(OSMesaCreateContextAttribs)     \
  X(OSMesaDestroyContext)           \
  X(OSMesaGetCurrentContext)        \
  X(OSMesaMakeCurrent)              \
  X(OSMesaPixelStore)

/// One pointer per function of FIXSTEP_OSMESA_FUNCTIONS, with the header's exact type.
struct OsmesaFunctions {
// (`function` names a declaration here: it cannot be parenthesised.)
// NOLINTNEXTLINE(bugprone-macro-parentheses)
#define FIXSTEP_OSMESA_MEMBER(function) decltype(&::function) function = nullptr;
  FIXSTEP_OSMESA_FUNCTIONS(FIXSTEP_OSMESA_MEMBER)
#undef FIXSTEP_OSMESA_MEMBER
};

/// The soname loaded: Mesa's OSMesa, ABI 8 (Debian 12's libosmesa6, Mesa 22).
inline constexpr const char* osmesa_soname = "libOSMesa.so.8";

/// OSMesa's functions, loaded (with api()'s GL functions) from osmesa_soname on the first call
/// of either, from any thread, once per process; the library stays loaded until the process
/// ends. Throws RenderError naming the library and dlopen's or dlsym's reason when it cannot be
/// loaded or lacks a function (every later call throws the same).
const OsmesaFunctions& osmesa();

}  // namespace fixstep::gl
