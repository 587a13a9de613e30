# Install rules and the fixstep package: headers, the component libraries, an exported target
# set fixstep::<component>, fixstepConfig.cmake + fixstepConfigVersion.cmake for find_package
# and one pkg-config file per component (fixstep-core.pc, ...).
include(CMakePackageConfigHelpers)

set(FIXSTEP_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/fixstep)

foreach(component IN LISTS FIXSTEP_COMPONENTS)
  install(TARGETS fixstep_${component} EXPORT fixstep-${component}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT fixstep_development
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT fixstep_runtime)
  if(IS_DIRECTORY ${PROJECT_SOURCE_DIR}/engine/${component}/include)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/${component}/include/
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT fixstep_development)
  endif()
  install(EXPORT fixstep-${component} NAMESPACE fixstep::
          FILE fixstep-${component}-targets.cmake DESTINATION ${FIXSTEP_CMAKE_DIR}
          COMPONENT fixstep_development)
endforeach()

# The app component brings the window when it was built with one.
set(FIXSTEP_APP_NEEDS "scene io core render capture")
if(TARGET fixstep_window)
  string(APPEND FIXSTEP_APP_NEEDS " window")
endif()
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/fixstepConfig.cmake.in
  ${PROJECT_BINARY_DIR}/fixstepConfig.cmake INSTALL_DESTINATION ${FIXSTEP_CMAKE_DIR})
# 0.x: a minor version may break the API, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/fixstepConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/fixstepConfig.cmake
              ${PROJECT_BINARY_DIR}/fixstepConfigVersion.cmake
        DESTINATION ${FIXSTEP_CMAKE_DIR} COMPONENT fixstep_development)

# pkg-config: what each component's static library needs at link time.
set(FIXSTEP_PC_core_REQUIRES "")
set(FIXSTEP_PC_core_LIBS "-pthread")
set(FIXSTEP_PC_core_CFLAGS "-std=c++20 -ffp-contract=off")
set(FIXSTEP_PC_io_REQUIRES "fixstep-core fmt")
set(FIXSTEP_PC_scene_REQUIRES "fixstep-io fixstep-core tomlplusplus fmt")
# render loads libOSMesa.so.8 when it creates its first context.
set(FIXSTEP_PC_render_REQUIRES "fixstep-core fmt")
set(FIXSTEP_PC_render_LIBS "-ldl")
# capture loads FFmpeg's shared libraries (libavcodec.so.59, ...) when it writes a video.
set(FIXSTEP_PC_capture_REQUIRES "fixstep-io fixstep-core fmt libdeflate")
set(FIXSTEP_PC_capture_LIBS "-pthread -ldl")
set(FIXSTEP_PC_window_REQUIRES "fixstep-render sdl2 fmt")
set(FIXSTEP_PC_app_REQUIRES "fixstep-scene fixstep-capture fixstep-render fmt")
if(TARGET fixstep_window)
  string(APPEND FIXSTEP_PC_app_REQUIRES " fixstep-window")
endif()
# net links ENet (libenet); net_app is a game's --host / --join (app and net).
set(FIXSTEP_PC_net_REQUIRES "fixstep-io fixstep-core libenet fmt")
set(FIXSTEP_PC_net_app_REQUIRES "fixstep-net fixstep-app fmt")
foreach(component IN LISTS FIXSTEP_COMPONENTS)
  set(FIXSTEP_PC_COMPONENT ${component})
  set(FIXSTEP_PC_REQUIRES ${FIXSTEP_PC_${component}_REQUIRES})
  set(FIXSTEP_PC_LIBS ${FIXSTEP_PC_${component}_LIBS})
  set(FIXSTEP_PC_CFLAGS ${FIXSTEP_PC_${component}_CFLAGS})
  configure_file(${CMAKE_CURRENT_LIST_DIR}/fixstep.pc.in
                 ${PROJECT_BINARY_DIR}/pkgconfig/fixstep-${component}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/pkgconfig/fixstep-${component}.pc
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT fixstep_development)
endforeach()
