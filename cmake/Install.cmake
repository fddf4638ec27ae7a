# cmake --install: the product library, its public headers, the `phongcl` command line, the kernels
# the library embeds (for reading), and a CMake package: find_package(phongcl) gives phongcl::phongcl.
# Nothing of the lab is installed.
include(CMakePackageConfigHelpers)

install(TARGETS phongcl_library EXPORT phongclTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS phongcl RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# The public headers and the room headers they include, beside them with the rooms' layout (they
# include each other by relative paths, so a consumer needs only <prefix>/include).
install(DIRECTORY include/phongcl DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(header common/error.h exr/pixel_window.h scene/scene.h gbuffer/gbuffer.h image/image.h
               color/color_config.h color/display.h color/color_conversion.h
               shading/precision.h shading/shade_stats.h shading/shadow_settings.h cl/device_info.h cl/cache_outcome.h
               composite/relight_over.h composite/composite.h composite/group_edits.h composite/group_fit.h
               composite/render_passes.h)
  get_filename_component(room ${header} DIRECTORY)
  install(FILES host/${header} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/phongcl/${room})
endforeach()
install(FILES ${PHONGCL_KERNEL_FILES} DESTINATION ${CMAKE_INSTALL_DATADIR}/phongcl/kernels)

set(PHONGCL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/phongcl)
install(EXPORT phongclTargets NAMESPACE phongcl:: DESTINATION ${PHONGCL_CMAKE_DIR})
configure_package_config_file(cmake/phongclConfig.cmake.in ${PROJECT_BINARY_DIR}/phongclConfig.cmake
                              INSTALL_DESTINATION ${PHONGCL_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/phongclConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/phongclConfig.cmake ${PROJECT_BINARY_DIR}/phongclConfigVersion.cmake
        DESTINATION ${PHONGCL_CMAKE_DIR})
