# SPDX-License-Identifier: MIT
# The API 1.2 example hosts (included from examples/CMakeLists.txt), strict C99 like minimal_host:
#   threaded_host  the GE on one thread, the game on another (pthreads): callbacks that wait on the
#                  game thread, config.hold_interrupts + ge2gl_interrupt_ack, peek-sync latency;
#   egl_host       GE2GL_BACKEND_GL_CURRENT on the host's own EGL surfaceless context (links libEGL
#                  only), its GL state checked around every ge2gl call, the frame texture presented
#                  into a PPM. Needs GE2GL_BUILD_GL (the EGL package found by the top-level file).
# tests/api_example_hosts.cpp (test_api) runs both and compares egl_host with the ge2gl CLI.
find_package(Threads REQUIRED)

set(_ge2gl_host_c_flags -pedantic -Werror -Wall -Wextra)

add_executable(threaded_host ${CMAKE_CURRENT_LIST_DIR}/threaded_host.c)
target_link_libraries(threaded_host PRIVATE ge2gl_api Threads::Threads)
set_target_properties(threaded_host PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
target_compile_options(threaded_host PRIVATE ${_ge2gl_host_c_flags})

if(GE2GL_BUILD_GL AND TARGET PkgConfig::EGL)
  add_executable(egl_host ${CMAKE_CURRENT_LIST_DIR}/egl_host.c)
  # libEGL only: every GL function comes through eglGetProcAddress (no libGL / libOpenGL).
  target_link_libraries(egl_host PRIVATE ge2gl_api PkgConfig::EGL)
  set_target_properties(egl_host PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
  target_compile_options(egl_host PRIVATE ${_ge2gl_host_c_flags})
endif()

if(GE2GL_BUILD_TESTS)
  add_test(NAME example_threaded_host COMMAND threaded_host --lists 1000)
  add_test(NAME example_threaded_host_hold COMMAND threaded_host --lists 1000 --hold)
  # The hosts' own watchdog ends a deadlock with status 3 after 120 s; this is the backstop.
  set_tests_properties(example_threaded_host example_threaded_host_hold PROPERTIES TIMEOUT 300)
  if(TARGET egl_host)
    add_test(NAME example_egl_host
             COMMAND egl_host ${PROJECT_SOURCE_DIR}/dumps/render_to_texture.ppdmp
                     ${CMAKE_CURRENT_BINARY_DIR}/egl_host_render_to_texture.ppm)
    # 77: no EGL surfaceless platform / GL 3.3 core context on this machine.
    set_tests_properties(example_egl_host PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
    if(GE2GL_SANITIZED)
      # Mesa's EGL keeps process-lifetime allocations that LeakSanitizer cannot attribute in the
      # host's own set-up; the library's leak checks on these paths run in test_api.
      set_tests_properties(example_egl_host PROPERTIES ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1")
    endif()
  endif()

  # test_api runs these hosts and the ge2gl CLI; tests/ is added after examples/, so the
  # dependencies are attached once the top-level directory has been processed.
  function(_ge2gl_example_hosts_test_deps)
    if(TARGET test_api)
      foreach(dep threaded_host egl_host ge2gl_cli)
        if(TARGET ${dep})
          add_dependencies(test_api ${dep})
        endif()
      endforeach()
    endif()
  endfunction()
  cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR} CALL _ge2gl_example_hosts_test_deps)
endif()
