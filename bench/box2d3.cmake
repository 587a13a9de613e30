# Box2D v3.1.1 (C, MIT), a peer of bench_discs only, never part of the engine: built from its
# source archive by its own CMakeLists (ExternalProject, offline: the URL is the local file,
# its sha256 checked), Release (-O3 -DNDEBUG, CMake's default for C), its default SIMD (SSE2
# on x86-64), no samples, tests, benchmarks or validation. Where the archive is absent (a
# user's checkout or CI's clean clone has no ../shared), the peer is skipped with a message and
# bench_discs runs the other engines.
#
# Box2D 2.4 (Debian, C++) and v3 share header paths (box2d/box2d.h) and type names (b2Vec2,
# b2BodyDef...): the v3 code lives in its own translation units (discs_box2d3*.cpp), an OBJECT
# library whose include path is v3's and which does not see 2.4's target. v3's functions have C
# linkage (b2CreateWorld...), 2.4's are C++-mangled; ctest bench_discs_box2d3_symbols checks that
# the two libraries define no common symbol (the v3 archive linked into the executable would
# otherwise interpose on the 2.4 shared library's).
set(FIXSTEP_BOX2D3_ARCHIVE "${PROJECT_SOURCE_DIR}/../shared/peers/box2d-3.1.1.tar.gz"
    CACHE FILEPATH "Box2D v3.1.1 source archive (git archive of tag v3.1.1) for bench_discs")
set(FIXSTEP_BOX2D3_SHA256 354794158917d44bd6a8eb7d5565177a78bfd3117a227a5438ad6ec1b5edc276)

if(NOT EXISTS "${FIXSTEP_BOX2D3_ARCHIVE}")
  message(STATUS "Box2D v3 peer skipped: ${FIXSTEP_BOX2D3_ARCHIVE} not found")
  set(FIXSTEP_HAVE_BOX2D3 OFF)
  return()
endif()
# Checked here too (ExternalProject checks it again when it unpacks), so that another archive
# stops the configure with its path rather than the build.
file(SHA256 "${FIXSTEP_BOX2D3_ARCHIVE}" box2d3_sha256)
if(NOT box2d3_sha256 STREQUAL FIXSTEP_BOX2D3_SHA256)
  message(FATAL_ERROR "Box2D v3 peer: ${FIXSTEP_BOX2D3_ARCHIVE} has sha256 ${box2d3_sha256}, not "
                      "${FIXSTEP_BOX2D3_SHA256} (Box2D v3.1.1's archive): set FIXSTEP_BOX2D3_ARCHIVE "
                      "to that archive, or to a path that does not exist to skip the peer")
endif()
set(FIXSTEP_HAVE_BOX2D3 ON)
message(STATUS "Box2D v3 peer: built from ${FIXSTEP_BOX2D3_ARCHIVE}")

include(ExternalProject)
set(box2d3_prefix ${CMAKE_CURRENT_BINARY_DIR}/box2d3)
set(box2d3_source ${box2d3_prefix}/src/box2d3)
set(box2d3_binary ${box2d3_prefix}/src/box2d3-build)
set(box2d3_library ${box2d3_binary}/src/${CMAKE_STATIC_LIBRARY_PREFIX}box2d${CMAKE_STATIC_LIBRARY_SUFFIX})
set(box2d3_launcher)
if(CMAKE_CXX_COMPILER_LAUNCHER)
  set(box2d3_launcher -DCMAKE_C_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER})
endif()
ExternalProject_Add(box2d3
  PREFIX ${box2d3_prefix}
  URL ${FIXSTEP_BOX2D3_ARCHIVE}
  URL_HASH SHA256=${FIXSTEP_BOX2D3_SHA256}
  DOWNLOAD_EXTRACT_TIMESTAMP ON
  CMAKE_ARGS -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=OFF -DBOX2D_SAMPLES=OFF
             -DBOX2D_UNIT_TESTS=OFF -DBOX2D_BENCHMARKS=OFF -DBOX2D_DOCS=OFF -DBOX2D_VALIDATE=OFF
             -DCMAKE_POSITION_INDEPENDENT_CODE=ON ${box2d3_launcher}
  INSTALL_COMMAND ""
  BUILD_BYPRODUCTS ${box2d3_library}
  UPDATE_DISCONNECTED ON)
# The include directory exists only once the archive is unpacked (at build time).
file(MAKE_DIRECTORY ${box2d3_source}/include)
add_library(fixstep_box2d3 STATIC IMPORTED GLOBAL)
set_target_properties(fixstep_box2d3 PROPERTIES
  IMPORTED_LOCATION ${box2d3_library}
  INTERFACE_INCLUDE_DIRECTORIES ${box2d3_source}/include)
add_dependencies(fixstep_box2d3 box2d3)
# Box2D 2.4's library (an imported target of this directory only), for the symbol check
# (tests/CMakeLists.txt: bench_discs_box2d3_symbols).
get_target_property(box2d24_library box2d::box2d LOCATION)
set_property(GLOBAL PROPERTY FIXSTEP_BOX2D24_LIBRARY ${box2d24_library})

find_package(Threads REQUIRED)
# discs_box2d3.cpp (the stepper) and discs_box2d3_tasks.cpp (its task system): v3's headers
# only; discs.hpp needs fixstep's types.
add_library(discs_box2d3 OBJECT discs_box2d3.cpp discs_box2d3_tasks.cpp)
target_link_libraries(discs_box2d3 PRIVATE fixstep::core fmt::fmt fixstep_options fixstep_box2d3
                      Threads::Threads)
# The object library's private dependencies reach bench_discs' link line only (LINK_ONLY): v3's
# include path stays out of the translation units that include Box2D 2.4's box2d/box2d.h.
target_link_libraries(bench_discs PRIVATE discs_box2d3)
target_compile_definitions(bench_discs PRIVATE FIXSTEP_HAVE_BOX2D3=1)
