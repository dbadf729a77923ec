# SPDX-License-Identifier: MIT
# make_scenes: writes the project's own frame dumps (dumps/*.ppdmp) from scene descriptions built
# with ge::ListBuilder (docs/scenes.md). Include from tools/CMakeLists.txt:
#   include(${CMAKE_CURRENT_SOURCE_DIR}/scenes.cmake)
# Regenerate the committed dumps with:  <build>/make_scenes   (or --out DIR)
file(GLOB make_scenes_srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/scenes/*.cpp)
add_executable(make_scenes ${CMAKE_CURRENT_LIST_DIR}/make_scenes.cpp ${make_scenes_srcs})
set_target_properties(make_scenes PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR})
target_link_libraries(make_scenes PRIVATE ge_authoring)
target_compile_definitions(make_scenes PRIVATE GE2GL_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
