# The installed package: `cmake --install BUILD --prefix P` puts
#   P/include/masav/*.h         the public API (documented: docs/api, docs/library.md)
#   P/include/masav/detail/     the engine headers the public ones include (not an API of their own)
#   P/lib/libmasav*.a           the libraries, every backend that was built, the embedded shaders
#   P/lib/cmake/masav/          masavConfig.cmake, masavConfigVersion.cmake, masavTargets.cmake
#   P/lib/pkgconfig/masav.pc    the same for pkg-config
# so that a consumer's `find_package(masav 0.2 CONFIG REQUIRED)` and
# `target_link_libraries(app PRIVATE masav::masav)` build against it. A backend that was not built
# or has no device is reported at run time (masav::backend_report), never a link error.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(masav_install_targets masav_api masav_registry masav_core masav_kernels masav_cpu masav_grid
    masav_util masav_io masav_scene masav_verify masav_volume masav_points masav_sph masav_atom)
if(MASAV_WITH_VULKAN)
  list(APPEND masav_install_targets masav_render masav_vulkan masav_vkdevice masav_shaders)
endif()
if(MASAV_WITH_CUDA)
  list(APPEND masav_install_targets masav_cuda)
endif()
install(TARGETS ${masav_install_targets} EXPORT masavTargets COMPONENT dev
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})

install(DIRECTORY include/masav/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/masav COMPONENT dev
        FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/include/masav/version.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/masav COMPONENT dev)
foreach(dir engine registry)
  install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/masav/detail/${dir}
          COMPONENT dev FILES_MATCHING PATTERN "*.h" PATTERN "*.inc")
endforeach()

set(masav_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/masav)
install(EXPORT masavTargets NAMESPACE masav:: DESTINATION ${masav_cmake_dir} COMPONENT dev)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/masavConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/masavConfig.cmake
                              INSTALL_DESTINATION ${masav_cmake_dir})
# 0.x: a minor version may change the API, so 0.2 is compatible with 0.2.* only.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/masavConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/masavConfig.cmake ${PROJECT_BINARY_DIR}/masavConfigVersion.cmake
        DESTINATION ${masav_cmake_dir} COMPONENT dev)

# pkg-config: the libraries in link order (dependants first), then what they need.
set(masav_pc_libs "")
foreach(t IN ITEMS masav_api masav_registry masav_atom masav_sph masav_points masav_volume
        masav_verify masav_scene masav_io masav_cpu masav_render masav_vulkan masav_cuda masav_vkdevice
        masav_shaders masav_grid masav_util masav_kernels masav_core)
  if(t IN_LIST masav_install_targets)
    get_target_property(out ${t} OUTPUT_NAME)
    if(NOT out)
      set(out ${t})
    endif()
    string(APPEND masav_pc_libs " -l${out}")
  endif()
endforeach()
set(masav_pc_private "-ltomlplusplus -lfmt -ldl -lpthread")
if(MASAV_WITH_VULKAN)
  string(APPEND masav_pc_private " -limgui -lstb")  # the renderer's (masav::SceneRenderer)
endif()
if(MASAV_WITH_CUDA)
  get_target_property(cudart CUDA::cudart_static IMPORTED_LOCATION)
  get_filename_component(cudart_dir "${cudart}" DIRECTORY)
  string(APPEND masav_pc_private " -L${cudart_dir} -lcudart_static -lrt")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/masav.pc.in ${PROJECT_BINARY_DIR}/masav.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/masav.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT dev)
