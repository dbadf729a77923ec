// SPDX-License-Identifier: MIT
// GLSL text for reading the hardware mode's uniform block (HwVsUniforms laid out as uvec4 u_hw[],
// shadergen/hw_vertex.h) and for exact float literals: shared by the vertex shader generator
// (hw_vertex.cpp) and the geometry-stage generator (hw_geometry.cpp). Internal to shadergen/.
#pragma once
#include <cstddef>
#include <cstdio>
#include <string>

#include "shadergen/hw_vertex.h"

// The word index of a HwVsUniforms member (4-byte words).
#define HW_WORD(member) int(offsetof(::ge::shadergen::HwVsUniforms, member) / 4)

namespace ge::shadergen::hwtext {

inline std::string word(int w) {
    static const char* const comp[4] = {"x", "y", "z", "w"};
    return "u_hw[" + std::to_string(w / 4) + "]." + comp[w % 4];
}
inline std::string uf(int w) { return "uintBitsToFloat(" + word(w) + ")"; }
inline std::string ui(int w) { return "int(" + word(w) + ")"; }
inline std::string ivec3At(int w) { return "ivec3(" + ui(w) + ", " + ui(w + 1) + ", " + ui(w + 2) + ")"; }
inline std::string vec3At(int w) { return "vec3(" + uf(w) + ", " + uf(w + 1) + ", " + uf(w + 2) + ")"; }

// A float literal that reads back as exactly f.
inline std::string flit(float f) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.9g", double(f));
    std::string s = buf;
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
}

}  // namespace ge::shadergen::hwtext
