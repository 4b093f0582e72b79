# Install-side packaging of libwefm: the CMake package (find_package(wefm) -> wefm::wefm, with a
# version file) and the pkg-config file wefm.pc. Both are relocatable, so `cmake --install --prefix`
# into any directory gives a usable tree (tests/capi installs into the build tree and builds against it).
include(CMakePackageConfigHelpers)

set(WEFM_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/wefm CACHE STRING
    "Where the CMake package files of wefm are installed (relative to the prefix)")

install(EXPORT wefmTargets NAMESPACE wefm:: FILE wefmTargets.cmake DESTINATION ${WEFM_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/wefmConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/wefmConfig.cmake INSTALL_DESTINATION ${WEFM_INSTALL_CMAKEDIR})
# SONAME is libwefm.so.MAJOR, so any library of the same major version is ABI compatible.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/wefmConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/wefmConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/wefmConfigVersion.cmake
        DESTINATION ${WEFM_INSTALL_CMAKEDIR})

# pkg-config: the prefix is derived from the .pc file's own location (${pcfiledir}) instead of the
# configure-time CMAKE_INSTALL_PREFIX, which `cmake --install --prefix` may override.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(WEFM_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  set(WEFM_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
else()
  file(RELATIVE_PATH _wefm_pc_up "/p/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/p")
  string(REGEX REPLACE "/$" "" _wefm_pc_up "${_wefm_pc_up}")
  set(WEFM_PC_PREFIX "\${pcfiledir}/${_wefm_pc_up}")
  set(WEFM_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
endif()
if(IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(WEFM_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
else()
  set(WEFM_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/wefm.pc.in ${CMAKE_CURRENT_BINARY_DIR}/wefm.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/wefm.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
