# `make install` / `cmake --install`: what a technique built in its own repository needs, as a
# plugin (docs/adding-a-technique.md, "As a plugin"). Installed: the gibench executable, the
# headers of the technique contract and of what it hands a technique (techniques/technique.h,
# techniques/common/*.h, harness/gl/*.h, harness/base/*.h, scenes/scene.h, glad's gl.h) under
# include/gibench/ at their paths from the repository root, a CMake package (find_package(gibench):
# gibench::technique, gibench::gibench, gibench_add_plugin) and a pkg-config file (gibench.pc). No
# library: a plugin is linked against nothing and its undefined symbols (gib_*, glad's GL pointers)
# are resolved by dlopen in the gibench executable, which exports them; a second, static copy of
# glad in a plugin would hold GL pointers nobody loaded.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set_target_properties(gibench PROPERTIES ENABLE_EXPORTS ON)

file(STRINGS ${CMAKE_SOURCE_DIR}/techniques/technique.h GIB_CONTRACT_LINE
     REGEX "^#define GIB_CONTRACT_VERSION [0-9]+")
string(REGEX REPLACE ".* ([0-9]+)$" "\\1" GIB_CONTRACT_VERSION "${GIB_CONTRACT_LINE}")

set(GIB_INCLUDE_INSTALL ${CMAKE_INSTALL_INCLUDEDIR}/gibench)
install(TARGETS gibench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES techniques/technique.h DESTINATION ${GIB_INCLUDE_INSTALL}/techniques)
install(DIRECTORY techniques/common/ DESTINATION ${GIB_INCLUDE_INSTALL}/techniques/common
        FILES_MATCHING PATTERN "*.h")
install(DIRECTORY harness/gl/ DESTINATION ${GIB_INCLUDE_INSTALL}/harness/gl
        FILES_MATCHING PATTERN "*.h")
install(DIRECTORY harness/base/ DESTINATION ${GIB_INCLUDE_INSTALL}/harness/base
        FILES_MATCHING PATTERN "*.h")
install(FILES scenes/scene.h scenes/light_eval.h DESTINATION ${GIB_INCLUDE_INSTALL}/scenes)
install(DIRECTORY ${GLAD_DIR}/include/ DESTINATION ${GIB_INCLUDE_INSTALL})

set(GIB_CMAKE_INSTALL ${CMAKE_INSTALL_LIBDIR}/cmake/gibench)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/gibenchConfig.cmake.in
  ${CMAKE_BINARY_DIR}/package/gibenchConfig.cmake
  INSTALL_DESTINATION ${GIB_CMAKE_INSTALL}
  PATH_VARS GIB_INCLUDE_INSTALL CMAKE_INSTALL_BINDIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/gibenchConfigVersion.cmake
  VERSION ${GIB_CONTRACT_VERSION} COMPATIBILITY ExactVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/gibenchConfig.cmake
              ${CMAKE_BINARY_DIR}/package/gibenchConfigVersion.cmake
        DESTINATION ${GIB_CMAKE_INSTALL})

# pkg-config: relocatable (prefix from the file's own place), so `cmake --install --prefix` works.
set(GIB_PC_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
file(RELATIVE_PATH GIB_PC_TO_PREFIX /root/${GIB_PC_DIR} /root)
configure_file(${CMAKE_SOURCE_DIR}/cmake/gibench.pc.in ${CMAKE_BINARY_DIR}/package/gibench.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/package/gibench.pc DESTINATION ${GIB_PC_DIR})
