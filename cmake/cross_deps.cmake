# fmt, toml++ and Eigen for cross builds (aarch64, wasm32), header-only, from the build machine's
# Debian packages. Their CMake package files sit under /usr/lib/x86_64-linux-gnu and name x86-64
# libraries, which a cross build can neither find (CMAKE_FIND_ROOT_PATH) nor link; the headers
# themselves are architecture-independent. They are reached through a directory of symbolic
# links, never -I/usr/include, which would put the build machine's glibc headers in front of
# the target's. Defines the targets the native build gets from find_package:
# fmt::fmt-header-only, tomlplusplus::tomlplusplus (header-only here) and Eigen3::Eigen.
set(fixstep_cross_include ${CMAKE_BINARY_DIR}/cross-include)
file(MAKE_DIRECTORY ${fixstep_cross_include})
foreach(dir fmt toml++ eigen3)
  if(NOT EXISTS /usr/include/${dir})
    message(FATAL_ERROR "cross build: /usr/include/${dir} is missing (bash .ci/install-deps)")
  endif()
  file(CREATE_LINK /usr/include/${dir} ${fixstep_cross_include}/${dir} SYMBOLIC)
endforeach()

# Imported targets: their include directories are system ones, so -Werror ignores their warnings.
add_library(fmt::fmt-header-only INTERFACE IMPORTED)
set_target_properties(fmt::fmt-header-only PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES ${fixstep_cross_include}
  INTERFACE_COMPILE_DEFINITIONS FMT_HEADER_ONLY=1)
add_library(tomlplusplus::tomlplusplus INTERFACE IMPORTED)
set_target_properties(tomlplusplus::tomlplusplus PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES ${fixstep_cross_include}
  INTERFACE_COMPILE_DEFINITIONS TOML_HEADER_ONLY=1)
add_library(Eigen3::Eigen INTERFACE IMPORTED)
set_target_properties(Eigen3::Eigen PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES ${fixstep_cross_include}/eigen3)
