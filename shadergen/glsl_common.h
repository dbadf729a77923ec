// SPDX-License-Identifier: MIT
// GLSL text that both generators of the GL hardware mode write (hw_vertex.cpp's vertex shader and
// hw_geometry.cpp's geometry shader), written once here. Internal to shadergen/.
#pragma once
#include <string>

namespace ge::shadergen::glsl {

// The first lines of a hardware-mode shader: GLSL 3.30 with GL_ARB_gpu_shader5 and
// GL_ARB_gpu_shader_fp64 enabled where the driver has them (hw_vertex.h, host features), the
// comment `// ge2gl <desc>`, and the macros PRECISE (`precise` when shader5 is there: no fused
// multiply-add) and GE_FP64 (doubles, unless the test hook GE_NO_FP64 is defined).
void hwPreamble(std::string& s, const std::string& desc);

// isNan(x), notFinite(x) from the float's bits.
extern const char* const kFloatClass;
// fdiv(a, b): a / b correctly rounded as the CPU's float division (through double with GE_FP64).
extern const char* const kFdiv;
// to16(f, off), depthToInt(z): geometry/transform.cpp projectToScreen's 1/16-pixel snap and depth.
extern const char* const kScreenRound;

}  // namespace ge::shadergen::glsl
