# SPDX-License-Identifier: MIT
# Install rules for libge2gl (included from the top-level CMakeLists.txt when GE2GL_INSTALL is on):
#   lib/libge2gl.so.0.1.0, libge2gl.so.0 (runtime) and the libge2gl.so namelink (development)
#   include/ge2gl/ge2gl.h, ge2gl.hpp
#   lib/cmake/ge2gl/ge2glConfig.cmake, ge2glConfigVersion.cmake, ge2glTargets*.cmake
#     (find_package(ge2gl) → imported target ge2gl::ge2gl)
#   lib/pkgconfig/ge2gl.pc
# Components: ge2gl_runtime (the versioned .so) and ge2gl_development (everything else), for
# cmake --install --component. scripts/check_install.sh installs into a temporary prefix and builds
# tests/install_consumer against it.
include(CMakePackageConfigHelpers)

set(GE2GL_CMAKE_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ge2gl)

install(TARGETS ge2gl_api EXPORT ge2glTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT ge2gl_runtime NAMELINK_COMPONENT ge2gl_development
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT ge2gl_development
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT ge2gl_runtime)
install(FILES ${PROJECT_SOURCE_DIR}/include/ge2gl/ge2gl.h ${PROJECT_SOURCE_DIR}/include/ge2gl/ge2gl.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ge2gl COMPONENT ge2gl_development)

# The exported target carries only the include directory: ge2gl_api links its static GE libraries
# PRIVATE, and a shared library's private dependencies are not part of its interface, so the
# package needs neither them nor their find_package() calls (scripts/check_install.sh checks that
# ge2glTargets.cmake names no other target).
install(EXPORT ge2glTargets NAMESPACE ge2gl:: FILE ge2glTargets.cmake
  DESTINATION ${GE2GL_CMAKE_PACKAGE_DIR} COMPONENT ge2gl_development)

# 0 or 1, for ge2gl_HAS_GL in the package.
if(GE2GL_BUILD_GL)
  set(GE2GL_PACKAGE_HAS_GL 1)
else()
  set(GE2GL_PACKAGE_HAS_GL 0)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ge2glConfig.cmake.in
  ${PROJECT_BINARY_DIR}/cmake-package/ge2glConfig.cmake
  INSTALL_DESTINATION ${GE2GL_CMAKE_PACKAGE_DIR})
# 0.x releases keep SOVERSION 0 and only add to the C ABI (docs/install.md), so any 0.y satisfies a
# request for 0.x with x <= y.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake-package/ge2glConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake-package/ge2glConfig.cmake
              ${PROJECT_BINARY_DIR}/cmake-package/ge2glConfigVersion.cmake
  DESTINATION ${GE2GL_CMAKE_PACKAGE_DIR} COMPONENT ge2gl_development)

# ge2gl.pc is written when installing, not when configuring: `cmake --install --prefix P` changes
# the prefix after configuration, and the file must name the prefix it is installed under.
# cmake/ge2glWritePc.cmake fills cmake/ge2gl.pc.in with it and installs the result.
install(CODE "
set(GE2GL_PC_TEMPLATE [==[${PROJECT_SOURCE_DIR}/cmake/ge2gl.pc.in]==])
set(GE2GL_PC_WORK_DIR [==[${PROJECT_BINARY_DIR}/pkgconfig]==])
set(GE2GL_PC_INSTALL_LIBDIR [==[${CMAKE_INSTALL_LIBDIR}]==])
set(GE2GL_PC_INSTALL_INCLUDEDIR [==[${CMAKE_INSTALL_INCLUDEDIR}]==])
set(GE2GL_PC_VERSION [==[${PROJECT_VERSION}]==])
set(GE2GL_PC_DESCRIPTION [==[${PROJECT_DESCRIPTION}]==])
include([==[${PROJECT_SOURCE_DIR}/cmake/ge2glWritePc.cmake]==])
" COMPONENT ge2gl_development)
