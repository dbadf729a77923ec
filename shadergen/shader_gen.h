// SPDX-License-Identifier: MIT
// GLSL generation: pure functions (key, caps) → source. No GL headers, no
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

#include "hle/types.h"
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
inline constexpr const char* kTexLevels = "u_texLevels";    // ivec4[8] (atlas y, 2^n w, 2^n h, 0)
inline constexpr const char* kTexParams = "u_texParams";    // ivec2 max level, bias (1/16)
inline constexpr const char* kTexSlope = "u_texSlope";      // float
inline constexpr const char* kPixScale = "u_pixScale";      // int: render scale N (texels per PSP pixel)
inline constexpr const char* kTexScale = "u_texScale";      // int: u_tex texels per PSP texel (render target)
inline constexpr const char* kClut = "u_clut";              // ivec2: CLUT shift, mask (render-target CLUT16/32)
}  // namespace uniform

inline constexpr int kAttrPos = 0, kAttrColor = 1, kAttrColor2 = 2, kAttrTex = 3, kAttrFog = 4;
inline constexpr int kUnitTex = 0, kUnitDstColor = 1, kUnitDstDepth = 2, kUnitTris = 3, kUnitClut = 5,
                     kUnitGradients = 6;  // 4: hw_vertex.h kUnitVertexBytes
inline constexpr const char* kClutTexUniform = "u_clutTex";  // usampler2D 256×1: palette per masked index
inline constexpr const char* kTrisUniform = "u_tris";  // usamplerBuffer of triangle records
inline constexpr const char* kGradientsUniform = "u_grads";  // usamplerBuffer of gradient planes (tri::kGradTexels each)

// Exact interpolation (HostCaps::exactInterp): every GL triangle has a record of kTexels RGBA32UI
// texels in the buffer texture u_tris, at index gl_VertexID / 3 (translator/tri_setup.h fills
// it from the software rasteriser's per-triangle setup, geometry/raster.h). Only a_pos is read
// from the vertex then; the vertex shader passes the record on as flat varyings and the fragment
// shader evaluates Z, colours, fog, s, t, level of detail and W at the sample point with the
// software rasteriser's arithmetic (geometry/raster.cpp rasterTriangle: int64 depth plane,
// single-precision attribute sums over float edge weights in the reference's vertex order).
namespace tri {
inline constexpr int kTexels = 15;
// Triangles ("o" = attribute order: in0, in1, in2, or in2, in1, in0 for negative area).
inline constexpr int kHeader = 0;     // x: kind | flags, y: fog byte, z: lod (float bits), w: W (float bits)
inline constexpr int kFog = 1;        // xyz: fog factor of o[i] (float bits); w: 1/area (float)
inline constexpr int kColors = 2;     // xyz: primary RGBA of o[i] (R in bits 0–7); w: sample offset
inline constexpr int kSecondary = 3;  // xyz: secondary RGB of o[i]; w: quad origin x | y << 16
inline constexpr int kS = 4;          // xyz: s of o[i]; w: level-0 width (float)
inline constexpr int kT = 5;          // xyz: t of o[i]; w: level-0 height (float)
inline constexpr int kQ = 6;          // xyz: q of o[i]; w: gradient reference x (kFlagColourGradients)
inline constexpr int kRecipW = 7;     // xyz: 1/w of o[i] (1 in through mode); w: gradient reference y
inline constexpr int kClipW = 8;      // xyz: w of o[i]; w: gradient planes index (kFlagColourGradients)
inline constexpr int kInts = 9;       // 12 int64 (2 per texel, low word first), see kI*
// Rectangles (rasterRectangle): texture coordinates as running single-precision sums from the
// first covered pixel (kRectBox.xy), one column-pair step per two columns added along the row to
// the row value, one row-pair step per two rows; the odd pixel of a pair adds half a step.
inline constexpr int kRectStart = 4;  // xy: s, t at the first pixel (float); zw: s, t step per column pair
inline constexpr int kRectRow = 5;    // xy: s, t step per row pair; zw: level-0 width, height (float)
inline constexpr int kRectBox = 6;    // covered pixels x1, y1, x2, y2 (int, inclusive)
// Fragments (lines, points: finished by the software rasteriser): s, t in kRectStart.xy, level of
// detail in the header.
// Kinds (header.x & 15) and flags.
inline constexpr u32 kKindTriangle = 0;
inline constexpr u32 kKindLinear = 1;             // constant fragment (lines, points): no edges
inline constexpr u32 kKindRect = 2;               // rectangle: constant colour, Z, fog; stepped s, t
inline constexpr u32 kFlagFogVaries = 1u << 4;    // fog interpolated (else header.y)
inline constexpr u32 kFlagColorVaries = 1u << 5;  // primary colour interpolated (else o[0]'s slot)
inline constexpr u32 kFlagSecVaries = 1u << 6;    // secondary colour interpolated (else o[0]'s slot)
inline constexpr u32 kFlagSwapped = 1u << 7;      // negative area: edges in in0, in2, in1 order
inline constexpr u32 kFlagThrough = 1u << 8;      // texture coordinates screen-linear
inline constexpr int kEdgeThresholdShift = 9;      // bits 9–11: edge i needs E_i ≥ bit (top-left rule)
// Colours stepped by gradient planes (geo::RasterParams::colourGradients): bits 12–13 the
// reference vertex (index in attribute order, geo::colourGradientReference), its drawing
// position (1/16 units, int bits) in kQ.w and kRecipW.w.
inline constexpr u32 kFlagColourGradients = 1u << 14;
inline constexpr int kGradientRefShift = 12;
// Int64. Edge i (opposite the i-th vertex of in0, in1, in2 — or in0, in2, in1 when swapped):
// E_i = A_i·(16x + o) + B_i·(16y + o) + C_i (o: sample offset). kIZ: the three vertex depths in
// attribute order.
inline constexpr int kIA = 0, kIB = 3, kIC = 6, kIZ = 9;
static_assert(kIZ + 3 <= 2 * (kTexels - kInts));
// Gradient planes (kFlagColourGradients; geo::colourGradientPlanes), in a buffer of their own
// (only such triangles have them; kClipW.w is the index): texel index·kGradTexels + ch holds
// channel ch's gx (int64, xy: low word first) and gy (zw); channels 0–3 primary RGBA, 4–6
// secondary RGB.
inline constexpr int kGradTexels = 7;
}  // namespace tri

// Return false and set err for keys the generator cannot express (e.g. framebuffer fetch
// requested but not in caps).
bool generateVertexShader(const VsKey& key, const HostCaps& caps, std::string& out, std::string* err = nullptr);
bool generateFragmentShader(const FsKey& key, const HostCaps& caps, std::string& out, std::string* err = nullptr);

}  // namespace ge::shadergen
