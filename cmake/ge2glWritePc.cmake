# SPDX-License-Identifier: MIT
# Runs inside `cmake --install` (cmake/ge2glInstall.cmake): writes ge2gl.pc for the prefix being
# installed to and installs it into <libdir>/pkgconfig. Inputs: GE2GL_PC_TEMPLATE, GE2GL_PC_WORK_DIR,
# GE2GL_PC_INSTALL_LIBDIR, GE2GL_PC_INSTALL_INCLUDEDIR (relative to the prefix or absolute),
# GE2GL_PC_VERSION, GE2GL_PC_DESCRIPTION; CMAKE_INSTALL_PREFIX is the install-time prefix (without
# DESTDIR, which file(INSTALL) adds).
if(IS_ABSOLUTE "${GE2GL_PC_INSTALL_LIBDIR}")
  set(GE2GL_PC_LIBDIR "${GE2GL_PC_INSTALL_LIBDIR}")
  set(pc_dest "${GE2GL_PC_INSTALL_LIBDIR}/pkgconfig")
else()
  set(GE2GL_PC_LIBDIR "\${exec_prefix}/${GE2GL_PC_INSTALL_LIBDIR}")
  set(pc_dest "${CMAKE_INSTALL_PREFIX}/${GE2GL_PC_INSTALL_LIBDIR}/pkgconfig")
endif()
if(IS_ABSOLUTE "${GE2GL_PC_INSTALL_INCLUDEDIR}")
  set(GE2GL_PC_INCLUDEDIR "${GE2GL_PC_INSTALL_INCLUDEDIR}")
else()
  set(GE2GL_PC_INCLUDEDIR "\${prefix}/${GE2GL_PC_INSTALL_INCLUDEDIR}")
endif()
configure_file("${GE2GL_PC_TEMPLATE}" "${GE2GL_PC_WORK_DIR}/ge2gl.pc" @ONLY)
file(INSTALL DESTINATION "${pc_dest}" TYPE FILE FILES "${GE2GL_PC_WORK_DIR}/ge2gl.pc")
