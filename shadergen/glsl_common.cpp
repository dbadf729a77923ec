// SPDX-License-Identifier: MIT
// GLSL text shared by the hardware-mode vertex and geometry shader generators (glsl_common.h).
#include "shadergen/glsl_common.h"

namespace ge::shadergen::glsl {

void hwPreamble(std::string& s, const std::string& desc) {
    s += "#version 330 core\n"
         "#extension GL_ARB_gpu_shader5 : enable\n"
         "#extension GL_ARB_gpu_shader_fp64 : enable\n";
    s += "// ge2gl " + desc + "\n";
    s += "#ifdef GL_ARB_gpu_shader5\n#define PRECISE precise\n#else\n#define PRECISE\n#endif\n"
         "#if defined(GL_ARB_gpu_shader_fp64) && !defined(GE_NO_FP64)\n#define GE_FP64 1\n#endif\n";
}

const char* const kFloatClass = R"(bool isNan(float x) { return (floatBitsToUint(x) & 0x7FFFFFFFu) > 0x7F800000u; }
bool notFinite(float x) { return (floatBitsToUint(x) & 0x7F800000u) == 0x7F800000u; }
)";

const char* const kFdiv = R"(// a / b correctly rounded (geometry/ float divisions).
float fdiv(float a, float b) {
#ifdef GE_FP64
  PRECISE double q = double(a) / double(b);
  return float(q);
#else
  PRECISE float q = a / b;
  return q;
#endif
}
)";

const char* const kScreenRound = R"(// geometry/transform projectToScreen: x16 = trunc(Xs·16 + 0.375 − OFF), limited to ±2^20.
int to16(float f, int off) {
  PRECISE float t = f * 16.0 + 0.375;
  t = t - float(off);
  if (isNan(t) || t <= -1048576.0) t = -1048576.0;
  if (t > 1048576.0) t = 1048576.0;
  return int(t);
}
int depthToInt(float z) { return z >= 0.0 ? (z <= 65535.0 ? int(z) : 65535) : 0; }
)";

}  // namespace ge::shadergen::glsl
