# Box2D v3.1.1 and v3.2 (C, MIT), peers of bench_discs, bench_boxes and bench_joints only, never
# part of the engine: each built from its source archive by its own CMakeLists (ExternalProject,
# offline: the URL is the local file, its sha256 checked), Release (-O3 -DNDEBUG, CMake's default
# for C), its default SIMD (SSE2 on x86-64), no samples, tests, benchmarks or validation. Where an
# archive is absent (a user's checkout or CI's clean clone has no ../shared), that peer is skipped
# with a message and the benchmarks run the other engines.
#
# Box2D 2.4 (Debian, C++) and v3 share header paths (box2d/box2d.h) and type names (b2Vec2,
# b2BodyDef...): the v3 code lives in its own translation units (discs_box2d3.cpp, boxes_box2d3.cpp,
# joints_box2d3.cpp), an OBJECT library per release whose include path is that release's and which
# does not see 2.4's target. v3's functions have C linkage (b2CreateWorld...), 2.4's are
# C++-mangled. v3.1.1 and v3.2 define the same C names: v3.2's archive has every global symbol it
# defines renamed with the prefix b232_ (box2d3_prefix.sh: objcopy --redefine-syms over the archive,
# and a header of #defines, force-included before v3.2's headers, that renames the same names where
# the stepper calls them), so both releases live in one executable. ctest bench_discs_box2d3_symbols
# and bench_discs_box2d32_symbols check that no two of the three libraries define or need a common
# symbol (an archive's definition would otherwise interpose on the other's). Sources shared by both
# releases keep v3's types out of templates and inline functions with external linkage (their
# layouts differ between releases).
set(FIXSTEP_BOX2D3_ARCHIVE "${PROJECT_SOURCE_DIR}/../shared/peers/box2d-3.1.1.tar.gz"
    CACHE FILEPATH "Box2D v3.1.1 source archive (git archive of tag v3.1.1) for bench_discs")
set(FIXSTEP_BOX2D3_SHA256 354794158917d44bd6a8eb7d5565177a78bfd3117a227a5438ad6ec1b5edc276)
# Box2D's main branch of 2026-08-20 (commit 617d32ab, "Tunable ccd"), which reports 3.2.0.
set(FIXSTEP_BOX2D32_ARCHIVE "${PROJECT_SOURCE_DIR}/../shared/peers/box2d-main-617d32a.tar.gz"
    CACHE FILEPATH "Box2D v3.2 source archive (git archive of main at 617d32a) for bench_discs")
set(FIXSTEP_BOX2D32_SHA256 10efafeeafd4934c8068599962cf5f9711d8f8624f2c57533092677e9fed860e)

include(ExternalProject)
find_package(Threads REQUIRED)
# Box2D 2.4's library (an imported target of this directory only), for the symbol checks
# (tests/CMakeLists.txt: bench_discs_box2d3_symbols, bench_discs_box2d32_symbols).
get_target_property(box2d24_library box2d::box2d LOCATION)
set_property(GLOBAL PROPERTY FIXSTEP_BOX2D24_LIBRARY ${box2d24_library})

# fixstep_box2d_v3(NAME ARCHIVE SHA256 MINOR [PREFIX p]): the imported library fixstep_NAME
# and the object library discs_NAME (the disc and box steppers of that release, compiled with
# FIXSTEP_BOX2D3_MINOR = MINOR), linked into bench_discs and bench_boxes; sets FIXSTEP_HAVE_NAME.
function(fixstep_box2d_v3 name archive sha256 minor)
  cmake_parse_arguments(PARSE_ARGV 4 arg "" "PREFIX" "")
  if(NOT EXISTS "${archive}")
    message(STATUS "Box2D v3.${minor} peer skipped: ${archive} not found")
    set(FIXSTEP_HAVE_${name} OFF PARENT_SCOPE)
    return()
  endif()
  if(arg_PREFIX AND (NOT CMAKE_NM OR NOT CMAKE_OBJCOPY))
    message(STATUS "Box2D v3.${minor} peer skipped: no nm or objcopy to rename its symbols")
    set(FIXSTEP_HAVE_${name} OFF PARENT_SCOPE)
    return()
  endif()
  # Checked here too (ExternalProject checks it again when it unpacks), so that another archive
  # stops the configure with its path rather than the build.
  file(SHA256 "${archive}" actual)
  if(NOT actual STREQUAL sha256)
    message(FATAL_ERROR "Box2D v3.${minor} peer: ${archive} has sha256 ${actual}, not ${sha256}: "
                        "point the cache variable at that archive, or at a path that does not "
                        "exist to skip the peer")
  endif()
  set(FIXSTEP_HAVE_${name} ON PARENT_SCOPE)
  message(STATUS "Box2D v3.${minor} peer: built from ${archive}")

  set(prefix ${CMAKE_CURRENT_BINARY_DIR}/${name})
  set(source ${prefix}/src/${name})
  set(binary ${prefix}/src/${name}-build)
  set(library ${binary}/src/${CMAKE_STATIC_LIBRARY_PREFIX}box2d${CMAKE_STATIC_LIBRARY_SUFFIX})
  set(launcher)
  if(CMAKE_CXX_COMPILER_LAUNCHER)
    set(launcher -DCMAKE_C_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER})
  endif()
  set(linked ${library})
  if(arg_PREFIX)
    set(linked ${binary}/${CMAKE_STATIC_LIBRARY_PREFIX}${name}_prefixed${CMAKE_STATIC_LIBRARY_SUFFIX})
    set(rename_header ${binary}/${name}_prefix.h)
  endif()
  ExternalProject_Add(${name}
    PREFIX ${prefix}
    URL ${archive}
    URL_HASH SHA256=${sha256}
    DOWNLOAD_EXTRACT_TIMESTAMP ON
    CMAKE_ARGS -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=OFF -DBOX2D_SAMPLES=OFF
               -DBOX2D_UNIT_TESTS=OFF -DBOX2D_BENCHMARKS=OFF -DBOX2D_DOCS=OFF -DBOX2D_VALIDATE=OFF
               -DCMAKE_POSITION_INDEPENDENT_CODE=ON ${launcher}
    INSTALL_COMMAND ""
    BUILD_BYPRODUCTS ${library}
    UPDATE_DISCONNECTED ON)
  if(arg_PREFIX)
    ExternalProject_Add_Step(${name} prefix_symbols
      COMMAND bash ${PROJECT_SOURCE_DIR}/bench/box2d3_prefix.sh ${CMAKE_NM} ${CMAKE_OBJCOPY}
              ${library} ${linked} ${rename_header} ${arg_PREFIX}
      DEPENDEES build
      DEPENDS ${PROJECT_SOURCE_DIR}/bench/box2d3_prefix.sh
      BYPRODUCTS ${linked} ${rename_header}
      COMMENT "Box2D v3.${minor}: its global symbols prefixed with ${arg_PREFIX}")
  endif()
  # The include directory exists only once the archive is unpacked (at build time).
  file(MAKE_DIRECTORY ${source}/include)
  add_library(fixstep_${name} STATIC IMPORTED GLOBAL)
  set_target_properties(fixstep_${name} PROPERTIES
    IMPORTED_LOCATION ${linked}
    INTERFACE_INCLUDE_DIRECTORIES ${source}/include)
  add_dependencies(fixstep_${name} ${name})

  # The steppers (discs_box2d3.cpp, boxes_box2d3.cpp; v3.1's task system): v3's headers only;
  # discs.hpp and boxes.hpp need fixstep's types.
  set(sources discs_box2d3.cpp boxes_box2d3.cpp)
  if(minor EQUAL 1)
    list(APPEND sources discs_box2d3_tasks.cpp)  # v3.2 runs its own scheduler
  endif()
  add_library(discs_${name} OBJECT ${sources})
  target_link_libraries(discs_${name} PRIVATE fixstep::core fmt::fmt fixstep_options fixstep_${name}
                        Threads::Threads)
  target_compile_definitions(discs_${name} PRIVATE FIXSTEP_BOX2D3_MINOR=${minor})
  if(arg_PREFIX)
    target_compile_options(discs_${name} PRIVATE -include ${rename_header})
  endif()
  # The joint stepper (joints_box2d3.cpp), bench_joints only: with discs_NAME (its version(), and
  # v3.1's task system).
  add_library(joints_${name} OBJECT joints_box2d3.cpp)
  target_link_libraries(joints_${name} PRIVATE fixstep::core fmt::fmt fixstep_options
                        fixstep_${name} Threads::Threads)
  target_compile_definitions(joints_${name} PRIVATE FIXSTEP_BOX2D3_MINOR=${minor})
  if(arg_PREFIX)
    target_compile_options(joints_${name} PRIVATE -include ${rename_header})
  endif()
endfunction()

fixstep_box2d_v3(box2d3 "${FIXSTEP_BOX2D3_ARCHIVE}" ${FIXSTEP_BOX2D3_SHA256} 1)
fixstep_box2d_v3(box2d32 "${FIXSTEP_BOX2D32_ARCHIVE}" ${FIXSTEP_BOX2D32_SHA256} 2 PREFIX b232_)

# The object libraries' private dependencies reach the executables' link lines only (LINK_ONLY):
# v3's include paths stay out of the translation units that include Box2D 2.4's box2d/box2d.h.
foreach(exe bench_discs bench_boxes bench_joints)
  if(FIXSTEP_HAVE_box2d3)
    target_link_libraries(${exe} PRIVATE discs_box2d3)
    target_compile_definitions(${exe} PRIVATE FIXSTEP_HAVE_BOX2D3=1)
  endif()
  if(FIXSTEP_HAVE_box2d32)
    target_link_libraries(${exe} PRIVATE discs_box2d32)
    target_compile_definitions(${exe} PRIVATE FIXSTEP_HAVE_BOX2D32=1)
  endif()
endforeach()
if(FIXSTEP_HAVE_box2d3)
  target_link_libraries(bench_joints PRIVATE joints_box2d3)
endif()
if(FIXSTEP_HAVE_box2d32)
  target_link_libraries(bench_joints PRIVATE joints_box2d32)
endif()
