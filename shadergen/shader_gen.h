// GLSL generation: pure functions (key, caps) → source (style-anchors §7.6). No GL headers, no
// state reads. The first line after #version/#extension is a comment holding describe(key).
//
// Interface between the generated shaders and the translator:
//   vertex attributes  0 a_pos    vec3  drawing x, y (1/16 pixel grid), screen z 0..65535
//                      1 a_color  vec4  primary RGBA 0..255
//                      2 a_color2 vec3  secondary RGB 0..255
//                      3 a_tex    vec4  (s·k, t·k, k, w): k = 1/w (perspective) or 1; s, t in
//                                       units of the level-0 size; w = clip w for TLEVEL slope
//                      4 a_fog    float fog factor f (1 = no fog), interpolated, 8-bit per pixel
//   fragment output    0 o_color  uvec4 on an RGBA8UI target holding stored pixels (16-bit
//                                       formats kept bit-replicated: what a read expands to)
//   texture units      0 u_tex (usampler2D atlas of decoded levels), 1 u_dstColor (usampler2D),
//                      2 u_dstDepth (sampler2D of the D32F depth target)
// Depth is written through gl_FragDepth as z/65536 (exact in D32F).
#pragma once
#include <string>

#include "shadergen/shader_keys.h"

namespace ge::shadergen {

// Uniform names (the translator looks them up once per program).
namespace uniform {
inline constexpr const char* kNdcScale = "u_ndcScale";      // vec2: 2/target width, 2/target height
inline constexpr const char* kTex = "u_tex";
inline constexpr const char* kDstColor = "u_dstColor";
inline constexpr const char* kDstDepth = "u_dstDepth";
inline constexpr const char* kTexEnv = "u_texEnv";          // ivec3
inline constexpr const char* kFogColor = "u_fogColor";      // ivec3
inline constexpr const char* kAlphaTest = "u_alphaTest";    // ivec2 ref, mask
inline constexpr const char* kColorRef = "u_colorRef";      // ivec3
inline constexpr const char* kColorMask = "u_colorMask";    // ivec3
inline constexpr const char* kStencil = "u_stencil";        // ivec2 ref, mask
inline constexpr const char* kFixA = "u_fixA";              // ivec3
inline constexpr const char* kFixB = "u_fixB";              // ivec3
inline constexpr const char* kDither = "u_dither";          // int[16], index y*4+x
inline constexpr const char* kKeep = "u_keep";              // ivec4 protected bits
inline constexpr const char* kZRange = "u_zRange";          // ivec2 MINZ, MAXZ
inline constexpr const char* kTexLevels = "u_texLevels";    // ivec4[8] (atlas y, w, h, 0)
inline constexpr const char* kTexParams = "u_texParams";    // ivec2 max level, bias (1/16)
inline constexpr const char* kTexSlope = "u_texSlope";      // float
}  // namespace uniform

inline constexpr int kAttrPos = 0, kAttrColor = 1, kAttrColor2 = 2, kAttrTex = 3, kAttrFog = 4;
inline constexpr int kUnitTex = 0, kUnitDstColor = 1, kUnitDstDepth = 2;

// Return false and set err for keys the generator cannot express (e.g. framebuffer fetch
// requested but not in caps).
bool generateVertexShader(const VsKey& key, const HostCaps& caps, std::string& out, std::string* err = nullptr);
bool generateFragmentShader(const FsKey& key, const HostCaps& caps, std::string& out, std::string* err = nullptr);

}  // namespace ge::shadergen
